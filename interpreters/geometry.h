#pragma once
// The geometry of one frame, as the turtle leaves it. Two kinds of output are kept apart:
// zero-radius line segments, and one triangle mesh holding every surface (cylinders,
// discs, spheres). Each surface is also recorded as a primitive (axis and radius, centre
// and plane) so that writers that do not want triangles (SVG) can draw it exactly.
//
// The mesh is indexed the way Wavefront OBJ is: each triangle corner names a position
// and a normal separately, so a capped cylinder shares its rim positions between the
// side and the caps (the mesh is watertight by position) while the side and the caps
// keep their own normals. Triangles wind counter-clockwise seen from outside (discs:
// seen from the side their normal points to).

#include <array>
#include <cstdint>
#include <cstddef>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace ontogen {

/// How finely surfaces are tessellated; validated when a Geometry is created.
struct MeshDef {
  /// Sides of a cylinder's cross-section: 12 reads as round at drawing sizes while a
  /// million cylinders stay near 48 million triangles.
  int cylinderSides = 12;
  /// Sides of a disc's rim: discs are drawn large (wheels, flowers), so finer.
  int discSides = 32;
  /// Meridians of a sphere.
  int sphereSlices = 12;
  /// Bands of a sphere from pole to pole.
  int sphereStacks = 6;
};

/// A line with no thickness, from start to end (model units).
struct Segment {
  glm::dvec3 start{0.0};
  glm::dvec3 end{0.0};
  uint32_t material = 0;  ///< palette index (palette.h)
};

/// A cylinder around the axis start -> end (model units).
struct CylinderPrimitive {
  glm::dvec3 start{0.0};
  glm::dvec3 end{0.0};
  double radius = 0;
  bool capped = false;  ///< both ends closed with discs
};

/// A flat annulus (inner == 0: a full disc) centred at centre, spanned by the unit
/// vectors axisA and axisB; its normal is axisA x axisB.
struct DiscPrimitive {
  glm::dvec3 centre{0.0};
  glm::dvec3 axisA{1.0, 0.0, 0.0};
  glm::dvec3 axisB{0.0, 1.0, 0.0};
  double inner = 0;
  double outer = 0;
};

/// A sphere (model units).
struct SpherePrimitive {
  glm::dvec3 centre{0.0};
  double radius = 0;
};

/// One triangle: 0-based indices into Mesh::positions, Mesh::normals and
/// Mesh::texcoords per corner, and its palette colour.
struct Triangle {
  std::array<uint32_t, 3> position{};
  std::array<uint32_t, 3> normal{};
  std::array<uint32_t, 3> texcoord{};  ///< primitives use texcoord 0, (0, 0)
  uint32_t material = 0;               ///< palette index (palette.h)
};

/// Every surface of a frame in one indexed triangle mesh.
struct Mesh {
  std::vector<glm::dvec3> positions;  ///< model units
  std::vector<glm::dvec3> normals;    ///< unit length
  std::vector<glm::dvec2> texcoords;  ///< (u, v) in [0, 1]; index 0 is (0, 0) once any exists
  std::vector<Triangle> triangles;    ///< anticlockwise seen from outside
};

namespace detail {
/// cos and sin of 2 pi i / n for i in 0..n-1, computed once per Geometry.
struct UnitCircle {
  explicit UnitCircle(int sides);  ///< sides >= 1
  std::vector<double> cos;         ///< cos(2 pi i / sides)
  std::vector<double> sin;         ///< sin(2 pi i / sides)
};
}  // namespace detail

/// An axis-aligned box; empty until something is added.
struct Box {
  glm::dvec3 min{0.0};  ///< model units; meaningless while empty
  glm::dvec3 max{0.0};  ///< model units; meaningless while empty
  bool empty = true;    ///< true until the first add

  /// Grows the box to hold point.
  void add(const glm::dvec3& point);
};

/// The primitives of one frame. Degenerate input (zero length or radius) adds nothing.
class Geometry {
 public:
  /// Throws std::invalid_argument when a MeshDef field is out of range (sides 3..1024,
  /// stacks 2..1024). The add functions throw std::length_error once the mesh would need
  /// more than 2^32 - 1 positions or normals (OBJ indices are kept in 32 bits).
  explicit Geometry(const MeshDef& def = {});

