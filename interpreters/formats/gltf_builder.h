#pragma once
// The parts every glTF binary ontogen writes shares: a binary buffer with the JSON that
// points into it (buffer views and accessors), materials, the camera that frames a run,
// and the GLB container around both.

#include <cstddef>
#include <cstdint>
#include <map>
#include <ostream>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "interpreters/formats/mesh_batches.h"
#include "interpreters/geometry.h"

namespace ontogen::gltf {

inline constexpr int kFloat = 5126;
inline constexpr int kUnsignedByte = 5121;
inline constexpr int kUnsignedShort = 5123;
inline constexpr int kUnsignedInt = 5125;
inline constexpr int kArrayBuffer = 34962;
inline constexpr int kElementArrayBuffer = 34963;
inline constexpr int kTriangles = 4;
inline constexpr int kLines = 1;

/// Where an accessor's bytes go: a buffer view of their own, or a view shared with every
/// accessor of the same pool (its bytes written together at the end), which saves a view
/// per accessor where there are thousands (a joint's track, a cell's joint indices).
/// Vertex data in a pool has a byteStride (the element's size), as glTF requires of a view
/// that several vertex accessors share.
struct Pool {
  int id = -1;  ///< -1: a view of its own; else the pool's number, chosen by the caller
};

class Builder {
 public:
  nlohmann::json gltf = nlohmann::json::object();
  std::vector<uint8_t> bin;

  /// A buffer view of bytes copied into the buffer (4-byte aligned); target 0: none.
  int addView(const void* data, std::size_t bytes, int target);
  /// An accessor of VEC3 floats; bounds: with min and max (POSITION needs them).
  int addVec3(const std::vector<glm::vec3>& values, int target, bool bounds, Pool pool = {});
  int addVec2(const std::vector<glm::vec2>& values, Pool pool = {});
  int addIndices(const std::vector<uint32_t>& values);
  /// An accessor of SCALAR floats with min and max (animation inputs need them).
  int addScalars(const std::vector<float>& values);
  /// An accessor of count elements of `type` ("VEC4", "MAT4") of floats, no bounds.
  int addFloats(const std::vector<float>& values, const char* type, std::size_t count, int target, Pool pool = {});
  /// An accessor of count VEC4 of unsigned bytes or shorts (componentType), 4 per
  /// element in values; normalized for weights.
  int addVec4Integers(const std::vector<uint16_t>& values, int componentType, bool normalized, Pool pool = {});
  /// Writes the pools' bytes into the buffer (writeGlb does).
  void flushPools();
  int addAccessor(const nlohmann::json& accessor);
  /// Adds extension to extensionsUsed (once).
  void useExtension(const char* extension);
  /// The material of a palette colour (made at its first use): the colour in linear
  /// light, metallic 0, rough, double-sided, since discs and lines have one side.
  int materialOf(uint32_t palette);

 private:
  // The view and byte offset of data added to a pool (or to a view of its own).
  std::pair<int, std::size_t> place(const void* data, std::size_t bytes, int target, int stride, Pool pool);
  struct PoolData {
    int view = -1;
    std::vector<uint8_t> bytes;
  };
  std::map<uint32_t, int> materials_;  // palette index -> glTF material
  std::map<int, PoolData> pools_;
};

/// The accessors of a batch's vertices: POSITION (with bounds), NORMAL, TEXCOORD_0, added
/// in that order.
nlohmann::json vertexAttributes(Builder& builder, const MeshBatch& batch);

/// A primitive of a batch's triangles in palette colour `material`: its vertexAttributes,
/// `cells` (one (cell number, birth) per vertex) as TEXCOORD_1 when given, then its
/// indices, added in that order.
nlohmann::json trianglePrimitive(Builder& builder, const MeshBatch& batch, uint32_t material,
                                 const std::vector<glm::vec2>* cells = nullptr);

/// A 32-bit float as the double of its shortest decimal form, so that the JSON shows
/// "0.70710677", not the float's exact value "0.7071067690849304" (which reads back to
/// the same float): a third shorter where there are thousands of nodes.
double shortFloat(float value);

/// The vertical field of view of the camera written with a run, radians (40 degrees,
/// a normal lens).
inline constexpr double kCameraFov = 0.6981317007977318;
/// Adds a perspective camera that frames `bounds` whole (the box a run's frames fill,
/// model units) from the pictures' default view (formats/renderer.h: the front of a
/// model flat in x-y, else azimuth 30, elevation 20 degrees); its node is appended to
/// sceneNodes. Nothing for an empty box.
/// No light is written: no one intensity suits every viewer (Blender reads glTF's lux
/// divided by 683, three.js and model-viewer as they are, so a light right for one is
/// black or white in the other), and each brings its own lights.
void addCamera(Builder& builder, const Box& bounds, nlohmann::json& sceneNodes);

/// Writes the GLB container of builder's JSON and buffer. Stream errors are left in out.
void writeGlb(Builder& builder, std::ostream& out);

}  // namespace ontogen::gltf
