// A frame of the dynamics set: the word's body drawn where the simulation has it, the
// joints touching the ground, the measures of the body's place, the first frame's MJCF.

#include "interpreters/dynamics/dynamics_set.h"

#include <algorithm>
#include <cstdio>
#include <limits>

#include "interpreters/dynamics/mujoco_model.h"

namespace ontogen {

namespace {

std::string numbers(const mjtNum* values, int count) {
  std::string out;
  char text[32];
  for (int i = 0; i < count; ++i) {
    std::snprintf(text, sizeof text, "%s%.17g", i > 0 ? " " : "", values[i]);
    out += text;
  }
  return out;
}

}  // namespace

void DynamicsSet::contribute(Scene& scene) {
  const double time = target_.time;
  advanceTo(time);
  const bool first = stats_.rebuilds > 0 && firstMjcf_.empty() && sim_;
  // Read by the reposer as the frame's word ends, below.
  const mjData* s = nullptr;
  std::vector<int> contacts;
  if (sim_) {
    stateAt(time);
    s = sim_->scratch();
    for (int c = 0; c < s->ncon; ++c) {
      const mjContact& contact = s->contact[c];
      if (contact.geom1 != groundGeom_ && contact.geom2 != groundGeom_) continue;
      const int body = sim_->model()->geom_bodyid[contact.geom1 == groundGeom_ ? contact.geom2 : contact.geom1];
      if (planOfBody_[static_cast<std::size_t>(body)] >= 0) contacts.push_back(planOfBody_[static_cast<std::size_t>(body)]);
    }
    std::sort(contacts.begin(), contacts.end());
    contacts.erase(std::unique(contacts.begin(), contacts.end()), contacts.end());
    draw_.setReposer([&](Skeleton& skeleton, std::vector<CreatureLimb>& limbs) {
      if (skeleton.joints.size() != skeletonBodies_) return;
      // Each joint to its body's place; its limbs move rigidly with it.
      std::vector<glm::dmat3> turns(skeleton.joints.size());
      std::vector<glm::dvec3> from(skeleton.joints.size());
      for (std::size_t j = 0; j < skeleton.joints.size(); ++j) {
        SceneJoint& joint = skeleton.joints[j];
        const int body = bodyIds_[j];
        if (body < 0) continue;
        const glm::dmat3 frame = frameOf(s, body);
        turns[j] = frame * glm::transpose(joint.orientation);
        from[j] = joint.position;
        joint.position = positionOf(s, body);
        joint.orientation = frame;
      }
      for (CreatureLimb& limb : limbs) {
        if (limb.joint < 0 || static_cast<std::size_t>(limb.joint) >= skeleton.joints.size()) continue;
        const std::size_t j = static_cast<std::size_t>(limb.joint);
        limb.start = skeleton.joints[j].position + turns[j] * (limb.start - from[j]);
        limb.frame = turns[j] * limb.frame;
      }
      skeleton.simulated = true;
      skeleton.contacts = contacts;
    });
  } else {
    draw_.setReposer({});
  }
  FrameTarget frame = target_;
  frame.time = time;
  replay(tape_, frame, draw_, stepStarts_);
  draw_.endWord();
  draw_.setReposer({});
  scene_.clear();
  draw_.contribute(scene_);
  scene_.time = time;

  if (sim_) {
    // The rods where the simulation has their bodies (a creature's own limbs are drawn above).
    for (std::size_t b = 0; b < plan_.bodies.size(); ++b) {
      const PlanBody& body = plan_.bodies[b];
      const int id = bodyIds_[b];
      if (id < 0) continue;
      const glm::dmat3 turn = frameOf(s, id) * glm::transpose(body.orientation);
      const glm::dvec3 at = positionOf(s, id);
      scene_.geometry.setMaterial(3);
      for (const PlanLimb& limb : body.limbs)
        if (limb.cylinder)
          scene_.geometry.addCylinder(at + turn * (limb.start - body.position), at + turn * (limb.end - body.position),
                                    limb.radius, false, turn * body.orientation[1]);
    }
    rodTips_.clear();
    for (const auto& [holder, tip] : rodTipsAtRest_) {
      if (holder < 0) continue;
      const PlanBody& body = plan_.bodies[static_cast<std::size_t>(holder)];
      const int id = bodyIds_[static_cast<std::size_t>(holder)];
      rodTips_.push_back(positionOf(s, id) + frameOf(s, id) * glm::transpose(body.orientation) * (tip - body.position));
    }
  }

  if (sim_) {
    // Where the body is: its first root, its centre of mass, its lowest joint.
    const mjModel* m = sim_->model();
    const glm::dvec3 root = positionOf(s, bodyIds_[0]);
    double mass = 0;
    glm::dvec3 centre(0.0);
    for (int b = 1; b < m->nbody; ++b) {
      mass += m->body_mass[b];
      centre += m->body_mass[b] * glm::dvec3(s->xipos[3 * b], s->xipos[3 * b + 1], s->xipos[3 * b + 2]);
    }
    const double height = (mass > 0 ? centre.y / mass : root.y) - physics_.ground;
    double lowest = std::numeric_limits<double>::infinity();
    for (const SceneJoint& joint : scene_.skeleton.joints) lowest = std::min(lowest, joint.position.y - physics_.ground);
    if (first) {
      stats_.rootStart = root;
      stats_.startHeight = height;
      stats_.lowest = lowest;
    }
    stats_.root = root;
    stats_.height = height;
    stats_.lowest = std::min(stats_.lowest, lowest);
  }
  if (first) {
    // The model as it stands at the first frame: its state as the keyframe MuJoCo resets to.
    const mjModel* m = sim_->model();
    const mjData* d = sim_->scratch();
    std::string key = "  <keyframe>\n    <key time=\"" + numbers(&d->time, 1) + "\" qpos=\"" + numbers(d->qpos, m->nq) +
                      "\" qvel=\"" + numbers(d->qvel, m->nv) + "\"";
    if (m->nu > 0) key += " ctrl=\"" + numbers(d->ctrl, m->nu) + "\"";
    key += "/>\n  </keyframe>\n";
    firstMjcf_ = mjcf_;
    firstMjcf_.insert(firstMjcf_.rfind("</mujoco>"), key);
  }
  scene.time = time;
  scene.append(scene_);
}

}  // namespace ontogen
