#include "interpreters/music/midi_file_writer.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>
#include <vector>

#include "interpreters/music/midi_sequence.h"
#include "tests/interpreters/midi_checkers.h"
#include "tests/checkers.h"

namespace ontogen {
namespace {

namespace fs = std::filesystem;
using namespace testing_support;

std::vector<uint8_t> vlq(uint32_t value) {
  std::vector<uint8_t> bytes;
  appendVariableLength(bytes, value);
  return bytes;
}

// The examples of the SMF 1.0 specification's table of variable-length quantities.
TEST(MidiFileWriter, VariableLengthQuantitiesMatchTheSpecification) {
  EXPECT_EQ(vlq(0x00), (std::vector<uint8_t>{0x00}));
  EXPECT_EQ(vlq(0x40), (std::vector<uint8_t>{0x40}));
  EXPECT_EQ(vlq(0x7F), (std::vector<uint8_t>{0x7F}));
  EXPECT_EQ(vlq(0x80), (std::vector<uint8_t>{0x81, 0x00}));
  EXPECT_EQ(vlq(0x2000), (std::vector<uint8_t>{0xC0, 0x00}));
  EXPECT_EQ(vlq(0x3FFF), (std::vector<uint8_t>{0xFF, 0x7F}));
  EXPECT_EQ(vlq(0x4000), (std::vector<uint8_t>{0x81, 0x80, 0x00}));
  EXPECT_EQ(vlq(0x100000), (std::vector<uint8_t>{0xC0, 0x80, 0x00}));
  EXPECT_EQ(vlq(0x1FFFFF), (std::vector<uint8_t>{0xFF, 0xFF, 0x7F}));
  EXPECT_EQ(vlq(0x200000), (std::vector<uint8_t>{0x81, 0x80, 0x80, 0x00}));
  EXPECT_EQ(vlq(0x0FFFFFFF), (std::vector<uint8_t>{0xFF, 0xFF, 0xFF, 0x7F}));
  EXPECT_THROW(vlq(0x10000000), std::invalid_argument);
}

TEST(MidiFileWriter, AChordInFormatZeroIsExactlyTheseBytes) {
  Score score;
  score.notes.push_back({0, 1, 0, 60, 100});
  score.notes.push_back({0, 1, 0, 64, 100});
  MidiFileDef def;
  def.format = 0;
  def.ppq = 96;
  std::vector<uint8_t> expected = {
      'M', 'T', 'h', 'd', 0, 0, 0, 6, 0, 0, 0, 1, 0, 96,  // format 0, one track, 96 ppq
      'M', 'T', 'r', 'k', 0, 0, 0, 33,                     // 33 bytes follow
      0x00, 0xFF, 0x58, 4, 4, 2, 24, 8,                    // 4/4
      0x00, 0xFF, 0x51, 3, 0x07, 0xA1, 0x20,               // 500000 us a quarter: 120 bpm
      0x00, 0x90, 60, 100,                                 // note-on C4
      0x00, 64, 100,                                       // running status: note-on E4
      0x60, 0x80, 60, 64,                                  // 96 ticks later, note-off C4
      0x00, 64, 64,                                        // running status: note-off E4
      0x00, 0xFF, 0x2F, 0,                                 // end of track
  };
  EXPECT_EQ(encodeMidiFile(score, def), expected);
}

TEST(MidiFileWriter, EachChannelsTrackStartsWithItsName) {
  Score score;
  score.notes.push_back({0, 1, 2, 40, 100});
  score.trackNames[2] = "Bass";
  score.trackNames[5] = "unused";  // a channel without messages has no track
  MidiFileDef def;
  def.ppq = 96;
  std::vector<uint8_t> bytes = encodeMidiFile(score, def);
  EXPECT_EQ(bytes[11], 2);  // two tracks: the conductor and channel 2's
  const std::vector<uint8_t> track = {'M', 'T', 'r', 'k', 0, 0, 0, 20,           // 20 bytes follow
                                      0x00, 0xFF, 0x03, 4, 'B', 'a', 's', 's',  // its name first
                                      0x00, 0x92, 40, 100, 0x60, 0x82, 40, 64, 0x00, 0xFF, 0x2F, 0};
  ASSERT_GE(bytes.size(), track.size());
  EXPECT_EQ(std::vector<uint8_t>(bytes.end() - static_cast<long>(track.size()), bytes.end()), track);
  score.trackNames[2] = std::string(70000, 'x');
  EXPECT_THROW(encodeMidiFile(score, def), std::invalid_argument);
}

TEST(MidiFileWriter, OverlappingNotesOfOnePitchRetriggerAndEveryNoteOnEnds) {
  Score score;
  score.notes.push_back({0, 2, 0, 50, 100});
  score.notes.push_back({1, 2, 0, 50, 90});
  MidiSequence sequence = makeMidiSequence(score, 10, 120);
  ASSERT_EQ(sequence.messages.size(), 4u);
  EXPECT_EQ(sequence.messages[0].status, 0x90);
  EXPECT_EQ(sequence.messages[1].status, 0x80);  // retrigger at tick 10
  EXPECT_EQ(sequence.messages[1].tick, 10u);
  EXPECT_EQ(sequence.messages[2].status, 0x90);
  EXPECT_EQ(sequence.messages[2].tick, 10u);
  EXPECT_EQ(sequence.messages[3].status, 0x80);
  EXPECT_EQ(sequence.messages[3].tick, 30u);
}

// At one tick a note-off goes before a controller, and a controller before a note-on, so
// that a note followed at once by the same pitch ends and sounds again; then the score's
// order.
TEST(MidiFileWriter, AtOneTickNoteOffsGoFirstThenControlsThenNoteOns) {
  Score score;
  score.notes.push_back({1, 1, 0, 50, 90});  // given first, starts where the next ends
  score.notes.push_back({0, 1, 0, 50, 100});
  score.notes.push_back({1, 1, 0, 52, 80});
  score.controls.push_back({1, ScoreControl::Kind::Controller, 0, 7, 99});
  score.controls.push_back({1, ScoreControl::Kind::Controller, 0, 10, 64});
  const MidiSequence sequence = makeMidiSequence(score, 10, 120);
  const std::vector<std::vector<int>> expected = {
      {0, 0x90, 50, 100}, {10, 0x80, 50, 64}, {10, 0xB0, 7, 99}, {10, 0xB0, 10, 64},
      {10, 0x90, 50, 90}, {10, 0x90, 52, 80}, {20, 0x80, 50, 64}, {20, 0x80, 52, 64}};
  std::vector<std::vector<int>> messages;
  for (const MidiMessage& m : sequence.messages)
    messages.push_back({static_cast<int>(m.tick), m.status, m.data1, m.data2});
  EXPECT_EQ(messages, expected);
}

TEST(MidiFileWriter, ScoreValuesOutsideMidiAreLeftOutAndBadSettingsRejected) {
  Score score;
  score.notes.push_back({0, 1, 0, 200, 100});  // pitch > 127
  score.notes.push_back({0, -1, 0, 60, 100});  // negative duration
  score.notes.push_back({0, 1, 16, 60, 100});  // channel > 15
  MidiSequence sequence = makeMidiSequence(score, 96, 120);
  EXPECT_TRUE(sequence.messages.empty());
  MidiFileDef def;
  def.format = 2;
  EXPECT_THROW(encodeMidiFile(score, def), std::invalid_argument);
  def = {};
  def.ppq = 0;
  EXPECT_THROW(encodeMidiFile(score, def), std::invalid_argument);
  def = {};
  def.timeSignatureDenominator = 3;
  EXPECT_THROW(encodeMidiFile(score, def), std::invalid_argument);
  def = {};
  def.tempo = -1;
  EXPECT_THROW(encodeMidiFile(score, def), std::invalid_argument);
}

TEST(MidiSequence, SecondsFollowTheTempoMap) {
  Score score;
  score.tempos.push_back({4, 60});
  score.notes.push_back({6, 1, 0, 60, 100});
  MidiSequence sequence = makeMidiSequence(score, 480, 120);
  EXPECT_DOUBLE_EQ(sequence.secondsAt(4 * 480), 2.0);      // 4 beats at 120 bpm
  EXPECT_DOUBLE_EQ(sequence.secondsAt(6 * 480), 2.0 + 2);  // then 2 beats at 60 bpm
}

class MidiRoundTrip : public ::testing::Test {
 protected:
  void SetUp() override {
    ONTOGEN_REQUIRE_CHECKER(haveMido(), "python3-mido is not installed (bash .ci/setup installs it)");
    directory_ = fs::temp_directory_path() / ("ontogen_midi_" + std::to_string(::getpid()));
    fs::create_directories(directory_);
  }
  void TearDown() override { fs::remove_all(directory_); }

