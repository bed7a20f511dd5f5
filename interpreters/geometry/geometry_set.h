#pragma once
// The "geometry" interpretation set: a 3-D turtle (turtle.h) that draws each frame into a
// Geometry and writes it in the formats chosen (applyGeometryFormats):
//  - per frame, DIR/<stem>.<ext>, or DIR/<stem>_0003.<ext> when the run has several
//    frames: svg, obj (with its mtl), ply, png-frames (png);
//  - once for the whole run, after its last frame: glb (every frame, animated;
//    glb_writer.h), png (the last frame), mp4 (every frame through ffmpeg).

#include <filesystem>
#include <span>
#include <string_view>
#include <vector>

#include "interpreters/formats/glb_writer.h"
#include "interpreters/formats/renderer.h"
#include "interpreters/formats/svg_writer.h"
#include "interpreters/geometry.h"
#include "interpreters/geometry/turtle.h"
#include "interpreters/interpretation_set.h"

namespace ontogen {

/// Settings of the set; validated when it is created.
struct GeometrySetDef {
  TurtleDef turtle{};    ///< step, angles and initial radius
  bool writeSvg = true;  ///< write <stem>.svg each frame
  bool writeObj = true;  ///< write <stem>.obj each frame
  bool writeMtl = false;       ///< with the OBJ, its materials as <stem>.mtl
  bool writePly = false;       ///< write <stem>.ply each frame
  bool writePngFrames = false; ///< render <stem>.png each frame
  bool writePng = false;       ///< render <stem>.png of the last frame
  bool writeGlb = false;       ///< write <stem>.glb of every frame after the last
  bool writeMp4 = false;       ///< write <stem>.mp4 of every frame after the last (ffmpeg)
  double framesPerSecond = 25; ///< of the MP4
  SvgOptions svg{};      ///< picture size and number format of the SVG
  MeshDef mesh{};        ///< tessellation of cylinders, discs and spheres
  RenderDef render{};    ///< size and view of PNG pictures and MP4 frames
};

/// The formats `--format` accepts, in the order `ontogen help` lists them.
inline constexpr const char* kGeometryFormats = "glb, png, png-frames, mp4, obj, ply, svg";

/// Sets def's write flags from a comma-separated list of formats (kGeometryFormats),
/// clearing the others. Returns an error message naming the bad entry, or "" on success.
std::string applyGeometryFormats(std::string_view list, GeometrySetDef& def);

/// True when an executable named ffmpeg is on PATH.
bool ffmpegAvailable();

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
  /// their paths, SVG first. Throws std::invalid_argument from the constructor when mp4
  /// is asked for and ffmpeg is not installed.
  std::vector<std::filesystem::path> endFrame() override;

  /// The geometry of the frame being drawn, or of the last one after endFrame.
  const Geometry& geometry() const { return geometry_; }
  /// The turtle's warnings (unmatched ], bad arguments) for the same frame.
  const TurtleWarnings& warnings() const { return turtle_.warnings(); }
  /// Unmatched ] and commands with bad arguments since the last call, located.
  std::vector<SetWarning> takeWarnings() override;
  /// The turtle, in its state at the end of the word executed so far.
  const Turtle& turtle() const { return turtle_; }

  /// DIR/<stem>.<extension>, or DIR/<stem>_<frame, 4 digits at least>.<extension> when
  /// target.frameCount > 1.
  static std::filesystem::path outputPath(const FrameTarget& target,
                                          std::string_view extension);

 private:
  std::filesystem::path mp4FramesDirectory() const;
  void writeMp4(std::vector<std::filesystem::path>& written);

  GeometrySetDef def_;
  WarningCounter unmatchedPops_;
  WarningCounter badArguments_;
  Turtle turtle_;
  Geometry geometry_;
  FrameTarget target_;
  GlbAnimationWriter glb_;
  int mp4Frames_ = 0;
};

}  // namespace ontogen
