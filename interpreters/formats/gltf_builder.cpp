#include "interpreters/formats/gltf_builder.h"

#include <glm/common.hpp>

#include "interpreters/palette.h"

namespace ontogen::gltf {

namespace {
constexpr uint32_t kGlbMagic = 0x46546C67;  // "glTF"
constexpr uint32_t kJsonChunk = 0x4E4F534A;  // "JSON"
constexpr uint32_t kBinChunk = 0x004E4942;   // "BIN\0"

void writeU32(std::ostream& out, uint32_t value) {
  unsigned char bytes[4] = {static_cast<unsigned char>(value), static_cast<unsigned char>(value >> 8),
                            static_cast<unsigned char>(value >> 16), static_cast<unsigned char>(value >> 24)};
  out.write(reinterpret_cast<const char*>(bytes), 4);
}
}  // namespace

int Builder::addView(const void* data, std::size_t bytes, int target) {
  while (bin.size() % 4 != 0) bin.push_back(0);
  nlohmann::json view = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}};
  if (target != 0) view["target"] = target;
  const auto* begin = static_cast<const uint8_t*>(data);
  bin.insert(bin.end(), begin, begin + bytes);
  gltf["bufferViews"].push_back(view);
  return static_cast<int>(gltf["bufferViews"].size() - 1);
}

int Builder::addVec3(const std::vector<glm::vec3>& values, int target, bool bounds) {
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

int Builder::addVec2(const std::vector<glm::vec2>& values) {
  int view = addView(values.data(), values.size() * sizeof(glm::vec2), kArrayBuffer);
  return addAccessor({{"bufferView", view}, {"componentType", kFloat}, {"count", values.size()}, {"type", "VEC2"}});
}

int Builder::addIndices(const std::vector<uint32_t>& values) {
  int view = addView(values.data(), values.size() * sizeof(uint32_t), kElementArrayBuffer);
  return addAccessor({{"bufferView", view}, {"componentType", kUnsignedInt}, {"count", values.size()}, {"type", "SCALAR"}});
}

int Builder::addScalars(const std::vector<float>& values) {
  int view = addView(values.data(), values.size() * sizeof(float), 0);
  float lo = values.front(), hi = values.front();
  for (float v : values) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  return addAccessor({{"bufferView", view},
                      {"componentType", kFloat},
                      {"count", values.size()},
                      {"type", "SCALAR"},
                      {"min", {lo}},
                      {"max", {hi}}});
}

int Builder::addFloats(const std::vector<float>& values, const char* type, std::size_t count, int target) {
  int view = addView(values.data(), values.size() * sizeof(float), target);
  return addAccessor({{"bufferView", view}, {"componentType", kFloat}, {"count", count}, {"type", type}});
}

int Builder::addAccessor(const nlohmann::json& accessor) {
  gltf["accessors"].push_back(accessor);
  return static_cast<int>(gltf["accessors"].size() - 1);
}

int Builder::materialOf(uint32_t palette) {
  auto [it, inserted] = materials_.try_emplace(palette, static_cast<int>(materials_.size()));
  if (inserted) {
    // glTF's colour factors are linear light; the palette holds display (sRGB) values,
    // which written as they are look pale in every viewer.
    const Color c = linearColor(paletteColor(palette));
    gltf["materials"].push_back({{"name", materialName(palette)},
                                 {"doubleSided", true},
                                 {"pbrMetallicRoughness",
                                  {{"baseColorFactor", {c.r, c.g, c.b, 1.0}},
                                   {"metallicFactor", 0.0},
                                   {"roughnessFactor", 0.8}}}});
  }
  return it->second;
}

void writeGlb(Builder& b, std::ostream& out) {
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

}  // namespace ontogen::gltf
