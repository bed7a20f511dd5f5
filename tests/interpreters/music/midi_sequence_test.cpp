// The encoding of a score into channel messages, at once (makeMidiSequence) and as a
// stream while the score still grows (MidiStreamEncoder): the same messages either way.

#include "interpreters/music/midi_sequence.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <tuple>
#include <vector>

namespace ontogen {
namespace {

std::vector<std::tuple<uint64_t, int, int, int>> bytesOf(const MidiSequence& sequence) {
  std::vector<std::tuple<uint64_t, int, int, int>> out;
  for (const MidiMessage& m : sequence.messages) out.emplace_back(m.tick, m.status, m.data1, m.data2);
  return out;
}

// A score built the way developmental time builds it: words every `step` beats, notes
// and controls at or after each word's time, held notes open until their cell is gone.
TEST(MidiStreamEncoder, StreamingAGrowingScoreGivesTheMessagesOfTheWholeScore) {
  std::mt19937 random(11);
  std::uniform_int_distribution<int> pitch(50, 53), channel(0, 2), value(0, 127);
  std::uniform_real_distribution<double> length(0.05, 3);
  const double step = 0.25;
  Score score;
  std::vector<std::pair<size_t, double>> open;  // held notes: index, end
  MidiStreamEncoder encoder(96, 120);
  MidiSequence streamed;
  uint64_t released = 0;
  for (int word = 0; word <= 80; ++word) {
    const double time = word * step;
    // Held notes whose cell is gone by now end (no later than the word).
    std::erase_if(open, [&](const std::pair<size_t, double>& held) {
      if (held.second > time) return false;
      score.notes[held.first].duration = held.second - score.notes[held.first].start;
      return true;
    });
    for (int i = 0; i < 3; ++i) {
      const double birth = time + step * (i / 3.0);
      const auto c = static_cast<uint8_t>(channel(random));
      if (i == 2 && word % 4 == 0) {
        score.notes.push_back({birth, INFINITY, c, static_cast<uint8_t>(pitch(random)), 80});
        open.emplace_back(score.notes.size() - 1, birth + length(random));
      } else {
        score.notes.push_back({birth, length(random), c, static_cast<uint8_t>(pitch(random)), 90});
      }
    }
    score.controls.push_back({time, ScoreControl::Kind::Controller, 1, 11, static_cast<uint16_t>(value(random))});
    if (word == 40) score.tempos.push_back({time, 90});
    const size_t before = streamed.messages.size();
    encoder.advance(score, time, streamed);
    // Nothing at or after the horizon's tick is sent; what is sent stays in order.
    for (size_t i = before; i < streamed.messages.size(); ++i) {
      EXPECT_LT(streamed.messages[i].tick, static_cast<uint64_t>(std::llround(time * 96)));
      if (i > 0) {
        EXPECT_GE(streamed.messages[i].tick, streamed.messages[i - 1].tick);
      }
    }
    EXPECT_GE(encoder.released(), released);
    released = encoder.released();
  }
  for (auto& [index, end] : open) score.notes[index].duration = end - score.notes[index].start;
  EXPECT_THROW(MidiStreamEncoder(96, 120).finish(Score{{{0, INFINITY, 0, 60, 90}}, {}, {}, {}}, streamed),
               std::invalid_argument);
  encoder.finish(score, streamed);
  const MidiSequence whole = makeMidiSequence(score, 96, 120);
  ASSERT_GT(whole.messages.size(), 400u);
  EXPECT_EQ(bytesOf(streamed), bytesOf(whole));
  ASSERT_EQ(whole.tempos.size(), 2u);
  EXPECT_EQ(streamed.tempos.size(), 2u);
  EXPECT_EQ(streamed.tempos[1].tick, whole.tempos[1].tick);
  EXPECT_EQ(streamed.tempos[1].microsecondsPerQuarter, 666667u);
}

TEST(MidiStreamEncoder, ANoteStillSoundingSendsItsNoteOnNowAndItsNoteOffWhenItEnds) {
  Score score;
  score.notes.push_back({0, INFINITY, 3, 48, 70});
  MidiStreamEncoder encoder(480, 120);
  MidiSequence out;
  encoder.advance(score, 1, out);
  ASSERT_EQ(out.messages.size(), 1u);
  EXPECT_EQ(out.messages[0].status, 0x93);
  EXPECT_EQ(out.messages[0].tick, 0u);
  encoder.advance(score, 5, out);
  EXPECT_EQ(out.messages.size(), 1u);  // still sounding
  score.notes[0].duration = 4.5;
  encoder.advance(score, 5, out);
  ASSERT_EQ(out.messages.size(), 2u);
  EXPECT_EQ(out.messages[1].status, 0x83);
  EXPECT_EQ(out.messages[1].tick, 2160u);
  EXPECT_EQ(out.tempos.size(), 1u);
  EXPECT_EQ(out.tempos[0].microsecondsPerQuarter, 500000u);
}

TEST(MidiSequence, SecondsAtAFractionOfATick) {
  Score score;
  score.tempos.push_back({1, 60});
  MidiSequence sequence = makeMidiSequence(score, 24, 120);
  EXPECT_DOUBLE_EQ(sequence.secondsAt(0.5), 0.5 / 48);         // a clock at 120 bpm is 1/48 s
  EXPECT_DOUBLE_EQ(sequence.secondsAt(24 + 12.5), 0.5 + 12.5 / 24);  // then 60 bpm
}

}  // namespace
}  // namespace ontogen