  fs::path write(const Score& score, const MidiFileDef& def, const std::string& name) {
    fs::path path = directory_ / name;
    std::ofstream out(path, std::ios::binary);
    writeMidiFile(score, def, out);
    return path;
  }

  fs::path directory_;
};

/// Notes in lanes (channel, pitch) that never overlap, so every note maps to exactly one
/// note-on/note-off pair; gaps up to 300 beats make delta times of 1 to 3 bytes.
Score randomScore(uint32_t seed, int count) {
  std::mt19937 random(seed);
  Score score;
  std::vector<double> laneEnd(16 * 128, 0);
  for (int i = 0; i < count; ++i) {
    int channel = static_cast<int>(random() % 16);
    int pitch = 24 + static_cast<int>(random() % 80);
    double& end = laneEnd[channel * 128 + pitch];
    double start = end + (random() % 4) * 0.25 + (random() % 50 == 0 ? 300 : 0);
    double duration = 0.25 * (1 + random() % 8);
    end = start + duration;
    score.notes.push_back({start, duration, static_cast<uint8_t>(channel), static_cast<uint8_t>(pitch),
                           static_cast<uint8_t>(1 + random() % 127)});
  }
  return score;
}

nlohmann::json expectedNotes(const Score& score, int ppq) {
  nlohmann::json notes = nlohmann::json::array();
  for (const ScoreNote& note : score.notes)
    notes.push_back({std::llround(note.start * ppq), std::llround((note.start + note.duration) * ppq), note.channel,
                     note.pitch, note.velocity});
  std::vector<nlohmann::json> sorted(notes.begin(), notes.end());
  std::sort(sorted.begin(), sorted.end());
  return nlohmann::json(sorted);
}

TEST_F(MidiRoundTrip, MidoReadsEveryNoteTimeChannelAndProgramBack) {
  Score score;
  score.notes.push_back({0, 1, 0, 60, 100});
  score.notes.push_back({0.5, 1.5, 0, 64, 80});
  score.notes.push_back({1, 0.25, 9, 36, 127});  // a kick drum
  score.notes.push_back({2, 3, 2, 50, 70});
  score.notes.push_back({3, 3, 2, 50, 71});      // overlaps the one before: retriggers at 3
  score.controls.push_back({0, ScoreControl::Kind::Program, 0, 0, 40});
  score.controls.push_back({0, ScoreControl::Kind::Program, 2, 0, 73});
  score.controls.push_back({1.5, ScoreControl::Kind::Controller, 2, 1, 64});
  score.controls.push_back({2, ScoreControl::Kind::PitchBend, 2, 0, 12288});
  score.tempos.push_back({4, 60});
  for (int format : {0, 1}) {
    for (int ppq : {96, 960}) {
      MidiFileDef def;
      def.format = format;
      def.ppq = ppq;
      def.tempo = 100;
      def.timeSignatureNumerator = 6;
      def.timeSignatureDenominator = 8;
      nlohmann::json read = dumpMidi(write(score, def, "piece.mid"));
      SCOPED_TRACE("format " + std::to_string(format) + ", ppq " + std::to_string(ppq));
      EXPECT_EQ(read["type"], format);
      EXPECT_EQ(read["ppq"], ppq);
      EXPECT_EQ(read["unmatched"], 0);
      nlohmann::json notes = {{0, ppq, 0, 60, 100},
                              {ppq / 2, 2 * ppq, 0, 64, 80},
                              {ppq, ppq + ppq / 4, 9, 36, 127},
                              {2 * ppq, 3 * ppq, 2, 50, 70},
                              {3 * ppq, 6 * ppq, 2, 50, 71}};
      EXPECT_EQ(read["notes"], notes);
      EXPECT_EQ(read["programs"], (nlohmann::json{{0, 0, 40}, {0, 2, 73}}));
      EXPECT_EQ(read["controls"], (nlohmann::json{{ppq + ppq / 2, 2, 1, 64}}));
      EXPECT_EQ(read["bends"], (nlohmann::json{{2 * ppq, 2, 12288}}));
      EXPECT_EQ(read["tempos"], (nlohmann::json{{0, 600000}, {4 * ppq, 1000000}}));
      EXPECT_EQ(read["timesigs"], (nlohmann::json{{0, 6, 8}}));
      for (const auto& end : read["track_ends"]) EXPECT_EQ(end, 6 * ppq);
      if (format == 1) {
        EXPECT_EQ(read["tracks"], 4);
        EXPECT_EQ(read["channels_per_track"], (nlohmann::json{nlohmann::json::array(), {0}, {2}, {9}}));
      } else {
        EXPECT_EQ(read["tracks"], 1);
      }
    }
  }
}

TEST_F(MidiRoundTrip, ThousandsOfRandomNotesSurviveByValue) {
  for (uint32_t seed : {1u, 2u, 3u}) {
    Score score = randomScore(seed, 3000);
    MidiFileDef def;
    def.format = seed == 2 ? 0 : 1;
    def.ppq = 960;
    nlohmann::json read = dumpMidi(write(score, def, "random.mid"));
    EXPECT_EQ(read["unmatched"], 0);
    EXPECT_EQ(read["notes"], expectedNotes(score, 960)) << "seed " << seed;
  }
}

TEST_F(MidiRoundTrip, RendersToAudibleSound) {
  ONTOGEN_REQUIRE_CHECKER(haveFluidsynth(), "fluidsynth or fluid-soundfont-gm is missing (bash .ci/setup installs them)");
  Score score;
  for (int i = 0; i < 4; ++i) score.notes.push_back({i * 0.5, 0.5, 0, static_cast<uint8_t>(60 + 2 * i), 100});
  fs::path midi = write(score, MidiFileDef{}, "audible.mid");
  double rms = renderRms(midi, directory_ / "audible.wav");
  RecordProperty("rms", std::to_string(rms));
  EXPECT_GT(rms, 0.01);
  // Silence renders as fluidsynth's dither only, so the measure means something.
  Score silent;
  silent.controls.push_back({4, ScoreControl::Kind::Controller, 0, 7, 100});
  EXPECT_LT(renderRms(write(silent, MidiFileDef{}, "silent.mid"), directory_ / "silent.wav"), 0.001);
}

}  // namespace
}  // namespace ontogen
