// The ontogen executable: parses the command line and dispatches to apps/command_*.cpp.

#include <CLI/CLI.hpp>

#include <iostream>

#include "apps/commands.h"
#include "apps/program_loader.h"

namespace {

using namespace ontogen::app;

void addCommon(CLI::App& command, CommonOptions& options) {
  command.add_option("file", options.file, "The program (.cell, or cpfg's .l and L-Py's .lpy, converted first)")->required()->check(CLI::ExistingFile);
  command.add_option("--system", options.system, "The root system (default: the first in the file)");
  // One NAME=VALUE per flag, so a --define before the file does not swallow it.
  command.add_option("--define", options.defines, "Set the program's #define NAME to a number (repeatable)")
      ->type_name("NAME=VALUE")
      ->allow_extra_args(false);
}

void addDevelopment(CLI::App& command, CommonOptions& options) {
  command.add_option("--seed", options.seed, "Seed of every stochastic choice (default: #seed, else 1)");
  command.add_option("--step", options.step, "Step of the development, seconds (default: #dt, else 1)")
      ->check(CLI::PositiveNumber);
  command.add_option("--max-cells", options.limits.maxCells, "Stop if the model grows past N cells")
      ->capture_default_str();
  command.add_option_function<uint64_t>(
             "--max-memory", [&options](uint64_t mib) { options.limits.maxMemoryBytes = mib << 20; },
             "Stop if the pools pass this many MiB (default 8192)")
      ->check(CLI::PositiveNumber);
  command.add_option("--max-events", options.limits.maxEventsPerStep, "Stop after N terminal events in one step")
      ->capture_default_str();
  command.add_option("--threads", options.threads, "Threads for rules and rates (0, the default: all cores; same result)")
      ->check(CLI::NonNegativeNumber);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"ontogen: a simulator of hierarchical, cellular development for generative media"};
  app.require_subcommand(1);

  CommonOptions check;
  auto* checkCommand = app.add_subcommand("check", "Parse and check a program");
  addCommon(*checkCommand, check);

  RunOptions run;
  auto* runCommand = app.add_subcommand("run", "Develop a program and write one output per frame");
  addCommon(*runCommand, run.common);
  addDevelopment(*runCommand, run.common);
  runCommand->add_option("--until", run.until, "End of the run, seconds of developmental time (default: #until)")
      ->check(CLI::NonNegativeNumber);
  runCommand->add_option("--from", run.from, "Time of the first frame, seconds (default: #from, else 0)")
      ->check(CLI::NonNegativeNumber);
  runCommand->add_option("--frames", run.frames,
                         "Frames spread over [from, until]; 1: the end only (default: #fps frames a second, else 1)")
      ->check(CLI::Range(1, 1000000));
  runCommand->add_option("--interpret", run.sets,
                         "Interpretation sets, comma-separated: geometry, creature, image, music, trace (default: the "
                         "program's #interpret, else geometry)")
      ->delimiter(',');
  runCommand->add_option("--out", run.out, "Output directory")->capture_default_str();
  runCommand->add_option("--format", run.format,
                         "Geometry outputs, comma-separated: glb, png, png-frames, mp4, obj, ply, svg, joints")
      ->capture_default_str();
  runCommand->add_option("--view", run.view, "Camera azimuth,elevation in degrees (default: automatic)")
      ->delimiter(',')
      ->expected(2);
  runCommand->add_option("--size", run.size, "Picture size WIDTHxHEIGHT in pixels")->capture_default_str();
  runCommand->add_flag("--stats", run.stats, "Print cell count, steps and time taken");
  runCommand->add_option("--midi-port", run.midiPort, "Play the music set live on this MIDI port (name or index)");
  runCommand->add_flag("--virtual-port", run.virtualPort, "Play the music set live on a new MIDI port 'ontogen'");

  WordOptions word;
  auto* wordCommand = app.add_subcommand("word", "Print the derivation word at given times");
  addCommon(*wordCommand, word.common);
  addDevelopment(*wordCommand, word.common);
  wordCommand->add_option("--at", word.times, "Global times, comma-separated")->required()->delimiter(',');
  wordCommand->add_flag("--json", word.json, "Print one JSON object");
  wordCommand->add_option("--precision", word.precision, "Significant digits of the text form")
      ->check(CLI::Range(1, 17))
      ->capture_default_str();

  TimelineOptions timeline;
  auto* timelineCommand =
      app.add_subcommand("timeline", "Draw the time-state diagram of a development (paper 002, Fig. 5)");
  addCommon(*timelineCommand, timeline.common);
  addDevelopment(*timelineCommand, timeline.common);
  timelineCommand->add_option("--until", timeline.until, "End of the diagram, seconds (default: #until)")
      ->check(CLI::NonNegativeNumber);
  timelineCommand->add_option("--out", timeline.out, "The diagram to write (.svg, or .png without text)")->required();
  timelineCommand->add_option("--max-rows", timeline.maxRows, "Most cells drawn; later ones are counted")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();

  ConvertOptions convert;
  auto* convertCommand =
      app.add_subcommand("convert", "Print a cpfg (.l) or L-Py (.lpy) L-system as a cell-language program");
  convertCommand->add_option("file", convert.file, "The cpfg or L-Py file")->required()->check(CLI::ExistingFile);

  auto* midiPortsCommand = app.add_subcommand("midi-ports", "List the MIDI output ports --midi-port can play on");
  app.add_subcommand("help", "List commands, turtle commands and functions");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    int code = app.exit(error);
    return code == 0 ? kExitOk : kExitUsage;
  }
  if (checkCommand->parsed()) return runCheck(check);
  if (runCommand->parsed()) return runRun(run);
  if (wordCommand->parsed()) return runWord(word);
  if (timelineCommand->parsed()) return runTimeline(timeline);
  if (midiPortsCommand->parsed()) return runMidiPorts();
  if (convertCommand->parsed()) return runConvert(convert);
  return runHelp();
}
