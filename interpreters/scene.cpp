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
  for (SceneNode node : other.nodes) {
    node.range.firstTriangle += triangles;
    node.range.firstSegment += segments;
    nodes.push_back(node);
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
