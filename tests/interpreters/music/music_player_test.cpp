#include "interpreters/music/music_player.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string_view>
#include <vector>

namespace ontogen {
namespace {

struct Played {
  MusicPlayer player;
  Score score;
  void run(std::string_view command, std::vector<double> args = {}) {
    ASSERT_TRUE(player.execute(command, args, score)) << command;
  }
  double scaleOf(std::string_view name) { return *musicConstant(name); }
};

TEST(MusicPlayer, NotesFollowEachOtherAndAdvanceTime) {
  Played p;
  p.run("note");
  p.run("up", {2});
  p.run("note", {0.5, 90});
  p.run("rest", {1.5});
  p.run("play", {67, 2});
  ASSERT_EQ(p.score.notes.size(), 3u);
  EXPECT_EQ(p.score.notes[0].start, 0);
  EXPECT_EQ(p.score.notes[0].pitch, 60);
  EXPECT_EQ(p.score.notes[0].duration, 1);
  EXPECT_EQ(p.score.notes[0].velocity, 100);
  EXPECT_EQ(p.score.notes[1].start, 1);
  EXPECT_EQ(p.score.notes[1].pitch, 62);
  EXPECT_EQ(p.score.notes[1].duration, 0.5);
  EXPECT_EQ(p.score.notes[1].velocity, 90);
  EXPECT_EQ(p.score.notes[2].start, 3);
  EXPECT_EQ(p.score.notes[2].pitch, 67);
  EXPECT_EQ(p.player.state().time, 5);
}

TEST(MusicPlayer, DegreesWalkTheScaleInTheKey) {
  Played p;
  // C major from middle C: D E F G ... and down through B A.
  std::vector<int> up;
  for (int i = 0; i < 8; ++i) {
    p.run("degree", {1});
    up.push_back(static_cast<int>(p.player.state().pitch));
  }
  EXPECT_EQ(up, (std::vector<int>{62, 64, 65, 67, 69, 71, 72, 74}));
  p.run("pitch", {60});
  p.run("degree", {-2});
  EXPECT_EQ(p.player.state().pitch, 57);
  // D minor (key 2): D E F G A Bb C D.
  p.run("scale", {p.scaleOf("minor")});
  p.run("key", {62});
  p.run("pitch", {62});
  std::vector<int> minor;
  for (int i = 0; i < 7; ++i) {
    p.run("+");
    minor.push_back(static_cast<int>(p.player.state().pitch));
  }
  EXPECT_EQ(minor, (std::vector<int>{64, 65, 67, 69, 70, 72, 74}));
  p.run("-");
  EXPECT_EQ(p.player.state().pitch, 72);
}

TEST(MusicPlayer, PitchOffTheScaleFallsToTheNoteBelowFirst) {
  Played p;
  p.run("pitch", {61});  // C# in C major
  p.run("degree", {1});
  EXPECT_EQ(p.player.state().pitch, 62);
  p.run("pitch", {61});
  p.run("degree", {-1});
  EXPECT_EQ(p.player.state().pitch, 60);
  p.run("pitch", {61});
  p.run("degree", {-2});
  EXPECT_EQ(p.player.state().pitch, 59);
}

TEST(MusicPlayer, BranchesAreVoicesStartingTogether) {
  Played p;
  p.run("[");
  p.run("up", {4});
  p.run("note", {2});
  p.run("]");
  p.run("[");
  p.run("up", {7});
  p.run("note", {2});
  p.run("]");
  p.run("note", {2});
  p.run("note");
  ASSERT_EQ(p.score.notes.size(), 4u);
  EXPECT_EQ(p.score.notes[0].start, 0);
  EXPECT_EQ(p.score.notes[0].pitch, 64);
  EXPECT_EQ(p.score.notes[1].start, 0);
  EXPECT_EQ(p.score.notes[1].pitch, 67);
  EXPECT_EQ(p.score.notes[2].start, 0);
  EXPECT_EQ(p.score.notes[2].pitch, 60);
  EXPECT_EQ(p.score.notes[3].start, 2);
  p.run("]");
  EXPECT_EQ(p.player.warnings().unmatchedPops, 1);
}

TEST(MusicPlayer, BadValuesAreDroppedOrClampedAndCounted) {
  Played p;
  p.run("pitch", {130});
  p.run("note");  // above 127: dropped, but time moves on
  p.run("pitch", {-3});
  p.run("note");
  EXPECT_EQ(p.player.warnings().droppedNotes, 2);
  EXPECT_TRUE(p.score.notes.empty());
  EXPECT_EQ(p.player.state().time, 2);
  p.run("note", {-1});  // negative length: nothing happens
  p.run("rest", {0});
  p.run("duration", {0});
  p.run("note", {std::numeric_limits<double>::quiet_NaN()});
  p.run("scale", {99});
  EXPECT_EQ(p.player.warnings().badArguments, 5);
  EXPECT_EQ(p.player.state().time, 2);
  EXPECT_EQ(p.player.state().duration, 1);
  p.run("pitch", {60});
  p.run("velocity", {300});
  p.run("note");
  p.run("note", {1, 0.7});
  double before = p.player.state().time;
  p.run("velocity", {-4});
  p.run("note");  // velocity 0: silent, a rest
  p.run("note", {2, 0.2});
  ASSERT_EQ(p.score.notes.size(), 2u);
  EXPECT_EQ(p.score.notes[0].velocity, 127);
  EXPECT_EQ(p.score.notes[1].velocity, 1);
  EXPECT_EQ(p.player.state().time, before + 3);
  p.run("at", {-2});
  EXPECT_EQ(p.player.state().time, 0);
  p.run("at", {7.5});
  EXPECT_EQ(p.player.state().time, 7.5);
}

TEST(MusicPlayer, ControllersProgramsBendsAndTempo) {
  Played p;
  p.run("channel", {3});
  p.run("program", {40});
  p.run("cc", {7, 200});
  p.run("sustain", {1});
  p.run("modulation", {-5});
  p.run("bend", {1});
  p.run("bend", {-9});
  p.run("tempo", {90});
  ASSERT_EQ(p.score.controls.size(), 6u);
  using Kind = ScoreControl::Kind;
  const auto& c = p.score.controls;
  EXPECT_EQ(c[0].kind, Kind::Program);
  EXPECT_EQ(c[0].value, 40);
  EXPECT_EQ(c[0].channel, 3);
  EXPECT_EQ(c[1].number, 7);
  EXPECT_EQ(c[1].value, 127);
  EXPECT_EQ(c[2].number, 64);
  EXPECT_EQ(c[2].value, 127);
  EXPECT_EQ(c[3].number, 1);
  EXPECT_EQ(c[3].value, 0);
  EXPECT_EQ(c[4].kind, Kind::PitchBend);
  EXPECT_EQ(c[4].value, 8192 + 4096);
  EXPECT_EQ(c[5].value, 0);
  ASSERT_EQ(p.score.tempos.size(), 1u);
  EXPECT_EQ(p.score.tempos[0].bpm, 90);
  p.run("channel", {16});  // out of 0..15: ignored
  EXPECT_EQ(p.player.state().channel, 3);
}

TEST(MusicPlayer, DevelopmentalTimeSendsOnlyControllerChangesAndCollectsHeldNotes) {
  Played p;
  p.player.setDevelopmental(true);
  p.run("modulation", {10});
  p.run("modulation", {10});
  p.run("modulation", {11});
  EXPECT_EQ(p.score.controls.size(), 2u);
  p.player.setTime(2.5);
  p.run("hold", {70});
  EXPECT_TRUE(p.score.notes.empty());
  auto held = p.player.takeHeldNotes();
  ASSERT_EQ(held.size(), 1u);
  EXPECT_EQ(held[0].start, 2.5);
  EXPECT_EQ(held[0].velocity, 70);
  EXPECT_TRUE(p.player.takeHeldNotes().empty());
  p.player.setNotesEnabled(false);
  p.run("note");
  EXPECT_TRUE(p.score.notes.empty());
}

TEST(MusicPlayer, RejectsABadDefinition) {
  MusicPlayerDef def;
  def.tempo = 0;
  EXPECT_THROW(MusicPlayer{def}, std::invalid_argument);
  def = {};
  def.initial.channel = 16;
  EXPECT_THROW(MusicPlayer{def}, std::invalid_argument);
}

TEST(MusicCommands, EveryCommandHasADocAndAUniqueName) {
  for (const MusicCommand& command : musicCommands()) {
    EXPECT_FALSE(command.doc.empty()) << command.name;
    EXPECT_EQ(findMusicCommand(command.name), &command);
  }
  EXPECT_EQ(musicConstant("major"), 0.0);
  EXPECT_FALSE(musicConstant("nonsense"));
}

}  // namespace
}  // namespace ontogen

