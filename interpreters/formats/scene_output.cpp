#include "interpreters/formats/scene_output.h"

#include "interpreters/temporary_files.h"

#include <cstdio>
#include <cstdlib>
#include <string>
#include <system_error>

#include "interpreters/formats/glb_writer.h"
#include "interpreters/formats/joints_writer.h"
#include "interpreters/formats/movie_writer.h"
#include "interpreters/formats/obj_writer.h"
#include "interpreters/formats/ply_writer.h"
#include "interpreters/formats/png_writer.h"
#include "interpreters/formats/skinned_glb_writer.h"
#include "interpreters/output_file.h"

namespace ontogen {

namespace {
// What a kept copy of a frame's geometry holds, near enough for the memory limit.
uint64_t geometryBytes(const Geometry& geometry) {
  const Mesh& mesh = geometry.mesh();
  return mesh.positions.size() * sizeof(glm::dvec3) + mesh.normals.size() * sizeof(glm::dvec3) +
         mesh.texcoords.size() * sizeof(glm::dvec2) + mesh.triangles.size() * sizeof(Triangle) +
         geometry.segments().size() * sizeof(Segment) +
         geometry.cylinders().size() * sizeof(CylinderPrimitive) + geometry.discs().size() * sizeof(DiscPrimitive) +
         geometry.spheres().size() * sizeof(SpherePrimitive);
}
}  // namespace

std::string applyGeometryFormats(std::string_view list, SceneOutputDef& def) {
  def.writeSvg = def.writeObj = def.writeMtl = def.writePly = false;
  def.writePng = def.writePngFrames = def.writeGlb = def.writeMp4 = def.writeJoints = def.writeMjcf = false;
  bool binaryPly = false, asciiPly = false;
  std::size_t start = 0;
  while (start <= list.size()) {
    std::size_t end = list.find(',', start);
    if (end == std::string_view::npos) end = list.size();
    std::string_view name = list.substr(start, end - start);
    if (name == "svg") {
      def.writeSvg = true;
    } else if (name == "obj") {
      def.writeObj = def.writeMtl = true;
    } else if (name == "ply") {
      def.writePly = binaryPly = true;
      def.plyBinary = true;
    } else if (name == "ply-ascii") {
      def.writePly = asciiPly = true;
      def.plyBinary = false;
    } else if (name == "png") {
      def.writePng = true;
    } else if (name == "png-frames") {
      def.writePngFrames = true;
    } else if (name == "glb") {
      def.writeGlb = true;
    } else if (name == "mp4") {
      def.writeMp4 = true;
    } else if (name == "joints") {
      def.writeJoints = true;
    } else if (name == "mjcf") {
      def.writeMjcf = true;
    } else if (name == "none") {
      return "the format 'none' (grow only, write nothing) goes alone, not with other formats";
    } else {
      return "unknown format '" + std::string(name) + "' (known: " + kGeometryFormats + ", or none alone)";
    }
    start = end + 1;
  }
  if (binaryPly && asciiPly) return "the formats 'ply' and 'ply-ascii' write the same file (<model>.ply); choose one";
  return "";
}

struct SceneOutput::Writers {
  GlbAnimationWriter glb;
  SkinnedGlbWriter skinnedGlb;  // the run's frames when they hold a skeleton
  JointTrackWriter joints;
};

SceneOutput::SceneOutput(const SceneOutputDef& def) : def_(def), writers_(std::make_unique<Writers>()) {
  checkSvgOptions(def.svg);
  if (def.writePng || def.writePngFrames || def.writeMp4) checkRenderDef(def.render);
  if (def.writeMp4 && !ffmpegAvailable()) {
    throw std::invalid_argument("the mp4 format needs ffmpeg, which is not installed (Debian: apt-get install ffmpeg)");
  }
  if (!(def.framesPerSecond > 0)) throw std::invalid_argument("framesPerSecond must be > 0");
}

SceneOutput::~SceneOutput() = default;
SceneOutput::SceneOutput(SceneOutput&&) noexcept = default;
SceneOutput& SceneOutput::operator=(SceneOutput&&) noexcept = default;

uint64_t SceneOutput::heldBytes() const { return writers_->glb.heldBytes() + movieBytes_; }

std::size_t SceneOutput::glbFrames() const { return writers_->glb.frameCount(); }

std::filesystem::path outputPath(const FrameTarget& target, std::string_view extension) {
  std::string name = target.stem.empty() ? std::string("geometry") : target.stem;
  if (target.frameCount > 1) {
    std::string number = std::to_string(target.frame);
    if (number.size() < 4) number.insert(0, 4 - number.size(), '0');
    name += "_" + number;
  }
  name += ".";
  name += extension;
  return target.directory / name;
}

void SceneOutput::renderMovieFrames(const FrameTarget& target, std::vector<std::filesystem::path>& written) {
  FrameTarget whole = target;
  whole.frameCount = 1;
  RenderDef render = def_.render;
  render.framing = movieBounds_;
  MovieWriter movie(outputPath(whole, "mp4"), def_.framesPerSecond);
  for (const Geometry& frame : movieFrames_) movie.addFrame(renderGeometry(frame, render));
  movieFrames_.clear();
  movieBounds_ = Box{};
  movieBytes_ = 0;
  movie.finish();
  written.push_back(outputPath(whole, "mp4"));
}

std::vector<SetWarning> SceneOutput::takeWarnings() {
  std::vector<SetWarning> out;
  auto frames = [](const WarningCounter& counter) {
    char first[32];
    std::snprintf(first, sizeof first, "%g", counter.first.time);
    return std::to_string(counter.count) + (counter.count == 1 ? " frame" : " frames") + " (the first at t = " + first +
           ")";
  };
  emptyObj_.takeInto(out, frames(emptyObj_) + " had nothing to draw: " + (emptyObj_.count == 1 ? "its" : "their") +
                              " .obj holds one point at the origin, as readers refuse one without a mesh");
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, "%g", 1.0 / def_.framesPerSecond);
  shortMovie_.takeInto(out, std::string("the movie has one frame, ") + seconds +
                                " s long: give the run --frames N or --speed S (or the program #speed), and a "
                                "span to grow over (--from before --until), for an animation");
  emptyPly_.takeInto(out, frames(emptyPly_) + " had no surface: no .ply was written for " +
                              (emptyPly_.count == 1 ? "it" : "them") + ", as readers refuse one without a face");
  return out;
}

