#include "interpreters/formats/gltf_builder.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <string>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

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

std::pair<int, std::size_t> Builder::place(const void* data, std::size_t bytes, int target, int stride, Pool pool) {
  if (pool.id < 0) return {addView(data, bytes, target), 0};
  PoolData& into = pools_[pool.id];
  if (into.view < 0) {
    nlohmann::json view = {{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 0}};
    if (target != 0) view["target"] = target;
    if (target == kArrayBuffer && stride > 0) view["byteStride"] = stride;
    gltf["bufferViews"].push_back(view);
    into.view = static_cast<int>(gltf["bufferViews"].size() - 1);
  }
  while (into.bytes.size() % 4 != 0) into.bytes.push_back(0);
  const std::size_t offset = into.bytes.size();
  const auto* begin = static_cast<const uint8_t*>(data);
  into.bytes.insert(into.bytes.end(), begin, begin + bytes);
  return {into.view, offset};
}

void Builder::flushPools() {
  for (auto& [id, pool] : pools_) {
    while (bin.size() % 4 != 0) bin.push_back(0);
    nlohmann::json& view = gltf["bufferViews"][pool.view];
    view["byteOffset"] = bin.size();
    view["byteLength"] = pool.bytes.size();
    bin.insert(bin.end(), pool.bytes.begin(), pool.bytes.end());
  }
  pools_.clear();
}

namespace {
nlohmann::json accessorAt(std::pair<int, std::size_t> place, int componentType, std::size_t count, const char* type) {
  nlohmann::json accessor = {{"bufferView", place.first}, {"componentType", componentType}, {"count", count}, {"type", type}};
  if (place.second != 0) accessor["byteOffset"] = place.second;
  return accessor;
}
}  // namespace

int Builder::addVec3(const std::vector<glm::vec3>& values, int target, bool bounds, Pool pool) {
  nlohmann::json accessor = accessorAt(place(values.data(), values.size() * sizeof(glm::vec3), target, 12, pool), kFloat,
                                       values.size(), "VEC3");
  if (bounds) {
    glm::vec3 lo = values.front(), hi = values.front();
    for (const glm::vec3& v : values) {
      lo = glm::min(lo, v);
      hi = glm::max(hi, v);
    }
    accessor["min"] = {shortFloat(lo.x), shortFloat(lo.y), shortFloat(lo.z)};
    accessor["max"] = {shortFloat(hi.x), shortFloat(hi.y), shortFloat(hi.z)};
  }
  return addAccessor(accessor);
}

int Builder::addVec2(const std::vector<glm::vec2>& values, Pool pool) {
  return addAccessor(accessorAt(place(values.data(), values.size() * sizeof(glm::vec2), kArrayBuffer, 8, pool), kFloat,
                                values.size(), "VEC2"));
}

int Builder::addIndices(const std::vector<uint32_t>& values) {
  int view = addView(values.data(), values.size() * sizeof(uint32_t), kElementArrayBuffer);
  return addAccessor({{"bufferView", view}, {"componentType", kUnsignedInt}, {"count", values.size()}, {"type", "SCALAR"}});
}

nlohmann::json vertexAttributes(Builder& b, const MeshBatch& batch) {
  return {{"POSITION", b.addVec3(batch.positions, kArrayBuffer, true)},
          {"NORMAL", b.addVec3(batch.normals, kArrayBuffer, false)},
          {"TEXCOORD_0", b.addVec2(batch.texcoords)}};
}

