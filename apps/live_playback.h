#pragma once
// `ontogen run --midi-port` / `--virtual-port`: the run's music set played on a live MIDI
// port (interpreters/music/live_playback.h), with its messages on the terminal.
// `--midi-clock` adds MIDI clock. Ctrl-C during a performance stops every note and ends
// the run with exit code 130.

#include <memory>
#include <vector>

#include "apps/commands.h"
#include "interpreters/interpretation_set.h"
#include "interpreters/run.h"

namespace ontogen::app {

class LiveSession;

/// If the options ask for live MIDI, opens the port and attaches it to the run's music
/// set. Returns kExitOk, or prints the error and returns kExitUsage (no music set,
/// --midi-clock without a port) or kExitMidiError (no MIDI system, no such port).
/// `playback` keeps the port open and the performer running.
int attachLivePlayback(const RunOptions& options, std::vector<std::unique_ptr<InterpretationSet>>& sets,
                       std::shared_ptr<LiveSession>& playback);

/// After the run: waits for the performance to end (the development may have finished
/// long before the music) and prints its statistics if asked. Returns kExitOk, or
/// kExitInterrupted when Ctrl-C stopped it, or kExitOutputError when sending failed.
/// Nothing to do without a playback.
int finishLivePlayback(const std::shared_ptr<LiveSession>& playback);

}  // namespace ontogen::app
