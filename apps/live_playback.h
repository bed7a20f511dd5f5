#pragma once
// `ontogen run --midi-port` / `--virtual-port`: connects the music set of a run to a live
// MIDI port, so each finished score is performed in real time, and turns Ctrl-C during
// a performance into all-notes-off and exit code 130.

#include <memory>
#include <stdexcept>
#include <vector>

#include "apps/commands.h"
#include "interpreters/interpretation_set.h"
#include "interpreters/run.h"

namespace ontogen::app {

/// Thrown out of a run when Ctrl-C stopped a performance (its notes already stopped).
struct PlaybackInterrupted : RunInterrupted {
  using RunInterrupted::RunInterrupted;
};

class LivePlayback;

/// If the options ask for live MIDI, opens the port and attaches it to the run's music
/// set. Returns kExitOk, or prints the error and returns kExitUsage (no music set) or
/// kExitMidiError (no MIDI system, no such port). `playback` keeps the port open.
int attachLivePlayback(const RunOptions& options, std::vector<std::unique_ptr<InterpretationSet>>& sets,
                       std::shared_ptr<LivePlayback>& playback);

}  // namespace ontogen::app
