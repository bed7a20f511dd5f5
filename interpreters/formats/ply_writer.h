#pragma once
// Stanford PLY output of a frame's surfaces: one vertex per (position, normal, texcoord)
// corner with its normal, texture coordinate and palette colour as 8-bit RGB, and
// triangles. Binary little-endian by default (half the ASCII file's size, the flower's
// 109 KB instead of 229, read back exactly, and what MeshLab, Blender and assimp read
// fastest), ASCII on request; both hold the same values (floats: x y z nx ny nz s t;
// uchars: red green blue; faces as a uchar count and uint indices). The file can be
// written z-up (up_axis.h).
// Zero-radius segments are not written (PLY has no standard line element readers agree
// on); OBJ and glTF carry them.

#include <ostream>

#include "interpreters/formats/up_axis.h"
#include "interpreters/geometry.h"

namespace ontogen {

/// How a PLY file is written.
struct PlyOptions {
  bool binary = true;        ///< binary_little_endian 1.0; false: ascii 1.0
  UpAxis up = UpAxis::Y;     ///< the file's up axis
};

/// Writes geometry's triangles to out as a PLY file. Stream errors are left in out's
/// state for the caller to check.
void writePly(const Geometry& geometry, std::ostream& out, const PlyOptions& options = {});

}  // namespace ontogen