  /// Removes everything; keeps the tessellation settings.
  void clear();

  /// Adds a line from start to end.
  void addSegment(const glm::dvec3& start, const glm::dvec3& end);
  /// Adds a cylinder of radius around start -> end. side, a direction across the axis
  /// (the turtle's L), fixes where the cross-section's first vertex lies; any other
  /// direction is used when it is parallel to the axis.
  void addCylinder(const glm::dvec3& start, const glm::dvec3& end, double radius, bool capped,
                   const glm::dvec3& side = {1.0, 0.0, 0.0});
  /// Adds an annulus of radii inner..outer around centre in the plane of the orthonormal
  /// vectors axisA, axisB (the turtle's H and L); it faces axisA x axisB.
  void addDisc(const glm::dvec3& centre, const glm::dvec3& axisA, const glm::dvec3& axisB,
               double inner, double outer);
  /// Adds a sphere; its poles lie along world z.
  void addSphere(const glm::dvec3& centre, double radius);
  /// Appends a mesh made elsewhere (generalized cylinders, surfaces): its indices are
  /// its own, 0-based; its triangles take the current material, or keep their own when
  /// keepMaterials (plates coloured by the gap filter).
  void addMesh(const Mesh& part, bool keepMaterials = false);
  /// Appends everything of another frame's geometry (lines, primitives, mesh), each part
  /// keeping its colour.
  void append(const Geometry& other);
  /// The same, taking other's primitives' buffers where this geometry has none of that
  /// kind instead of copying them (its mesh is copied); other is left valid but
  /// unspecified (clear it).
  void append(Geometry&& other);

  /// Makes room for `count` lines in all without moving them again (a hint: more may be
  /// added). Throws std::bad_alloc as a vector's reserve does.
  void reserveSegments(std::size_t count) { segments_.reserve(count); }

  /// The palette colour of everything added from now on.
  void setMaterial(uint32_t material) { material_ = material; }
  /// The palette colour used now.
  uint32_t material() const { return material_; }

  /// The zero-radius lines, in the order they were drawn.
  const std::vector<Segment>& segments() const { return segments_; }
  /// The cylinders, discs and spheres as drawn; their triangles are all in mesh().
  const std::vector<CylinderPrimitive>& cylinders() const { return cylinders_; }
  const std::vector<DiscPrimitive>& discs() const { return discs_; }      ///< see cylinders()
  const std::vector<SpherePrimitive>& spheres() const { return spheres_; }  ///< see cylinders()
  /// Every surface, tessellated.
  const Mesh& mesh() const { return mesh_; }
  /// The tessellation settings.
  const MeshDef& meshDef() const { return def_; }

  /// Holds every segment end and every mesh position (surfaces as tessellated).
  const Box& bounds() const { return bounds_; }
  /// Number of zero-radius lines.
  std::size_t segmentCount() const { return segments_.size(); }
  /// Number of triangles of the mesh.
  std::size_t triangleCount() const { return mesh_.triangles.size(); }
  /// True when there is nothing to draw.
  bool empty() const { return segments_.empty() && mesh_.triangles.empty(); }
  /// Primitives and meshes not drawn because a coordinate was not finite or beyond ±1e30
  /// model units (so no writer ever writes a non-finite number).
  uint64_t dropped() const { return dropped_; }

 private:
  uint32_t addPosition(const glm::dvec3& position);
  uint32_t addNormal(const glm::dvec3& normal);
  void addTriangle(std::array<uint32_t, 3> positions, std::array<uint32_t, 3> normals);
  void checkIndexSpace(std::size_t positions, std::size_t normals) const;

  MeshDef def_;
  detail::UnitCircle cylinderCircle_;
  detail::UnitCircle discCircle_;
  detail::UnitCircle sphereCircle_;
  std::vector<Segment> segments_;
  std::vector<CylinderPrimitive> cylinders_;
  std::vector<DiscPrimitive> discs_;
  std::vector<SpherePrimitive> spheres_;
  Mesh mesh_;
  Box bounds_;
  uint64_t dropped_ = 0;
  uint32_t material_ = 0;
};

}  // namespace ontogen
