// MIDI writing throughput: a Score of N notes on 16 channels with controllers and tempo
// changes, encoded as a Standard MIDI File (format 1 and 0), in MIDI events (channel
// messages, note-offs included) per second. Also the player filling the score from
// instructions, and the whole path from a Koch word to the file bytes.

#include <benchmark/benchmark.h>

#include <random>
#include <string>

#include "bench/bench_support.h"
#include "interpreters/interpret.h"
#include "interpreters/music/midi_file_writer.h"
#include "interpreters/music/midi_sequence.h"
#include "interpreters/music/music_player.h"
#include "interpreters/music/music_set.h"

namespace ontogen::bench {
namespace {

Score makeScore(int notes) {
  std::mt19937 random(1);
  Score score;
  score.notes.reserve(static_cast<size_t>(notes));
  double time = 0;
  for (int i = 0; i < notes; ++i) {
    time += 0.125 * (random() % 4);
    score.notes.push_back({time, 0.25 * (1 + random() % 4), static_cast<uint8_t>(random() % 16),
                           static_cast<uint8_t>(36 + random() % 60), static_cast<uint8_t>(1 + random() % 127)});
    if (i % 8 == 0)
      score.controls.push_back({time, ScoreControl::Kind::Controller, static_cast<uint8_t>(random() % 16), 1,
                                static_cast<uint16_t>(random() % 128)});
    if (i % 1000 == 0) score.tempos.push_back({time, 90.0 + random() % 60});
  }
  return score;
}

void encode(benchmark::State& state, int format) {
  Score score = makeScore(static_cast<int>(state.range(0)));
  MidiFileDef def;
  def.format = format;
  size_t events = makeMidiSequence(score, def.ppq, def.tempo).messages.size();
  size_t bytes = 0;
  for (auto _ : state) {
    std::vector<uint8_t> file = encodeMidiFile(score, def);
    bytes = file.size();
    benchmark::DoNotOptimize(file.data());
  }
  if (bytes < events * 2) state.SkipWithError("the file is shorter than its events");
  state.counters["events/s"] = benchmark::Counter(static_cast<double>(events), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["bytes/event"] = static_cast<double>(bytes) / static_cast<double>(events);
}

void BM_MidiEncodeFormat1(benchmark::State& state) { encode(state, 1); }
void BM_MidiEncodeFormat0(benchmark::State& state) { encode(state, 0); }
BENCHMARK(BM_MidiEncodeFormat1)->Arg(1000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MidiEncodeFormat0)->Arg(1000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);

// The player turning instructions into a score: note, degree moves and voices.
void BM_MusicPlayerInstructions(benchmark::State& state) {
  const int count = static_cast<int>(state.range(0));
  MusicPlayer player;
  Score score;
  const double none[] = {0};
  for (auto _ : state) {
    player.reset();
    score.clear();
    for (int i = 0; i < count; ++i) {
      player.execute(i % 3 == 0 ? "+" : i % 3 == 1 ? "F" : "-", std::span<const double>(none, 0), score);
    }
    benchmark::DoNotOptimize(score.notes.data());
  }
  if (score.notes.size() != static_cast<size_t>((count + 1) / 3)) state.SkipWithError("wrong number of notes");
  state.counters["instructions/s"] = benchmark::Counter(count, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_MusicPlayerInstructions)->Arg(1000000)->Unit(benchmark::kMillisecond);

// From a grown Koch word (5^n notes) to the file's bytes: interpretation + encoding.
void BM_KochWordToMidi(benchmark::State& state) {
  Compiled compiled = compileText("koch.cell", "lsystem k {\n  axiom F\n  F -> F + F - F - F + F\n}\n");
  if (!compiled.program) {
    state.SkipWithError(compiled.error.c_str());
    return;
  }
  World world(compiled.program, kBenchWorld);
  world.advanceTo(static_cast<double>(state.range(0)), 1);
  MusicSet set(MusicSetDef{.writeFile = false});
  size_t events = 0;
  for (auto _ : state) {
    set.beginFrame(FrameTarget{});
    interpretWord(world, set);
    std::vector<uint8_t> file = encodeMidiFile(set.score(), MidiFileDef{});
    events = set.score().notes.size() * 2;
    benchmark::DoNotOptimize(file.data());
  }
  size_t expected = 1;
  for (int i = 0; i < state.range(0); ++i) expected *= 5;
  if (set.score().notes.size() != expected) state.SkipWithError("wrong number of notes");
  state.counters["events/s"] = benchmark::Counter(static_cast<double>(events), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_KochWordToMidi)->Arg(6)->Arg(8)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace ontogen::bench
