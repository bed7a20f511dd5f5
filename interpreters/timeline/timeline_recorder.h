#pragma once
// The time-state diagram of paper 002, Fig. 5, as data: one row per cell that lived,
// from its birth to the moment it was gone, rows ordered so that a cell appears next to
// the cell before it in its pool when it was first seen, and a system's cells nested
// under its cell's row. Recorded by sampling a developing world after every step.

#include <cstdint>
#include <list>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "core/world.h"

namespace ontogen {

struct TimelineRow {
  std::string label;
  int depth = 0;       ///< 0 for the root pool, 1 for a system's pool in it, ...
  double born = 0;     ///< birth time (exact: the cell's own)
  double gone = 0;     ///< first sample without the cell, or the end of the recording
  bool system = false;  ///< a system cell, with its pool's rows under it
};

struct Timeline {
  double start = 0;
  double end = 0;
  std::vector<TimelineRow> rows;
  uint64_t omitted = 0;  ///< cells not given a row once maxRows was reached
};

class TimelineRecorder {
 public:
  /// Rows past maxRows are counted, not kept: a huge model still gives a diagram.
  explicit TimelineRecorder(size_t maxRows = 4000) : maxRows_(maxRows) {}

  /// Records the world at its current time. Cells that only steer the turtle (brackets
  /// and symbols without rules) have no row: the diagram shows what develops.
  void sample(const World& world);
  Timeline finish() const;

 private:
  struct Entry {
    TimelineRow row;
    uint64_t lastSample = 0;
    bool alive = true;
  };
  void walk(const World& world, int depth, std::list<Entry>::iterator& previous);

  size_t maxRows_;
  std::list<Entry> rows_;
  std::unordered_map<uint64_t, std::list<Entry>::iterator> byId_;
  uint64_t samples_ = 0;
  double start_ = 0;
  double time_ = 0;
  uint64_t omitted_ = 0;
  std::unordered_set<uint64_t> omittedIds_;
};

/// Develops a fresh world of the program to `until` in steps of dt and records it.
Timeline recordTimeline(std::shared_ptr<const Program> program, const WorldDef& def, double until, double dt,
                        size_t maxRows = 4000);

}  // namespace ontogen
