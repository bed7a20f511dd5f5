#include "interpreters/formats/skinned_glb_writer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <tuple>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include "interpreters/formats/gltf_builder.h"
#include "interpreters/formats/mesh_batches.h"

namespace ontogen {

namespace {

// A unit quaternion whose components stay inside [-1, 1] after rounding, as glTF requires.
glm::dquat unit(const glm::dquat& q) {
  glm::dquat n = glm::normalize(q);
  for (int k = 0; k < 4; ++k) n[k] = std::clamp(n[k], -1.0, 1.0);
  return n;
}

// How far a joint's offset from its parent may move before it gets a translation channel
// of its own: rounding in the posing, not a limb that stretches.
constexpr double kRigidTolerance = 1e-6;

// A joint's transform relative to its parent (or the world, for a root).
struct Local {
  glm::dvec3 translation{0.0};
  glm::dquat rotation{1, 0, 0, 0};
  bool present = true;
};

}  // namespace

void SkinnedGlbWriter::clear() {
  bind_.clear();
  frames_.clear();
}

void SkinnedGlbWriter::addFrame(const Scene& scene) {
  Frame frame;
  frame.time = scene.time;
  for (const SceneJoint& joint : scene.skeleton.joints) frame.joints[joint.id] = {joint.position, joint.orientation};
  if (frames_.empty() || scene.skeleton.joints.size() > bind_.skeleton.joints.size()) bind_ = scene;
  frames_.push_back(std::move(frame));
}

uint64_t SkinnedGlbWriter::ignoredJoints() const {
  std::unordered_map<uint64_t, bool> known;
  for (const SceneJoint& joint : bind_.skeleton.joints) known[joint.id] = true;
  uint64_t ignored = 0;
  for (const Frame& frame : frames_)
    for (const auto& [id, pose] : frame.joints) ignored += known.count(id) == 0;
  return ignored;
}

void SkinnedGlbWriter::write(std::ostream& out) const {
  gltf::Builder b;
  b.gltf["asset"] = {{"version", "2.0"}, {"generator", "ontogen"}};
  const auto& joints = bind_.skeleton.joints;
  const std::size_t count = joints.size();
  nlohmann::json sceneNodes = nlohmann::json::array();

  // Every frame's local pose of every joint of the skeleton; a joint a frame lacks keeps
  // its pose in the skeleton's own frame, hidden.
  auto worldIn = [&](const Frame& frame, std::size_t j) {
    auto found = frame.joints.find(joints[j].id);
    return found != frame.joints.end() ? found->second : Pose{joints[j].position, joints[j].orientation};
  };
  std::vector<std::vector<Local>> poses(frames_.size(), std::vector<Local>(count));
  std::vector<bool> everHidden(count, false);
  for (std::size_t f = 0; f < frames_.size(); ++f) {
    for (std::size_t j = 0; j < count; ++j) {
      const Pose world = worldIn(frames_[f], j);
      Local& local = poses[f][j];
      local.present = frames_[f].joints.count(joints[j].id) > 0;
      everHidden[j] = everHidden[j] || !local.present;
      const int parent = joints[j].parent;
      if (parent < 0) {
        local.translation = world.position;
        local.rotation = unit(glm::quat_cast(world.rotation));
      } else {
        const Pose up = worldIn(frames_[f], static_cast<std::size_t>(parent));
        const glm::dmat3 inverse = glm::transpose(up.rotation);
        local.translation = inverse * (world.position - up.position);
        local.rotation = unit(glm::quat_cast(inverse * world.rotation));
      }
      // Each track in one hemisphere, so that linear interpolation takes the short way.
      if (f > 0 && glm::dot(local.rotation, poses[f - 1][j].rotation) < 0) local.rotation = -local.rotation;
    }
  }
  std::size_t bindFrame = 0;
  for (std::size_t f = 0; f < frames_.size(); ++f)
    if (frames_[f].time == bind_.time) bindFrame = f;

  // Joint nodes, posed as in the first frame.
  std::vector<nlohmann::json> children(count, nlohmann::json::array());
  for (std::size_t j = 0; j < count; ++j)
    if (joints[j].parent >= 0) children[joints[j].parent].push_back(j);
  for (std::size_t j = 0; j < count; ++j) {
    const Local local = poses.empty() ? Local{} : poses[bindFrame][j];
    nlohmann::json node = {{"name", joints[j].name},
                           {"translation", {local.translation.x, local.translation.y, local.translation.z}},
                           {"rotation", {local.rotation.x, local.rotation.y, local.rotation.z, local.rotation.w}},
                           {"extras", {{"id", std::to_string(joints[j].id)}}}};
    if (!children[j].empty()) node["children"] = children[j];
    b.gltf["nodes"].push_back(node);
    if (joints[j].parent < 0) sceneNodes.push_back(j);
  }

  // The skinned mesh: per colour, a vertex per (position, normal, texcoord, joint).
  const Mesh& mesh = bind_.geometry.mesh();
  std::vector<int> jointOf(mesh.triangles.size(), -1);
  for (const SkinRange& range : bind_.skeleton.skin)
    for (uint32_t t = range.firstTriangle; t < range.firstTriangle + range.triangleCount && t < jointOf.size(); ++t)
      jointOf[t] = range.joint;
  struct Batch {
    std::vector<glm::vec3> positions, normals;
    std::vector<glm::vec2> texcoords;
    std::vector<uint16_t> joints;
    std::vector<float> weights;
    std::vector<uint32_t> indices;
    std::map<std::tuple<uint32_t, uint32_t, uint32_t, int>, uint32_t> corners;
  };
  std::map<uint32_t, Batch> batches;
  Geometry unskinned(bind_.geometry.meshDef());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Triangle& triangle = mesh.triangles[t];
    if (jointOf[t] < 0) {
      // Outside the skin: kept as a mesh of its own.
      Mesh part;
      Triangle copy = triangle;
      for (int k = 0; k < 3; ++k) {
        part.positions.push_back(mesh.positions[triangle.position[k]]);
        part.normals.push_back(mesh.normals[triangle.normal[k]]);
        part.texcoords.push_back(triangle.texcoord[k] < mesh.texcoords.size() ? mesh.texcoords[triangle.texcoord[k]]
                                                                             : glm::dvec2(0.0));
        copy.position[k] = copy.normal[k] = copy.texcoord[k] = static_cast<uint32_t>(k);
      }
      part.triangles.push_back(copy);
      unskinned.addMesh(part, true);
      continue;
    }
    Batch& batch = batches[triangle.material];
    for (int k = 0; k < 3; ++k) {
      const auto key = std::make_tuple(triangle.position[k], triangle.normal[k], triangle.texcoord[k], jointOf[t]);
      auto [it, inserted] = batch.corners.try_emplace(key, static_cast<uint32_t>(batch.positions.size()));
      if (inserted) {
        batch.positions.emplace_back(mesh.positions[triangle.position[k]]);
        batch.normals.emplace_back(mesh.normals[triangle.normal[k]]);
        batch.texcoords.emplace_back(triangle.texcoord[k] < mesh.texcoords.size()
                                         ? glm::vec2(mesh.texcoords[triangle.texcoord[k]])
                                         : glm::vec2(0.0f));
        batch.joints.insert(batch.joints.end(), {static_cast<uint16_t>(jointOf[t]), 0, 0, 0});
        batch.weights.insert(batch.weights.end(), {1.0f, 0.0f, 0.0f, 0.0f});
      }
      batch.indices.push_back(it->second);
    }
  }
  for (const Segment& segment : bind_.geometry.segments()) unskinned.addSegment(segment.start, segment.end);

