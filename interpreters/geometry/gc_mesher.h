#pragma once
// Generalized cylinders (paper 000, section 4.1, Fig. 3 B): one continuous tube through
// control points that the turtle leaves as it moves.
//
//  - The carrier curve is a cubic Hermite spline through the control points with
//    Catmull-Rom tangents (end tangents: the first and last chords), so it passes through
//    every point with a continuous tangent.
//  - Frames are carried along it by rotation minimisation (the double reflection method,
//    Wang, Jüttler, Zheng & Liu 2008) starting from the turtle's L at the first point, so
//    the tube never twists suddenly, whatever the turtle's rolls.
//  - Radius and cross-section are interpolated linearly between control points; every
//    section is resampled by arc length to the same point count so they blend point by
//    point.
//  - Rings share positions at the seam (u = 0 and u = 1 differ only in texture
//    coordinates) and the caps reuse the end rings, so a capped tube is watertight.

#include <span>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "interpreters/geometry.h"

namespace ontogen {

/// A closed polyline in the cross-section plane: x along the frame's side vector (the
/// turtle's L), y along the other (U), anticlockwise; scaled by the radius.
struct GcSection {
  std::vector<glm::dvec2> points;  ///< at least 3
};

/// A circle of n points of radius 1, starting at (1, 0).
GcSection circleSection(int points);

/// One control point of a generalized cylinder.
struct GcControlPoint {
  glm::dvec3 position{0.0};          ///< model units
  glm::dvec3 side{-1.0, 0.0, 0.0};   ///< the turtle's L here; only the first one is used
  double radius = 1;                 ///< model units, >= 0
  const GcSection* section = nullptr;  ///< null: the default circle
};

/// How finely a generalized cylinder is meshed; validated by meshGeneralizedCylinder.
struct GcDef {
  int samplesPerSpan = 8;   ///< rings between two control points (1..256), the last excluded
  int sectionPoints = 0;    ///< points per ring (3..1024); 0: the most of any section used
  bool caps = true;         ///< close both ends with a fan around the end centre
};

/// The tube through points (at least 2 distinct positions; fewer give an empty mesh).
/// Indices of the result are 0-based into its own arrays; normals are unit length.
/// Throws std::invalid_argument when def is out of range or a section has < 3 points.
Mesh meshGeneralizedCylinder(std::span<const GcControlPoint> points, const GcDef& def = {});

}  // namespace ontogen
