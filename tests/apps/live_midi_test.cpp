// Live MIDI against a real peer on a headless machine: a JACK server with the dummy
// backend (no sound card needed) and jack_midi_dump recording what arrives, both from
// Debian's jackd2. Each test runs its own named server (JACK_DEFAULT_SERVER), so tests
// running in parallel do not meet, and stops every process it started, by its pid.

#include <gtest/gtest.h>

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <thread>

#include "tests/interpreters/midi_checkers.h"
#include "tests/checkers.h"

extern char** environ;

namespace {

namespace fs = std::filesystem;
using namespace ontogen::testing_support;
using nlohmann::json;

fs::path scratch(const std::string& name) {
  fs::path dir = fs::path(ONTOGEN_BINARY_DIR) / "live_midi_test" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string readFile(const fs::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Starts `command` under /bin/sh; with `exec` in front the pid is the program's own.
pid_t spawnShell(const std::string& command) {
  pid_t pid = -1;
  std::string copy = command;
  char* argv[] = {const_cast<char*>("/bin/sh"), const_cast<char*>("-c"), copy.data(), nullptr};
  if (posix_spawn(&pid, "/bin/sh", nullptr, nullptr, argv, environ) != 0) return -1;
  return pid;
}

int waitExit(pid_t pid) {
  int status = 0;
  if (waitpid(pid, &status, 0) != pid) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

void stop(pid_t& pid) {
  if (pid <= 0) return;
  kill(pid, SIGTERM);
  waitExit(pid);
  pid = -1;
}

std::string ontogenCommand(const std::string& args, const fs::path& err) {
  return std::string("exec ") + ONTOGEN_EXECUTABLE + " " + args + " 2>'" + err.string() + "'";
}

/// `part` is `whole` less some of its elements, the rest in the same order.
bool inOrderWithin(const std::vector<std::vector<int>>& part, const std::vector<std::vector<int>>& whole) {
  size_t at = 0;
  for (const std::vector<int>& message : part) {
    while (at < whole.size() && whole[at] != message) ++at;
    if (at == whole.size()) return false;
    ++at;
  }
  return true;
}

/// A JACK server of its own with a recording MIDI client, for one test.
class JackPeer : public ::testing::Test {
 protected:
  void SetUp() override {
    int code = -1;
    runCommand("command -v jackd && command -v jack_midi_dump && command -v jack_wait && command -v jack_lsp", &code);
    ONTOGEN_REQUIRE_CHECKER(code == 0, "jackd2 is not installed (bash .ci/setup installs it)");
    ONTOGEN_REQUIRE_CHECKER(haveMido(), "python3-mido is not installed (bash .ci/setup installs it)");
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = scratch(info->name());
    server_ = "ontogen_test_" + std::to_string(getpid());
    setenv("JACK_DEFAULT_SERVER", server_.c_str(), 1);
    // The dummy backend keeps time like a sound card would, without one.
    // -R: the server and its clients' process threads run with real-time priority, so a
    // machine busy with other work makes them miss fewer cycles.
    jackd_ = spawnShell("exec jackd -R -n " + server_ + " -d dummy -r 48000 -p 256 >'" + (dir_ / "jackd.log").string() +
                        "' 2>&1");
    ASSERT_GT(jackd_, 0);
    std::string waited = runCommand("jack_wait -w -t 10 2>&1", &code);
    ASSERT_EQ(code, 0) << waited << readFile(dir_ / "jackd.log");
    ASSERT_NO_FATAL_FAILURE(startRecorder());
  }
  /// Starts jack_midi_dump on a fresh dump.txt: -a gives absolute timestamps in frames;
  /// line-buffered so nothing is lost when it is stopped.
  void startRecorder() {
    stop(dump_);
    fs::remove(dir_ / "dump.txt");
    dump_ = spawnShell("exec stdbuf -oL jack_midi_dump -a >'" + (dir_ / "dump.txt").string() + "' 2>/dev/null");
    ASSERT_GT(dump_, 0);
    for (int i = 0; i < 100 && runCommand("jack_lsp 2>/dev/null").find("midi-monitor:input") == std::string::npos; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    ASSERT_NE(runCommand("jack_lsp 2>/dev/null").find("midi-monitor:input"), std::string::npos);
  }
  /// Cycles the dummy server missed so far: a recorder that missed its cycle may have
  /// lost what arrived in it, which says nothing about the sender.
  int xruns() {
    std::string log = readFile(dir_ / "jackd.log");
    int count = 0;
    for (size_t at = log.find("XRun"); at != std::string::npos; at = log.find("XRun", at + 1)) ++count;
    return count;
  }
  void TearDown() override {
    stop(dump_);
    stop(jackd_);
  }

  struct Arrival {
    double seconds;
    std::vector<int> bytes;
  };
  /// What jack_midi_dump recorded: "  58368: 90 45 4b note on ..." per event.
  std::vector<Arrival> arrivals() {
    stop(dump_);
    std::vector<Arrival> list;
    std::istringstream lines(readFile(dir_ / "dump.txt"));
    std::string line;
    while (std::getline(lines, line)) {
      std::istringstream fields(line);
      long frame;
      char colon;
      if (!(fields >> frame >> colon) || colon != ':') continue;
      Arrival arrival{frame / 48000.0, {}};
      std::string hex;
      while (fields >> hex && hex.size() == 2 && std::isxdigit(hex[0]) && std::isxdigit(hex[1]))
        arrival.bytes.push_back(std::stoi(hex, nullptr, 16));
      list.push_back(arrival);
    }
    return list;
  }

  fs::path writeProgram(const std::string& text) {
    fs::path path = dir_ / "live.cell";
    std::ofstream(path) << text;
    return path;
  }

  fs::path dir_;
  std::string server_;
  pid_t jackd_ = -1;
  pid_t dump_ = -1;
};

// Two voices on two channels with program changes: 27 sixteenths and 13 eighths below
// them at 150 bpm, 2.7 seconds.
const char* kPiece =
    "#tempo 150\n"
    "lsystem live {\n"
    "  #until 3\n"
    "  axiom Setup F\n"
    "  interpret music Setup { program(73) duration(0.25) scale(minor) key(57) pitch(57) }\n"
    "  interpret music B { [ channel(1) program(32) down(12) note(0.5) ] }\n"
    "  F -> F + F B - F\n"
    "}\n";

TEST_F(JackPeer, PortsAreListedAndEveryMessageArrivesByValueOnTime) {
  fs::path err = dir_ / "ports.txt";
  int code = -1;
  std::string ports = runCommand(std::string(ONTOGEN_EXECUTABLE) + " midi-ports 2>'" + err.string() + "'", &code);
  EXPECT_EQ(code, 0) << readFile(err);
  EXPECT_NE(ports.find("0  midi-monitor:input  (jack)"), std::string::npos) << ports;

  fs::path program = writeProgram(kPiece);
  // On a machine busy with other work the dummy server can miss cycles (xruns), and the
  // recorder may lose what arrived in them; such an attempt measures the recorder, not
  // ontogen. Up to three attempts for one that recorded everything; if none did, what
  // arrived must still be, per channel, what was sent in the order sent, less some.
  std::vector<Arrival> received;
  int missed = 0;
  bool whole = false;
  for (int attempt = 0; attempt < 3; ++attempt) {
    if (attempt > 0) {
      ASSERT_NO_FATAL_FAILURE(startRecorder());
    }
    int before = xruns();
    pid_t run = spawnShell(ontogenCommand("run '" + program.string() +
                                              "' --interpret music --midi-port midi-monitor:input --stats --out '" +
                                              (dir_ / "out").string() + "'",
                                          dir_ / "run.txt"));
    ASSERT_EQ(waitExit(run), 0) << readFile(dir_ / "run.txt");
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    received = arrivals();
    missed = xruns() - before;
    whole = received.size() == dumpMidi(dir_ / "out" / "live.mid")["timeline"].size();
    if (whole || missed == 0) break;  // all there, or lost without a missed cycle: ontogen's fault
  }
  if (missed > 0) std::cout << missed << " xruns of the dummy server in the measured attempt\n";
  json file = dumpMidi(dir_ / "out" / "live.mid");
  const json& timeline = file["timeline"];
  ASSERT_GT(timeline.size(), 20u);
  if (!whole) {
    ASSERT_GT(missed, 0) << "messages were lost though the recorder missed no cycle\n" << readFile(dir_ / "dump.txt");
    ASSERT_FALSE(received.empty());
  }

  // By value: per channel, the same messages in the same order as the file holds them.
  std::map<int, std::vector<std::vector<int>>> sent, got;
  std::map<int, std::vector<double>> sentTimes, gotTimes;
  for (const json& event : timeline) {
    std::vector<int> bytes = event[1].get<std::vector<int>>();
    sent[bytes[0] & 0x0F].push_back(bytes);
    sentTimes[bytes[0] & 0x0F].push_back(event[0].get<double>());
  }
  for (const Arrival& arrival : received) {
    got[arrival.bytes.at(0) & 0x0F].push_back(arrival.bytes);
    gotTimes[arrival.bytes.at(0) & 0x0F].push_back(arrival.seconds);
  }
  if (whole) {
    EXPECT_EQ(got, sent);
  } else {
    for (auto& [channel, messages] : got)
      EXPECT_TRUE(inOrderWithin(messages, sent[channel])) << "channel " << channel;
  }
  EXPECT_EQ(sent.size(), 2u);

  // Timing: each arrival against its schedule, both measured from the first message.
  double sentStart = timeline[0][0].get<double>(), gotStart = received[0].seconds;
  std::vector<std::pair<double, double>> pairs;  // (scheduled, arrived)
  for (auto& [channel, times] : sentTimes)
    for (size_t i = 0; i < times.size() && i < gotTimes[channel].size(); ++i)
      pairs.emplace_back(times[i] - sentStart, gotTimes[channel][i] - gotStart);
  // The dummy backend's frames are a sleeping thread's count, not wall-clock time: on a
  // busy machine it runs slow by a fraction of a percent. A straight line through
  // (scheduled, arrived) takes that rate out; what remains is jitter.
  double n = static_cast<double>(pairs.size()), mx = 0, my = 0, sxx = 0, sxy = 0;
  for (auto [x, y] : pairs) mx += x / n, my += y / n;
  for (auto [x, y] : pairs) sxx += (x - mx) * (x - mx), sxy += (x - mx) * (y - my);
  double rate = sxy / sxx;
  std::vector<double> errors, jitter;
  for (auto [x, y] : pairs) {
    errors.push_back(std::abs(y - x));
    jitter.push_back(std::abs(y - (my + rate * (x - mx))));
  }
  auto percentile = [](std::vector<double> values, double p) {
    std::sort(values.begin(), values.end());
    return values[static_cast<size_t>(std::ceil(p * static_cast<double>(values.size()))) - 1];
  };
  std::cout << "arrival error against the schedule over " << errors.size() << " messages: median "
            << percentile(errors, 0.5) * 1e3 << " ms, p99 " << percentile(errors, 0.99) * 1e3
            << " ms; frame clock rate " << rate << ", jitter around it: median " << percentile(jitter, 0.5) * 1e3
            << " ms, p99 " << percentile(jitter, 0.99) * 1e3 << " ms\n"
            << readFile(dir_ / "run.txt");
  RecordProperty("arrival_median_ms", std::to_string(percentile(errors, 0.5) * 1e3));
  RecordProperty("arrival_p99_ms", std::to_string(percentile(errors, 0.99) * 1e3));
  // The pace and the jitter are measurements, not pass marks: both depend on how busy
  // the machine is (on a loaded one the dummy server's clock ran 2 % slow). They are
  // printed above and recorded; bench/live_midi_timing.sh measures them on their own
  // (docs/LIVE_MIDI.md). What is asserted is what a busy machine cannot change: every
  // message, by value, in the order of the schedule, and the arrivals in time order.
  RecordProperty("frame_clock_rate", std::to_string(rate));
  RecordProperty("jitter_p99_ms", std::to_string(percentile(jitter, 0.99) * 1e3));
  for (size_t i = 1; i < received.size(); ++i) EXPECT_GE(received[i].seconds, received[i - 1].seconds) << i;
}

// A developmental model whose growth takes seconds: a pulse renewed every quarter beat
// plays a note, beside a crowd of oscillators that the development integrates at small
// steps. The music streams: the first note arrives while the model is still growing.
const char* kSlowGrowth =
    "#music developmental\n"
    "#tempo 240\n"
    "#until 16\n"
    "#dt 0.005\n"
    "cell Pulse(n = 0) {\n"
    "  lifetime 0.25;\n"
    "  rules { terminal: -> Pulse(n + 1) }\n"
    "  interpret music { pitch(60 + n % 12) note(0.2, 90) }\n"
    "}\n"
    "cell Crowd(k = 0) {\n"
    "  lifetime 0.005;\n"
    "  rules { terminal: -> Crowd(k + 1) Mass(k, 1) }\n"
    "}\n"
    "cell Mass(x = 0, v = 1) { rules { rate(x) = v; rate(v) = -x - 0.1 * v; } }\n"
    "system slow { pool linear; axiom Pulse Crowd; }\n";

TEST_F(JackPeer, DevelopmentalMusicStreamsWhileTheModelGrows) {
  fs::path program = writeProgram(kSlowGrowth);
  using Clock = std::chrono::steady_clock;
  const Clock::time_point begin = Clock::now();
  pid_t run = spawnShell(ontogenCommand("run '" + program.string() + "' --interpret music --midi-port 0 --stats --out '" +
                                            (dir_ / "out").string() + "'",
                                        dir_ / "run.txt"));
  ASSERT_GT(run, 0);
  // The test's own clock: when the first note arrives, and when ontogen says it has grown.
  std::optional<double> firstNote, grown;
  int status = 0;
  auto since = [&] { return std::chrono::duration<double>(Clock::now() - begin).count(); };
  while (waitpid(run, &status, WNOHANG) == 0) {
    if (!firstNote && readFile(dir_ / "dump.txt").find("note on") != std::string::npos) firstNote = since();
    if (!grown && readFile(dir_ / "run.txt").find("grown;") != std::string::npos) grown = since();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << readFile(dir_ / "run.txt");
  ASSERT_TRUE(firstNote.has_value()) << readFile(dir_ / "dump.txt");
  ASSERT_TRUE(grown.has_value()) << readFile(dir_ / "run.txt");
  std::cout << "first note at " << *firstNote << " s, grown at " << *grown << " s, ended at " << since() << " s\n"
            << readFile(dir_ / "run.txt");
  RecordProperty("first_note_s", std::to_string(*firstNote));
  RecordProperty("grown_s", std::to_string(*grown));
  EXPECT_LT(*firstNote, *grown) << "the first note did not sound while the model was growing";

  // Everything the file holds arrived, per channel by value and in order.
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  std::vector<Arrival> received = arrivals();
  json file = dumpMidi(dir_ / "out" / "live.mid");
  std::vector<std::vector<int>> sent, got;
  for (const json& event : file["timeline"]) sent.push_back(event[1].get<std::vector<int>>());
  for (const Arrival& arrival : received) got.push_back(arrival.bytes);
  EXPECT_GT(sent.size(), 100u);
  if (xruns() == 0) {
    EXPECT_EQ(got, sent);
  } else {
    EXPECT_LE(got.size(), sent.size());  // a recorder that missed cycles may have lost some
  }
}

TEST_F(JackPeer, MidiClockIsSentTwentyFourTimesABeatBetweenStartAndStop) {
  fs::path program = writeProgram(kPiece);
  pid_t run = spawnShell(ontogenCommand("run '" + program.string() +
                                            "' --interpret music --midi-port 0 --midi-clock --out '" +
                                            (dir_ / "out").string() + "'",
                                        dir_ / "run.txt"));
  ASSERT_EQ(waitExit(run), 0) << readFile(dir_ / "run.txt");
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  std::vector<Arrival> received = arrivals();
  json file = dumpMidi(dir_ / "out" / "live.mid");
  long lastTick = 0;
  for (const json& note : file["notes"]) lastTick = std::max(lastTick, note[1].get<long>());
  const long expectedClocks = lastTick * 24 / 480 + 1;  // one at beat 0, then every 20 ticks
  std::vector<double> clocks;
  int starts = 0, stops = 0;
  size_t firstClock = received.size(), startAt = received.size(), stopAt = 0;
  for (size_t i = 0; i < received.size(); ++i) {
    const int status = received[i].bytes.at(0);
    if (status == 0xF8) {
      clocks.push_back(received[i].seconds);
      firstClock = std::min(firstClock, i);
    }
    if (status == 0xFA) ++starts, startAt = i;
    if (status == 0xFC) ++stops, stopAt = i;
  }
  if (xruns() == 0) {
    EXPECT_EQ(static_cast<long>(clocks.size()), expectedClocks);
  } else {
    EXPECT_LE(static_cast<long>(clocks.size()), expectedClocks);  // a recorder that missed cycles may have lost some
  }
  EXPECT_EQ(starts, 1);
  EXPECT_EQ(stops, 1);
  EXPECT_LT(startAt, firstClock);
  EXPECT_EQ(stopAt, received.size() - 1) << "stop comes after the last note-off";
  // 150 bpm: a clock every 60 / (150 * 24) s. The spacing as it arrived is a measurement
  // of the machine as much as of ontogen (2.3 % off on a busy one): reported, not
  // asserted; bench/live_midi_timing.sh measures it. The clocks come in time order.
  ASSERT_GT(clocks.size(), 20u);
  for (size_t i = 1; i < clocks.size(); ++i) EXPECT_GE(clocks[i], clocks[i - 1]) << i;
  const double spacing = (clocks.back() - clocks.front()) / static_cast<double>(clocks.size() - 1);
  std::cout << clocks.size() << " clocks, mean spacing " << spacing * 1e3 << " ms (scheduled " << 60e3 / (150 * 24)
            << " ms)\n";
  RecordProperty("clock_spacing_ms", std::to_string(spacing * 1e3));
  // The notes arrived as without the clock.
  std::vector<std::vector<int>> sent, got;
  for (const json& event : file["timeline"]) sent.push_back(event[1].get<std::vector<int>>());
  for (const Arrival& arrival : received)
    if (arrival.bytes.at(0) < 0xF0) got.push_back(arrival.bytes);
  if (xruns() == 0) {
    std::map<int, std::vector<std::vector<int>>> sentBy, gotBy;
    for (auto& b : sent) sentBy[b[0] & 0x0F].push_back(b);
    for (auto& b : got) gotBy[b[0] & 0x0F].push_back(b);
    EXPECT_EQ(gotBy, sentBy);
  }
}

TEST_F(JackPeer, CtrlCStopsEveryNoteThatStartedAndExits130) {
  // A long piece: Ctrl-C after a second interrupts it.
  fs::path program = writeProgram("#tempo 120\nlsystem long {\n  #until 6\n  axiom A\n"
                                  "  interpret music A { [ channel(2) hold ] }\n"
                                  "  A -> F + A\n}\n");
  pid_t run = spawnShell(ontogenCommand("run '" + program.string() + "' --interpret music --midi-port 0 --out '" +
                                            (dir_ / "out").string() + "'",
                                        dir_ / "run.txt"));
  // Wait until it plays (the first note arrived), then interrupt.
  for (int i = 0; i < 200 && readFile(dir_ / "dump.txt").find("note on") == std::string::npos; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  kill(run, SIGINT);
  EXPECT_EQ(waitExit(run), 130) << readFile(dir_ / "run.txt");
  EXPECT_NE(readFile(dir_ / "run.txt").find("interrupted: every note stopped"), std::string::npos);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  std::vector<Arrival> received = arrivals();
  std::map<std::pair<int, int>, int> sounding;
  int ons = 0;
  std::map<int, bool> allOff;
  for (const Arrival& arrival : received) {
    int kind = arrival.bytes[0] & 0xF0, channel = arrival.bytes[0] & 0x0F;
    if (kind == 0x90) ++sounding[{channel, arrival.bytes[1]}], ++ons;
    if (kind == 0x80) --sounding[{channel, arrival.bytes[1]}];
    if (kind == 0xB0 && arrival.bytes[1] == 123) allOff[channel] = true;
  }
  EXPECT_GT(ons, 0);
  for (auto& [key, count] : sounding) EXPECT_EQ(count, 0) << "channel " << key.first << " pitch " << key.second;
  EXPECT_TRUE(allOff[0]);
  // The piece is 64 notes long; the interrupt came before its end (how long before
  // depends on how busy the machine is).
  EXPECT_LT(ons, 64);
}

TEST_F(JackPeer, AVirtualPortAppearsWhilePlaying) {
  fs::path program = writeProgram(kPiece);
  pid_t run = spawnShell(ontogenCommand("run '" + program.string() + "' --interpret music --virtual-port --out '" +
                                            (dir_ / "out").string() + "'",
                                        dir_ / "run.txt"));
  // Looked for as long as ontogen plays, however slowly a busy machine runs jack_lsp.
  bool seen = false;
  int status = 0;
  pid_t ended = 0;
  while (!seen && (ended = waitpid(run, &status, WNOHANG)) == 0) {
    seen = runCommand("jack_lsp 2>/dev/null").find("ontogen:ontogen") != std::string::npos;
    if (!seen) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  EXPECT_TRUE(seen) << runCommand("jack_lsp 2>&1");
  if (ended == 0) {
    EXPECT_EQ(waitExit(run), 0) << readFile(dir_ / "run.txt");
  } else {
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << readFile(dir_ / "run.txt");
  }
}

TEST_F(JackPeer, NoSuchPortIsExitCode5AndNamesThePorts) {
  fs::path err = dir_ / "err.txt";
  int code = -1;
  runCommand(std::string(ONTOGEN_EXECUTABLE) + " run " + ONTOGEN_SOURCE_DIR +
                 "/models/koch_melody.cell --interpret music --midi-port synth --out '" + (dir_ / "out").string() +
                 "' 2>'" + err.string() + "'",
             &code);
  EXPECT_EQ(code, 5);
  EXPECT_NE(readFile(err).find("ontogen: error: no MIDI output port 'synth'; the output ports are: 0 "
                               "'midi-monitor:input'"),
            std::string::npos)
      << readFile(err);
  // An index past every number is no port either, not an exception.
  runCommand(std::string(ONTOGEN_EXECUTABLE) + " run " + ONTOGEN_SOURCE_DIR +
                 "/models/koch_melody.cell --interpret music --midi-port 999999999999999999999999 --out '" +
                 (dir_ / "out").string() + "' 2>'" + err.string() + "'",
             &code);
  EXPECT_EQ(code, 5);
  EXPECT_NE(readFile(err).find("ontogen: error: no MIDI output port '999999999999999999999999'"), std::string::npos)
      << readFile(err);
}

TEST_F(JackPeer, APortIndexPastEveryNumberIsNoSuchPort) {
  fs::path err = dir_ / "err.txt";
  int code = -1;
  runCommand(std::string(ONTOGEN_EXECUTABLE) + " run " + ONTOGEN_SOURCE_DIR +
                 "/models/koch_melody.cell --interpret music --midi-port 99999999999999999999999 --out '" +
                 (dir_ / "out").string() + "' 2>'" + err.string() + "'",
             &code);
  EXPECT_EQ(code, 5);
  EXPECT_NE(readFile(err).find("ontogen: error: no MIDI output port '99999999999999999999999'"), std::string::npos)
      << readFile(err);
}

TEST(LiveMidi, WithoutAMidiSystemTheErrorIsClearAndExitCode5) {
  // A server name nobody runs: no JACK; and these machines have no ALSA sequencer.
  if (fs::exists("/dev/snd/seq")) GTEST_SKIP() << "this machine has an ALSA sequencer, so a MIDI system runs";
  setenv("JACK_DEFAULT_SERVER", ("ontogen_none_" + std::to_string(getpid())).c_str(), 1);
  fs::path dir = scratch("no_system");
  int code = -1;
  runCommand(std::string(ONTOGEN_EXECUTABLE) + " midi-ports 2>'" + (dir / "err.txt").string() + "'", &code);
  EXPECT_EQ(code, 5);
  EXPECT_EQ(readFile(dir / "err.txt"),
            "ontogen: error: no MIDI system is running (no JACK server and no ALSA sequencer); start one, e.g. "
            "'jackd -d dummy &' on a machine without a sound card\n");
  runCommand(std::string(ONTOGEN_EXECUTABLE) + " run " + ONTOGEN_SOURCE_DIR +
                 "/models/koch_melody.cell --interpret music --midi-port 0 --out '" + (dir / "out").string() + "' 2>/dev/null",
             &code);
  EXPECT_EQ(code, 5);
  EXPECT_FALSE(fs::exists(dir / "out"));  // nothing developed, nothing written
  runCommand(std::string(ONTOGEN_EXECUTABLE) + " run " + ONTOGEN_SOURCE_DIR +
                 "/models/koch_melody.cell --midi-port 0 --out '" + (dir / "out").string() + "' 2>/dev/null",
             &code);
  EXPECT_EQ(code, 2);  // live MIDI plays the music set only
}

}  // namespace
