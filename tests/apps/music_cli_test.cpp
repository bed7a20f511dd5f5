// `ontogen run --interpret music` as a user meets it: the MIDI files of the models, read
// back by an independent parser (python3-mido) and compared by value with what the
// model says, and rendered to audio by fluidsynth.

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "tests/interpreters/midi_checkers.h"
#include "tests/checkers.h"

namespace {

namespace fs = std::filesystem;
using namespace ontogen::testing_support;
using nlohmann::json;

struct Result {
  int exitCode = -1;
  std::string out;
  std::string err;
};

fs::path scratch(const std::string& name) {
  fs::path dir = fs::path(ONTOGEN_BINARY_DIR) / "music_cli_test" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

Result ontogen(const std::string& args) {
  fs::path errFile = fs::path(ONTOGEN_BINARY_DIR) / "music_cli_test" / ("stderr_" + std::to_string(getpid()) + ".txt");
  fs::create_directories(errFile.parent_path());
  Result result;
  result.out = runCommand(std::string(ONTOGEN_EXECUTABLE) + " " + args + " 2>" + errFile.string(), &result.exitCode);
  std::ifstream in(errFile);
  std::ostringstream text;
  text << in.rdbuf();
  result.err = text.str();
  return result;
}

std::string model(const std::string& name) { return std::string(ONTOGEN_SOURCE_DIR) + "/models/" + name; }

class MusicCli : public ::testing::Test {
 protected:
  void SetUp() override {
    ONTOGEN_REQUIRE_CHECKER(haveMido(), "python3-mido is not installed (bash .ci/setup installs it)");
  }
  /// Runs a model with the music set and returns what mido reads in its file.
  json play(const std::string& file, const std::string& directory, const std::string& extra = "") {
    fs::path out = scratch(directory);
    Result result = ontogen("run " + file + " --interpret music --out " + out.string() + " " + extra);
    EXPECT_EQ(result.exitCode, 0) << result.err;
    out_ = out / (fs::path(file).stem().string() + ".mid");
    EXPECT_TRUE(fs::exists(out_));
    json read = dumpMidi(out_);
    EXPECT_EQ(read["unmatched"], 0);
    return read;
  }
  json word(const std::string& file, double t) {
    Result result = ontogen("word " + file + " --json --at " + std::to_string(t));
    EXPECT_EQ(result.exitCode, 0) << result.err;
    return json::parse(result.out)["times"][0]["cells"];
  }
  fs::path out_;
};

TEST_F(MusicCli, KochMelodyPlaysTheDerivationWordAsPitchMoves) {
  json read = play(model("koch_melody.cell"), "koch_melody");
  // The expectation, from the word itself: F sounds, + and - move a degree of D dorian.
  const int dorian[] = {0, 2, 3, 5, 7, 9, 10};
  json expected = json::array();
  int degree = 0, beat = 0;
  for (const json& cell : word(model("koch_melody.cell"), 3)) {
    std::string label = cell["label"];
    if (label == "+") ++degree;
    if (label == "-") --degree;
    if (label != "F") continue;
    int octave = degree >= 0 ? degree / 7 : -((-degree + 6) / 7);
    int pitch = 62 + 12 * octave + dorian[degree - 7 * octave];
    expected.push_back({beat * 240, (beat + 1) * 240, 0, pitch, 90});  // eighth notes at 480 ppq
    ++beat;
  }
  ASSERT_EQ(expected.size(), 125u);
  EXPECT_EQ(read["notes"], expected);
  EXPECT_EQ(read["programs"], (json{{0, 0, 11}}));
  EXPECT_EQ(read["tempos"], (json{{0, 375000}}));  // 160 bpm
  EXPECT_EQ(read["timesigs"], (json{{0, 5, 4}}));
  EXPECT_EQ(read["type"], 1);
}

TEST_F(MusicCli, ChordsAreTheSoundingSitesOfThePitchTimeGrid) {
  json read = play(model("chords.cell"), "chords");
  const int thirds[] = {45, 49, 52, 56, 59, 62, 66};  // A major, degrees 0, 2, 4 ... 12
  std::vector<json> expected;
  for (const json& cell : word(model("chords.cell"), 12)) {
    if (cell["params"][0] != 1) continue;
    int x = cell["position"][0], y = cell["position"][1];
    expected.push_back({x * 240, (x + 1) * 240, 0, thirds[y], 64 + 6 * y});
  }
  std::sort(expected.begin(), expected.end());
  ASSERT_GT(expected.size(), 10u);
  EXPECT_EQ(read["notes"], json(expected));
  EXPECT_EQ(read["tempos"], (json{{0, 625000}}));  // 96 bpm
}

TEST_F(MusicCli, DevelopmentalTimePlaysEachCellAtItsBirthAndHoldsWhileItLives) {
  fs::path dir = scratch("developmental_program");
  fs::path program = dir / "growth.cell";
  std::ofstream(program) << "#music developmental\n#until 6\n"
                            "cell A(n = 0) {\n  lifetime 2;\n  rules { terminal: -> A(n + 1) B(n) }\n"
                            "  interpret music { pitch(60 + n) note(0.5) }\n}\n"
                            "cell B(n = 0) {\n  lifetime 3;\n  interpret music { pitch(48 + n) hold(80) }\n}\n"
                            "system s { pool linear; axiom A(0); }\n";
  json read = play(program.string(), "growth", "--step 0.5");
  // A is reborn every 2 s (n = 0, 1, 2, 3) and plays half a beat. B(0), born at 2, holds
  // its note for its lifetime of 3 s and is then renewed (no terminal rule: the same
  // cell, a new life), which plays again until the run ends at 6; B(1), born at 4, is
  // cut by the end of the run.
  json expected = {{0, 240, 0, 60, 100},    {960, 1200, 0, 61, 100},  {960, 2400, 0, 48, 80},
                   {1920, 2160, 0, 62, 100}, {1920, 2880, 0, 49, 80},  {2400, 2880, 0, 48, 80},
                   {2880, 3120, 0, 63, 100}};
  EXPECT_EQ(read["notes"], expected);
}

TEST_F(MusicCli, ARateVariableSwellsTheExpressionController) {
  json read = play(model("swell.cell"), "swell");
  int checked = 0;
  for (const json& control : read["controls"]) {
    if (control[1] != 0 || control[2] != 11) continue;
    double t = control[0].get<double>() / 480;  // one beat is one second of development
    double expected = std::clamp(std::round(64 + 126 * std::sin(t / 2)), 0.0, 127.0);
    EXPECT_NEAR(control[3].get<double>(), expected, 1) << "at t = " << t;
    ++checked;
  }
  EXPECT_GT(checked, 100);
  // The pulse's loudness follows the swell: its notes at the top are louder than at the
  // bottom (x = 1 near t = π, x = -1 near t = 3π).
  int top = 0, bottom = 0;
  for (const json& note : read["notes"]) {
    if (note[2] != 1) continue;
    double t = note[0].get<double>() / 480;
    if (std::abs(t - M_PI - 0.5) < 0.3) top = note[4];
    if (std::abs(t - 3 * M_PI - 0.5) < 0.3) bottom = note[4];
  }
  EXPECT_GT(top, 110);
  EXPECT_LT(bottom, 10);
}

TEST_F(MusicCli, ThePistonPlaysItsOwnDevelopment) {
  json read = play(model("piston.cell"), "piston", "--until 12");
  std::vector<json> strokes, rod;
  for (const json& note : read["notes"]) (note[2] == 0 ? strokes : rod).push_back(note);
  // The piston is rebuilt at 0.04 s and every 4 s after: a bar of four beats each time.
  ASSERT_EQ(strokes.size(), 12u);
  const int accents[] = {110, 70, 90, 70};
  for (int i = 0; i < 12; ++i) {
    double beat = 0.04 + 4 * (i / 4) + (i % 4);
    EXPECT_EQ(strokes[i][0], std::lround(beat * 480)) << i;
    EXPECT_EQ(strokes[i][3], 38);
    EXPECT_EQ(strokes[i][4], accents[i % 4]);
  }
  // The rod's counter x = 1, 2, 3 climbs D minor by thirds: F, A, C; each held 4 s.
  ASSERT_EQ(rod.size(), 3u);
  const int pitches[] = {53, 57, 60};
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(rod[i][0], std::lround((0.04 + 4 * i) * 480));
    EXPECT_EQ(rod[i][3], pitches[i]);
  }
  EXPECT_EQ(read["programs"], (json{{19, 0, 116}, {19, 1, 89}}));
}

TEST_F(MusicCli, RhythmTakesLengthsRestsAndDynamicsFromTheNotesParameters) {
  json read = play(model("rhythm.cell"), "rhythm_notes");
  // The expectation, from the word: N(d, g, k) sounds d beats (staccato below half a
  // beat) at 112 - 16 k on degree g of A minor; R(d) rests d beats.
  const int minor[] = {0, 2, 3, 5, 7, 8, 10};
  json expected = json::array();
  double beat = 0, rests = 0;
  std::set<double> lengths;
  std::set<int> velocities;
  for (const json& cell : word(model("rhythm.cell"), 4)) {
    const std::string label = cell["label"];
    if (label == "R") {
      beat += cell["params"][0].get<double>();
      rests += cell["params"][0].get<double>();
    }
    if (label != "N") continue;
    const double d = cell["params"][0];
    const int g = cell["params"][1], k = cell["params"][2];
    const int octave = g >= 0 ? g / 7 : -((-g + 6) / 7);
    const int pitch = 57 + 12 * octave + minor[g - 7 * octave];
    const double sounding = d * (d < 0.5 ? 0.6 : 0.95);
    expected.push_back({std::lround(beat * 480), std::lround((beat + sounding) * 480), 0, pitch, 112 - 16 * k});
    lengths.insert(d);
    velocities.insert(112 - 16 * k);
    beat += d;
  }
  EXPECT_EQ(beat, 16);  // four bars of 4/4, rests included
  // The seed makes a rhythm of several lengths and accents, with rests.
  EXPECT_GE(lengths.size(), 4u);
  EXPECT_GE(velocities.size(), 3u);
  EXPECT_GT(rests, 0);
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(read["notes"], expected);
  EXPECT_EQ(read["track_names"], (json{"rhythm", "Marimba"}));  // #track
}

TEST_F(MusicCli, DevelopmentalNotesTakeTheirLengthAndLoudnessFromTheCell) {
  fs::path dir = scratch("developmental_lengths");
  fs::path program = dir / "lives.cell";
  std::ofstream(program) << "#music developmental\n#until 5.5\n"
                            "cell A(n = 0) {\n  lifetime 1.5;\n  rules { terminal: -> A(n + 1) }\n"
                            "  interpret music { pitch(60 + n) rest(n / 4) note(lifetime - n / 4, 40 + 20 * n) }\n}\n"
                            "system s { pool linear; axiom A(0); }\n";
  json read = play(program.string(), "lives", "--step 0.5");
  // A(n) is born at 1.5 n, rests n/4 beats, then sounds to the end of its life, louder
  // each generation.
  EXPECT_EQ(read["notes"], (json{{0, 720, 0, 60, 40}, {840, 1440, 0, 61, 60}, {1680, 2160, 0, 62, 80},
                                 {2520, 2880, 0, 63, 100}}));
  EXPECT_EQ(read["track_names"], (json{"lives", "A"}));
}

TEST_F(MusicCli, EachChannelsTrackIsNamedAfterTheCellsThatPlayOnIt) {
  json piston = play(model("piston.cell"), "piston_tracks", "--until 5");
  // turn only sends modulation on bend's channel: the track is bend's, who plays.
  EXPECT_EQ(piston["track_names"], (json{"piston", "mov", "bend"}));
  EXPECT_EQ(piston["channels_per_track"], (json{json::array(), {0}, {1}}));
  json swell = play(model("swell.cell"), "swell_tracks", "--until 3");
  EXPECT_EQ(swell["track_names"], (json{"swell", "Drone", "Pulse"}));
  // #track names a channel's track; the others keep their cells' names.
  fs::path named = scratch("named_tracks");
  std::ofstream(named / "duo.cell") << "#track 1 \"Bass line\"\nlsystem duo {\n  axiom Lead Low\n"
                                       "  interpret music Lead { note(1) }\n"
                                       "  interpret music Low { channel(1) pitch(36) note(2) }\n}\n";
  json duo = play((named / "duo.cell").string(), "named_tracks_out");
  EXPECT_EQ(duo["track_names"], (json{"duo", "Lead", "Bass line"}));
  // A cell that only sets the program (or another controller) plays nothing: the track is
  // named after the cells that play notes, and after it only on a channel where none do.
  fs::path setup = scratch("setup_tracks");
  std::ofstream(setup / "setup.cell") << "lsystem setup {\n  axiom Setup Lead Ctl\n"
                                         "  interpret music Setup { program(11) }\n"
                                         "  interpret music Lead { note(1) }\n"
                                         "  interpret music Ctl { channel(2) program(40) }\n}\n";
  json named_after_players = play((setup / "setup.cell").string(), "setup_tracks_out");
  EXPECT_EQ(named_after_players["track_names"], (json{"setup", "Lead", "Ctl"}));
  // Setup sets the program and the scale, + and - move the degree: only F plays.
  json koch = play(model("koch_melody.cell"), "koch_melody_tracks", "--until 1");
  EXPECT_EQ(koch["track_names"], (json{"koch_melody", "F"}));
  // Format 0 has one track, named after the model.
  fs::path dir = scratch("one_track");
  std::ofstream(dir / "one.cell") << "#midiformat 0\nlsystem one { axiom A\n interpret music A { note(1) } }\n";
  json one = play((dir / "one.cell").string(), "one_track_out");
  EXPECT_EQ(one["track_names"], (json{"one"}));
}

TEST(MusicCliFlags, MidiClockWithoutLivePlaybackIsAUsageError) {
  fs::path out = scratch("clock_alone");
  Result result = ontogen("run " + model("koch_melody.cell") + " --interpret music --midi-clock --out " + out.string());
  EXPECT_EQ(result.exitCode, 2);
  EXPECT_EQ(result.err,
            "ontogen: error: --midi-clock is sent with live playback: add --midi-port or --virtual-port\n");
  EXPECT_FALSE(fs::exists(out / "koch_melody.mid"));
}

TEST_F(MusicCli, EveryMusicModelRendersToSound) {
  ONTOGEN_REQUIRE_CHECKER(haveFluidsynth(), "fluidsynth or fluid-soundfont-gm is missing (bash .ci/setup installs them)");
  for (const char* name : {"koch_melody", "markov_melody", "rhythm", "chords", "swell", "piston"}) {
    play(model(std::string(name) + ".cell"), name);  // each at its own #until
    double rms = renderRms(out_, out_.parent_path() / "render.wav");
    EXPECT_GT(rms, 0.005) << name;
  }
}

// The README's **Listen** paragraph: its commands, run as written (ontogen, models/ and
// the linked file's path pointed at this build and a scratch folder), make the audio it
// links: the same length and loudness, decoded by sox, and normalised to a peak near
// -1 dBFS.
TEST_F(MusicCli, TheReadmesRenderCommandsMakeTheLinkedAudio) {
  int code = -1;
  runCommand("command -v sox >/dev/null && command -v oggenc >/dev/null", &code);
  ONTOGEN_REQUIRE_CHECKER(code == 0 && haveFluidsynth(), "fluidsynth, sox or oggenc is missing (bash .ci/setup installs them)");
  std::ifstream in(std::string(ONTOGEN_SOURCE_DIR) + "/README.md");
  std::string readme((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t listen = readme.find("**Listen:**");
  ASSERT_NE(listen, std::string::npos);
  const size_t open = readme.find("```\n", listen), close = readme.find("```\n", open + 4);
  ASSERT_NE(close, std::string::npos);
  std::istringstream lines(readme.substr(open + 4, close - open - 4));
  fs::path dir = scratch("readme_render");
  std::string script = "set -e\ncd '" + dir.string() + "'\n";
  std::string line;
  int commands = 0;
  while (std::getline(lines, line)) {
    auto replace = [&](const std::string& from, const std::string& to) {
      for (size_t at = line.find(from); at != std::string::npos; at = line.find(from, at + to.size()))
        line.replace(at, from.size(), to);
    };
    if (line.rfind("ontogen ", 0) == 0) line.replace(0, 7, ONTOGEN_EXECUTABLE);
    replace(" models/", std::string(" ") + ONTOGEN_SOURCE_DIR + "/models/");
    replace("docs/media/piston.ogg", "piston.ogg");
    script += line + " 2>/dev/null\n";
    ++commands;
  }
  EXPECT_EQ(commands, 4);
  std::ofstream(dir / "render.sh") << script;
  std::string log = runCommand("sh '" + (dir / "render.sh").string() + "' 2>&1", &code);
  ASSERT_EQ(code, 0) << script << log;
  auto stat = [](const fs::path& file) {
    std::string text = runCommand("sox '" + file.string() + "' -n stat 2>&1");
    auto value = [&](const std::string& name) {
      size_t at = text.find(name);
      return at == std::string::npos ? -1.0 : std::stod(text.substr(text.find(':', at) + 1));
    };
    return std::array<double, 3>{value("Length (seconds)"), value("RMS     amplitude"), value("Maximum amplitude")};
  };
  const auto made = stat(dir / "piston.ogg");
  const auto linked = stat(fs::path(ONTOGEN_SOURCE_DIR) / "docs/media/piston.ogg");
  EXPECT_NEAR(made[0], linked[0], 0.01);
  EXPECT_NEAR(made[1], linked[1], linked[1] * 0.005);
  EXPECT_NEAR(made[2], linked[2], 0.02);
  // Normalised: the loudest sample of the render is 1 dB below full scale (10^(-1/20)),
  // give or take what the lossy encoding moves.
  const auto normalised = stat(dir / "out" / "piston_norm.wav");
  EXPECT_NEAR(normalised[2], std::pow(10.0, -1.0 / 20), 0.001);
  EXPECT_GT(linked[2], 0.8);
}

TEST_F(MusicCli, MarkovMelodyIsAWalkThatTheSeedChooses) {
  json first = play(model("markov_melody.cell"), "markov_first");
  json again = play(model("markov_melody.cell"), "markov_again");
  json other = play(model("markov_melody.cell"), "markov_other", "--seed 99");
  EXPECT_EQ(first["notes"], again["notes"]);
  EXPECT_NE(first["notes"], other["notes"]);
  ASSERT_EQ(first["notes"].size(), 48u);
  // Each note is one step of the chain: a pentatonic degree from the table of moves.
  const int pentatonic[] = {0, 2, 4, 7, 9};
  auto degreeOf = [&](int pitch) {
    int octave = (pitch - 60) / 12, within = (pitch - 60) % 12;
    for (int i = 0; i < 5; ++i)
      if (pentatonic[i] == within) return octave * 5 + i;
    return -100;
  };
  for (size_t i = 1; i < 48; ++i) {
    int from = degreeOf(first["notes"][i - 1][3]), to = degreeOf(first["notes"][i][3]);
    int step = to - from;
    if (from < 3) EXPECT_TRUE(step == 0 || step == 1 || step == 2) << i;
    else if (from <= 7) EXPECT_TRUE(step == 1 || step == -1 || step == 2 || step == -2) << i;
    else EXPECT_TRUE(step == -1 || step == -3) << i;
  }
}

TEST_F(MusicCli, BadValuesAreSkippedWithAWarningAndTheFileStaysValid) {
  fs::path dir = scratch("bad_values_program");
  fs::path program = dir / "climb.cell";
  // Twelve octaves up from 60: the notes above 127 are dropped, not wrapped or clamped.
  std::ofstream(program) << "lsystem climb {\n  #until 12\n  axiom A\n"
                            "  interpret music A { note(-1) ] }\n  A -> F up(12) A\n}\n";
  fs::path out = scratch("bad_values");
  Result result = ontogen("run " + program.string() + " --interpret music --out " + out.string());
  EXPECT_EQ(result.exitCode, 0) << result.err;
  // Each kind of problem once, counted over the whole run, at the first place it happened.
  for (const char* expected : {":5:8: warning: the music player skipped 6 notes outside MIDI's 0..127",
                               ":4:23: warning: the music player skipped 1 commands with bad arguments",
                               ":4:32: warning: the music player ignored 1 unmatched ']'"})
    EXPECT_NE(result.err.find(program.string() + expected), std::string::npos) << expected << "\n" << result.err;
  json read = dumpMidi(out / "climb.mid");
  EXPECT_EQ(read["unmatched"], 0);
  json expected = json::array();
  for (int i = 0; i < 6; ++i) expected.push_back({i * 480, (i + 1) * 480, 0, 60 + 12 * i, 100});
  EXPECT_EQ(read["notes"], expected);
}

TEST_F(MusicCli, DirectivesChooseFormatResolutionTempoAndTimeSignature) {
  fs::path dir = scratch("directives_program");
  fs::path program = dir / "settings.cell";
  std::ofstream(program) << "#midiformat 0\n#ppq 96\n#tempo 90\n#timesig 7/8\n"
                            "lsystem settings {\n  #until 1\n  axiom F\n  F -> F [ channel(3) up(4) F ] F\n}\n";
  json read = play(program.string(), "directives");
  EXPECT_EQ(read["type"], 0);
  EXPECT_EQ(read["tracks"], 1);
  EXPECT_EQ(read["ppq"], 96);
  EXPECT_EQ(read["tempos"], (json{{0, 666667}}));
  EXPECT_EQ(read["timesigs"], (json{{0, 7, 8}}));
  // The branch is a voice on channel 3 that starts with the note after it.
  EXPECT_EQ(read["notes"], (json{{0, 96, 0, 60, 100}, {96, 192, 0, 60, 100}, {96, 192, 3, 64, 100}}));
}

TEST(MusicCliErrors, ABadMusicDirectiveWritesNothing) {
  fs::path dir = scratch("bad");
  fs::path program = dir / "bad.cell";
  std::ofstream(program) << "#timesig 7/6\nlsystem a { axiom F }\n";
  Result result = ontogen("run " + program.string() + " --interpret music --out " + (dir / "out").string());
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_NE(result.err.find(":1:12: error: expected a note value 1, 2, 4, 8, 16, 32 or 64 below the '/' of #timesig"),
            std::string::npos)
      << result.err;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

}  // namespace
