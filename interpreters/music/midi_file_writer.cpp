#include "interpreters/music/midi_file_writer.h"

#include <array>
#include <stdexcept>
#include <string>

#include "interpreters/music/midi_sequence.h"

namespace ontogen {

namespace {

constexpr uint32_t kMaxDelta = 0x0FFFFFFF;  // four bytes of variable-length quantity
// Names longer than this are no names a DAW shows; the meta event itself would take more.
constexpr size_t kMaxName = 65535;

void appendBig(std::vector<uint8_t>& bytes, uint32_t value, int size) {
  for (int i = size - 1; i >= 0; --i) bytes.push_back(static_cast<uint8_t>(value >> (8 * i)));
}

/// One track chunk being built: events appended in time order.
class TrackBuilder {
 public:
  void meta(uint64_t tick, uint8_t type, const std::vector<uint8_t>& data) {
    delta(tick);
    body_.push_back(0xFF);
    body_.push_back(type);
    appendVariableLength(body_, static_cast<uint32_t>(data.size()));
    body_.insert(body_.end(), data.begin(), data.end());
    runningStatus_ = 0;  // meta events cancel running status (SMF 1.0)
  }
  void channel(const MidiMessage& message) {
    delta(message.tick);
    if (message.status != runningStatus_) body_.push_back(message.status);
    runningStatus_ = message.status;
    body_.push_back(message.data1);
    if (message.size() == 3) body_.push_back(message.data2);
  }
  void finish(std::vector<uint8_t>& file, uint64_t endTick) {
    meta(endTick < tick_ ? tick_ : endTick, 0x2F, {});
    file.insert(file.end(), {'M', 'T', 'r', 'k'});
    appendBig(file, static_cast<uint32_t>(body_.size()), 4);
    file.insert(file.end(), body_.begin(), body_.end());
  }

 private:
  void delta(uint64_t tick) {
    uint64_t gap = tick - tick_;
    if (gap > kMaxDelta)
      throw std::invalid_argument("the score has a gap of " + std::to_string(gap) +
                                  " ticks between two events; a MIDI file holds at most 268435455");
    appendVariableLength(body_, static_cast<uint32_t>(gap));
    tick_ = tick;
  }

