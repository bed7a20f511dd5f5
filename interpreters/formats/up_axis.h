#pragma once
// Which axis a written file calls up. ontogen's world is y-up (the turtle's heading starts
// along +y, as in cpfg and glTF); Blender, 3ds Max, many CAD and print tools and most PLY
// viewers take +z as up, and show a y-up file lying on its back. Writers of OBJ and PLY
// can rotate the world into z-up as they write it: a quarter turn about +x,
// (x, y, z) -> (x, -z, y), the same turn Blender's glTF importer makes. It is a rotation,
// so lengths, handedness and the winding of triangles are kept; normals turn with the
// positions.

#include <glm/vec3.hpp>

namespace ontogen {

/// The up axis of a written file.
enum class UpAxis {
  Y,  ///< as the world is: +y up
  Z,  ///< turned a quarter about +x: the world's +y is the file's +z, its +z the file's -y
};

/// point (or a normal) of the y-up world in the file's axes.
template <typename Vec>
Vec toUpAxis(const Vec& point, UpAxis up) {
  if (up == UpAxis::Y) return point;
  // 0 - z rather than -z: a zero stays +0, which text writers print as "0", not "-0".
  return Vec(point.x, typename Vec::value_type(0) - point.z, point.y);
}

}  // namespace ontogen
