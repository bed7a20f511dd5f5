// Reading a .glb back in tests: its JSON and binary chunks, accessors as numbers,
// animation channels, and the lines a node draws as instances of the unit tube.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

namespace ontogen::test {

// A .glb split into its JSON and binary chunks, with accessors read as numbers.
struct Glb {
  nlohmann::json json;
  std::string bin;

  explicit Glb(const std::string& glb) {
    uint32_t length = 0;
    std::memcpy(&length, glb.data() + 12, 4);
    json = nlohmann::json::parse(glb.substr(20, length));
    if (glb.size() > 20 + length + 8) bin = glb.substr(20 + length + 8);
  }
  // Every component of an accessor, in order (normalized integers as they are stored).
  std::vector<double> values(int accessor) const {
    const auto& a = json["accessors"][accessor];
    const auto& view = json["bufferViews"][a["bufferView"].get<int>()];
    const std::size_t offset = view["byteOffset"].get<std::size_t>() + a.value("byteOffset", 0);
    const std::string type = a["type"];
    const std::size_t width = type == "SCALAR" ? 1 : type == "VEC2" ? 2 : type == "VEC3" ? 3 : type == "VEC4" ? 4 : 16;
    const std::size_t n = a["count"].get<std::size_t>() * width;
    std::vector<double> out(n);
    const int component = a["componentType"];
    for (std::size_t k = 0; k < n; ++k) {
      if (component == 5126) {
        float f = 0;
        std::memcpy(&f, bin.data() + offset + 4 * k, 4);
        out[k] = f;
      } else if (component == 5121) {
        out[k] = static_cast<uint8_t>(bin[offset + k]);
      } else if (component == 5123) {
        uint16_t u = 0;
        std::memcpy(&u, bin.data() + offset + 2 * k, 2);
        out[k] = u;
      } else {
        uint32_t u = 0;
        std::memcpy(&u, bin.data() + offset + 4 * k, 4);
        out[k] = u;
      }
    }
    return out;
  }
  // The node of a name, or -1.
  int node(const std::string& name) const {
    for (std::size_t n = 0; n < json["nodes"].size(); ++n)
      if (json["nodes"][n].value("name", "") == name) return static_cast<int>(n);
    return -1;
  }
  // The output values of the animation's channel for node and path (empty: none), and its
  // interpolation.
  std::vector<double> channel(int node, const std::string& path, std::string* interpolation = nullptr) const {
    if (!json.contains("animations")) return {};
    const auto& animation = json["animations"][0];
    for (const auto& c : animation["channels"]) {
      if (c["target"]["node"].get<int>() != node || c["target"]["path"] != path) continue;
      const auto& sampler = animation["samplers"][c["sampler"].get<int>()];
      if (interpolation) *interpolation = sampler["interpolation"];
      return values(sampler["output"].get<int>());
    }
    return {};
  }
  // The value of a node's channel (first component) at an animation time, as a viewer
  // samples it: held before the first key and after the last.
  double sample(int node, const std::string& path, double time) const {
    const auto& animation = json["animations"][0];
    for (const auto& c : animation["channels"]) {
      if (c["target"]["node"].get<int>() != node || c["target"]["path"] != path) continue;
      const auto& sampler = animation["samplers"][c["sampler"].get<int>()];
      const std::vector<double> in = values(sampler["input"].get<int>());
      const std::vector<double> out = values(sampler["output"].get<int>());
      const std::size_t width = out.size() / in.size();
      std::size_t k = 0;
      while (k + 1 < in.size() && in[k + 1] <= time) ++k;
      return out[k * width];  // the channels this samples are STEP
    }
    return std::nan("");
  }
  std::vector<double> keys() const {
    return values(json["animations"][0]["samplers"][0]["input"].get<int>());
  }
};

inline std::vector<std::string> nodeNames(const Glb& glb) {
  std::vector<std::string> names;
  for (const auto& node : glb.json["nodes"]) names.push_back(node.value("name", ""));
  return names;
}

// The lines a node draws as instances of the unit tube (EXT_mesh_gpu_instancing): each
// instance's ends (its translation, the middle, less and plus its rotated half length)
// and its radius (its scale across).
struct InstancedLine {
  glm::dvec3 from, to;
  double radius;
};
inline std::vector<InstancedLine> instancedLines(const Glb& glb, int node) {
  const auto& attributes = glb.json["nodes"][node]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"];
  const std::vector<double> t = glb.values(attributes["TRANSLATION"].get<int>());
  const std::vector<double> r = glb.values(attributes["ROTATION"].get<int>());
  const std::vector<double> sc = glb.values(attributes["SCALE"].get<int>());
  std::vector<InstancedLine> lines;
  for (std::size_t i = 0; 3 * i < t.size(); ++i) {
    const glm::dquat q(r[4 * i + 3], r[4 * i], r[4 * i + 1], r[4 * i + 2]);
    const glm::dvec3 middle(t[3 * i], t[3 * i + 1], t[3 * i + 2]);
    const glm::dvec3 half = q * glm::dvec3(0, sc[3 * i + 1], 0);
    lines.push_back({middle - half, middle + half, sc[3 * i]});
  }
  return lines;
}

}  // namespace ontogen::test
