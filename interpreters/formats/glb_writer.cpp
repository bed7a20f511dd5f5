#include "interpreters/formats/glb_writer.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>

#include <glm/common.hpp>
#include <nlohmann/json.hpp>

#include "interpreters/formats/gltf_builder.h"
#include "interpreters/palette.h"

namespace ontogen {

namespace {
using gltf::Builder;
using gltf::kArrayBuffer;
using gltf::kLines;
using gltf::kTriangles;
constexpr double kFallbackFramesPerSecond = 25;
}  // namespace

void GlbAnimationWriter::addFrame(const Geometry& geometry, double time) {
  frames_.push_back({batchByMaterial(geometry), time});
  for (const MeshBatch& batch : frames_.back().batches)
    heldBytes_ += batch.positions.size() * sizeof(glm::vec3) + batch.normals.size() * sizeof(glm::vec3) +
                  batch.texcoords.size() * sizeof(glm::vec2) + batch.indices.size() * sizeof(uint32_t) +
                  batch.lines.size() * sizeof(glm::vec3);
}

void GlbAnimationWriter::write(std::ostream& out) const {
  Builder b;
  b.gltf["asset"] = {{"version", "2.0"}, {"generator", "ontogen"}};
  auto materialOf = [&](uint32_t palette) { return b.materialOf(palette); };
  nlohmann::json sceneNodes = nlohmann::json::array();
  const std::size_t count = frames_.size();
  for (std::size_t f = 0; f < count; ++f) {
    nlohmann::json primitives = nlohmann::json::array();
    for (const MeshBatch& batch : frames_[f].batches) {
      if (!batch.indices.empty()) {
        nlohmann::json attributes = {{"POSITION", b.addVec3(batch.positions, kArrayBuffer, true)},
                                     {"NORMAL", b.addVec3(batch.normals, kArrayBuffer, false)},
                                     {"TEXCOORD_0", b.addVec2(batch.texcoords)}};
        primitives.push_back({{"attributes", attributes},
                              {"indices", b.addIndices(batch.indices)},
                              {"material", materialOf(batch.material)},
                              {"mode", kTriangles}});
      }
      if (!batch.lines.empty()) {
        primitives.push_back({{"attributes", {{"POSITION", b.addVec3(batch.lines, kArrayBuffer, true)}}},
                              {"material", materialOf(batch.material)},
                              {"mode", kLines}});
      }
    }
    nlohmann::json node = {{"name", "frame " + std::to_string(f)}};
    if (!primitives.empty()) {
      b.gltf["meshes"].push_back({{"name", "frame " + std::to_string(f)}, {"primitives", primitives}});
      node["mesh"] = b.gltf["meshes"].size() - 1;
    }
    if (count > 1 && f + 1 != count) node["scale"] = {0.0, 0.0, 0.0};
    b.gltf["nodes"].push_back(node);
    sceneNodes.push_back(f);
  }
  if (count > 1) {
    std::vector<float> times(count);
    bool increasing = true;
    for (std::size_t f = 0; f < count; ++f) {
      times[f] = static_cast<float>(frames_[f].time);
      if (f > 0 && !(times[f] > times[f - 1])) increasing = false;
    }
    if (!increasing) {
      for (std::size_t f = 0; f < count; ++f) times[f] = static_cast<float>(f / kFallbackFramesPerSecond);
    }
    int input = b.addScalars(times);
    nlohmann::json samplers = nlohmann::json::array();
    nlohmann::json channels = nlohmann::json::array();
    std::vector<glm::vec3> scales(count);
    for (std::size_t f = 0; f < count; ++f) {
      for (std::size_t k = 0; k < count; ++k) scales[k] = glm::vec3(k == f ? 1.0f : 0.0f);
      int output = b.addVec3(scales, 0, false);
      samplers.push_back({{"input", input}, {"output", output}, {"interpolation", "STEP"}});
      channels.push_back({{"sampler", samplers.size() - 1}, {"target", {{"node", f}, {"path", "scale"}}}});
    }
    b.gltf["animations"].push_back({{"name", "development"}, {"samplers", samplers}, {"channels", channels}});
  }
  b.gltf["scenes"] = {{{"name", "ontogen"}, {"nodes", sceneNodes}}};
  b.gltf["scene"] = 0;
  gltf::writeGlb(b, out);
}

}  // namespace ontogen
