#include "interpreters/scene.h"

namespace ontogen {

const SceneNode* Scene::find(uint64_t id) const {
  for (const SceneNode& node : nodes)
    if (node.id == id) return &node;
  return nullptr;
}

void Scene::clear() {
  time = 0;
  geometry.clear();
  nodes.clear();
  skeleton.joints.clear();
  skeleton.skin.clear();
  skeleton.simulated = false;
  skeleton.contacts.clear();
}

void Scene::append(const Scene& other) {
  const auto triangles = static_cast<uint32_t>(geometry.triangleCount());
  const auto segments = static_cast<uint32_t>(geometry.segmentCount());
  geometry.append(other.geometry);
  // Reserved: a plant's million nodes are copied once, not regrown.
  nodes.reserve(nodes.size() + other.nodes.size());
  for (const SceneNode& node : other.nodes) {
    nodes.push_back(node);
    nodes.back().range.firstTriangle += triangles;
    nodes.back().range.firstSegment += segments;
  }
  const int joints = static_cast<int>(skeleton.joints.size());
  for (SceneJoint joint : other.skeleton.joints) {
    if (joint.parent >= 0) joint.parent += joints;
    skeleton.joints.push_back(std::move(joint));
  }
  for (SkinRange range : other.skeleton.skin) {
    range.firstTriangle += triangles;
    range.joint += joints;
    skeleton.skin.push_back(range);
  }
  skeleton.simulated = skeleton.simulated || other.skeleton.simulated;
  for (int contact : other.skeleton.contacts) skeleton.contacts.push_back(contact + joints);
}

}  // namespace ontogen
