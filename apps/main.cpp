// The ontogen executable: parses the command line and dispatches to apps/command_*.cpp.

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <iostream>
#include <new>
#include <string_view>
#include <vector>

#include "apps/cli_values.h"
#include "apps/command_names.h"
#include "apps/commands.h"
#include "apps/program_loader.h"
#include "core/limits.h"
#include "interpreters/formats/look.h"
#include "interpreters/interpretation_set.h"
#include "interpreters/temporary_files.h"

namespace {

using namespace ontogen::app;

void addCommon(CLI::App& command, CommonOptions& options,
               const std::string& defineDoc = "Set the program's #define NAME to a number (repeatable)",
               const std::string& defineType = "NAME=VALUE") {
  command.add_option("file", options.file, "The program (.cell, or cpfg's .l and L-Py's .lpy, converted first)")->required()->check(CLI::ExistingFile);
  command.add_option("--system", options.system, "The root system (default: the first in the file)");
  // One NAME=VALUE per flag, so a --define before the file does not swallow it.
  command.add_option("--define", options.defines, defineDoc)
      ->type_name(defineType)
      ->allow_extra_args(false);
  addWholeOption(command, "--max-errors", options.maxErrors, WholeRange::between(0, kMaxErrorsLimit),
                 "Stop after N errors in the program (default 20; 0: report every one)");
  command
      .add_option_function<std::string>(
          "--max-source",
          [&options](const std::string& text) {
            options.maxSourceBytes = detail::wholeOrThrow("--max-source", text, WholeRange::between(1, kMaxSourceMiB)) << 20;
          },
          "Most MiB of source text, the program with its imports (default 16)")
      ->type_name("MIB");
}

// The step and the growth limits.
void addLimits(CLI::App& command, CommonOptions& options) {
  addRealOption(command, "--step", options.step, RealRange::above(0),
                "Step of the development, seconds (default: #dt, else 1)");
  addWholeOption(command, "--max-cells", options.limits.maxCells, WholeRange::atLeast(1),
                 "Stop if the model grows past N cells (default 100000000)");
  command
      .add_option_function<std::string>(
          "--max-memory",
          [&options](const std::string& text) {
            options.limits.maxMemoryBytes =
                detail::wholeOrThrow("--max-memory", text, WholeRange::between(1, kMaxMemoryMiB)) << 20;
          },
          "Stop if the pools and outputs pass this many MiB (default: half the memory this process may use, here " +
              std::to_string(ontogen::defaultMemoryLimitBytes() >> 20) + ")")
      ->type_name("MIB");
  addWholeOption(command, "--max-events", options.limits.maxEventsPerStep, WholeRange::atLeast(1),
                 "Stop after N terminal events in one step (default 200000000)");
  addWholeOption(command, "--max-steps", options.limits.maxSteps, WholeRange::atLeast(1),
                 "Stop if the development would take more than N steps");
}

void addDevelopment(CLI::App& command, CommonOptions& options) {
  addWholeOption(command, "--seed", options.seed, WholeRange::any(), "Seed of every stochastic choice (default: #seed, else 1)");
  addLimits(command, options);
  addWholeOption(command, "--threads", options.threads, WholeRange::between(0, kMaxThreads),
                 "Threads for rules and rates (0, the default: all cores; same result)");
}

// `--size WxH`, a picture's size in pixels, kept as written.
void addSizeOption(CLI::App& command, std::string& into, const std::string& doc) {
  command
      .add_option_function<std::string>(
          "--size",
          [&into](const std::string& text) {
            if (!parsePictureSize(text))
              throw CLI::ValidationError("--size", "'" + text + "' is not WIDTHxHEIGHT in pixels, each 1 to " +
                                                       std::to_string(kMaxPictureSide) + ", as in 800x600");
            into = text;
          },
          doc)
      ->type_name("WxH");
}

// What `sweep` and `evolve` share: each variant's run, its measures, the output folder.
void addSweepCommon(CLI::App& command, SweepCommonOptions& options, const std::string& defineDoc,
                    const std::string& defineType) {
  addCommon(command, options.common, defineDoc, defineType);
  addLimits(command, options.common);
  addRealOption(command, "--until", options.until, RealRange::atLeast(0),
                "End of each variant's development, seconds (default: #until)");
  addWholeOption(command, "--frames", options.frames, WholeRange::between(1, kMaxFrames),
                 "Frames of each variant's run over [from, until] (default: #fps, else one); the measures "
                 "of the creature set follow them");
  command.add_option("--measure", options.measures, "A column of the table: NAME=EXPR over what the run reports (repeatable)")
      ->type_name("NAME=EXPR")
      ->allow_extra_args(false);
  command.add_option("--interpret", options.sets, "Interpretation sets of each variant (default: #interpret, else geometry)")
      ->delimiter(',');
  command.add_option("--out", options.out, "The output folder: results.csv, results.json, gallery.png, thumbnails/, programs/")
      ->required();
  command.add_flag("--resume", options.resume, "Continue the sweep in --out, skipping the variants it finished");
  // Flag functions: CLI11 gives an std::optional<bool> flag a value even when absent.
  command.add_flag_function("--progress", [&options](std::int64_t) { options.progress = true; },
                            "Draw the progress bar on stderr, on rank 0 only (default: when stderr is a terminal; "
                            "under mpirun it is not, so ask)");
  command.add_flag_function("--no-progress", [&options](std::int64_t) { options.progress = false; },
                            "Draw no progress bar");
  addWholeOption(command, "--workers", options.workers, WholeRange::between(0, kMaxThreads),
                 "Variants run at once on this machine, one thread each (0, the default: all cores; same result)");
  addSizeOption(command, options.size, "Thumbnail size WIDTHxHEIGHT in pixels (default 128x128)");
  addRealListOption(command, "--view", options.view, {RealRange::between(-360, 360), RealRange::between(-90, 90)},
                    "Camera azimuth,elevation in degrees (default: automatic)")
      ->type_name("AZ,EL");
}

// A flag the command does not have, with the nearest one it does; empty when every
// flag is known (the error is something else).
std::string unknownFlagMessage(const CLI::App& command, int argc, const char* const* argv) {
  std::vector<std::string> names;
  for (const CLI::Option* option : command.get_options())
    for (const std::string& name : option->get_lnames()) names.push_back("--" + name);
  std::vector<std::string_view> views(names.begin(), names.end());
  for (int i = 2; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (!arg.starts_with("--")) continue;
    const std::string_view flag = arg.substr(0, arg.find('='));
    if (std::find(views.begin(), views.end(), flag) != views.end()) continue;
    std::string message = "unknown flag '" + std::string(flag) + "' for '" + command.get_name() + "'";
    if (std::string nearest = nearMiss(flag, views); !nearest.empty()) message += "; did you mean '" + nearest + "'?";
    return message + " (ontogen " + command.get_name() + " --help lists them)";
  }
  return {};
}

int dispatch(int argc, char** argv) {
  CLI::App app{"ontogen: a simulator of hierarchical, cellular development for generative media"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("ontogen ") + ONTOGEN_VERSION);
  // One line, like every other message of the executable; subcommands copy it.
  app.failure_message(
      [](const CLI::App*, const CLI::Error& error) { return "ontogen: error: " + std::string(error.what()) + "\n"; });
  if (std::string message = emptyAssignment(argc, argv); !message.empty()) {
    std::cerr << "ontogen: error: " << message << "\n";
    return kExitUsage;
  }
  if (std::string message = emptyListItem(argc, argv, {"--at", "--view", "--format", "--interpret"});
      !message.empty()) {
    std::cerr << "ontogen: error: " << message << "\n";
    return kExitUsage;
  }
  if (std::string message = unknownCommandMessage(argc, argv); !message.empty()) {
    std::cerr << "ontogen: error: " << message << "\n";
    return kExitUsage;
  }

  CommonOptions check;
  auto* checkCommand = app.add_subcommand("check", "Parse and check a program");
  addCommon(*checkCommand, check);

  RunOptions run;
  auto* runCommand = app.add_subcommand("run", "Develop a program and write one output per frame");
  addCommon(*runCommand, run.common);
  addDevelopment(*runCommand, run.common);
  addRealOption(*runCommand, "--until", run.until, RealRange::atLeast(0),
                "End of the run, seconds of developmental time (default: #until)");
  addRealOption(*runCommand, "--from", run.from, RealRange::atLeast(0),
                "Time of the first frame, seconds (default: #from, else 0)");
  addWholeOption(*runCommand, "--frames", run.frames, WholeRange::between(1, kMaxFrames),
                 "Frames spread over [from, until]; 1: the end only (default: from --speed or #speed, else #fps "
                 "frames a second, else a 4 s movie when mp4 is written, else 1)");
  addRealOption(*runCommand, "--speed", run.speed, RealRange::above(0),
                "Seconds of developmental time a second of the movie shows: frames S/fps apart (default: #speed)")
      ->type_name("S");
  addRealOption(*runCommand, "--fps", run.fps, RealRange::between(1, kMaxMovieFps),
                "Frames per second of the movie (default 25); #fps is another thing, frames per second of growth")
      ->type_name("F");
  runCommand
      ->add_option_function<std::string>(
          "--look",
          [&run](const std::string& text) {
            if (!ontogen::findLook(text))
              throw CLI::ValidationError("--look", "'" + text + "' is no look (known: " + ontogen::lookList() + ")");
            run.look = text;
          },
          "Background, light and palette of pictures and movies: " + ontogen::lookList() + " (default: #look, else light)")
      ->type_name("NAME");
  runCommand->add_option("--interpret", run.sets,
                         "Interpretation sets, comma-separated: geometry, creature, dynamics, physics, image, music, trace (default: the "
                         "program's #interpret, else geometry)")
      ->delimiter(',');
  runCommand->add_option("--out", run.out, "Output directory")->capture_default_str();
  runCommand->add_option("--format", run.format,
                         "Geometry outputs, comma-separated: glb, png, png-frames, mp4, obj, ply, ply-ascii, svg, joints, mjcf (the dynamics set's MuJoCo model); none: grow only, "
                         "interpret and write nothing (with --stats, for measuring)")
      ->capture_default_str();
  addRealListOption(*runCommand, "--view", run.view, {RealRange::between(-360, 360), RealRange::between(-90, 90)},
                    "Camera azimuth,elevation in degrees (default: automatic)")
      ->type_name("AZ,EL");
  addSizeOption(*runCommand, run.size, "Picture size WIDTHxHEIGHT in pixels (default 800x800)");
  runCommand
      ->add_option_function<std::string>(
          "--up",
          [&run](const std::string& text) {
            if (text != "y" && text != "z")
              throw CLI::ValidationError("--up", "'" + text + "' is no up axis: y (ontogen's own) or z (Blender, most PLY viewers)");
            run.up = text == "z" ? ontogen::UpAxis::Z : ontogen::UpAxis::Y;
          },
          "Up axis of the OBJ and PLY files: y (default, as the model grows) or z (turned a quarter about x)")
      ->type_name("y|z");
  runCommand->add_flag("--stats", run.stats, "Print cell count, steps and time taken");
  runCommand->add_option("--midi-port", run.midiPort, "Play the music set live on this MIDI port (name or index)");
  runCommand->add_flag("--virtual-port", run.virtualPort, "Play the music set live on a new MIDI port 'ontogen'");
  runCommand->add_flag("--midi-clock", run.midiClock,
                       "With live playback, send MIDI clock (start, 24 clocks a quarter note, stop) so a DAW follows");

  WordOptions word;
  auto* wordCommand = app.add_subcommand("word", "Print the derivation word at given times");
  addCommon(*wordCommand, word.common);
  addDevelopment(*wordCommand, word.common);
  addRealListOption(*wordCommand, "--at", word.times, {RealRange::atLeast(0)}, "Global times, seconds, comma-separated")
      ->required();
  wordCommand
      ->add_flag("--json{full}", word.json,
                 "Print one JSON object: --json every field, ids and parents included; --json=compact "
                 "labels, values and the ages of timed cells, without ids")
      ->check(CLI::IsMember({"full", "compact"}));
  wordCommand->add_flag("--interpreted", word.interpreted,
                        "Print the word as interpretation reads it, after the homomorphism rules");
  addWholeOption(*wordCommand, "--precision", word.precision, WholeRange::between(1, 17),
                 "Significant digits of the text form (default 6)");

  StaticsOptions statics;
  auto* staticsCommand =
      app.add_subcommand("statics", "Solve the physics design model of the word at a time (paper 003)");
  addCommon(*staticsCommand, statics.common);
  addDevelopment(*staticsCommand, statics.common);
  addRealOption(*staticsCommand, "--at", statics.at, RealRange::atLeast(0), "Global time, seconds (default: #until)");
  staticsCommand->add_flag("--json", statics.json, "Print one JSON object");
  staticsCommand->add_option("--equations", statics.equations, "Write the system of equations to this text file");

  TimelineOptions timeline;
  auto* timelineCommand =
      app.add_subcommand("timeline", "Draw the time-state diagram of a development (paper 002, Fig. 5)");
  addCommon(*timelineCommand, timeline.common);
  addDevelopment(*timelineCommand, timeline.common);
  addRealOption(*timelineCommand, "--until", timeline.until, RealRange::atLeast(0), "End of the diagram, seconds (default: #until)");
  timelineCommand->add_option("--out", timeline.out, "The diagram to write (.svg, or .png without text)")->required();
  addWholeOption(*timelineCommand, "--max-rows", timeline.maxRows, WholeRange::between(1, kMaxTimelineRows),
                 "Most cells drawn; later ones are counted (default 4000)");

  StudioOptions studio;
  auto* studioCommand = app.add_subcommand(
      "studio", "Serve a live page at 127.0.0.1: the model in 3-D, re-grown as its file is saved, with time and "
                "#define sliders, its music, and a gallery of variants to breed");
  addCommon(*studioCommand, studio.common);
  addDevelopment(*studioCommand, studio.common);
  addRealOption(*studioCommand, "--until", studio.until, RealRange::atLeast(0),
                "End of the development, seconds (default: #until)");
  addWholeOption(*studioCommand, "--frames", studio.frames, WholeRange::between(1, kMaxFrames),
                 "Frames of the animation over [from, until] (default: #fps frames a second, else 60)");
  addWholeOption(*studioCommand, "--port", studio.port, WholeRange::between(0, 65535),
                 "Port on 127.0.0.1 (default 8420; 0: a free one, printed)");
  addWholeOption(*studioCommand, "--gallery-seed", studio.gallerySeed, WholeRange::any(),
                 "Seed of the gallery's mutations (default 1)");
  studioCommand->add_flag("--vary-constants", studio.varyConstants,
                          "The gallery varies the program's numeric constants as well as its #defines");
  studioCommand->add_option("--save", studio.save, "Folder saved variants go to (default: the program's folder)");
  studioCommand->add_option("--interpret", studio.sets,
                            "Interpretation sets, comma-separated, as run's: music sounds in the page (default: the "
                            "program's #interpret, else geometry)")
      ->delimiter(',');

  ConvertOptions convert;
  auto* convertCommand =
      app.add_subcommand("convert", "Print a cpfg (.l) or L-Py (.lpy) L-system as a cell-language program");
  convertCommand->add_option("file", convert.file, "The cpfg or L-Py file")->required()->check(CLI::ExistingFile);

  SweepOptions sweep;
  auto* sweepCommand = app.add_subcommand(
      "sweep", "Run every combination of defines and seeds on all cores (and MPI ranks) into a table of measures");
  addSweepCommon(*sweepCommand, sweep.sweep,
                 "Values of the program's #define NAME: A:B:N, N values from A to B, or a list (repeatable)",
                 "NAME=A:B:N|v1,v2");
  addWholeOption(*sweepCommand, "--seed", sweep.sweep.common.seed, WholeRange::any(),
                 "The one seed of every variant (default: #seed, else 1)");
  sweepCommand->add_option("--seeds", sweep.seeds, "Seeds S1 to S2, each variant with each (default: --seed)")
      ->type_name("S1:S2");

  EvolveOptions evolve;
  auto* evolveCommand = app.add_subcommand(
      "evolve", "Evolve a program's #define values (and constants) for the first --measure, a generation at a time");
  addSweepCommon(*evolveCommand, evolve.sweep, "Hold the program's #define NAME at a number: no gene (repeatable)",
                 "NAME=VALUE");
  addWholeOption(*evolveCommand, "--seed", evolve.sweep.common.seed, WholeRange::any(),
                 "Seed of every variant's world (default: #seed, else 1)");
  addWholeOption(*evolveCommand, "--generations", evolve.generations, WholeRange::between(1, kMaxGenerations),
                 "Generations (default 10)");
  addWholeOption(*evolveCommand, "--population", evolve.population, WholeRange::between(2, kMaxPopulation),
                 "Variants a generation (default 12)");
  addWholeOption(*evolveCommand, "--elite", evolve.elite, WholeRange::between(0, kMaxPopulation - 1),
                 "The fittest kept unchanged into the next generation (default 2)");
  std::optional<double> crossover, mutationRate, mutationStrength;
  addRealOption(*evolveCommand, "--crossover", crossover, RealRange::between(0, 1),
                "Chance a child has two parents (uniform crossover) rather than one (default 0.7)");
  addRealOption(*evolveCommand, "--mutation-rate", mutationRate, RealRange::between(0, 1),
                "Chance each gene of a child is mutated; at least one always is (default 0.3)");
  addRealOption(*evolveCommand, "--mutation-strength", mutationStrength, RealRange::between(1e-9, 1),
                "A mutation's standard deviation, a fraction of the gene's range (default 0.15)");
  addWholeOption(*evolveCommand, "--evolve-seed", evolve.evolveSeed, WholeRange::any(),
                 "Seed of selection, crossover and mutation (default 1)");
  evolveCommand->add_flag("--vary-constants", evolve.varyConstants,
                          "Also evolve the numeric constants of the program's rules and expressions");
  evolveCommand->add_option("--range", evolve.ranges, "A gene's range, over the program's #range (repeatable)")
      ->type_name("NAME=LOW:HIGH")
      ->allow_extra_args(false);

  auto* midiPortsCommand = app.add_subcommand("midi-ports", "List the MIDI output ports --midi-port can play on");
  HelpOptions help;
  auto* helpCommand = app.add_subcommand("help", "List commands, keywords, directives, set commands and functions");
  helpCommand->add_flag("--grammar", help.grammar,
                        "Print the cell language's TextMate grammar (JSON) for editors, made from the same tables");
  helpCommand->add_flag("--reference", help.reference,
                        "Print the sets' commands as Markdown (docs/COMMANDS.md), made from the same tables");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    if (dynamic_cast<const CLI::ExtrasError*>(&error) && argc > 1)
      for (const CLI::App* command : app.get_subcommands([&](CLI::App* c) { return c->get_name() == argv[1]; }))
        if (std::string message = unknownFlagMessage(*command, argc, argv); !message.empty()) {
          std::cerr << "ontogen: error: " << message << "\n";
          return kExitUsage;
        }
    int code = app.exit(error);
    return code == 0 ? kExitOk : kExitUsage;
  }
  if (checkCommand->parsed()) return runCheck(check);
  if (runCommand->parsed()) return runRun(run);
  if (wordCommand->parsed()) return runWord(word);
  if (staticsCommand->parsed()) return runStatics(statics);
  if (timelineCommand->parsed()) return runTimeline(timeline);
  if (midiPortsCommand->parsed()) return runMidiPorts();
  if (convertCommand->parsed()) return runConvert(convert);
  if (studioCommand->parsed()) return runStudio(studio);
  if (sweepCommand->parsed()) return runSweep(sweep);
  if (evolveCommand->parsed()) {
    if (crossover) evolve.crossover = *crossover;
    if (mutationRate) evolve.mutationRate = *mutationRate;
    if (mutationStrength) evolve.mutationStrength = *mutationStrength;
    return runEvolve(evolve);
  }
  return runHelp(help);
}

}  // namespace

