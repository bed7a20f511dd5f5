#pragma once
// glTF 2.0 binary (.glb) of a whole run in one file, made of persistent parts
// (formats/scene_parts.h): each cell's shape written once, moved over the frames.
//
// The layout is skinned meshes whose joints are the cells (a joint per cell and shape it
// drew), so that Blender imports a run as an armature, a mesh per kJointsPerSkin joints,
// a camera and a light, with one action, however many frames it has; three.js and other
// viewers play it as skeletons. (A node per cell would make Blender import an object and
// an action per cell.)
// - Joints: nodes under one root, "cells", named "<label> <id>" (a cell's second shape:
//   "<label> <id> ~1"), with extras id, parent (64-bit ids as decimal strings), label,
//   birth (seconds) and shape, which Blender keeps as the bones' custom properties.
//   Their rest transform is where the cell stood in the last frame that has it.
// - The meshes: the first kJointsPerSkin joints' parts in the first, with a skin of those
//   joints, and so on. Shapes lie in their cell's frame, so skins' inverse bind matrices
//   are identities. A shape one joint draws goes into one primitive per colour with
//   every such shape; a shape several joints draw (the same sphere in a thousand cells)
//   is written once and each joint gets a primitive that reuses its positions, normals,
//   texture coordinates and indices, with only its own JOINTS_0 and TEXCOORD_1. Every
//   vertex carries TEXCOORD_1 = (cell number, birth in seconds): Blender imports it as the
//   UV map "UVMap.001" (its v flipped: 1 - birth), which Geometry Nodes and shaders read
//   per cell. Colours are the palette's materials in linear light.
// - Lines (zero-radius segments) are written as open tubes of radius kLineRadiusFraction
//   of the run's bounding diagonal (kTubeSides sides), so that they render everywhere.
//   A shape drawn at several scales takes the radius of its mean scale.
// - One animation, "development": per joint, a translation, rotation and scale channel
//   where they change (linear; scale STEP for a joint that is absent from some frame,
//   where its scale is 0: parts appear, vanish and switch shape), keyed at the frames'
//   developmental times less the first's; and a constant scale of the root keyed at the
//   first and last time, so that the action an importer makes spans the whole run. A run longer than kMaxAnimationSeconds is
//   played faster to last that long: Blender 3.4's importer keys at 24 frames a second
//   and sets no scene range, and its default range (frames 1 to 250) then shows the whole
//   run. The scene's extras say how: ontogen_time_start (developmental seconds at the
//   first key), ontogen_time_scale (animation seconds per developmental second) and
//   ontogen_bounds (min and max of every frame, model units).
// - A perspective camera framing every frame (gltf::addCamera); no light, which viewers
//   bring themselves.
// - Parts that never move while they show are no joints: those in every frame are written
//   in world coordinates in a mesh "still"; the others in world coordinates skinned to
//   one joint per span of frames they show in ("frames A to B", extras frames and
//   parts), which a STEP scale shows in those frames. Past kMaxBakedLines lines in such
//   parts, their lines are instances of one tube (formats/still_glb.h), a node per span
//   and colour ("lines <colour> frames A to B", or "lines <colour>" in every frame)
//   shown by a STEP scale of its own; a span left without a surface is no joint.
// With more than kMaxJoints joints each frame is instead
// a node of its own, its parts placed in world coordinates, shown by a STEP scale
// channel (1 in its frame, 0 otherwise); without animation the last frame shows. Past
// kMaxBakedLines lines in the run, a frame's lines are instances of one tube in nodes
// under its node ("lines <colour> frame <f>").

#include <cstdint>
#include <ostream>
#include <vector>

#include "interpreters/formats/scene_parts.h"
#include "interpreters/scene.h"

namespace ontogen {

/// The radius of the tubes lines are written as, a fraction of the diagonal of the box
/// every frame fills: 1/500 makes a line 1/250 of the model wide, a few pixels in a
/// picture of the whole model, like a drawn line.
inline constexpr double kLineRadiusFraction = 1.0 / 500;
/// Sides of those tubes: 8 reads as round at a line's width.
inline constexpr int kTubeSides = 8;
/// The joints of one skin and its mesh: JOINTS_0 then holds bytes, and Blender 3.4's
/// importer, whose time grows as a mesh's vertices times its skin's joints, imports a
/// colony of 4,700 joints and 290,000 vertices in seconds (in one skin: six minutes).
inline constexpr std::size_t kJointsPerSkin = 256;
/// The most joints written as skins; beyond, a mesh per frame. A run with so many parts
/// (Koch's curve at n = 7) is a picture more than an animation of parts.
inline constexpr std::size_t kMaxJoints = 65536;
/// The longest animation written, seconds: Blender's default range, 250 frames at 24
/// per second, is 10.4 s.
inline constexpr double kMaxAnimationSeconds = 10;

/// Collects frames and writes them as one .glb.
class GlbAnimationWriter {
 public:
  /// Adds a frame's scene (its geometry and nodes), shown from scene.time. The first is
  /// kept as it is and taken into parts only when a second comes: a run of one frame is
  /// written still (formats/still_glb.h) without being taken apart.
  void addFrame(const Scene& scene);
  /// Frames added so far.
  std::size_t frameCount() const { return frames_; }
  /// Removes every frame.
  void clear();
  /// Bytes the frames added so far hold (they are all written at the end).
  uint64_t heldBytes() const { return parts_.heldBytes() + firstBytes_; }
  /// The parts the frames were taken into (empty while there is one frame).
  const SceneParts& parts() const { return parts_; }
  /// Writes the file. Stream errors are left in out's state.
  void write(std::ostream& out) const;
  /// Writes the file of one frame, the bytes addFrame(scene) then write(out) give,
  /// without keeping a copy of the scene.
  static void writeFrame(const Scene& scene, std::ostream& out);

 private:
  // Writes the still file of one scene, or (null) the frames taken into parts.
  void writeWith(const Scene* still, std::ostream& out) const;

  SceneParts parts_;
  Scene first_;             // the first frame, until a second comes
  uint64_t firstBytes_ = 0; // what first_ holds
  std::size_t frames_ = 0;
};

}  // namespace ontogen
