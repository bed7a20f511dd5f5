#include "interpreters/music/music_set.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "interpreters/output_file.h"

namespace ontogen {

namespace {
// No later than the MIDI file reaches at its resolution.
MusicPlayerDef playerWithin(const MusicSetDef& def) {
  MusicPlayerDef player = def.player;
  if (def.file.ppq > 0) player.maxBeats = std::min(player.maxBeats, musicBeatsWithin(def.file.ppq));
  return player;
}
}  // namespace

MusicSet::MusicSet(const MusicSetDef& def)
    : def_(def), player_(playerWithin(def)), output_(ScoreOutputDef{def.file, def.writeFile}) {
  checkMidiFileDef(def.file);
  player_.setDevelopmental(def.time == MusicTime::Developmental);
}

MusicSetDef MusicSet::defFrom(const MusicSettings& settings) {
  MusicSetDef def;
  def.time = settings.time;
  def.player.tempo = settings.tempo;
  def.file.tempo = settings.tempo;
  def.file.ppq = settings.ppq;
  def.file.format = settings.format;
  def.file.timeSignatureNumerator = settings.timeSignatureNumerator;
  def.file.timeSignatureDenominator = settings.timeSignatureDenominator;
  def.trackNames = settings.trackNames;
  return def;
}

bool MusicSet::knows(std::string_view command) const { return findMusicCommand(command) != nullptr; }

void MusicSet::beginFrame(const FrameTarget& target) {
  target_ = target;
  player_.reset();
  score_.clear();
  played_.clear();
  seen_.clear();
  held_.clear();
  trackCells_ = {};
  trackControlCells_ = {};
  wordTime_ = lastWordTime_ = 0;
}

void MusicSet::execute(std::string_view command, std::span<const double> args) {
  if (const MusicCommand* found = findMusicCommand(command)) run(*found, args);
}

void MusicSet::executeCommand(int id, std::string_view command, std::span<const double> args) {
  const auto table = musicCommands();
  if (id >= 0 && static_cast<size_t>(id) < table.size())
    run(table[id], args);
  else
    execute(command, args);
}

void MusicSet::run(const MusicCommand& command, std::span<const double> args) {
  const MusicWarnings before = player_.warnings();
  const size_t notes = score_.notes.size() + player_.heldCount(), controls = score_.controls.size();
  try {
    player_.execute(command, args, score_);
  } catch (const MusicTimeError& late) {
    refuse(late.what());
  }
  // A track is named after the cells that play notes on it; a cell that only sets the
  // program, a controller or the tempo names it only when no cell plays there.
  const bool played = score_.notes.size() + player_.heldCount() != notes;
  if ((played || score_.controls.size() != controls) && !site_.cell.empty()) {
    const size_t channel = static_cast<size_t>(player_.state().channel);
    std::vector<std::string_view>& cells = played ? trackCells_[channel] : trackControlCells_[channel];
    if (std::find(cells.begin(), cells.end(), site_.cell) == cells.end()) cells.push_back(site_.cell);
  }
  const MusicWarnings& after = player_.warnings();
  droppedNotes_.add(static_cast<uint64_t>(after.droppedNotes - before.droppedNotes), site_);
  badArguments_.add(static_cast<uint64_t>(after.badArguments - before.badArguments), site_);
  unmatchedPops_.add(static_cast<uint64_t>(after.unmatchedPops - before.unmatchedPops), site_);
}

std::vector<SetWarning> MusicSet::takeWarnings() {
  std::vector<SetWarning> out;
  droppedNotes_.takeInto(out, "the music player skipped " + std::to_string(droppedNotes_.count) +
                                  " notes outside MIDI's 0..127 (the first here; docs/LANGUAGE.md, \"Music\")");
  badArguments_.takeInto(out, "the music player skipped " + std::to_string(badArguments_.count) +
                                  " commands with bad arguments (the first here)");
  unmatchedPops_.takeInto(out, "the music player ignored " + std::to_string(unmatchedPops_.count) +
                                   " unmatched ']' (the first here)");
  return out;
}

void MusicSet::beginWord(double time) {
  player_.restart();
  seen_.clear();
  lastWordTime_ = wordTime_;
  wordTime_ = time;
}

void MusicSet::beginCell(const CellContext& cell) {
  if (!followsDevelopment()) return;
  collectHeld();
  current_ = {cell.id, cell.birth};
  currentLifetime_ = cell.lifetime;
  seen_.insert(current_);
  bool first = played_.insert(current_).second;
  // A new cell plays from its birth; a cell that already played only updates controllers,
  // at the time of the word.
  player_.setNotesEnabled(first);
  player_.setTime(first ? cell.birth : cell.time);
}

void MusicSet::collectHeld() {
  for (ScoreNote& note : player_.takeHeldNotes()) {
    double end = current_.second + currentLifetime_;
    // In the score at once, still sounding: a streamed performance sends its note-on now.
    note.duration = INFINITY;
    score_.notes.push_back(note);
    held_.emplace(current_, Held{score_.notes.size() - 1, std::isfinite(end) ? end : INFINITY});
  }
}

void MusicSet::closeHeld(double beats, bool all) {
  for (auto it = held_.begin(); it != held_.end();) {
    if (!all && seen_.count(it->first)) {
      ++it;
      continue;
    }
    // A cell that died of age ended exactly then; one removed otherwise is noticed at
    // the first word without it.
    double end = std::min(it->second.end, beats);
    ScoreNote& note = score_.notes[it->second.note];
    // A note that ended before it began has no length, and the writer leaves it out.
    note.duration = std::max(end - note.start, 0.0);
    it = held_.erase(it);
  }
}

void MusicSet::endWord() {
  if (!followsDevelopment()) return;
  collectHeld();
  closeHeld(wordTime_, false);
  if (streamer_) streamer_(score_, wordTime_, false, def_.file);
}

void MusicSet::nameTracks() {
  // A DAW shows a few words; past this many cells the name says how many more there are.
  constexpr size_t kNamedCells = 4;
  for (size_t channel = 0; channel < trackCells_.size(); ++channel) {
    if (!def_.trackNames[channel].empty()) {
      score_.trackNames[channel] = def_.trackNames[channel];
      continue;
    }
    const std::vector<std::string_view>& cells =
        trackCells_[channel].empty() ? trackControlCells_[channel] : trackCells_[channel];
    std::string name;
    for (size_t i = 0; i < cells.size() && i < kNamedCells; ++i) name += (i ? ", " : "") + std::string(cells[i]);
    if (cells.size() > kNamedCells) name += " and " + std::to_string(cells.size() - kNamedCells) + " more";
    score_.trackNames[channel] = std::move(name);
  }
}

std::vector<std::filesystem::path> MusicSet::endFrame() {
  if (followsDevelopment()) closeHeld(wordTime_, true);
  nameTracks();
  std::vector<std::filesystem::path> written = output_.write(score_, target_);
  if (streamer_) streamer_(score_, INFINITY, true, def_.file);
  return written;
}

}  // namespace ontogen
