#include "interpreters/interpret.h"

#include <optional>

#include "core/cell_frame.h"
#include "core/homomorphism.h"
#include "core/parents.h"
#include "core/salts.h"
#include "core/word.h"
#include "pools/label_cursor.h"

namespace ontogen {

namespace {

// Whether the set runs a command of each master: its number in the set's table (the
// compiler resolved it, Program::commandSets), -2 by name (a set the compiler did not
// know, asked once per master), -1 none.
class CommandsOfMasters {
 public:
  CommandsOfMasters(const Program& program, const InterpretationSet& set)
      : program_(program),
        set_(set),
        setIndex_(program.commandSetIndex(set.name())),
        known_(setIndex_ < 0 ? program.masters.size() : 0, -1) {}
  int operator()(uint32_t m) {
    if (setIndex_ >= 0) return program_.masters[m].commandIds[setIndex_];
    int8_t& knows = known_[m];
    if (knows < 0) knows = set_.knows(program_.masters[m].command) ? 1 : 0;
    return knows ? -2 : -1;
  }

 private:
  const Program& program_;
  const InterpretationSet& set_;
  int setIndex_;
  std::vector<int8_t> known_;
};

// A word held without ids that nothing reads ids of (readableAsHeld), walked as it is
// held: no replay makes its ids again. Each cell runs its symbol's command, if the set
// has one, with its parameters (no master in the word develops them); a cell gets the
// birth of its run (docs/COMPACT_WORDS.md, "Timeless modules join runs").
void interpretAsHeld(const World& world, InterpretationSet& set, CommandsOfMasters& commandOf) {
  const Program& program = world.program();
  for (LabelCursor cursor(world.rootPool().compactWord()); !cursor.done(); cursor.next()) {
    const uint32_t m = cursor.master();
    const int id = commandOf(m);
    if (id == -1) continue;
    const MasterCell& master = program.masters[m];
    const std::span<const double> params(cursor.state(), master.stateCount());
    set.beginCell({0, kNoParent, cursor.birth(), master.lifetime, world.time(), master.label});
    set.locate({master.span, master.label, world.time()});
    if (id >= 0)
      set.executeCommand(id, master.command, params);
    else
      set.execute(master.command, params);
  }
}

// One pool, then (recursively) the pools of its system cells.
void interpretPool(const World& world, InterpretationSet& set) {
  const Program& program = world.program();
  const Pool& pool = world.rootPool();
  FunctionTable functions = program.functionTable();
  std::vector<double> frame;
  std::vector<double> args;
  std::vector<double> developed;
  CommandsOfMasters commandOf(program, set);
  // An L-system with homomorphism rules is interpreted through its image (the word
  // itself does not change); parents, positions and nested pools are the source's.
  std::optional<HomomorphismImage> image;
  if (world.rootSystem().homomorphism) image.emplace(world);
  // Parents cost a pass over the word: found when the set or an interpretation block reads them.
  bool readsParent = set.wantsParents();
  for (const MasterCell& master : program.masters) readsParent = readsParent || master.readsParent;
  const std::vector<uint64_t> parents = readsParent ? parentIds(world) : std::vector<uint64_t>{};
  // Per master, whether its cells' ids are read: by the set, by an interpretation block
  // (its frame and random stream), by a development function (its random stream), or to
  // find a system cell's pool. The others' ids are not computed.
  std::vector<uint8_t> readsId(program.masters.size());
  for (size_t m = 0; m < program.masters.size(); ++m) {
    const MasterCell& master = program.masters[m];
    readsId[m] = set.wantsIds() || master.interpretation(set.name()) ||
                 (!set.alsoReads().empty() && master.interpretation(set.alsoReads())) ||
                 master.developmentFunction >= 0 || master.system >= 0;
  }
  if (!image && !readsParent && !set.wantsIds() && readableAsHeld(world, readsId)) {
    interpretAsHeld(world, set, commandOf);
    return;
  }
  for (CellCursor cursor = image ? image->cursor() : pool.cursor(); !cursor.done(); cursor.next()) {
    const uint32_t label = cursor.master();
    const CellView cell{label, cursor.state(), cursor.birth(), readsId[label] ? cursor.id() : 0, cursor.index()};
    const size_t i = image ? image->sourceOf(cell.index) : cell.index;  // in the word
    const uint64_t parent = parents.empty() ? kNoParent : parents[i];
    const MasterCell& master = program.masters[cell.master];
    const InterpretationBlock* own = master.interpretation(set.name());
    const InterpretationBlock* block =
        own != nullptr || set.alsoReads().empty() ? own : master.interpretation(set.alsoReads());
    // Another set's block: its commands were resolved against that set's table, so by name.
    const bool borrowed = block != nullptr && own == nullptr;
    if (block) {
      frame.resize(master.stateCount() + FrameSlot::kCount);
      loadCellFrame(frame.data(), master, cell, world.time(), world.positionOf(i),
                    parent == kNoParent ? -1 : idValue(parent));
      set.beginCell({cell.id, parent, cell.birth, master.lifetime, world.time(), master.label});
      RandomStream random(mixKey(mixKey(world.seed() ^ kInterpretSalt, cell.id), keyOf(world.time())));
      EvalContext context{frame.data(), EvalEnvironment{&random, world.seed()}, &functions};
      context.ancestors = world.ancestorValues();
      for (const Instruction& instruction : block->instructions) {
        set.locate({instruction.span, master.label, world.time()});
        args.clear();
        for (const CompiledExpression& arg : instruction.args) args.push_back(arg.evaluate(context));
        if (instruction.commandId >= 0 && !borrowed)
          set.executeCommand(instruction.commandId, instruction.command, args);
        else
          set.execute(instruction.command, args);
      }
    } else {
      const int id = commandOf(cell.master);
      if (id != -1) {
        world.developedValues(cell, developed);
        set.beginCell({cell.id, parent, cell.birth, master.lifetime, world.time(), master.label});
        set.locate({master.span, master.label, world.time()});
        if (id >= 0)
          set.executeCommand(id, master.command, developed);
        else
          set.execute(master.command, developed);
      }
    }
    // A system cell's pool is realised where the cell stands, as a branch: what it
    // draws or plays starts from the state here and leaves it unchanged.
    if (const World* child = master.system >= 0 ? world.childOf(cell.id) : nullptr) {
      set.execute("[", {});
      interpretPool(*child, set);
      set.execute("]", {});
    }
  }
}
}  // namespace

void interpretWord(const World& world, InterpretationSet& set) {
  set.beginWord(world.time());
  set.expectCells(world.rootPool().size());
  interpretPool(world, set);
  set.endWord();
}

std::vector<std::filesystem::path> interpretFrame(const World& world, InterpretationSet& set,
                                                  const FrameTarget& target) {
  set.beginFrame(target);
  interpretWord(world, set);
  return set.endFrame();
}

}  // namespace ontogen
