#pragma once
// Independent checkers of MIDI files for the tests: Debian's python3-mido reads a file
// back (midi_dump.py prints what it holds as JSON) and fluidsynth with the General MIDI
// soundfont renders it to audio. Both are installed by .ci/setup; a test skips with a
// message only when they are really missing.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace ontogen::testing_support {

// mido imports only under Debian's own interpreter, not a python3 earlier on PATH.
inline constexpr const char* kPython = "/usr/bin/python3";
inline constexpr const char* kSoundFont = "/usr/share/sounds/sf2/FluidR3_GM.sf2";

inline std::string runCommand(const std::string& command, int* exitCode = nullptr) {
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return out;
  std::array<char, 4096> buffer;
  size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) out.append(buffer.data(), n);
  int status = pclose(pipe);
  if (exitCode) *exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return out;
}

inline bool haveMido() {
  int code = -1;
  runCommand(std::string(kPython) + " -c 'import mido' 2>/dev/null", &code);
  return code == 0;
}

inline bool haveFluidsynth() {
  int code = -1;
  runCommand("command -v fluidsynth >/dev/null 2>&1", &code);
  return code == 0 && std::filesystem::exists(kSoundFont);
}

/// What mido reads in the file (see midi_dump.py), or a test failure.
inline nlohmann::json dumpMidi(const std::filesystem::path& file) {
  int code = -1;
  std::string text = runCommand(std::string(kPython) + " " + ONTOGEN_SOURCE_DIR +
                                    "/tests/interpreters/midi_dump.py '" + file.string() + "' 2>&1",
                                &code);
  EXPECT_EQ(code, 0) << text;
  if (code != 0) return nlohmann::json::object();
  return nlohmann::json::parse(text);
}

/// Renders the file with fluidsynth and returns the RMS of the audio, full scale 1; -1
/// when rendering failed.
inline double renderRms(const std::filesystem::path& midi, const std::filesystem::path& wav) {
  int code = -1;
  std::string log = runCommand("fluidsynth -ni -q -g 1.0 -F '" + wav.string() + "' -r 44100 " + kSoundFont + " '" +
                                   midi.string() + "' 2>&1",
                               &code);
  EXPECT_EQ(code, 0) << log;
  std::ifstream in(wav, std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // RIFF/WAVE: find the "data" chunk of 16-bit samples.
  for (size_t i = 12; i + 8 <= bytes.size();) {
    uint32_t size = static_cast<uint8_t>(bytes[i + 4]) | static_cast<uint8_t>(bytes[i + 5]) << 8 |
                    static_cast<uint8_t>(bytes[i + 6]) << 16 | static_cast<uint32_t>(static_cast<uint8_t>(bytes[i + 7])) << 24;
    if (std::string(&bytes[i], 4) == "data") {
      double sum = 0;
      size_t count = 0;
      for (size_t j = i + 8; j + 1 < bytes.size() && j + 1 < i + 8 + size; j += 2) {
        int16_t sample = static_cast<int16_t>(static_cast<uint8_t>(bytes[j]) | static_cast<uint8_t>(bytes[j + 1]) << 8);
        sum += (sample / 32768.0) * (sample / 32768.0);
        ++count;
      }
      return count ? std::sqrt(sum / count) : 0;
    }
    i += 8 + size + (size & 1);
  }
  return -1;
}

}  // namespace ontogen::testing_support
