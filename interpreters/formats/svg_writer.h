#pragma once
// SVG output of a frame's geometry: an orthographic projection onto the world x-y plane,
// seen from +z with y up (the view of a turtle that only turns with + and -). Primitives
// are drawn exactly, not from the mesh: lines as hairlines, cylinders as lines as wide as
// their diameter (butt ends), discs as their projected outlines (ellipses, filled, holes
// left open), spheres as circles. They are painted far to near by the z of their middle,
// in a fixed order otherwise (discs, cylinders, spheres, lines), so the text depends only
// on the geometry and the options.

#include <ostream>

#include "interpreters/geometry.h"

namespace ontogen {

/// The picture's size and the text's number format.
struct SvgOptions {
  double size = 1000;    ///< the picture's larger side including margins, SVG user units (px)
  double margin = 20;    ///< blank border around the drawing, user units (>= hairline)
  double hairline = 1;   ///< stroke width of lines and outlines, user units; thinner
                         ///< cylinders are widened to it so they stay visible
  int decimals = 2;      ///< digits after the point of every number (0..6): 2 resolves
                         ///< 1/100000 of a 1000-unit picture
};

/// Throws std::invalid_argument naming the first option out of range.
void checkSvgOptions(const SvgOptions& options);

/// Writes geometry as a standalone SVG document to out. An empty geometry gives an empty
/// white picture. Throws std::invalid_argument on options out of range; stream errors
/// are left in out's state for the caller to check.
void writeSvg(const Geometry& geometry, std::ostream& out, const SvgOptions& options = {});

}  // namespace ontogen
