#include "interpreters/music/live_playback.h"

#include <span>
#include <stdexcept>

namespace ontogen {

LivePlayback::LivePlayback(LivePlaybackDef def) : def_(std::move(def)), output_(def_.midi) {
  if (!def_.stop) throw std::invalid_argument("LivePlaybackDef::stop is required");
}

LivePlayback::~LivePlayback() {
  def_.stop->store(true);
  join();
}

void LivePlayback::attach(const std::shared_ptr<LivePlayback>& playback, MusicSet& music) {
  std::weak_ptr<LivePlayback> weak = playback;
  music.setStreamer([weak](const Score& score, double horizon, bool finished, const MidiFileDef& file) {
    if (auto live = weak.lock()) live->stream(score, horizon, finished, file);
  });
}

void LivePlayback::stream(const Score& score, double horizon, bool finished, const MidiFileDef& file) {
  if (def_.stop->load()) {
    join();  // its notes are stopped before the run ends
    throw PlaybackInterrupted("interrupted: every note stopped");
  }
  if (std::string failed = error(); !failed.empty()) throw OutputError(failed);
  if (!performer_.joinable()) start();
  if (!encoder_) {
    encoder_.emplace(file.ppq, file.tempo);
    sequence_ = MidiSequence{};
    forwarded_ = 0;
    stream_.begin(file.ppq);
  }
  try {
    if (finished)
      encoder_->finish(score, sequence_);
    else
      encoder_->advance(score, horizon, sequence_);
  } catch (const std::invalid_argument& bad) {
    throw OutputError(std::string("live MIDI: ") + bad.what());
  }
  stream_.add(std::span(sequence_.messages).subspan(forwarded_), sequence_.tempos, encoder_->released(), finished);
  forwarded_ = sequence_.messages.size();
  if (finished) encoder_.reset();
}

PlaybackOutcome LivePlayback::finish() {
  stream_.close();
  join();
  return PlaybackOutcome{report_, error()};
}

void LivePlayback::start() {
  if (def_.started) def_.started(output_.portName());
  performer_ = std::thread([this] {
    try {
      report_ = output_.perform(stream_, *def_.stop);
    } catch (const LiveMidiError& failure) {
      std::lock_guard lock(errorMutex_);
      error_ = failure.what();
    }
  });
}

void LivePlayback::join() {
  stream_.close();
  if (performer_.joinable()) performer_.join();
}

std::string LivePlayback::error() {
  std::lock_guard lock(errorMutex_);
  return error_;
}

}  // namespace ontogen
