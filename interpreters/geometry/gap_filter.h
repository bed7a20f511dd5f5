#pragma once
// Surface plates and the gap filter of paper 004 section VIII. The turtle draws flat
// facets ("plates") corner by corner; neighbouring plates meet at shared corners, but
// attractors and repellers bend each F, so corners that should coincide drift apart and
// the surface opens gaps (paper 004 section VI). The filter closes them "by slightly
// elongating the edge lengths": corners closer than a tolerance are joined (single
// linkage) and moved to their mean, and each facet is coloured by how much its edges had
// to stretch, blue (unperturbed) to red (stressed).

#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "interpreters/geometry.h"

namespace ontogen {

/// A flat facet drawn between plate and endplate: its corners in order (>= 3).
struct Plate {
  std::vector<glm::dvec3> corners;  ///< model units, anticlockwise seen from the front
  uint32_t material = 0;            ///< palette index it was drawn with
};

/// The plates as triangles (a fan per plate), each plate with corners of its own, flat
/// normals and its own material: what the turtle draws without the filter.
Mesh platesAsMesh(std::span<const Plate> plates);

/// What the filter made.
struct JoinedPlates {
  Mesh mesh;                    ///< shared corners, flat normals, stress materials
  std::vector<double> stretch;  ///< per triangle of mesh: its plate's stretch
  double maxStretch = 0;        ///< the largest stretch, which gets the reddest colour
};

/// Joins corners of different or the same plates that lie within tolerance (model units,
/// >= 0) of each other, transitively, moving each group to its mean. A plate's stretch
/// is the largest |l' / l - 1| over its edges (l before, l' after; edges of zero length
/// are skipped). Its triangles get material stressMaterial(stretch / maxStretch) (all
/// blue when nothing moved). Triangles whose corners were joined into one point are
/// dropped.
JoinedPlates joinPlates(std::span<const Plate> plates, double tolerance);

}  // namespace ontogen
