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

#include "interpreters/formats/scene_output.h"
#include "interpreters/geometry.h"
#include "interpreters/geometry/turtle.h"
#include "interpreters/interpretation_set.h"
#include "interpreters/scene.h"

namespace ontogen {

/// Settings of the set; validated when it is created.
struct GeometrySetDef {
  TurtleDef turtle{};       ///< step, angles and initial radius
  SceneOutputDef output{};  ///< what endFrame() writes when the set is used on its own
  MeshDef mesh{};           ///< tessellation of cylinders, discs and spheres
  /// Record the scene's nodes (a node per drawing cell, with its parent and frame). They
  /// cost about a third of the interpretation of a large word, so only a host that needs
  /// them (skeletons, physics, a viewer) asks; output.writeGlb asks too, as the .glb
  /// follows each cell's part over the frames (formats/glb_writer.h).
  bool sceneNodes = false;
};

/// The 3-D turtle's drawing as a scene (interpreters/scene.h): a node per cell that
/// draws. In a run the output stage writes it; used on its own, endFrame() writes it
/// through a SceneOutput of its own.
class GeometrySet : public InterpretationSet {
 public:
  /// Throws std::invalid_argument when def is out of range.
  explicit GeometrySet(const GeometrySetDef& def = {});

  std::string_view name() const override { return "geometry"; }
  bool knows(std::string_view command) const override;
  void beginFrame(const FrameTarget& target) override;
  void beginCell(const CellContext& cell) override;
  bool wantsParents() const override { return recordsNodes_; }
  bool wantsIds() const override { return recordsNodes_; }
  void execute(std::string_view command, std::span<const double> args) override;
  /// `id` indexes turtleCommands().
  void executeCommand(int id, std::string_view command, std::span<const double> args) override;
  /// Writes the enabled files atomically (throws OutputError on failure) and returns
  /// their paths, SVG first. Throws std::invalid_argument from the constructor when mp4
  /// is asked for and ffmpeg is not installed.
  std::vector<std::filesystem::path> endFrame() override;
  bool drawsScene() const override { return true; }
  /// Reserves a line per cell (the most a word of symbols draws), and a node per cell
  /// where the set records nodes.
  void expectCells(std::size_t cells) override;
  /// Adds the frame's scene to `scene`, handing it the set's buffers when `scene` is empty
  /// (the set's own scene is then empty until its next frame).
  void contribute(Scene& scene) override;
  /// The scene of the frame being drawn, or of the last one after endFrame.
  const Scene& scene() const { return scene_; }

  /// The geometry of the frame being drawn, or of the last one after endFrame.
  const Geometry& geometry() const { return scene_.geometry; }
  /// The turtle's warnings (unmatched ], bad arguments) for the same frame.
  const TurtleWarnings& warnings() const { return turtle_.warnings(); }
  /// Unmatched ] and commands with bad arguments since the last call, located.
  std::vector<SetWarning> takeWarnings() override;
  /// The turtle, in its state at the end of the word executed so far.
  const Turtle& turtle() const { return turtle_; }

  /// DIR/<stem>.<extension>, or DIR/<stem>_<frame, 4 digits>.<extension> (formats/scene_output.h).
  static std::filesystem::path outputPath(const FrameTarget& target, std::string_view extension) {
    return ontogen::outputPath(target, extension);
  }

 private:
  void run(const TurtleCommand& command, std::span<const double> args);
  void closeNode();
  void finishScene();

  GeometrySetDef def_;
  bool recordsNodes_ = false;  // def_.sceneNodes or the .glb is written
  SceneOutput output_;
  WarningCounter unmatchedPops_;
  WarningCounter badArguments_;
  WarningCounter notDrawn_;  // shapes left out: a coordinate not finite or beyond ±1e30
  Turtle turtle_;
  Scene scene_;
  SceneNode pending_;        // the cell being drawn, a node if it draws
  bool hasPending_ = false;
  FrameTarget target_;
};

}  // namespace ontogen
