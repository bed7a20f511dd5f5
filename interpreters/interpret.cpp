#include "interpreters/interpret.h"

#include <optional>

#include "core/cell_frame.h"
#include "core/homomorphism.h"
#include "core/parents.h"
#include "core/salts.h"

namespace ontogen {

namespace {

// One pool, then (recursively) the pools of its system cells.
void interpretPool(const World& world, InterpretationSet& set) {
  const Program& program = world.program();
  const Pool& pool = world.rootPool();
  FunctionTable functions = program.functionTable();
  std::vector<double> frame;
  std::vector<double> args;
  std::vector<double> developed;
  // Commands were resolved by the compiler for the sets it knew (Program::commandSets);
  // for another set, whether it knows each master's command is asked once per master.
  const int setIndex = program.commandSetIndex(set.name());
  std::vector<int8_t> known(setIndex < 0 ? program.masters.size() : 0, -1);
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
      int id = -1;  // the command's number in the set, -2: by name, -1: not the set's
      if (setIndex >= 0) {
        id = master.commandIds[setIndex];
      } else {
        int8_t& knows = known[cell.master];
        if (knows < 0) knows = set.knows(master.command) ? 1 : 0;
        id = knows ? -2 : -1;
      }
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