nlohmann::json trianglePrimitive(Builder& b, const MeshBatch& batch, uint32_t material,
                                 const std::vector<glm::vec2>* cells) {
  nlohmann::json attributes = vertexAttributes(b, batch);
  if (cells != nullptr) attributes["TEXCOORD_1"] = b.addVec2(*cells);
  const int indices = b.addIndices(batch.indices);
  return {{"attributes", attributes}, {"indices", indices}, {"material", b.materialOf(material)}, {"mode", kTriangles}};
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

int Builder::addFloats(const std::vector<float>& values, const char* type, std::size_t count, int target, Pool pool) {
  return addAccessor(accessorAt(place(values.data(), values.size() * sizeof(float), target, 0, pool), kFloat, count, type));
}

int Builder::addVec4Integers(const std::vector<uint16_t>& values, int componentType, bool normalized, Pool pool) {
  std::pair<int, std::size_t> at;
  if (componentType == kUnsignedByte) {
    std::vector<uint8_t> bytes(values.begin(), values.end());
    at = place(bytes.data(), bytes.size(), kArrayBuffer, 4, pool);
  } else {
    at = place(values.data(), values.size() * sizeof(uint16_t), kArrayBuffer, 8, pool);
  }
  nlohmann::json accessor = accessorAt(at, componentType, values.size() / 4, "VEC4");
  if (normalized) accessor["normalized"] = true;
  return addAccessor(accessor);
}

void Builder::useExtension(const char* extension) {
  nlohmann::json& used = gltf["extensionsUsed"];
  if (std::find(used.begin(), used.end(), extension) == used.end()) used.push_back(extension);
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

namespace {
// The pictures' default view (formats/renderer.cpp): a model flat in x-y is seen from
// the front, any other from azimuth 30, elevation 20 degrees.
constexpr double kDefaultAzimuth = 30;
constexpr double kDefaultElevation = 20;
constexpr double kFlatRatio = 1e-9;
// Room left around the model, as a fraction of the distance that fits it exactly.
constexpr double kCameraMargin = 0.05;

nlohmann::json rotationOf(const glm::dvec3& x, const glm::dvec3& y, const glm::dvec3& z) {
  glm::dquat q = glm::normalize(glm::quat_cast(glm::dmat3(x, y, z)));
  for (int k = 0; k < 4; ++k) q[k] = std::clamp(q[k], -1.0, 1.0);
  return {q.x, q.y, q.z, q.w};
}
}  // namespace

double shortFloat(float value) {
  if (!std::isfinite(value)) return value;
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text - 1, value).ptr;
  *end = '\0';
  return std::strtod(text, nullptr);
}

void addCamera(Builder& b, const Box& bounds, nlohmann::json& sceneNodes) {
  if (bounds.empty) return;
  const glm::dvec3 size = bounds.max - bounds.min;
  const glm::dvec3 centre = (bounds.min + bounds.max) * 0.5;
  const double extent = std::max({size.x, size.y, size.z});
  const bool flat = size.z <= kFlatRatio * std::max(extent, 1e-300);
  const double azimuth = (flat ? 0.0 : kDefaultAzimuth) * std::numbers::pi / 180;
  const double elevation = (flat ? 0.0 : kDefaultElevation) * std::numbers::pi / 180;
  const glm::dvec3 towardsEye{std::sin(azimuth) * std::cos(elevation), std::sin(elevation),
                              std::cos(azimuth) * std::cos(elevation)};
  const glm::dvec3 right = glm::normalize(glm::cross(glm::dvec3(0, 1, 0), towardsEye));
  const glm::dvec3 up = glm::cross(towardsEye, right);
  // The sphere around the box fits the vertical field of view (and any wider one).
  double radius = 0.5 * glm::length(size);
  if (!(radius > 0)) radius = 1;
  const double distance = radius / std::sin(kCameraFov / 2) * (1 + kCameraMargin);
  const glm::dvec3 eye = centre + towardsEye * distance;
  b.gltf["cameras"].push_back({{"name", "ontogen camera"},
                               {"type", "perspective"},
                               {"perspective",
                                {{"yfov", kCameraFov},
                                 {"znear", std::max(distance - 2 * radius, distance * 1e-3)},
                                 {"zfar", distance + 2 * radius}}}});
  // A camera looks down its -z axis.
  b.gltf["nodes"].push_back({{"name", "ontogen camera"},
                             {"camera", b.gltf["cameras"].size() - 1},
                             {"translation", {eye.x, eye.y, eye.z}},
                             {"rotation", rotationOf(right, up, towardsEye)}});
  sceneNodes.push_back(b.gltf["nodes"].size() - 1);
}

void writeGlb(Builder& b, std::ostream& out) {
  b.flushPools();
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