  std::vector<uint8_t> body_;
  uint64_t tick_ = 0;
  uint8_t runningStatus_ = 0;
};

void conductor(TrackBuilder& track, const MidiFileDef& def, const MidiSequence& sequence) {
  if (!def.name.empty()) track.meta(0, 0x03, std::vector<uint8_t>(def.name.begin(), def.name.end()));
  uint8_t power = 0;
  while ((1 << power) < def.timeSignatureDenominator) ++power;
  // numerator, denominator as a power of 2, 24 MIDI clocks per metronome click,
  // 8 thirty-second notes per quarter note.
  track.meta(0, 0x58, {static_cast<uint8_t>(def.timeSignatureNumerator), power, 24, 8});
  for (const MidiTempo& tempo : sequence.tempos) {
    uint32_t t = tempo.microsecondsPerQuarter;
    track.meta(tempo.tick, 0x51, {static_cast<uint8_t>(t >> 16), static_cast<uint8_t>(t >> 8), static_cast<uint8_t>(t)});
  }
}

}  // namespace

void appendVariableLength(std::vector<uint8_t>& bytes, uint32_t value) {
  if (value > kMaxDelta) throw std::invalid_argument("a variable-length quantity holds at most 0x0FFFFFFF");
  uint8_t groups[4];
  int count = 0;
  do {
    groups[count++] = value & 0x7F;
    value >>= 7;
  } while (value != 0);
  for (int i = count - 1; i >= 0; --i) bytes.push_back(static_cast<uint8_t>(groups[i] | (i > 0 ? 0x80 : 0)));
}

void checkMidiFileDef(const MidiFileDef& def) {
  if (def.format != 0 && def.format != 1) throw std::invalid_argument("the MIDI file format must be 0 or 1");
  if (def.ppq < 1 || def.ppq > 32767) throw std::invalid_argument("the resolution (ppq) must be 1..32767");
  if (!(def.tempo > 0)) throw std::invalid_argument("the tempo must be > 0");
  if (def.timeSignatureNumerator < 1 || def.timeSignatureNumerator > 255)
    throw std::invalid_argument("the time signature's numerator must be 1..255");
  int d = def.timeSignatureDenominator;
  if (d < 1 || d > 64 || (d & (d - 1)) != 0)
    throw std::invalid_argument("the time signature's denominator must be 1, 2, 4, 8, 16, 32 or 64");
  if (def.name.size() > kMaxName) throw std::invalid_argument("the sequence name is too long");
}

std::vector<uint8_t> encodeMidiFile(const Score& score, const MidiFileDef& def) {
  checkMidiFileDef(def);
  for (const std::string& name : score.trackNames)
    if (name.size() > kMaxName) throw std::invalid_argument("a track name is too long");
  MidiSequence sequence = makeMidiSequence(score, def.ppq, def.tempo);
  uint64_t end = sequence.endTick();
  if (!sequence.tempos.empty() && sequence.tempos.back().tick > end) end = sequence.tempos.back().tick;

  std::vector<TrackBuilder> tracks;
  if (def.format == 0) {
    // One track: conductor events first at each tick, then the channel messages.
    TrackBuilder track;
    if (!def.name.empty()) track.meta(0, 0x03, std::vector<uint8_t>(def.name.begin(), def.name.end()));
    uint8_t power = 0;
    while ((1 << power) < def.timeSignatureDenominator) ++power;
    track.meta(0, 0x58, {static_cast<uint8_t>(def.timeSignatureNumerator), power, 24, 8});
    size_t nextTempo = 0;
    auto tempoUpTo = [&](uint64_t tick) {
      for (; nextTempo < sequence.tempos.size() && sequence.tempos[nextTempo].tick <= tick; ++nextTempo) {
        uint32_t t = sequence.tempos[nextTempo].microsecondsPerQuarter;
        track.meta(sequence.tempos[nextTempo].tick, 0x51,
                   {static_cast<uint8_t>(t >> 16), static_cast<uint8_t>(t >> 8), static_cast<uint8_t>(t)});
      }
    };
    for (const MidiMessage& message : sequence.messages) {
      tempoUpTo(message.tick);
      track.channel(message);
    }
    tempoUpTo(end);
    tracks.push_back(std::move(track));
  } else {
    TrackBuilder first;
    conductor(first, def, sequence);
    tracks.push_back(std::move(first));
    // One pass deals the messages out to their channels' tracks.
    std::array<TrackBuilder, 16> channels;
    std::array<bool, 16> used{};
    for (size_t channel = 0; channel < 16; ++channel) {
      const std::string& name = score.trackNames[channel];
      if (!name.empty()) channels[channel].meta(0, 0x03, std::vector<uint8_t>(name.begin(), name.end()));
    }
    for (const MidiMessage& message : sequence.messages) {
      channels[message.channel()].channel(message);
      used[message.channel()] = true;
    }
    for (int channel = 0; channel < 16; ++channel)
      if (used[channel]) tracks.push_back(std::move(channels[channel]));
  }

  std::vector<uint8_t> file = {'M', 'T', 'h', 'd', 0, 0, 0, 6};
  appendBig(file, static_cast<uint32_t>(def.format), 2);
  appendBig(file, static_cast<uint32_t>(tracks.size()), 2);
  appendBig(file, static_cast<uint32_t>(def.ppq), 2);
  for (TrackBuilder& track : tracks) track.finish(file, end);
  return file;
}

void writeMidiFile(const Score& score, const MidiFileDef& def, std::ostream& out) {
  std::vector<uint8_t> bytes = encodeMidiFile(score, def);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

}  // namespace ontogen
