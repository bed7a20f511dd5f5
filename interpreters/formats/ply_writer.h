#pragma once
// Stanford PLY output of a frame's surfaces, ASCII: one vertex per (position, normal,
// texcoord) corner with its normal and its palette colour as 8-bit RGB, and triangles.
// Zero-radius segments are not written (PLY has no standard line element readers agree
// on); OBJ and glTF carry them.

#include <ostream>

#include "interpreters/geometry.h"

namespace ontogen {

/// Writes geometry's triangles to out as an ASCII PLY file.
void writePly(const Geometry& geometry, std::ostream& out);

}  // namespace ontogen
