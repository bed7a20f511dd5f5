#pragma once
// The output stage of the music set: writes a frame's finished score as a Standard MIDI
// File (DIR/<stem>.mid, or DIR/<stem>_0003.mid when the run has several frames) and hands
// it to a performer (live MIDI). The set only plays the word into a score.

#include <filesystem>
#include <functional>
#include <vector>

#include "interpreters/interpretation_set.h"
#include "interpreters/music/midi_file_writer.h"
#include "interpreters/music/score.h"

namespace ontogen {

/// Called with each finished score (live playback); may throw OutputError.
using ScorePerformer = std::function<void(const Score& score, const MidiFileDef& file)>;

/// Called with the score while it grows: everything before `horizon` beats is final (the
/// score only grows after it; notes of infinite duration still sound); `finished`: the
/// score is whole (horizon is then infinite). May throw RunInterrupted or OutputError.
using ScoreStreamer = std::function<void(const Score& score, double horizon, bool finished, const MidiFileDef& file)>;

struct ScoreOutputDef {
  MidiFileDef file{};
  bool writeFile = true;  ///< write the MIDI file (else only perform)
};

class ScoreOutput {
 public:
  explicit ScoreOutput(const ScoreOutputDef& def) : def_(def) {}
  /// Plays each finished score, e.g. on a MIDI port.
  void setPerformer(ScorePerformer performer) { performer_ = std::move(performer); }
  /// Writes the score atomically (a score that cannot be encoded leaves no file and
  /// throws OutputError), then performs it; returns the paths written.
  std::vector<std::filesystem::path> write(const Score& score, const FrameTarget& target);

 private:
  ScoreOutputDef def_;
  ScorePerformer performer_;
};

}  // namespace ontogen
