#pragma once
// The parts every glTF binary ontogen writes shares: a binary buffer with the JSON that
// points into it (buffer views and accessors), and the GLB container around both.

#include <cstddef>
#include <cstdint>
#include <map>
#include <ostream>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

namespace ontogen::gltf {

inline constexpr int kFloat = 5126;
inline constexpr int kUnsignedByte = 5121;
inline constexpr int kUnsignedShort = 5123;
inline constexpr int kUnsignedInt = 5125;
inline constexpr int kArrayBuffer = 34962;
inline constexpr int kElementArrayBuffer = 34963;
inline constexpr int kTriangles = 4;
inline constexpr int kLines = 1;

class Builder {
 public:
  nlohmann::json gltf = nlohmann::json::object();
  std::vector<uint8_t> bin;

  /// A buffer view of bytes copied into the buffer (4-byte aligned); target 0: none.
  int addView(const void* data, std::size_t bytes, int target);
  /// An accessor of VEC3 floats; bounds: with min and max (POSITION needs them).
  int addVec3(const std::vector<glm::vec3>& values, int target, bool bounds);
  int addVec2(const std::vector<glm::vec2>& values);
  int addIndices(const std::vector<uint32_t>& values);
  /// An accessor of SCALAR floats with min and max (animation inputs need them).
  int addScalars(const std::vector<float>& values);
  /// An accessor of count elements of `type` ("VEC4", "MAT4") of floats, no bounds.
  int addFloats(const std::vector<float>& values, const char* type, std::size_t count, int target);
  int addAccessor(const nlohmann::json& accessor);
  /// The material of a palette colour (made at its first use): the colour in linear
  /// light, metallic 0, rough, double-sided, since discs and lines have one side.
  int materialOf(uint32_t palette);

 private:
  std::map<uint32_t, int> materials_;  // palette index -> glTF material
};

/// Writes the GLB container of builder's JSON and buffer. Stream errors are left in out.
void writeGlb(Builder& builder, std::ostream& out);

}  // namespace ontogen::gltf
