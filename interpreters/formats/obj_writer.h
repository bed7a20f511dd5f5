#pragma once
// Wavefront OBJ output of a frame's geometry: the mesh as `v`, `vn` and
// `f p//n p//n p//n` (1-based, positions and normals indexed apart, triangles wound
// anticlockwise seen from outside), and zero-radius segments as `l a b` over vertices
// that follow the mesh's (a segment that starts where the previous one ended reuses its
// vertex). Numbers have 10 significant digits, so a written file reads back to within
// 1e-10 of the geometry, relative to the model's size. Empty geometry is written as one
// point at the origin (`v 0 0 0`, `p 1`): readers such as assimp refuse an OBJ without a
// mesh. With UpAxis::Z the positions and normals are written turned into z-up
// (up_axis.h).

#include <ostream>
#include <string_view>

#include "interpreters/formats/up_axis.h"
#include "interpreters/geometry.h"

namespace ontogen {

/// Writes geometry to out as an OBJ file with a comment header of counts. Stream errors
/// are left in out's state for the caller to check.
void writeObj(const Geometry& geometry, std::ostream& out, UpAxis up = UpAxis::Y);

/// The same with materials: `mtllib <mtlName>`, texture coordinates (`vt`), and the
/// triangles and segments grouped by palette colour under `usemtl ontogen_<i>`, faces as
/// `f p/t/n`.
void writeObj(const Geometry& geometry, std::ostream& out, std::string_view mtlName, UpAxis up = UpAxis::Y);

/// The MTL file for writeObj: one `newmtl ontogen_<i>` with its diffuse colour (Kd) per
/// palette colour the geometry uses.
void writeMtl(const Geometry& geometry, std::ostream& out);

}  // namespace ontogen
