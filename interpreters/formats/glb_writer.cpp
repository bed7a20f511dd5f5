#include "interpreters/formats/glb_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "interpreters/formats/gltf_builder.h"
#include "interpreters/formats/still_glb.h"

namespace ontogen {

namespace {
using gltf::Builder;
using gltf::kArrayBuffer;
using gltf::kTriangles;
// The pools of accessors there are many of: a joint's tracks, a cell's joint indices and
// its (cell number, birth) per vertex.
constexpr gltf::Pool kTrackPool{0};
constexpr gltf::Pool kJointPool{1};
constexpr gltf::Pool kCellPool{2};
// Frame times that do not increase are replaced by the frame's index at this rate.
constexpr double kFallbackFramesPerSecond = 25;

// The keys of the animation: each frame's time less the first's, played faster when the
// run is longer than kMaxAnimationSeconds (glb_writer.h).
struct Timing {
  std::vector<float> keys;
  double start = 0;  // developmental seconds at the first key
  double scale = 1;  // animation seconds per developmental second
};

Timing timingOf(const std::vector<PartFrame>& frames) {
  Timing timing;
  const std::size_t count = frames.size();
  timing.keys.resize(count);
  bool increasing = true;
  for (std::size_t f = 1; f < count; ++f)
    if (!(frames[f].time > frames[f - 1].time)) increasing = false;
  if (!increasing) {
    for (std::size_t f = 0; f < count; ++f) timing.keys[f] = static_cast<float>(f / kFallbackFramesPerSecond);
    timing.scale = 0;  // no developmental time to tell
    return timing;
  }
  timing.start = count > 0 ? frames.front().time : 0;
  const double span = count > 0 ? frames.back().time - timing.start : 0;
  if (span > kMaxAnimationSeconds) timing.scale = kMaxAnimationSeconds / span;
  for (std::size_t f = 0; f < count; ++f) timing.keys[f] = static_cast<float>((frames[f].time - timing.start) * timing.scale);
  return timing;
}

std::string jointName(const PartJoint& joint) {
  if (joint.cell == kRestPart) return joint.variant == 0 ? "rest" : "rest ~" + std::to_string(joint.variant);
  std::string name = (joint.label.empty() ? std::string("cell") : joint.label) + " " + std::to_string(joint.cell);
  if (joint.variant > 0) name += " ~" + std::to_string(joint.variant);
  return name;
}

nlohmann::json jointExtras(const PartJoint& joint) {
  nlohmann::json extras = {{"label", joint.label}, {"birth", joint.birth}, {"shape", joint.shape}};
  if (joint.cell != kRestPart) extras["id"] = std::to_string(joint.cell);
  if (joint.parent != kNoParentNode) extras["parent"] = std::to_string(joint.parent);
  return extras;
}

// The radius of the tubes lines are written as, model units.
double lineRadiusOf(const Box& bounds) {
  const double diagonal = bounds.empty ? 0 : glm::length(bounds.max - bounds.min);
  return diagonal > 0 ? diagonal * kLineRadiusFraction : 1e-3;
}

// The shapes as written: their lines made tubes of one width in the model's units.
std::vector<std::vector<MeshBatch>> finalShapes(const SceneParts& parts) {
  const double radius = lineRadiusOf(parts.bounds());
  std::vector<std::vector<MeshBatch>> out;
  out.reserve(parts.shapes().size());
  for (const PartShape& shape : parts.shapes()) out.push_back(shapeWithTubes(shape, radius / shape.meanScale(), kTubeSides));
  return out;
}

// A joint's transform in every frame: where it is placed, or (hidden, scale 0) where it
// was placed last, or will be first.
struct Track {
  std::vector<glm::vec3> translations;
  std::vector<float> rotations;  // x, y, z, w per frame
  std::vector<glm::vec3> scales;
  bool hidden = false;           // absent from some frame
};

std::vector<Track> tracksOf(const SceneParts& parts) {
  const auto& frames = parts.frames();
  const std::size_t count = frames.size();
  std::vector<std::vector<const PartPlacement*>> at(parts.joints().size(), std::vector<const PartPlacement*>(count, nullptr));
  for (std::size_t f = 0; f < count; ++f)
    for (const PartPlacement& p : frames[f].placements) at[p.joint][f] = &p;
  std::vector<Track> tracks(parts.joints().size());
  for (std::size_t j = 0; j < tracks.size(); ++j) {
    Track& track = tracks[j];
    const PartPlacement* held = nullptr;
    for (std::size_t f = 0; f < count && held == nullptr; ++f) held = at[j][f];
    glm::dquat previous{1, 0, 0, 0};
    for (std::size_t f = 0; f < count; ++f) {
      const PartPlacement* p = at[j][f];
      if (p != nullptr) held = p;
      track.hidden = track.hidden || p == nullptr;
      glm::dquat q = held->rotation;
      // Each track in one hemisphere, so that linear interpolation takes the short way.
      if (f > 0 && glm::dot(q, previous) < 0) q = -q;
      previous = q;
      track.translations.emplace_back(held->translation);
      track.rotations.insert(track.rotations.end(), {static_cast<float>(q.x), static_cast<float>(q.y),
                                                     static_cast<float>(q.z), static_cast<float>(q.w)});
      track.scales.emplace_back(p != nullptr ? static_cast<float>(p->scale) : 0.0f);
    }
  }
  return tracks;
}

template <typename T>
bool changes(const std::vector<T>& values, std::size_t stride = 1) {
  for (std::size_t k = stride; k < values.size(); ++k)
    if (values[k] != values[k % stride]) return true;
  return false;
}

// Weights (1, 0, 0, 0) for `vertices` vertices: the first joint slot carries each whole.
int unitWeights(Builder& b, std::size_t vertices) {
  std::vector<uint16_t> weights(4 * vertices, 0);
  for (std::size_t v = 0; v < vertices; ++v) weights[4 * v] = 255;
  return b.addVec4Integers(weights, gltf::kUnsignedByte, true);
}

// One colour's vertices of every shape a single joint draws, each with its joint.
struct SkinnedBatch {
  MeshBatch mesh;
  std::vector<uint16_t> joints;   // 4 per vertex
  std::vector<glm::vec2> cells;   // (cell number, birth) per vertex
};

// The frames [first, last] of a joint that is in each of them in one place and absent
// from the others: a part that never moves while it shows. {1, 0} when it moves.
std::pair<std::size_t, std::size_t> steadySpan(const Track& t) {
  const std::pair<std::size_t, std::size_t> moves{1, 0};
  if (changes(t.translations) || changes(t.rotations, 4)) return moves;
  std::size_t first = 0, last = t.scales.size();
  while (first < t.scales.size() && t.scales[first] == glm::vec3(0.0f)) ++first;
  while (last > first && t.scales[last - 1] == glm::vec3(0.0f)) --last;
  if (first >= last) return moves;
  for (std::size_t f = first; f < last; ++f)
    if (t.scales[f] != t.scales[first]) return moves;
  return {first, last - 1};
}

// A shape placed in world coordinates, appended to a batch with its cell per vertex.
void appendPlaced(MeshBatch& into, std::vector<glm::vec2>& cells, const MeshBatch& shape, const PartPlacement& p,
                  const PartJoint& joint) {
  const glm::dmat3 rotation = glm::mat3_cast(p.rotation);
  const auto base = static_cast<uint32_t>(into.positions.size());
  for (const glm::vec3& v : shape.positions) into.positions.emplace_back(p.translation + rotation * (glm::dvec3(v) * p.scale));
  for (const glm::vec3& n : shape.normals) into.normals.emplace_back(rotation * glm::dvec3(n));
  into.texcoords.insert(into.texcoords.end(), shape.texcoords.begin(), shape.texcoords.end());
  cells.insert(cells.end(), shape.positions.size(),
               glm::vec2(static_cast<float>(joint.cellNumber), static_cast<float>(joint.birth)));
  for (uint32_t index : shape.indices) into.indices.push_back(base + index);
}

// The parts that never move, in world coordinates in one mesh of a primitive per colour,
// each vertex with (cell number, birth) as the joints' are.
void writeStillParts(const SceneParts& parts, const std::vector<std::vector<MeshBatch>>& shapes,
                     const std::vector<uint32_t>& stillJoints, const std::vector<const PartPlacement*>& placed,
                     Builder& b, nlohmann::json& sceneNodes) {
  if (stillJoints.empty()) return;
  struct Batch {
    MeshBatch mesh;
    std::vector<glm::vec2> cells;
  };
  std::map<uint32_t, Batch> world;  // by colour
  for (uint32_t joint : stillJoints) {
    const PartJoint& pj = parts.joints()[joint];
    for (const MeshBatch& batch : shapes[pj.shape]) {
      if (batch.indices.empty()) continue;
      Batch& into = world[batch.material];
      appendPlaced(into.mesh, into.cells, batch, *placed[joint], pj);
    }
  }
  if (world.empty()) return;
  nlohmann::json primitives = nlohmann::json::array();
  for (const auto& [material, batch] : world)
    primitives.push_back(gltf::trianglePrimitive(b, batch.mesh, material, &batch.cells));
  b.gltf["meshes"].push_back({{"name", "still"}, {"primitives", primitives}});
  b.gltf["nodes"].push_back({{"name", "still"}, {"mesh", b.gltf["meshes"].size() - 1}});
  sceneNodes.push_back(b.gltf["nodes"].size() - 1);
}

// A frame span's track: at the origin, shown (scale 1) in frames [first, last] only.
Track spanTrack(std::pair<std::size_t, std::size_t> span, std::size_t frames) {
  Track t;
  t.hidden = true;
  for (std::size_t f = 0; f < frames; ++f) {
    t.translations.emplace_back(0.0f);
    t.rotations.insert(t.rotations.end(), {0.0f, 0.0f, 0.0f, 1.0f});
    t.scales.emplace_back(f >= span.first && f <= span.second ? 1.0f : 0.0f);
  }
  return t;
}

std::string spanName(std::pair<std::size_t, std::size_t> span) {
  return "frames " + std::to_string(span.first) + " to " + std::to_string(span.second);
}

std::size_t lineCount(const PartShape& shape) {
  std::size_t lines = 0;
  for (const MeshBatch& batch : shape.batches) lines += batch.lines.size() / 2;
  return lines;
}

// The shapes' surfaces alone, their lines left out (written as instances).
std::vector<std::vector<MeshBatch>> surfacesOf(const SceneParts& parts) {
  std::vector<std::vector<MeshBatch>> out;
  out.reserve(parts.shapes().size());
  for (const PartShape& shape : parts.shapes()) {
    out.emplace_back();
    for (const MeshBatch& batch : shape.batches) {
      if (batch.indices.empty()) continue;
      out.back().push_back(batch);
      out.back().back().lines.clear();
    }
  }
  return out;
}

// The lines of parts that never move while they show, by their span of frames (the
// whole run for parts in every frame), then colour: in world coordinates, as tubes of
// one radius.
using SpanLines = std::map<std::pair<std::size_t, std::size_t>, std::map<uint32_t, TubeInstances>>;

// A placed part's lines, in world coordinates, added by colour to `into`.
void addPlacedLines(const SceneParts& parts, const PartPlacement& p, double radius,
                    std::map<uint32_t, TubeInstances>& into) {
  const PartJoint& pj = parts.joints()[p.joint];
  const glm::dmat3 rotation = glm::mat3_cast(p.rotation);
  const glm::vec2 cell(static_cast<float>(pj.cellNumber), static_cast<float>(pj.birth));
  for (const MeshBatch& batch : parts.shapes()[pj.shape].batches) {
    for (std::size_t k = 0; k + 1 < batch.lines.size(); k += 2) {
      const glm::dvec3 a = p.translation + rotation * (glm::dvec3(batch.lines[k]) * p.scale);
      const glm::dvec3 z = p.translation + rotation * (glm::dvec3(batch.lines[k + 1]) * p.scale);
      if (a != z) into[batch.material].add(a, z, radius, cell);
    }
  }
}

void writeSkinned(const SceneParts& parts, Builder& b, nlohmann::json& sceneNodes) {
  const auto& joints = parts.joints();
  if (joints.empty()) return;
  const std::vector<std::vector<MeshBatch>> shapes = finalShapes(parts);
  const std::vector<Track> tracks = tracksOf(parts);
  const std::size_t frames = parts.frames().size();
  std::vector<const PartPlacement*> placed(joints.size(), nullptr);  // where each first stands
  for (const PartFrame& frame : parts.frames())
    for (const PartPlacement& p : frame.placements)
      if (placed[p.joint] == nullptr) placed[p.joint] = &p;
  // The joints that move are nodes (the k-th is node k). Those that never move while they
  // show are written in world coordinates: in the still mesh when they show in every
  // frame, else as one node per span of frames they show in, after the moving ones.
  std::vector<uint32_t> moving, stillJoints;
  std::map<std::pair<std::size_t, std::size_t>, std::vector<uint32_t>> steady;  // by span
  std::vector<std::size_t> slot(joints.size(), 0);
  for (uint32_t j = 0; j < joints.size(); ++j) {
    const auto span = steadySpan(tracks[j]);
    if (span.first > span.second) {
      slot[j] = moving.size();
      moving.push_back(j);
    } else if (span.first == 0 && span.second + 1 == frames) {
      stillJoints.push_back(j);
    } else {
      steady[span].push_back(j);
    }
  }
  // Past kMaxBakedLines lines in the parts that never move, their lines are instances
  // of one tube, as in a run of one frame (formats/still_glb.h), a node per span and
  // colour shown by its span's scale; their surfaces stay where they were, and a span
  // left without a surface is no joint.
  std::size_t steadyLines = 0;
  for (uint32_t j : stillJoints) steadyLines += lineCount(parts.shapes()[joints[j].shape]);
  for (const auto& [span, members] : steady)
    for (uint32_t j : members) steadyLines += lineCount(parts.shapes()[joints[j].shape]);
  const bool instanced = steadyLines > kMaxBakedLines;
  SpanLines spanLines;
  const std::vector<std::vector<MeshBatch>> surfaces =
      instanced ? surfacesOf(parts) : std::vector<std::vector<MeshBatch>>{};
  const std::vector<std::vector<MeshBatch>>& steadyShapes = instanced ? surfaces : shapes;
  if (instanced) {
    const double radius = lineRadiusOf(parts.bounds());
    for (uint32_t j : stillJoints) addPlacedLines(parts, *placed[j], radius, spanLines[{0, frames - 1}]);
    for (const auto& [span, members] : steady)
      for (uint32_t j : members) addPlacedLines(parts, *placed[j], radius, spanLines[span]);
    std::erase_if(steady, [&](const auto& entry) {
      return std::none_of(entry.second.begin(), entry.second.end(),
                          [&](uint32_t j) { return !steadyShapes[joints[j].shape].empty(); });
    });
  }
  // A span's node is keyed like a joint that shows in those frames, at the origin.
  std::vector<Track> spanTracks;
  std::vector<nlohmann::json> spanNodes;
  for (const auto& [span, members] : steady) {
    spanTracks.push_back(spanTrack(span, frames));
    spanNodes.push_back(
        {{"name", spanName(span)}, {"extras", {{"frames", {span.first, span.second}}, {"parts", members.size()}}}});
  }
  const std::size_t count = moving.size() + steady.size();
  auto trackOf = [&](std::size_t k) -> const Track& {
    return k < moving.size() ? tracks[moving[k]] : spanTracks[k - moving.size()];
  };
  // The animation: each node keyed from its first frame to its last (and, for the scale
  // of a node that appears or vanishes, the frames either side, where it is 0); before
  // and after its keys a channel holds its first and last value.
  const Timing timing = timingOf(parts.frames());
  std::map<std::pair<std::size_t, std::size_t>, int> inputs;  // keys lo..hi -> accessor
  auto inputOf = [&](std::size_t lo, std::size_t hi) {
    auto [it, added] = inputs.try_emplace({lo, hi}, 0);
    if (added) it->second = b.addScalars(std::vector<float>(timing.keys.begin() + lo, timing.keys.begin() + hi + 1));
    return it->second;
  };
  nlohmann::json samplers = nlohmann::json::array();
  nlohmann::json channels = nlohmann::json::array();
  auto channel = [&](int input, int output, std::size_t node, const char* path, const char* interpolation) {
    samplers.push_back({{"input", input}, {"output", output}, {"interpolation", interpolation}});
    channels.push_back({{"sampler", samplers.size() - 1}, {"target", {{"node", node}, {"path", path}}}});
  };
  auto key = [&](const Track& t, std::size_t node) {
    std::size_t first = 0, last = frames - 1;
    while (first < last && t.scales[first] == glm::vec3(0.0f)) ++first;
    while (last > first && t.scales[last] == glm::vec3(0.0f)) --last;
    auto slice = [&](const auto& values, std::size_t lo, std::size_t hi, std::size_t stride) {
      using Values = std::decay_t<decltype(values)>;
      return Values(values.begin() + lo * stride, values.begin() + (hi + 1) * stride);
    };
    const auto translations = slice(t.translations, first, last, 1);
    const auto rotations = slice(t.rotations, first, last, 4);
    if (changes(translations))
      channel(inputOf(first, last), b.addVec3(translations, 0, false, kTrackPool), node, "translation", "LINEAR");
    if (changes(rotations, 4))
      channel(inputOf(first, last), b.addFloats(rotations, "VEC4", last - first + 1, 0, kTrackPool), node, "rotation",
              "LINEAR");
    const std::size_t lo = first > 0 ? first - 1 : 0, hi = last + 1 < frames ? last + 1 : last;
    const auto scales = slice(t.scales, lo, hi, 1);
    if (changes(scales))
      channel(inputOf(lo, hi), b.addVec3(scales, 0, false, kTrackPool), node, "scale", t.hidden ? "STEP" : "LINEAR");
  };
  auto finish = [&] {
    writeStillParts(parts, steadyShapes, stillJoints, placed, b, sceneNodes);
    // The instanced lines: in every frame, or shown by their span's scale.
    TubeInstancer instancer(b);
    for (const auto& [span, colours] : spanLines) {
      const bool always = span.first == 0 && span.second + 1 == frames;
      for (const auto& [material, lines] : colours) {
        const std::string name = "lines " + std::to_string(material) + (always ? "" : " " + spanName(span));
        const std::size_t node = instancer.addNode(material, lines, name);
        sceneNodes.push_back(node);
        if (always) continue;
        if (span.second + 1 != frames) b.gltf["nodes"][node]["scale"] = {0.0, 0.0, 0.0};
        key(spanTrack(span, frames), node);
      }
    }
    if (!channels.empty())
      b.gltf["animations"].push_back({{"name", "development"}, {"samplers", samplers}, {"channels", channels}});
  };
  if (count == 0) {
    finish();
    return;
  }

  // The joints under one root; their rest transform is their last frame's.
  nlohmann::json children = nlohmann::json::array();
  for (std::size_t k = 0; k < count; ++k) {
    const Track& t = trackOf(k);
    const std::size_t last = t.translations.size() - 1;
    nlohmann::json node = k < moving.size()
                              ? nlohmann::json{{"name", jointName(joints[moving[k]])}, {"extras", jointExtras(joints[moving[k]])}}
                              : spanNodes[k - moving.size()];
    const glm::vec3 translation = t.translations[last], scale = t.scales[last];
    using gltf::shortFloat;
    node["translation"] = {shortFloat(translation.x), shortFloat(translation.y), shortFloat(translation.z)};
    node["rotation"] = {shortFloat(t.rotations[4 * last]), shortFloat(t.rotations[4 * last + 1]),
                        shortFloat(t.rotations[4 * last + 2]), shortFloat(t.rotations[4 * last + 3])};
    if (scale != glm::vec3(1.0f)) node["scale"] = {shortFloat(scale.x), shortFloat(scale.y), shortFloat(scale.z)};
    b.gltf["nodes"].push_back(node);
    children.push_back(k);
  }
  b.gltf["nodes"].push_back({{"name", "cells"}, {"children", children}});
  const std::size_t root = b.gltf["nodes"].size() - 1;
  sceneNodes.push_back(root);

  // The meshes: one per kJointsPerSkin joints, each with a skin of those joints.
  const std::size_t skins = (count + kJointsPerSkin - 1) / kJointsPerSkin;
  std::vector<nlohmann::json> primitives(skins, nlohmann::json::array());
  std::vector<std::vector<uint32_t>> instances = parts.jointsByShape();
  std::vector<char> isMoving(joints.size(), 0);
  for (uint32_t j : moving) isMoving[j] = 1;
  for (auto& of : instances) std::erase_if(of, [&](uint32_t j) { return !isMoving[j]; });
  std::vector<std::map<uint32_t, SkinnedBatch>> single(skins);  // by skin, then colour
  // The spans' parts, in world coordinates, skinned to their span's joint.
  std::size_t spanSlot = moving.size();
  for (const auto& [span, members] : steady) {
    for (uint32_t joint : members) {
      for (const MeshBatch& batch : steadyShapes[joints[joint].shape]) {
        if (batch.indices.empty()) continue;
        SkinnedBatch& into = single[spanSlot / kJointsPerSkin][batch.material];
        const std::size_t before = into.mesh.positions.size();
        appendPlaced(into.mesh, into.cells, batch, *placed[joint], joints[joint]);
        for (std::size_t v = before; v < into.mesh.positions.size(); ++v)
          into.joints.insert(into.joints.end(), {static_cast<uint16_t>(spanSlot % kJointsPerSkin), 0, 0, 0});
      }
    }
    ++spanSlot;
  }
  auto perVertex = [&](uint32_t joint, std::size_t vertices, std::vector<uint16_t>& jointsOut,
                       std::vector<glm::vec2>& cellsOut) {
    const PartJoint& pj = joints[joint];
    for (std::size_t v = 0; v < vertices; ++v) {
      jointsOut.insert(jointsOut.end(), {static_cast<uint16_t>(slot[joint] % kJointsPerSkin), 0, 0, 0});
      cellsOut.emplace_back(static_cast<float>(pj.cellNumber), static_cast<float>(pj.birth));
    }
  };
  for (std::size_t s = 0; s < shapes.size(); ++s) {
    if (instances[s].empty()) continue;
    if (instances[s].size() == 1) {
      const uint32_t joint = instances[s][0];
      for (const MeshBatch& batch : shapes[s]) {
        if (batch.indices.empty()) continue;
        SkinnedBatch& into = single[slot[joint] / kJointsPerSkin][batch.material];
        const auto base = static_cast<uint32_t>(into.mesh.positions.size());
        into.mesh.positions.insert(into.mesh.positions.end(), batch.positions.begin(), batch.positions.end());
        into.mesh.normals.insert(into.mesh.normals.end(), batch.normals.begin(), batch.normals.end());
        into.mesh.texcoords.insert(into.mesh.texcoords.end(), batch.texcoords.begin(), batch.texcoords.end());
        for (uint32_t index : batch.indices) into.mesh.indices.push_back(base + index);
        perVertex(joint, batch.positions.size(), into.joints, into.cells);
      }
      continue;
    }
    // Written once, drawn by every joint of the shape.
    for (const MeshBatch& batch : shapes[s]) {
      if (batch.indices.empty()) continue;
      const nlohmann::json shared = gltf::vertexAttributes(b, batch);
      const int indices = b.addIndices(batch.indices);
      const int weights = unitWeights(b, batch.positions.size());
      for (uint32_t joint : instances[s]) {
        std::vector<uint16_t> jointValues;
        std::vector<glm::vec2> cells;
        perVertex(joint, batch.positions.size(), jointValues, cells);
        nlohmann::json attributes = shared;
        attributes["JOINTS_0"] = b.addVec4Integers(jointValues, gltf::kUnsignedByte, false, kJointPool);
        attributes["WEIGHTS_0"] = weights;
        attributes["TEXCOORD_1"] = b.addVec2(cells, kCellPool);
        primitives[slot[joint] / kJointsPerSkin].push_back({{"attributes", attributes},
                                                       {"indices", indices},
                                                       {"material", b.materialOf(batch.material)},
                                                       {"mode", kTriangles}});
      }
    }
  }
  // Identity inverse bind matrices, as the shapes lie in their joints' frames: glTF lets
  // a skin leave them out, but assimp 5.2 crashes on such a skin.
  std::vector<float> identity;
  for (std::size_t j = 0; j < std::min(count, kJointsPerSkin); ++j)
    for (int k = 0; k < 16; ++k) identity.push_back(k % 5 == 0 ? 1.0f : 0.0f);
  const int identityView = b.addView(identity.data(), identity.size() * sizeof(float), 0);
  for (std::size_t k = 0; k < skins; ++k) {
    for (auto& [material, batch] : single[k]) {
      nlohmann::json attributes = gltf::vertexAttributes(b, batch.mesh);
      attributes["JOINTS_0"] = b.addVec4Integers(batch.joints, gltf::kUnsignedByte, false);
      attributes["WEIGHTS_0"] = unitWeights(b, batch.mesh.positions.size());
      attributes["TEXCOORD_1"] = b.addVec2(batch.cells);
      primitives[k].push_back({{"attributes", attributes},
                               {"indices", b.addIndices(batch.mesh.indices)},
                               {"material", b.materialOf(material)},
                               {"mode", kTriangles}});
    }
    if (primitives[k].empty()) continue;
    const std::string name = skins == 1 ? std::string("parts") : "parts " + std::to_string(k);
    nlohmann::json skinJoints = nlohmann::json::array();
    for (std::size_t j = k * kJointsPerSkin; j < std::min(count, (k + 1) * kJointsPerSkin); ++j) skinJoints.push_back(j);
    b.gltf["meshes"].push_back({{"name", name}, {"primitives", primitives[k]}});
    const int inverseBind = b.addAccessor(
        {{"bufferView", identityView}, {"componentType", gltf::kFloat}, {"count", skinJoints.size()}, {"type", "MAT4"}});
    b.gltf["skins"].push_back(
        {{"name", name}, {"joints", skinJoints}, {"skeleton", root}, {"inverseBindMatrices", inverseBind}});
    b.gltf["nodes"].push_back(
        {{"name", name}, {"mesh", b.gltf["meshes"].size() - 1}, {"skin", b.gltf["skins"].size() - 1}});
    sceneNodes.push_back(b.gltf["nodes"].size() - 1);
  }
  for (std::size_t j = 0; j < count; ++j) key(trackOf(j), j);
  // The root's scale, 1 at the first and the last key: the action Blender makes spans
  // the whole run even where the first or last frames move nothing.
  const int ends = b.addScalars({timing.keys.front(), timing.keys.back()});
  samplers.push_back({{"input", ends},
                      {"output", b.addVec3({glm::vec3(1.0f), glm::vec3(1.0f)}, 0, false)},
                      {"interpolation", "LINEAR"}});
  channels.push_back({{"sampler", samplers.size() - 1}, {"target", {{"node", root}, {"path", "scale"}}}});
  finish();
}

// Beyond kMaxJoints: a node per frame, its parts in world coordinates; past
// kMaxBakedLines lines in the run, each frame's lines are instances of one tube in
// nodes under the frame's ("lines <colour> frame <f>").
void writeFramePerNode(const SceneParts& parts, Builder& b, nlohmann::json& sceneNodes) {
  const auto& frames = parts.frames();
  const std::size_t count = frames.size();
  std::size_t lines = 0;
  for (const PartFrame& frame : frames)
    for (const PartPlacement& p : frame.placements) lines += lineCount(parts.shapes()[parts.joints()[p.joint].shape]);
  const bool instanced = lines > kMaxBakedLines;
  const std::vector<std::vector<MeshBatch>> shapes = instanced ? surfacesOf(parts) : finalShapes(parts);
  const double radius = lineRadiusOf(parts.bounds());
  TubeInstancer instancer(b);
  std::vector<std::size_t> frameNodes;
  for (std::size_t f = 0; f < count; ++f) {
    std::map<uint32_t, MeshBatch> world;
    std::map<uint32_t, TubeInstances> tubes;
    for (const PartPlacement& p : frames[f].placements) {
      if (instanced) addPlacedLines(parts, p, radius, tubes);
      const glm::dmat3 rotation = glm::mat3_cast(p.rotation);
      for (const MeshBatch& batch : shapes[parts.joints()[p.joint].shape]) {
        if (batch.indices.empty()) continue;
        MeshBatch& into = world[batch.material];
        const auto base = static_cast<uint32_t>(into.positions.size());
        for (const glm::vec3& v : batch.positions)
          into.positions.emplace_back(p.translation + rotation * (glm::dvec3(v) * p.scale));
        for (const glm::vec3& n : batch.normals) into.normals.emplace_back(rotation * glm::dvec3(n));
        into.texcoords.insert(into.texcoords.end(), batch.texcoords.begin(), batch.texcoords.end());
        for (uint32_t index : batch.indices) into.indices.push_back(base + index);
      }
    }
    nlohmann::json primitives = nlohmann::json::array();
    for (auto& [material, batch] : world) primitives.push_back(gltf::trianglePrimitive(b, batch, material));
    nlohmann::json node = {{"name", "frame " + std::to_string(f)}};
    if (!primitives.empty()) {
      b.gltf["meshes"].push_back({{"name", "frame " + std::to_string(f)}, {"primitives", primitives}});
      node["mesh"] = b.gltf["meshes"].size() - 1;
    }
    nlohmann::json children = nlohmann::json::array();
    for (const auto& [material, instances] : tubes)
      children.push_back(
          instancer.addNode(material, instances, "lines " + std::to_string(material) + " frame " + std::to_string(f)));
    if (!children.empty()) node["children"] = children;
    if (count > 1 && f + 1 != count) node["scale"] = {0.0, 0.0, 0.0};
    b.gltf["nodes"].push_back(node);
    frameNodes.push_back(b.gltf["nodes"].size() - 1);
    sceneNodes.push_back(frameNodes.back());
  }
  if (count < 2) return;
  const Timing timing = timingOf(frames);
  const int input = b.addScalars(timing.keys);
  nlohmann::json samplers = nlohmann::json::array();
  nlohmann::json channels = nlohmann::json::array();
  std::vector<glm::vec3> scales(count);
  for (std::size_t f = 0; f < count; ++f) {
    for (std::size_t k = 0; k < count; ++k) scales[k] = glm::vec3(k == f ? 1.0f : 0.0f);
    samplers.push_back({{"input", input}, {"output", b.addVec3(scales, 0, false)}, {"interpolation", "STEP"}});
    channels.push_back({{"sampler", samplers.size() - 1}, {"target", {{"node", frameNodes[f]}, {"path", "scale"}}}});
  }
  b.gltf["animations"].push_back({{"name", "development"}, {"samplers", samplers}, {"channels", channels}});
}

}  // namespace

namespace {
// What a kept scene holds, near enough for the memory limit.
uint64_t sceneBytes(const Scene& scene) {
  const Mesh& mesh = scene.geometry.mesh();
  return mesh.positions.size() * sizeof(glm::dvec3) + mesh.normals.size() * sizeof(glm::dvec3) +
         mesh.texcoords.size() * sizeof(glm::dvec2) + mesh.triangles.size() * sizeof(Triangle) +
         scene.geometry.segments().size() * sizeof(Segment) + scene.nodes.size() * sizeof(SceneNode);
}
}  // namespace

void GlbAnimationWriter::addFrame(const Scene& scene) {
  if (frames_ == 0) {
    first_ = scene;
    firstBytes_ = sceneBytes(scene);
  } else {
    if (frames_ == 1) {
      parts_.addFrame(first_);
      first_ = Scene();
      firstBytes_ = 0;
    }
    parts_.addFrame(scene);
  }
  ++frames_;
}

void GlbAnimationWriter::clear() {
  parts_.clear();
  first_ = Scene();
  firstBytes_ = 0;
  frames_ = 0;
}

void GlbAnimationWriter::write(std::ostream& out) const { writeWith(frames_ == 1 ? &first_ : nullptr, out); }

void GlbAnimationWriter::writeFrame(const Scene& scene, std::ostream& out) { GlbAnimationWriter{}.writeWith(&scene, out); }

void GlbAnimationWriter::writeWith(const Scene* still, std::ostream& out) const {
  Builder b;
  b.gltf["asset"] = {{"version", "2.0"}, {"generator", "ontogen"}};
  nlohmann::json sceneNodes = nlohmann::json::array();
  const Box box = still != nullptr ? still->geometry.bounds() : parts_.bounds();
  if (still != nullptr)
    addStillScene(b, *still, lineRadiusOf(box), sceneNodes);
  else if (parts_.joints().size() <= kMaxJoints)
    writeSkinned(parts_, b, sceneNodes);
  else
    writeFramePerNode(parts_, b, sceneNodes);
  gltf::addCamera(b, box, sceneNodes);
  nlohmann::json scene = {{"name", "ontogen"}};
  if (!sceneNodes.empty()) scene["nodes"] = sceneNodes;  // glTF allows no empty list
  nlohmann::json extras = nlohmann::json::object();
  if (const Timing timing = timingOf(parts_.frames()); parts_.frames().size() > 1 && timing.scale > 0) {
    extras["ontogen_time_start"] = timing.start;
    extras["ontogen_time_scale"] = timing.scale;
  }
  if (!box.empty) extras["ontogen_bounds"] = {box.min.x, box.min.y, box.min.z, box.max.x, box.max.y, box.max.z};
  if (!extras.empty()) scene["extras"] = extras;
  // Pushed, not braced: `{scene}` is the object itself to some compilers (clang).
  b.gltf["scenes"] = nlohmann::json::array();
  b.gltf["scenes"].push_back(scene);
  b.gltf["scene"] = 0;
  gltf::writeGlb(b, out);
}

}  // namespace ontogen
