#pragma once
// The subcommands of the ontogen executable. Each takes its parsed options and returns
// an exit code (apps/program_loader.h).

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "batch/sweep.h"
#include "core/world.h"
#include "model/diagnostics.h"
#include "lang/source_reader.h"
#include "interpreters/set_registry.h"

namespace ontogen::app {

// The ranges of the flags, each with why it is that number.
/// --max-errors: past a million errors no one reads them.
inline constexpr uint64_t kMaxErrorsLimit = 1'000'000;
/// --max-source, MiB: 4 GiB is what a byte offset in the source (uint32_t) can reach.
inline constexpr uint64_t kMaxSourceMiB = 4095;
/// --max-memory, MiB: the most whose bytes a uint64_t still holds.
inline constexpr uint64_t kMaxMemoryMiB = (uint64_t{1} << 44) - 1;
/// --threads: more threads than cores only slow a run down, and no machine has more.
inline constexpr uint64_t kMaxThreads = 4096;
/// --frames: a million frames is eleven hours of film at 25 per second.
inline constexpr uint64_t kMaxFrames = 1'000'000;
/// --fps: 240 frames a second is the fastest displays show; 1 the slowest a movie is.
inline constexpr double kMaxMovieFps = 240;
/// --fps when not given: PAL's 25, smooth enough for growth and what ffmpeg assumes.
inline constexpr double kDefaultMovieFps = 25;
/// --generations, --population: ten thousand of each is a million runs, days of work for
/// a small model on a cluster; a larger evolution is a mistyped number.
inline constexpr uint64_t kMaxGenerations = 10'000;
inline constexpr uint64_t kMaxPopulation = 10'000;
/// Variants of one sweep (batch/sweep.h says why).
inline constexpr uint64_t kMaxVariants = kMaxSweepVariants;
/// --max-rows: a diagram taller than ten million rows is no picture.
inline constexpr uint64_t kMaxTimelineRows = 10'000'000;

struct CommonOptions {
  std::string file;
  std::string system;               ///< root system, empty: the first
  std::vector<std::string> defines;  ///< `--define NAME=VALUE` as written, in order
  std::optional<uint64_t> seed;     ///< empty: the program's #seed, else 1
  std::optional<double> step;       ///< empty: the program's #dt
  WorldLimits limits;
  unsigned threads = 0;             ///< 0: all cores
  int maxErrors = kDefaultMaxErrors;  ///< errors reported before the check stops; 0: all
  uint64_t maxSourceBytes = kDefaultMaxSourceBytes;  ///< of the program and its imports
};

struct RunOptions {
  CommonOptions common;
  std::optional<double> until;      ///< empty: the program's #until
  std::optional<double> from;       ///< empty: the program's #from
  std::optional<int> frames;        ///< empty: from the speed, the program's #fps, a default movie, else 1
  std::optional<double> speed;      ///< seconds of developmental time a second of movie shows; empty: #speed
  std::optional<double> fps;        ///< frames per second of the movie; empty: kDefaultMovieFps
  std::optional<std::string> look;  ///< look of pictures and movies; empty: the program's #look, else light
  std::vector<std::string> sets;    ///< empty: the program's #interpret, else geometry
  std::string out = "out";
  bool stats = false;
  std::string format = "glb,png";   ///< geometry outputs, comma-separated
  std::vector<double> view;         ///< azimuth, elevation in degrees; empty: automatic
  std::string size = "800x800";     ///< picture size, WIDTHxHEIGHT pixels
  UpAxis up = UpAxis::Y;            ///< up axis of the OBJ and PLY files
  std::string midiPort;        ///< play the music set live on this port (name or index)
  bool virtualPort = false;    ///< or on a virtual port named "ontogen"
  bool midiClock = false;      ///< send MIDI clock with the live playback
};

struct WordOptions {
  CommonOptions common;
  std::vector<double> times;
  /// "full" (--json) or "compact" (--json=compact, docs/LANGUAGE.md "The word as JSON");
  /// empty: the text.
  std::string json;
  int precision = 6;
  bool interpreted = false;  ///< print the homomorphism's image, as interpretation reads it
};

struct TimelineOptions {
  CommonOptions common;
  std::optional<double> until;      ///< empty: the program's #until
  std::string out;                  ///< the .svg or .png to write
  size_t maxRows = 4000;
};

struct StaticsOptions {
  CommonOptions common;
  std::optional<double> at;  ///< empty: the program's #until
  bool json = false;
  std::string equations;     ///< the text file of the equations to write; empty: none
};

struct StudioOptions {
  CommonOptions common;
  std::optional<double> until;  ///< empty: the program's #until
  std::optional<int> frames;    ///< empty: the program's #fps, else 60
  uint16_t port = 8420;         ///< 0: a free port
  uint64_t gallerySeed = 1;     ///< of the gallery's mutations
  bool varyConstants = false;   ///< the gallery varies numeric constants as well as defines
  std::string save;             ///< where saved variants go; empty: the program's folder
  std::vector<std::string> sets;  ///< empty: the program's #interpret, else geometry
};

struct HelpOptions {
  bool grammar = false;  ///< print the editors' TextMate grammar instead (editors/text_mate_grammar.h)
  bool reference = false;  ///< print the sets' command reference instead (editors/command_reference.h)
};

/// What `sweep` and `evolve` share.
struct SweepCommonOptions {
  CommonOptions common;              ///< common.defines: sweep's NAME=A:B:N or lists, evolve's fixed values
  std::optional<double> until;       ///< empty: the program's #until
  std::optional<int> frames;         ///< empty: the program's #fps, else 1
  std::vector<std::string> measures; ///< `NAME=EXPR`, as given
  std::vector<std::string> sets;     ///< empty: the program's #interpret, else geometry
  std::string out;                   ///< the output folder
  bool resume = false;
  std::optional<bool> progress;      ///< --progress / --no-progress; empty: when stderr is a terminal
  unsigned workers = 0;              ///< 0: all cores
  std::string size = "128x128";      ///< thumbnails, WIDTHxHEIGHT pixels
  std::vector<double> view;          ///< azimuth, elevation in degrees; empty: automatic
};

struct SweepOptions {
  SweepCommonOptions sweep;
  std::string seeds;  ///< "S1:S2" or "S"; empty: --seed, else the program's #seed
};

struct EvolveOptions {
  SweepCommonOptions sweep;
  int generations = 10;
  int population = 12;
  int elite = 2;
  double crossover = 0.7;          ///< chance a child is bred from two parents rather than one
  double mutationRate = 0.3;       ///< VariationOptions::rate
  double mutationStrength = 0.15;  ///< VariationOptions::strength
  uint64_t evolveSeed = 1;         ///< of selection, crossover and mutation
  bool varyConstants = false;
  std::vector<std::string> ranges;  ///< `NAME=LOW:HIGH`, as given
};

struct ConvertOptions {
  std::string file;  ///< a cpfg (.l) or L-Py (.lpy) file
};

/// The world's settings from the command line, the program's directives filling in.
inline WorldDef worldDefOf(const CommonOptions& options, const Program& program) {
  WorldDef def;
  def.seed = options.seed.value_or(program.seed);
  def.limits = options.limits;
  def.threads = options.threads;
  // Query modules are answered by the turtle, as the geometry set draws the word, or by
  // the physics set's solve.
  def.environment = queryEnvironmentOf(program);
  return def;
}

/// Runs a development; a model that fails or passes a limit is reported on stderr and
/// gives kExitModelError, success gives 0.
int developReporting(const std::function<void()>& develop);

int runCheck(const CommonOptions& options);
int runTimeline(const TimelineOptions& options);
int runRun(const RunOptions& options);
int runWord(const WordOptions& options);
int runStatics(const StaticsOptions& options);
int runHelp(const HelpOptions& options);
int runConvert(const ConvertOptions& options);
int runStudio(const StudioOptions& options);
int runMidiPorts();
int runSweep(const SweepOptions& options);
int runEvolve(const EvolveOptions& options);

}  // namespace ontogen::app
