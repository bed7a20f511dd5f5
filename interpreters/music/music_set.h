#pragma once
// The "music" interpretation set (paper 002, section 4.2): the music player
// (music_player.h) turns the word into a Score, written as a Standard MIDI File
// DIR/<stem>.mid and optionally performed live. Two ways to place notes in time
// (docs/LANGUAGE.md, "Music"):
//
//  - sequential: each frame's word is read left to right like the turtle reads it, from
//    beat 0; a branch is a voice that starts where it opens. One file per frame.
//  - developmental: the set follows the development (followsDevelopment()); one second of
//    developmental time is one beat. A cell's notes start at its birth, once per cell
//    (cells are told apart by id and birth), `hold` sounds while the cell lives, and
//    controllers, tempo and programs are re-read at every step and sent when their value
//    changes, so a `rate` variable can drive a swell. One file for the run.
//
// Each channel's track is named by the program's `#track C "NAME"`, else after the cells
// whose instructions put notes or controller messages on it, in the order they first
// did ("Drone", "bend, turn").

#include <array>
#include <functional>
#include <map>
#include <set>
#include <string_view>
#include <utility>
#include <vector>

#include "interpreters/interpretation_set.h"
#include "interpreters/music/midi_file_writer.h"
#include "interpreters/music/music_player.h"
#include "interpreters/music/score.h"
#include "interpreters/music/score_output.h"
#include "model/program.h"

namespace ontogen {

struct MusicSetDef {
  MusicPlayerDef player{};
  MidiFileDef file{};
  MusicTime time = MusicTime::Sequential;
  bool writeFile = true;  ///< write DIR/<stem>.mid at the end of each frame
  /// Names of the channels' tracks (#track); empty: the cells that play on the channel.
  std::array<std::string, 16> trackNames{};
};


class MusicSet final : public InterpretationSet {
 public:
  /// Throws std::invalid_argument when def is out of range.
  explicit MusicSet(const MusicSetDef& def = {});

  /// The set's settings from a system's #music, #tempo, #ppq, #midiformat, #timesig and
  /// #track.
  static MusicSetDef defFrom(const MusicSettings& settings);

  std::string_view name() const override { return "music"; }
  bool knows(std::string_view command) const override;
  void beginFrame(const FrameTarget& target) override;
  void execute(std::string_view command, std::span<const double> args) override;
  /// `id` indexes musicCommands().
  void executeCommand(int id, std::string_view command, std::span<const double> args) override;
  /// Writes DIR/<stem>.mid atomically (throws OutputError on failure), then performs the
  /// score if a performer is set.
  std::vector<std::filesystem::path> endFrame() override;

  bool followsDevelopment() const override { return def_.time == MusicTime::Developmental; }
  void beginWord(double time) override;
  void beginCell(const CellContext& cell) override;
  void endWord() override;

  /// Plays each finished score, e.g. on a MIDI port.
  void setPerformer(ScorePerformer performer) { output_.setPerformer(std::move(performer)); }
  /// Hands the score to `streamer` as the development makes it: in developmental time
  /// after every word (what lies before the word's time is final), and each finished
  /// frame's score, so live playback can start before the development ends.
  void setStreamer(ScoreStreamer streamer) { streamer_ = std::move(streamer); }

  /// The score of the frame being played, or of the last one after endFrame. While a
  /// frame plays in developmental time, a note `hold` sounds has an infinite duration
  /// until its cell is gone.
  const Score& score() const { return score_; }
  const MusicWarnings& warnings() const { return player_.warnings(); }
  /// Dropped notes, bad arguments and unmatched ] since the last call, located.
  std::vector<SetWarning> takeWarnings() override;
  const MusicSetDef& def() const { return def_; }

 private:
  using CellKey = std::pair<uint64_t, double>;  // id and birth: one life of one cell
  struct Held {
    size_t note;  // index in score_.notes, where it sounds with an infinite duration until closed
    double end;   // beats; infinite until the cell is gone
  };
  void run(const MusicCommand& command, std::span<const double> args);
  void collectHeld();
  void closeHeld(double beats, bool all);
  /// Score::trackNames from the cells that played on each channel.
  void nameTracks();

  MusicSetDef def_;
  WarningCounter droppedNotes_;
  WarningCounter badArguments_;
  WarningCounter unmatchedPops_;
  MusicPlayer player_;
  Score score_;
  FrameTarget target_;
  ScoreOutput output_;  // writes and performs each finished score
  ScoreStreamer streamer_;
  std::array<std::vector<std::string_view>, 16> trackCells_;  // per channel, cells that play notes, in order
  std::array<std::vector<std::string_view>, 16> trackControlCells_;  // per channel, cells that send only controls
  // Developmental time:
  std::set<CellKey> played_;           // cells whose notes have sounded
  std::set<CellKey> seen_;             // cells of the current word
  std::multimap<CellKey, Held> held_;  // notes of `hold`, sounding while their cell lives
  CellKey current_{0, 0};
  double currentLifetime_ = 0;
  double wordTime_ = 0;
  double lastWordTime_ = 0;
};

}  // namespace ontogen
