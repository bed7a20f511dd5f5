#include "interpreters/music/music_player.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "model/message_number.h"

namespace ontogen {

namespace {

// Pitches and degrees are kept within this many semitones of 0 so that no arithmetic on
// them can overflow; anything this far out is long past MIDI's 0..127 anyway.
constexpr double kPitchBound = 1e6;

double clampPitch(double pitch) { return std::clamp(pitch, -kPitchBound, kPitchBound); }

int clampToInt(double value, int low, int high) {
  return static_cast<int>(std::clamp(std::round(value), static_cast<double>(low), static_cast<double>(high)));
}

}  // namespace

MusicPlayer::MusicPlayer(const MusicPlayerDef& def) : def_(def) {
  if (!(def.tempo > 0) || !std::isfinite(def.tempo)) throw std::invalid_argument("the tempo must be > 0");
  const MusicState& s = def.initial;
  if (!(s.duration > 0) || !std::isfinite(s.duration)) throw std::invalid_argument("the duration must be > 0");
  if (!(s.gate > 0 && s.gate <= 1)) throw std::invalid_argument("the gate must be > 0 and <= 1");
  if (s.velocity < 1 || s.velocity > 127) throw std::invalid_argument("the velocity must be 1..127");
  if (s.channel < 0 || s.channel > 15) throw std::invalid_argument("the channel must be 0..15");
  if (s.scale < 0 || s.scale >= static_cast<int>(musicScales().size()))
    throw std::invalid_argument("no such scale");
  if (s.key < 0 || s.key > 11) throw std::invalid_argument("the key must be 0..11");
  if (!(def.maxBeats > 0)) throw std::invalid_argument("the latest time must be > 0 beats");
  reset();
}

void MusicPlayer::reset() {
  restart();
  warnings_ = {};
  lastControl_.clear();
  held_.clear();
  tempo_ = def_.tempo;
}

void MusicPlayer::restart() {
  state_ = def_.initial;
  stack_.clear();
}

std::vector<ScoreNote> MusicPlayer::takeHeldNotes() {
  std::vector<ScoreNote> notes;
  notes.swap(held_);
  return notes;
}

bool MusicPlayer::execute(std::string_view command, std::span<const double> args, Score& score) {
  const MusicCommand* found = findMusicCommand(command);
  if (!found) return false;
  execute(*found, args, score);
  return true;
}

bool MusicPlayer::finite(std::span<const double> args) {
  for (double a : args)
    if (!std::isfinite(a)) {
      ++warnings_.badArguments;
      return false;
    }
  return true;
}

void MusicPlayer::execute(const MusicCommand& command, std::span<const double> args, Score& score) {
  if (static_cast<int>(args.size()) < command.minArity ||
      (command.maxArity >= 0 && static_cast<int>(args.size()) > command.maxArity)) {
    // Words from a turtle reading carry arguments the player does not use.
    if (command.op != MusicOp::TurtleNote && command.op != MusicOp::TurtleRest && command.op != MusicOp::TurtleUp &&
        command.op != MusicOp::TurtleDown) {
      ++warnings_.badArguments;
      return;
    }
  }
  auto arg = [&](size_t i, double fallback) { return i < args.size() ? args[i] : fallback; };
  switch (command.op) {
    case MusicOp::TurtleNote:
      playNote(state_.duration, state_.velocity, score);
      return;
    case MusicOp::TurtleRest:
      checkTime(state_.time + state_.duration, "the rest would end at");
      state_.time += state_.duration;
      return;
    case MusicOp::TurtleUp:
      moveDegrees(1);
      return;
    case MusicOp::TurtleDown:
      moveDegrees(-1);
      return;
    case MusicOp::Push:
      stack_.push_back(state_);
      return;
    case MusicOp::Pop:
      if (stack_.empty()) {
        ++warnings_.unmatchedPops;
        return;
      }
      state_ = stack_.back();
      stack_.pop_back();
      return;
    default:
      break;
  }
  if (!finite(args)) return;
  switch (command.op) {
    case MusicOp::Note:
      playNote(arg(0, state_.duration), arg(1, state_.velocity), score);
      break;
    case MusicOp::Play:
      state_.pitch = clampPitch(std::round(args[0]));
      playNote(arg(1, state_.duration), arg(2, state_.velocity), score);
      break;
    case MusicOp::Hold:
      if (!developmental_) {
        playNote(state_.duration, arg(0, state_.velocity), score);
      } else if (notesEnabled_) {
        double pitch = state_.pitch;
        if (pitch < 0 || pitch > 127) {
          ++warnings_.droppedNotes;
          break;
        }
        if (clampToInt(arg(0, state_.velocity), 0, 127) == 0) break;
        held_.push_back(ScoreNote{state_.time, 0, static_cast<uint8_t>(state_.channel), static_cast<uint8_t>(pitch),
                                  static_cast<uint8_t>(clampToInt(arg(0, state_.velocity), 1, 127))});
      }
      break;
    case MusicOp::Rest: {
      double d = arg(0, state_.duration);
      if (!(d > 0)) {
        ++warnings_.badArguments;
        break;
      }
      checkTime(state_.time + d, "the rest would end at");
      state_.time += d;
      break;
    }
    case MusicOp::At:
      checkTime(args[0], "the time would move to");
      setTime(args[0]);
      break;
    case MusicOp::Pitch:
      state_.pitch = clampPitch(std::round(args[0]));
      break;
    case MusicOp::Up:
      state_.pitch = clampPitch(state_.pitch + std::round(arg(0, 1)));
      break;
    case MusicOp::Down:
      state_.pitch = clampPitch(state_.pitch - std::round(arg(0, 1)));
      break;
    case MusicOp::Degree:
      moveDegrees(std::round(args[0]));
      break;
    case MusicOp::Scale: {
      double s = std::round(args[0]);
      if (s < 0 || s >= static_cast<double>(musicScales().size())) {
        ++warnings_.badArguments;
        break;
      }
      state_.scale = static_cast<int>(s);
      break;
    }
    case MusicOp::Key: {
      double k = std::fmod(std::round(clampPitch(args[0])), 12.0);
      state_.key = static_cast<int>(k < 0 ? k + 12 : k);
      break;
    }
    case MusicOp::Velocity:
      state_.velocity = clampToInt(args[0], 0, 127);
      break;
    case MusicOp::Duration:
      if (!(args[0] > 0)) {
        ++warnings_.badArguments;
        break;
      }
      state_.duration = args[0];
      break;
    case MusicOp::Gate:
      if (!(args[0] > 0 && args[0] <= 1)) {
        ++warnings_.badArguments;
        break;
      }
      state_.gate = args[0];
      break;
    case MusicOp::Channel:
      if (args[0] < -0.5 || args[0] >= 15.5) {
        ++warnings_.badArguments;
        break;
      }
      state_.channel = clampToInt(args[0], 0, 15);
      break;
    case MusicOp::Program:
      sendControl(ScoreControl::Kind::Program, 0, args[0], score);
      break;
    case MusicOp::Tempo:
      if (!(args[0] > 0)) {
        ++warnings_.badArguments;
        break;
      }
      if (args[0] != tempo_) {
        tempo_ = args[0];
        score.tempos.push_back(ScoreTempo{state_.time, args[0]});
      }
      break;
    case MusicOp::Controller:
      if (args[0] < -0.5 || args[0] >= 127.5) {
        ++warnings_.badArguments;
        break;
      }
      sendControl(ScoreControl::Kind::Controller, args[0], args[1], score);
      break;
    case MusicOp::Sustain:
      sendControl(ScoreControl::Kind::Controller, 64, args[0] != 0 ? 127 : 0, score);
      break;
    case MusicOp::Modulation:
      sendControl(ScoreControl::Kind::Controller, 1, args[0], score);
      break;
    case MusicOp::Bend:
      // ±2 semitones is the General MIDI default bend range: 8192 per 2 semitones.
      sendControl(ScoreControl::Kind::PitchBend, 0, 8192 + std::clamp(args[0], -2.0, 2.0) * 4096, score);
      break;
    default:
      break;
  }
}

void MusicPlayer::checkTime(double beats, const char* what) const {
  if (beats <= def_.maxBeats) [[likely]]
    return;
  throw MusicTimeError(std::string(what) + " beat " + messageNumber(beats) + ", past beat " +
                       messageNumber(def_.maxBeats) + ", the end of any MIDI file at this resolution (#ppq)");
}

void MusicPlayer::playNote(double duration, double velocity, Score& score) {
  if (!std::isfinite(duration) || !(duration > 0) || !std::isfinite(velocity)) {
    ++warnings_.badArguments;
    return;
  }
  checkTime(state_.time + duration, "the note would end at");
  // Velocity 0 is MIDI's note-off: such a note is a rest, so blocks can silence notes
  // with an expression, e.g. note(1, if(on, 90, 0)).
  if (notesEnabled_ && clampToInt(velocity, 0, 127) > 0) {
    if (state_.pitch < 0 || state_.pitch > 127) {
      ++warnings_.droppedNotes;
    } else {
      score.notes.push_back(ScoreNote{state_.time, duration * state_.gate, static_cast<uint8_t>(state_.channel),
                                      static_cast<uint8_t>(state_.pitch),
                                      static_cast<uint8_t>(clampToInt(velocity, 1, 127))});
    }
  }
  state_.time += duration;
}

void MusicPlayer::moveDegrees(double degrees) {
  std::span<const int> steps = musicScales()[static_cast<size_t>(state_.scale)].steps;
  const long size = static_cast<long>(steps.size());
  long relative = static_cast<long>(state_.pitch) - state_.key;
  long octave = relative >= 0 ? relative / 12 : -((-relative + 11) / 12);
  long within = relative - octave * 12;  // 0..11
  long index = 0;
  while (index + 1 < size && steps[static_cast<size_t>(index + 1)] <= within) ++index;
  long moves = static_cast<long>(std::clamp(degrees, -kPitchBound, kPitchBound));
  // Off the scale, falling to the scale note below is already the first step down.
  if (steps[static_cast<size_t>(index)] != within && moves < 0) ++moves;
  long degree = octave * size + index + moves;
  long newOctave = degree >= 0 ? degree / size : -((-degree + size - 1) / size);
  long newIndex = degree - newOctave * size;
  state_.pitch = clampPitch(static_cast<double>(state_.key + newOctave * 12 + steps[static_cast<size_t>(newIndex)]));
}

void MusicPlayer::sendControl(ScoreControl::Kind kind, double number, double value, Score& score) {
  int high = kind == ScoreControl::Kind::PitchBend ? 16383 : 127;
  int v = clampToInt(value, 0, high);
  int n = clampToInt(number, 0, 127);
  if (developmental_) {
    auto key = std::make_tuple(static_cast<int>(kind), state_.channel, n);
    auto it = lastControl_.find(key);
    if (it != lastControl_.end() && it->second == v) return;
    lastControl_[key] = v;
  }
  score.controls.push_back(ScoreControl{state_.time, kind, static_cast<uint8_t>(state_.channel),
                                        static_cast<uint8_t>(n), static_cast<uint16_t>(v)});
}

}  // namespace ontogen
