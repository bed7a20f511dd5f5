#include "interpreters/formats/glb_writer.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>

#include <glm/common.hpp>
#include <nlohmann/json.hpp>

#include "interpreters/palette.h"

namespace ontogen {

namespace {

constexpr uint32_t kGlbMagic = 0x46546C67;  // "glTF"
constexpr uint32_t kJsonChunk = 0x4E4F534A;  // "JSON"
constexpr uint32_t kBinChunk = 0x004E4942;   // "BIN\0"
constexpr int kFloat = 5126;
constexpr int kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;
constexpr int kTriangles = 4;
constexpr int kLines = 1;
constexpr double kFallbackFramesPerSecond = 25;

/// The binary buffer and the JSON that points into it.
class Builder {
 public:
  nlohmann::json gltf = nlohmann::json::object();
  std::vector<uint8_t> bin;

  int addView(const void* data, std::size_t bytes, int target) {
    while (bin.size() % 4 != 0) bin.push_back(0);
    nlohmann::json view = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}};
    if (target != 0) view["target"] = target;
    const auto* begin = static_cast<const uint8_t*>(data);
    bin.insert(bin.end(), begin, begin + bytes);
    gltf["bufferViews"].push_back(view);
    return static_cast<int>(gltf["bufferViews"].size() - 1);
  }

  int addVec3(const std::vector<glm::vec3>& values, int target, bool bounds) {
    int view = addView(values.data(), values.size() * sizeof(glm::vec3), target);
    nlohmann::json accessor = {{"bufferView", view}, {"componentType", kFloat}, {"count", values.size()}, {"type", "VEC3"}};
    if (bounds) {
      glm::vec3 lo = values.front(), hi = values.front();
      for (const glm::vec3& v : values) {
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
      }
      accessor["min"] = {lo.x, lo.y, lo.z};
      accessor["max"] = {hi.x, hi.y, hi.z};
    }
    return addAccessor(accessor);
  }

  int addVec2(const std::vector<glm::vec2>& values) {
    int view = addView(values.data(), values.size() * sizeof(glm::vec2), kArrayBuffer);
    return addAccessor({{"bufferView", view}, {"componentType", kFloat}, {"count", values.size()}, {"type", "VEC2"}});
  }

  int addIndices(const std::vector<uint32_t>& values) {
    int view = addView(values.data(), values.size() * sizeof(uint32_t), kElementArrayBuffer);
    return addAccessor({{"bufferView", view}, {"componentType", kUnsignedInt}, {"count", values.size()}, {"type", "SCALAR"}});
  }

  int addAccessor(const nlohmann::json& accessor) {
    gltf["accessors"].push_back(accessor);
    return static_cast<int>(gltf["accessors"].size() - 1);
  }
};

void writeU32(std::ostream& out, uint32_t value) {
  unsigned char bytes[4] = {static_cast<unsigned char>(value), static_cast<unsigned char>(value >> 8),
                            static_cast<unsigned char>(value >> 16), static_cast<unsigned char>(value >> 24)};
  out.write(reinterpret_cast<const char*>(bytes), 4);
}

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
  std::map<uint32_t, int> materials;  // palette index -> glTF material
  auto materialOf = [&](uint32_t palette) {
    auto [it, inserted] = materials.try_emplace(palette, static_cast<int>(materials.size()));
    if (inserted) {
      Color c = paletteColor(palette);
      b.gltf["materials"].push_back({{"name", materialName(palette)},
                                     {"doubleSided", true},
                                     {"pbrMetallicRoughness",
                                      {{"baseColorFactor", {c.r, c.g, c.b, 1.0}},
                                       {"metallicFactor", 0.0},
                                       {"roughnessFactor", 0.8}}}});
    }
    return it->second;
  };
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
    int timeView = b.addView(times.data(), times.size() * sizeof(float), 0);
    int input = b.addAccessor({{"bufferView", timeView},
                               {"componentType", kFloat},
                               {"count", count},
                               {"type", "SCALAR"},
                               {"min", {times.front()}},
                               {"max", {times.back()}}});
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
  while (b.bin.size() % 4 != 0) b.bin.push_back(0);
  if (!b.bin.empty()) b.gltf["buffers"] = {{{"byteLength", b.bin.size()}}};

  std::string json = b.gltf.dump();
  while (json.size() % 4 != 0) json.push_back(' ');
  const std::size_t total = 12 + 8 + json.size() + (b.bin.empty() ? 0 : 8 + b.bin.size());
  writeU32(out, kGlbMagic);
  writeU32(out, 2);
  writeU32(out, static_cast<uint32_t>(total));
  writeU32(out, static_cast<uint32_t>(json.size()));
  writeU32(out, kJsonChunk);
  out.write(json.data(), static_cast<std::streamsize>(json.size()));
  if (!b.bin.empty()) {
    writeU32(out, static_cast<uint32_t>(b.bin.size()));
    writeU32(out, kBinChunk);
    out.write(reinterpret_cast<const char*>(b.bin.data()), static_cast<std::streamsize>(b.bin.size()));
  }
}

}  // namespace ontogen