  if (!batches.empty() && count > 0) {
    nlohmann::json primitives = nlohmann::json::array();
    for (auto& [material, batch] : batches) {
      const int jointView = b.addView(batch.joints.data(), batch.joints.size() * sizeof(uint16_t), gltf::kArrayBuffer);
      const int jointAccessor = b.addAccessor({{"bufferView", jointView},
                                               {"componentType", gltf::kUnsignedShort},
                                               {"count", batch.positions.size()},
                                               {"type", "VEC4"}});
      nlohmann::json attributes = {{"POSITION", b.addVec3(batch.positions, gltf::kArrayBuffer, true)},
                                   {"NORMAL", b.addVec3(batch.normals, gltf::kArrayBuffer, false)},
                                   {"TEXCOORD_0", b.addVec2(batch.texcoords)},
                                   {"JOINTS_0", jointAccessor},
                                   {"WEIGHTS_0", b.addFloats(batch.weights, "VEC4", batch.positions.size(),
                                                             gltf::kArrayBuffer)}};
      primitives.push_back({{"attributes", attributes},
                            {"indices", b.addIndices(batch.indices)},
                            {"material", b.materialOf(material)},
                            {"mode", gltf::kTriangles}});
    }
    b.gltf["meshes"].push_back({{"name", "creature"}, {"primitives", primitives}});
    // Inverse bind matrices: the inverse of each joint's world pose in the first frame.
    std::vector<float> inverseBind;
    for (const SceneJoint& joint : joints) {
      glm::dmat4 world(joint.orientation);
      world[3] = glm::dvec4(joint.position, 1.0);
      const glm::dmat4 inverse = glm::inverse(world);
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) inverseBind.push_back(static_cast<float>(inverse[c][r]));
    }
    nlohmann::json jointList = nlohmann::json::array();
    for (std::size_t j = 0; j < count; ++j) jointList.push_back(j);
    nlohmann::json skin = {{"name", "skeleton"},
                           {"joints", jointList},
                           {"inverseBindMatrices", b.addFloats(inverseBind, "MAT4", count, 0)}};
    if (!sceneNodes.empty()) skin["skeleton"] = sceneNodes.front();
    b.gltf["skins"].push_back(skin);
    b.gltf["nodes"].push_back({{"name", "creature"}, {"mesh", b.gltf["meshes"].size() - 1}, {"skin", 0}});
    sceneNodes.push_back(b.gltf["nodes"].size() - 1);
  }

  if (!unskinned.empty()) {
    nlohmann::json primitives = nlohmann::json::array();
    for (const MeshBatch& batch : batchByMaterial(unskinned)) {
      if (!batch.indices.empty()) primitives.push_back(gltf::trianglePrimitive(b, batch, batch.material));
      if (!batch.lines.empty())
        primitives.push_back({{"attributes", {{"POSITION", b.addVec3(batch.lines, gltf::kArrayBuffer, true)}}},
                              {"material", b.materialOf(batch.material)},
                              {"mode", gltf::kLines}});
    }
    b.gltf["meshes"].push_back({{"name", "still"}, {"primitives", primitives}});
    b.gltf["nodes"].push_back({{"name", "still"}, {"mesh", b.gltf["meshes"].size() - 1}});
    sceneNodes.push_back(b.gltf["nodes"].size() - 1);
  }

  // The animation: every frame's local pose of every joint.
  const std::size_t frames = frames_.size();
  bool increasing = frames > 1;
  for (std::size_t f = 1; f < frames; ++f)
    if (!(frames_[f].time > frames_[f - 1].time)) increasing = false;
  if (increasing && count > 0) {
    std::vector<float> times(frames);
    for (std::size_t f = 0; f < frames; ++f) times[f] = static_cast<float>(frames_[f].time - frames_.front().time);
    const int input = b.addScalars(times);
    nlohmann::json samplers = nlohmann::json::array();
    nlohmann::json channels = nlohmann::json::array();
    auto channel = [&](int output, std::size_t node, const char* path, const char* interpolation = "LINEAR") {
      samplers.push_back({{"input", input}, {"output", output}, {"interpolation", interpolation}});
      channels.push_back({{"sampler", samplers.size() - 1}, {"target", {{"node", node}, {"path", path}}}});
    };
    for (std::size_t j = 0; j < count; ++j) {
      std::vector<float> rotations;
      bool moves = joints[j].parent < 0;
      for (std::size_t f = 0; f < frames; ++f) {
        const Local& local = poses[f][j];
        rotations.insert(rotations.end(), {static_cast<float>(local.rotation.x), static_cast<float>(local.rotation.y),
                                           static_cast<float>(local.rotation.z), static_cast<float>(local.rotation.w)});
        const glm::dvec3 offset = local.translation - poses[bindFrame][j].translation;
        if (std::abs(offset.x) + std::abs(offset.y) + std::abs(offset.z) > kRigidTolerance) moves = true;
      }
      channel(b.addFloats(rotations, "VEC4", frames, 0), j, "rotation");
      if (moves) {
        std::vector<glm::vec3> translations;
        for (std::size_t f = 0; f < frames; ++f) translations.emplace_back(poses[f][j].translation);
        channel(b.addVec3(translations, 0, false), j, "translation");
      }
      if (everHidden[j]) {
        std::vector<glm::vec3> scales;
        for (std::size_t f = 0; f < frames; ++f) scales.emplace_back(poses[f][j].present ? 1.0f : 0.0f);
        channel(b.addVec3(scales, 0, false), j, "scale", "STEP");
      }
    }
    b.gltf["animations"].push_back({{"name", "walk"}, {"samplers", samplers}, {"channels", channels}});
  }
  // The camera frames the body as bound, carried along by its root in every frame.
  Box framed;
  const Box& bound = bind_.geometry.bounds();
  if (!bound.empty && count > 0) {
    for (const Frame& frame : frames_) {
      const auto root = frame.joints.find(joints.front().id);
      const glm::dvec3 shift = root != frame.joints.end() ? root->second.position - joints.front().position : glm::dvec3(0.0);
      framed.add(bound.min + shift);
      framed.add(bound.max + shift);
    }
  }
  gltf::addCamera(b, framed, sceneNodes);
  b.gltf["scenes"] = {{{"name", "ontogen"}, {"nodes", sceneNodes}}};
  b.gltf["scene"] = 0;
  gltf::writeGlb(b, out);
}

}  // namespace ontogen