namespace ontogen {
namespace {

TEST(MusicPlayer, TheGateShortensWhatSoundsButNotTheBeat) {
  MusicPlayer player;
  Score score;
  auto run = [&](std::string_view command, std::vector<double> args = {}) { player.execute(command, args, score); };
  run("gate", {0.5});
  run("note", {1});
  run("note", {0.25, 60});
  run("[");
  run("gate", {1});
  run("note", {2});
  run("]");
  run("F");  // the turtle reading: duration 1 at the gate the ] restored
  ASSERT_EQ(score.notes.size(), 4u);
  EXPECT_EQ(score.notes[0].start, 0);
  EXPECT_EQ(score.notes[0].duration, 0.5);
  EXPECT_EQ(score.notes[1].start, 1);
  EXPECT_EQ(score.notes[1].duration, 0.125);
  EXPECT_EQ(score.notes[1].velocity, 60);
  EXPECT_EQ(score.notes[2].start, 1.25);
  EXPECT_EQ(score.notes[2].duration, 2);
  EXPECT_EQ(score.notes[3].start, 1.25);
  EXPECT_EQ(score.notes[3].duration, 0.5);
  EXPECT_EQ(player.state().time, 2.25);
  // Outside 0 < g <= 1 the gate is left as it was and the command counted.
  for (double bad : {0.0, -0.5, 1.5, std::numeric_limits<double>::quiet_NaN()}) run("gate", {bad});
  EXPECT_EQ(player.warnings().badArguments, 4);
  EXPECT_EQ(player.state().gate, 0.5);
  MusicPlayerDef def;
  def.initial.gate = 0;
  EXPECT_THROW(MusicPlayer{def}, std::invalid_argument);
}

}  // namespace
}  // namespace ontogen