// A command's words on standard output are an output like any file: when they could not
// all be written (a full disk, /dev/full, a closed terminal) the command fails with
// kExitOutputError, unless it failed already for its own reason.
int checkStandardOutput(int code) {
  std::cout.flush();
  errno = 0;
  const bool failed = !std::cout || std::fflush(stdout) != 0 || std::ferror(stdout) != 0;
  if (!failed) return code;
  const int error = errno;
  std::cerr << "ontogen: error: cannot write the standard output" << (error != 0 ? std::string(": ") + std::strerror(error) : "")
            << "\n";
  return code == kExitOk ? kExitOutputError : code;
}

// Nothing ontogen throws may end the process through std::terminate: what the commands
// do not turn into a message of their own becomes one here, with its exit code.
int main(int argc, char** argv) {
  ontogen::removeTemporariesOnSignals();
  try {
    return checkStandardOutput(dispatch(argc, argv));
  } catch (const ontogen::OutputError& error) {
    std::cerr << "\nontogen: error: " << error.what() << "\n";
    return kExitOutputError;
  } catch (const std::bad_alloc&) {
    std::cerr << "\nontogen: error: the machine ran out of memory; lower the limits with --max-memory MIB or "
                 "--max-cells N\n";
    return kExitModelError;
  } catch (const ontogen::LimitError& limit) {
    std::cerr << "\nontogen: error: " << limit.what() << "\n";
    return kExitModelError;
  } catch (const std::exception& error) {
    // The libraries' logic errors already say "ontogen: internal error: "; say it once.
    std::string_view what = error.what();
    for (std::string_view prefix : {"ontogen: internal error: ", "ontogen: "})
      if (what.starts_with(prefix)) {
        what.remove_prefix(prefix.size());
        break;
      }
    std::cerr << "\nontogen: internal error: " << what << " (please report it)\n";
    return kExitInternalError;
  } catch (...) {
    std::cerr << "\nontogen: internal error: an unknown exception (please report it)\n";
    return kExitInternalError;
  }
}
