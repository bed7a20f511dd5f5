#pragma once
// An interpretation set realises a developed world: the interpreter walks the cells in
// pool order and hands each instruction (a command the compiler resolved, and its
// evaluated arguments) to the set. A set produces a frame and an output stage writes it:
// the geometry set draws a scene (interpreters/scene.h) that a run merges with the
// scenes of other drawing sets and writes through formats/scene_output.h; the music set
// plays a score that music/score_output.h writes and performs; the image set paints a
// picture that formats/picture_output.h writes. endFrame() finishes a frame and writes
// it through the set's stage when the set is used on its own. Sets never print; they
// report problems by throwing OutputError and by takeWarnings().

#include <cstdint>
#include <filesystem>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "model/source.h"

namespace ontogen {

struct Scene;

/// A failure to write an output (disk, permissions); carries a message for the user.
struct OutputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Where a frame's outputs go: DIR/<stem>[_<frame, 4 digits>].<ext>.
struct FrameTarget {
  std::filesystem::path directory;
  std::string stem;       ///< the model's name
  int frame = 0;          ///< index of the frame, from 0
  int frameCount = 1;     ///< frames in the run; a single frame gets no number in its name
  double time = 0;        ///< global time of the frame, seconds of developmental time
};

/// The cell whose instructions come next, for sets that follow cells over time.
struct CellContext {
  uint64_t id = 0;     ///< the cell's stable id
  uint64_t parent = ~uint64_t{0};  ///< the id of the cell it hangs from (core/parents.h); all ones: none
  double birth = 0;    ///< global time at which the cell had age 0, seconds
  double lifetime = 0; ///< terminal age, seconds (infinite: lives until an action removes it)
  double time = 0;     ///< global time of the word being interpreted, seconds
  std::string_view label;  ///< the master's label (the program outlives every run)
};

/// Where the instructions a set executes next come from: the instruction's source (or
/// the symbol's), the cell's label and the time of the word. Set by the interpreter.
struct InstructionSite {
  SourceSpan span;
  std::string_view cell;  ///< the master's label (the program outlives every run)
  double time = 0;        ///< seconds
};

/// An instruction a set cannot carry out (a pixel outside any picture, a note past the
/// end of any MIDI file, a surface never defined): a run-time error of the model,
/// located at the instruction, its cell and the time of its word.
struct InstructionError : std::runtime_error {
  InstructionError(const std::string& message, const InstructionSite& site)
      : std::runtime_error(message), span(site.span), cell(site.cell), time(site.time) {}
  SourceSpan span;
  std::string cell;  ///< the label of the cell whose instruction it is
  double time = 0;   ///< of the word, seconds
};

/// A kind of problem a set skipped over: how often, and where it happened first.
struct SetWarning {
  std::string message;  ///< "the turtle ignored 2 unmatched ']'"
  SourceSpan span;      ///< the first instruction it happened at (may be invalid)
  std::string cell;     ///< that instruction's cell
  double time = 0;      ///< and the time of its word, seconds
  uint64_t count = 0;
};

/// Counts one kind of problem and keeps where it first happened.
struct WarningCounter {
  uint64_t count = 0;
  InstructionSite first;
  void add(uint64_t n, const InstructionSite& site) {
    if (n == 0) return;
    if (count == 0) first = site;
    count += n;
  }
  /// Appends a SetWarning with `message` when anything was counted, and starts again.
  void takeInto(std::vector<SetWarning>& out, std::string message) {
    if (count > 0) out.push_back({std::move(message), first.span, std::string(first.cell), first.time, count});
    *this = {};
  }
};

class InterpretationSet {
 public:
  virtual ~InterpretationSet() = default;

