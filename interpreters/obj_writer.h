#pragma once
// Wavefront OBJ output of a frame's geometry: the mesh as `v`, `vn` and
// `f p//n p//n p//n` (1-based, positions and normals indexed apart, triangles wound
// anticlockwise seen from outside), and zero-radius segments as `l a b` over vertices
// that follow the mesh's (a segment that starts where the previous one ended reuses its
// vertex). Numbers have 10 significant digits, so a written file reads back to within
// 1e-10 of the geometry, relative to the model's size.

#include <ostream>

#include "interpreters/geometry.h"

namespace ontogen {

/// Writes geometry to out as an OBJ file with a comment header of counts. Stream errors
/// are left in out's state for the caller to check.
void writeObj(const Geometry& geometry, std::ostream& out);

}  // namespace ontogen
