// The same development as music: models/creature.cell through the music set plays a note
// at each footfall, one pitch per leg, read back by an independent MIDI parser (mido).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>

#include "interpreters/run.h"
#include "tests/core/test_support.h"
#include "tests/interpreters/midi_checkers.h"

namespace ontogen {
namespace {

namespace fs = std::filesystem;

TEST(CreatureMusic, EachFootfallPlaysItsLegsNote) {
  if (!testing_support::haveMido()) {
    const char* ci = std::getenv("CI");
    if (ci != nullptr && std::string(ci) == "true") FAIL() << "python3-mido is missing";
    GTEST_SKIP() << "python3-mido is missing (bash .ci/setup installs it)";
  }
  RunDef def;
  def.program = testing_support::compileModel("creature.cell");
  def.stem = "creature";
  def.sets = {"music"};
  def.out = fs::path(ONTOGEN_BINARY_DIR) / "creature_music_test";
  fs::remove_all(def.out);
  ontogen::Run run(std::move(def));
  const RunReport report = run.execute();
  ASSERT_TRUE(report.ok());
  const nlohmann::json midi = testing_support::dumpMidi(fs::path(ONTOGEN_BINARY_DIR) / "creature_music_test" / "creature.mid");
  const double ppq = midi["ppq"].get<double>();  // #tempo 60: a beat is a second
  // models/creature.cell: 3 segments, DUTY 1/2, PERIOD 1.2 s, until 3.6 s: the legs are
  // made at the end of the first step (t = 0.05) and their footfall cells live a cycle each.
  const double period = 1.2, duty = 0.5;
  std::map<int, std::vector<double>> byPitch;
  for (const auto& note : midi["notes"]) byPitch[note[3].get<int>()].push_back(note[0].get<double>() / ppq);
  ASSERT_EQ(byPitch.size(), 6u) << "one pitch per leg: " << midi.dump();
  std::set<int> expectedPitches;
  for (int m = 0; m < 3; ++m)
    for (int side = 0; side < 2; ++side) {
      const int pitch = 45 + (5 * m + 7 * side) % 36;
      expectedPitches.insert(pitch);
      const std::vector<double>& starts = byPitch[pitch];
      ASSERT_EQ(starts.size(), 3u) << "a footfall a cycle, pitch " << pitch;
      const double phase = m * duty + side / 2.0;
      for (double start : starts) {
        // A touchdown: (k + phase) * period, to the tick.
        const double cycles = start / period - phase;
        EXPECT_NEAR(cycles, std::round(cycles), 1.5 / ppq / period) << "pitch " << pitch << " at " << start;
      }
    }
  std::set<int> seen;
  for (const auto& [pitch, starts] : byPitch) seen.insert(pitch);
  EXPECT_EQ(seen, expectedPitches);
}

}  // namespace
}  // namespace ontogen
