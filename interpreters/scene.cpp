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
}

}  // namespace ontogen
