#pragma once
// glTF 2.0 binary (.glb) of a whole run in one file.
//
// Each frame is a node holding that frame's mesh (one primitive per palette colour for
// its triangles, with POSITION, NORMAL and TEXCOORD_0, and one LINES primitive per colour
// for its zero-radius segments). With more than one frame an animation shows one frame at
// a time: a STEP-interpolated scale channel per node is 1 while its frame is current and 0
// otherwise, keyed at the frames' developmental times (seconds; frame index / 25 when the
// times do not increase). Without animation playback the last frame shows. Materials are
// the palette colours in linear light (metallic 0, rough, double-sided, since discs and lines have one
// side).

#include <ostream>
#include <cstdint>
#include <vector>

#include "interpreters/formats/mesh_batches.h"
#include "interpreters/geometry.h"

namespace ontogen {

/// Collects frames and writes them as one .glb.
class GlbAnimationWriter {
 public:
  /// Adds geometry as the next frame, shown from time (seconds).
  void addFrame(const Geometry& geometry, double time);
  /// Frames added so far.
  std::size_t frameCount() const { return frames_.size(); }
  /// Removes every frame.
  void clear() {
    frames_.clear();
    heldBytes_ = 0;
  }
  /// Bytes the frames added so far hold (they are all written at the end).
  uint64_t heldBytes() const { return heldBytes_; }
  /// Writes the file. Stream errors are left in out's state.
  void write(std::ostream& out) const;

 private:
  struct Frame {
    std::vector<MeshBatch> batches;
    double time = 0;
  };
  std::vector<Frame> frames_;
  uint64_t heldBytes_ = 0;
};

}  // namespace ontogen
