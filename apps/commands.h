#pragma once
// The subcommands of the ontogen executable. Each takes its parsed options and returns
// an exit code (apps/program_loader.h).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/world.h"

namespace ontogen::app {

struct CommonOptions {
  std::string file;
  std::string system;               ///< root system, empty: the first
  std::optional<uint64_t> seed;     ///< empty: the program's #seed, else 1
  std::optional<double> step;       ///< empty: the program's #dt
  WorldLimits limits;
  unsigned threads = 0;             ///< 0: all cores
};

struct RunOptions {
  CommonOptions common;
  std::optional<double> until;      ///< empty: the program's #until
  int frames = 1;
  std::vector<std::string> sets{"geometry"};
  std::string out = "out";
  bool stats = false;
  std::string midiPort;        ///< play the music set live on this port (name or index)
  bool virtualPort = false;    ///< or on a virtual port named "ontogen"
};

struct WordOptions {
  CommonOptions common;
  std::vector<double> times;
  bool json = false;
  int precision = 6;
};

int runCheck(const CommonOptions& options);
int runRun(const RunOptions& options);
int runWord(const WordOptions& options);
int runHelp();
int runMidiPorts();

}  // namespace ontogen::app