uint64_t SceneOutput::pictureBytes(const FrameTarget& target) const {
  const bool last = target.frame + 1 >= target.frameCount;
  const bool picture = def_.writePngFrames || (def_.writePng && last) || def_.writeMp4;
  return picture ? renderBytes(def_.render) : 0;
}

std::vector<std::filesystem::path> SceneOutput::write(const Scene& scene, const FrameTarget& target_) {
  const Geometry& geometry_ = scene.geometry;
  std::vector<std::filesystem::path> written;
  const bool last = target_.frame + 1 >= target_.frameCount;
  FrameTarget whole = target_;
  whole.frameCount = 1;
  if (def_.writeSvg) {
    std::filesystem::path path = outputPath(target_, "svg");
    writeFileAtomically(path, [&](std::ostream& out) { writeSvg(geometry_, out, def_.svg); });
    written.push_back(std::move(path));
  }
  // Readers (assimp) refuse an .obj without a mesh, or a .ply without a face: the .obj of
  // a frame with nothing to draw holds a point (obj_writer.h), a frame without a surface
  // gets no .ply; both are warned of.
  if (def_.writeObj && geometry_.empty()) emptyObj_.add(1, InstructionSite{SourceSpan{}, "", target_.time});
  if (def_.writePly && geometry_.triangleCount() == 0)
    emptyPly_.add(1, InstructionSite{SourceSpan{}, "", target_.time});
  if (def_.writeObj) {
    std::filesystem::path path = outputPath(target_, "obj");
    std::filesystem::path mtl = outputPath(target_, "mtl");
    if (def_.writeMtl) {
      writeFileAtomically(path, [&](std::ostream& out) { writeObj(geometry_, out, mtl.filename().string(), def_.up); });
    } else {
      writeFileAtomically(path, [&](std::ostream& out) { writeObj(geometry_, out, def_.up); });
    }
    written.push_back(std::move(path));
    if (def_.writeMtl) {
      writeFileAtomically(mtl, [&](std::ostream& out) { writeMtl(geometry_, out); });
      written.push_back(std::move(mtl));
    }
  }
  if (def_.writePly && geometry_.triangleCount() > 0) {
    std::filesystem::path path = outputPath(target_, "ply");
    writeFileAtomically(path, [&](std::ostream& out) {
      writePly(geometry_, out, PlyOptions{.binary = def_.plyBinary, .up = def_.up});
    });
    written.push_back(std::move(path));
  }
  if (def_.writeMp4) {
    movieFrames_.push_back(geometry_);
    movieBytes_ += geometryBytes(geometry_);
    if (!geometry_.empty()) {
      movieBounds_.add(geometry_.bounds().min);
      movieBounds_.add(geometry_.bounds().max);
    }
  }
  const bool picture = def_.writePngFrames || (def_.writePng && last);
  if (picture) {
    const Image image = renderGeometry(geometry_, def_.render);
    if (def_.writePngFrames || (def_.writePng && last)) {
      std::filesystem::path path = outputPath(def_.writePngFrames ? target_ : whole, "png");
      writeFileAtomically(path, [&](std::ostream& out) { writePng(image, out); });
      written.push_back(std::move(path));
    }
  }
  // A run whose frames hold a skeleton is written as one skin, from the first frame that
  // holds one (it fixes the skeleton; the frames before it, where the body had not grown
  // yet, are left out); any other as persistent parts (glb_writer.h).
  const bool skinned = writers_->skinnedGlb.frameCount() > 0 || !scene.skeleton.empty();
  // A run of one frame is written from its scene at once, not kept (glb_writer.h).
  const bool still = !skinned && target_.frameCount <= 1 && writers_->glb.frameCount() == 0;
  if (def_.writeGlb && !still) {
    if (skinned)
      writers_->skinnedGlb.addFrame(scene);
    else
      writers_->glb.addFrame(scene);
  }
  if (def_.writeJoints) writers_->joints.addFrame(scene);
  if (last) {
    if (def_.writeGlb) {
      std::filesystem::path path = outputPath(whole, "glb");
      writeFileAtomically(path, [&](std::ostream& out) {
        if (skinned)
          writers_->skinnedGlb.write(out);
        else if (still)
          GlbAnimationWriter::writeFrame(scene, out);
        else
          writers_->glb.write(out);
      });
      writers_->glb.clear();
      writers_->skinnedGlb.clear();
      written.push_back(std::move(path));
    }
    if (def_.writeJoints) {
      std::filesystem::path path = outputPath(whole, "joints.json");
      writeFileAtomically(path, [&](std::ostream& out) { writers_->joints.write(out); });
      writers_->joints.clear();
      written.push_back(std::move(path));
    }
    if (def_.writeMp4) {
      if (movieFrames_.size() == 1) shortMovie_.add(1, InstructionSite{SourceSpan{}, "", target_.time});
      renderMovieFrames(target_, written);
    }
  }
  return written;
}

}  // namespace ontogen
