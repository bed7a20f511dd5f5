#pragma once
// The output stage of the geometry: writes the scenes of a run's frames in the formats
// asked for. Per frame: SVG, OBJ (+ MTL), PLY, PNG pictures; once for the run: the
// animated glTF binary of every frame (skinned when the frames hold a skeleton), the
// picture of the last, the MP4 of all (through ffmpeg), the skeleton's joint tracks. Sets only draw scenes (interpreters/scene.h); this writes them, so several
// sets can draw into one frame. Every file is written atomically: complete or absent.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "interpreters/formats/renderer.h"
#include "interpreters/formats/svg_writer.h"
#include "interpreters/formats/up_axis.h"
#include "interpreters/interpretation_set.h"
#include "interpreters/scene.h"

namespace ontogen {

/// Which formats to write, and how; validated when a SceneOutput is created.
struct SceneOutputDef {
  bool writeSvg = true;        ///< write <stem>.svg each frame
  bool writeObj = true;        ///< write <stem>.obj each frame
  bool writeMtl = false;       ///< with the OBJ, its materials as <stem>.mtl
  bool writePly = false;       ///< write <stem>.ply each frame
  bool plyBinary = true;       ///< the .ply binary little-endian; false: ASCII
  bool writePngFrames = false; ///< render <stem>.png each frame
  bool writePng = false;       ///< render <stem>.png of the last frame
  bool writeGlb = false;       ///< write <stem>.glb of every frame after the last
  bool writeMp4 = false;       ///< write <stem>.mp4 of every frame after the last (ffmpeg)
  bool writeJoints = false;    ///< write <stem>.joints.json, the skeleton's tracks, after the last
  bool writeMjcf = false;      ///< the dynamics set writes <stem>.xml, its MuJoCo model (the stage writes nothing)
  double framesPerSecond = 25; ///< of the MP4
  UpAxis up = UpAxis::Y;       ///< the up axis of the OBJ and PLY files (glTF is y-up by its specification)
  SvgOptions svg{};            ///< picture size and number format of the SVG
  RenderDef render{};          ///< size and view of PNG pictures and MP4 frames
};

/// The formats `--format` accepts, in the order `ontogen help` lists them.
inline constexpr const char* kGeometryFormats = "glb, png, png-frames, mp4, obj, ply, ply-ascii, svg, joints, mjcf";

/// Sets def's write flags from a comma-separated list of formats (kGeometryFormats),
/// clearing the others. Returns an error message naming the bad entry, or "" on success.
std::string applyGeometryFormats(std::string_view list, SceneOutputDef& def);


/// DIR/<stem>.<extension>, or DIR/<stem>_<frame, 4 digits at least>.<extension> when
/// target.frameCount > 1.
std::filesystem::path outputPath(const FrameTarget& target, std::string_view extension);

class SceneOutput {
 public:
  /// Throws std::invalid_argument when def is out of range, or asks for mp4 without ffmpeg.
  explicit SceneOutput(const SceneOutputDef& def);
  ~SceneOutput();
  SceneOutput(SceneOutput&&) noexcept;
  SceneOutput& operator=(SceneOutput&&) noexcept;

  /// Writes one frame's scene (and, at the run's last frame, the outputs of the whole
  /// run); returns the paths written, SVG first. Throws OutputError on failure.
  std::vector<std::filesystem::path> write(const Scene& scene, const FrameTarget& target);
  const SceneOutputDef& def() const { return def_; }
  /// Bytes this stage holds between frames (the .glb's frames and the movie's, all
  /// written at the end).
  uint64_t heldBytes() const;
  /// Bytes the write() of `target` needs for a while to render a picture (0: none).
  uint64_t pictureBytes(const FrameTarget& target) const;
  /// Frames the .glb holds so far.
  std::size_t glbFrames() const;
  /// What the stage left out since the last call (frames with nothing an .obj or .ply
  /// can hold, which get no such file), one entry per kind; starts again.
  std::vector<SetWarning> takeWarnings();

 private:
  // The writers that keep the run's frames until the last (scene_output.cpp), behind a
  // pointer so that this header, which the run's public header includes, needs none of
  // theirs.
  struct Writers;

  void renderMovieFrames(const FrameTarget& target, std::vector<std::filesystem::path>& written);

  SceneOutputDef def_;
  std::unique_ptr<Writers> writers_;
  /// The movie's frames, kept until the last so that one camera frames them all (on the
  /// union of their bounds): a growing model grows on screen instead of zooming.
  std::vector<Geometry> movieFrames_;
  Box movieBounds_;
  uint64_t movieBytes_ = 0;
  WarningCounter shortMovie_;  // a movie of one frame
  WarningCounter emptyObj_;  // frames with nothing to draw: no .obj
  WarningCounter emptyPly_;  // frames without a surface: no .ply
};

}  // namespace ontogen