  /// The name programs use in `interpret NAME { ... }` and `--interpret NAME`.
  virtual std::string_view name() const = 0;
  /// True if the set executes this command (so the interpreter can tell a user symbol
  /// with no meaning from one the set draws).
  virtual bool knows(std::string_view command) const = 0;
  /// Resets the set's state (turtle, buffers) for a new frame.
  virtual void beginFrame(const FrameTarget& target) = 0;
  /// Executes one instruction. Unknown commands are ignored (knows() says which).
  virtual void execute(std::string_view command, std::span<const double> args) = 0;
  /// Executes an instruction the compiler resolved: `id` is the command's number in the
  /// table this set gave the compiler (set_registry.h, commandSets(); CommandInfo::id),
  /// `command` its name. The default runs it by name; a set with a table runs it by id,
  /// so nothing looks a command up per cell and frame.
  virtual void executeCommand(int /*id*/, std::string_view command, std::span<const double> args) {
    execute(command, args);
  }
  /// Finishes the frame and writes its outputs; returns the paths written.
  virtual std::vector<std::filesystem::path> endFrame() = 0;

  /// True for a set that follows the development over time (music in developmental
  /// time): a run calls beginFrame once, interpretWord at the start and after every step
  /// of the development, and endFrame at the end, instead of one frame per --frames.
  virtual bool followsDevelopment() const { return false; }
  /// True for a set that simulates between frames (the dynamics set): a run feeds it the
  /// word at the start and at every instant of the step grid k * dt (never at a frame off
  /// that grid, so frames cannot change what it does), and at each frame calls
  /// beginFrame() and contribute() without a word; at the end, endFrame() returns the
  /// files it wrote of the whole run. It must also draw a scene (drawsScene()).
  virtual bool simulates() const { return false; }
  /// Another set whose `interpret` blocks this set reads where a cell has none of its own
  /// (the dynamics set reads the creature set's); their instructions come by name
  /// through execute(). Empty: none.
  virtual std::string_view alsoReads() const { return {}; }
  /// Called by interpretWord before the first cell of a word, with the word's time.
  virtual void beginWord(double /*time*/) {}
  /// Called by interpretWord after beginWord with the number of cells of the word's root
  /// pool, so that a set can size what it records once (a hint: an image or nested pools
  /// may hold more).
  virtual void expectCells(std::size_t /*cells*/) {}
  /// Called by interpretWord before the instructions of each cell the set realises.
  virtual void beginCell(const CellContext& /*cell*/) {}
  /// True when the set reads CellContext::parent (finding parents costs a pass over the word).
  virtual bool wantsParents() const { return false; }
  /// False when the set never reads CellContext::id: a compact word then does not compute
  /// the id of a cell nothing else reads it of (a hash a module; docs/COMPACT_WORDS.md).
  /// A word grown without ids is then walked as it is held, without the replay that makes
  /// its ids again, when nothing else reads them (parents, a homomorphism, interpretation
  /// blocks, development functions, nested pools): CellContext::id is 0 and the birth of
  /// a timeless module that of the run it joined ("Words without ids" there).
  virtual bool wantsIds() const { return true; }
  /// Called by interpretWord after the last cell of a word.
  virtual void endWord() {}

  /// True for a set that draws a scene (interpreters/scene.h) instead of writing files:
  /// at the end of a frame a run calls contribute() instead of endFrame(), and the output
  /// stage writes the scene every such set drew into.
  virtual bool drawsScene() const { return false; }
  /// Finishes the frame and adds what the set drew to `scene`.
  virtual void contribute(Scene& /*scene*/) {}

  /// Tells the set where the next instructions come from (for its warnings and errors).
  void locate(const InstructionSite& site) { site_ = site; }
  /// The problems skipped over since the last call, one entry per kind; starts again.
  virtual std::vector<SetWarning> takeWarnings() { return {}; }

 protected:
  /// Stops the run with an InstructionError at the instruction being executed.
  [[noreturn]] void refuse(const std::string& message) const { throw InstructionError(message, site_); }

  InstructionSite site_;  ///< of the instruction being executed
};

}  // namespace ontogen
