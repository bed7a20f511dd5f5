#pragma once
// The "geometry" interpretation set: a 3-D turtle (turtle.h) that draws each frame into a
// Geometry and writes it as DIR/<stem>.svg and DIR/<stem>.obj, or as
// DIR/<stem>_0003.svg ... when the run has several frames.

#include <filesystem>
#include <span>
#include <string_view>
#include <vector>

#include "interpreters/geometry.h"
#include "interpreters/interpretation_set.h"
#include "interpreters/svg_writer.h"
#include "interpreters/turtle.h"

namespace ontogen {

/// Settings of the set; validated when it is created.
struct GeometrySetDef {
  TurtleDef turtle{};    ///< step, angles and initial radius
  bool writeSvg = true;  ///< write <stem>.svg each frame
  bool writeObj = true;  ///< write <stem>.obj each frame
  SvgOptions svg{};      ///< picture size and number format of the SVG
  MeshDef mesh{};        ///< tessellation of cylinders, discs and spheres
};

/// Turtle geometry written as SVG and OBJ.
class GeometrySet : public InterpretationSet {
 public:
  /// Throws std::invalid_argument when def is out of range.
  explicit GeometrySet(const GeometrySetDef& def = {});

  std::string_view name() const override { return "geometry"; }
  bool knows(std::string_view command) const override;
  void beginFrame(const FrameTarget& target) override;
  void execute(std::string_view command, std::span<const double> args) override;
  /// Writes the enabled files atomically (throws OutputError on failure) and returns
  /// their paths, SVG first.
  std::vector<std::filesystem::path> endFrame() override;

  /// The geometry of the frame being drawn, or of the last one after endFrame.
  const Geometry& geometry() const { return geometry_; }
  /// The turtle's warnings (unmatched ], bad arguments) for the same frame.
  const TurtleWarnings& warnings() const { return turtle_.warnings(); }
  /// The turtle, in its state at the end of the word executed so far.
  const Turtle& turtle() const { return turtle_; }

  /// DIR/<stem>.<extension>, or DIR/<stem>_<frame, 4 digits at least>.<extension> when
  /// target.frameCount > 1.
  static std::filesystem::path outputPath(const FrameTarget& target,
                                          std::string_view extension);

 private:
  GeometrySetDef def_;
  Turtle turtle_;
  Geometry geometry_;
  FrameTarget target_;
};

}  // namespace ontogen
