#include "interpreters/scene.h"

namespace ontogen {

namespace {

// Appends other's joints, skin (its triangles shifted by `triangles`) and contacts.
void appendSkeleton(Skeleton& into, const Skeleton& other, uint32_t triangles) {
  const int joints = static_cast<int>(into.joints.size());
  for (SceneJoint joint : other.joints) {
    if (joint.parent >= 0) joint.parent += joints;
    into.joints.push_back(std::move(joint));
  }
  for (SkinRange range : other.skin) {
    range.firstTriangle += triangles;
    range.joint += joints;
    into.skin.push_back(range);
  }
  into.simulated = into.simulated || other.simulated;
  for (int contact : other.contacts) into.contacts.push_back(contact + joints);
}

}  // namespace

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
  appendSkeleton(skeleton, other.skeleton, triangles);
}

void Scene::append(Scene&& other) {
  if (!nodes.empty() || !geometry.empty()) {
    append(static_cast<const Scene&>(other));
    return;
  }
  // Nothing here to shift the nodes' ranges past: they are taken as they are.
  geometry.append(std::move(other.geometry));
  nodes.swap(other.nodes);
  appendSkeleton(skeleton, other.skeleton, 0);
}

}  // namespace ontogen
