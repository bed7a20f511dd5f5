#include "interpreters/formats/joints_writer.h"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "core/salts.h"

namespace ontogen {

void JointTrackWriter::clear() {
  joints_.clear();
  frames_.clear();
}

void JointTrackWriter::addFrame(const Scene& scene) {
  if (frames_.empty() || scene.skeleton.joints.size() > joints_.size()) joints_ = scene.skeleton.joints;
  Frame frame;
  frame.time = scene.time;
  for (const SceneJoint& joint : scene.skeleton.joints) frame.positions[joint.id] = joint.position;
  frame.simulated = scene.skeleton.simulated;
  for (int contact : scene.skeleton.contacts) frame.contacts.push_back(scene.skeleton.joints[contact].id);
  frames_.push_back(std::move(frame));
}

void JointTrackWriter::write(std::ostream& out) const {
  // Non-finite numbers have no JSON form; a pose never holds one, but a file never gets one.
  auto number = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  nlohmann::json doc;
  doc["up"] = {0, 1, 0};
  doc["ground"] = number(ground_);
  doc["joints"] = nlohmann::json::array();
  for (const SceneJoint& joint : joints_) {
    nlohmann::json entry = {{"id", static_cast<uint64_t>(idValue(joint.id))},
                            {"name", joint.name},
                            {"parent", joint.parent},
                            {"foot", joint.foot}};
    entry["side"] = joint.side == BodySide::Left    ? nlohmann::json("left")
                    : joint.side == BodySide::Right ? nlohmann::json("right")
                                                    : nlohmann::json(nullptr);
    entry["segment"] = joint.segment >= 0 ? nlohmann::json(joint.segment) : nlohmann::json(nullptr);
    doc["joints"].push_back(entry);
  }
  doc["frames"] = nlohmann::json::array();
  for (const Frame& frame : frames_) {
    nlohmann::json positions = nlohmann::json::array();
    for (const SceneJoint& joint : joints_) {
      auto found = frame.positions.find(joint.id);
      if (found == frame.positions.end()) {
        positions.push_back(nullptr);
        continue;
      }
      const glm::dvec3& p = found->second;
      positions.push_back({number(p.x), number(p.y), number(p.z)});
    }
    nlohmann::json entry = {{"t", number(frame.time)}, {"positions", positions}};
    if (frame.simulated) {
      // Indices in the listed joints, ascending.
      std::vector<int> contacts;
      for (uint64_t id : frame.contacts)
        for (std::size_t i = 0; i < joints_.size(); ++i)
          if (joints_[i].id == id) contacts.push_back(static_cast<int>(i));
      std::sort(contacts.begin(), contacts.end());
      entry["contacts"] = contacts;
    }
    doc["frames"].push_back(std::move(entry));
  }
  out << doc.dump() << "\n";
}

}  // namespace ontogen
