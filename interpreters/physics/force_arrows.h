#pragma once
// Arrows drawn into a frame's geometry: a cylinder shaft and a cone head (two heads for
// a moment, the engineer's double arrow), coloured along the palette's blue-to-red ramp
// by magnitude. Paper 003 draws the force and the moment at every rod's base joint.

#include <glm/vec3.hpp>

#include "interpreters/geometry.h"

namespace ontogen {

struct ArrowStyle {
  double shaftRadius = 0.05;  ///< model units
  double headLength = 0.3;    ///< model units; shortened on short arrows
  int heads = 1;              ///< 1: a force, 2: a moment
  uint32_t material = 0;      ///< palette index
};

/// An arrow as drawn, for tests and reports.
struct DrawnArrow {
  glm::dvec3 start{0.0};   ///< model units
  glm::dvec3 vector{0.0};  ///< model units
  double magnitude = 0;    ///< of what it shows: N, or N m
  int heads = 1;           ///< 1: a force, 2: a moment
  uint32_t material = 0;
  bool load = false;       ///< an external force, drawn thick where it acts
};

/// Adds an arrow from `start` along `vector` (model units); a zero vector adds nothing.
void addArrow(Geometry& geometry, const glm::dvec3& start, const glm::dvec3& vector, const ArrowStyle& style);

}  // namespace ontogen
