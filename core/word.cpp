#include "core/word.h"

#include <algorithm>
#include <array>
#include <type_traits>

#include "core/homomorphism.h"
#include "core/parents.h"
#include "pools/label_counts.h"
#include "pools/label_cursor.h"

namespace ontogen {

namespace {

// Streams the word under `cell` (the pool's, or a homomorphism's image whose i-th cell
// comes from the pool's cell sourceOf(i)). A LabelCursor gives labels, values and run
// births alone: the caller has made sure (labelsAlone) that nothing else is read.
template <typename Cursor, typename SourceOf>
void stream(const World& world, Cursor cell, SourceOf&& sourceOf, bool interpreted, WordVisitor& visitor) {
  constexpr bool kWithIds = !std::is_same_v<Cursor, LabelCursor>;
  const Program& program = world.program();
  const bool grid = world.rootSystem().poolKind == PoolKind::Grid;
  const bool spatial = world.rootSystem().poolKind == PoolKind::Spatial;
  const int dimensions = spatial ? 3 : world.rootSystem().grid.dimensions;
  const uint64_t above = world.parent() ? world.systemCellId() : kNoParent;
  const bool linear = world.rootSystem().poolKind == PoolKind::Linear;
  AxialWalk walk(above);
  std::vector<double> developed;
  std::array<double, 3> position{};
  // One view, refilled for each cell (a fresh one per cell costs more than the cell).
  WordCellView view;
  for (; !cell.done(); cell.next()) {
    const MasterCell& master = program.masters[cell.master()];
    view.label = master.label;
    const double* state = cell.state();
    const size_t count = master.stateCount();
    view.params = std::span<const double>(state, count);
    view.timed = master.timedNotation;
    if constexpr (!kWithIds) {
      view.developed = view.params;
      view.age = world.time() - cell.birth();
      visitor.cell(view);
    } else {
      if (grid || spatial) {
        position = world.positionOf(sourceOf(cell.index()));
        view.position = std::span<const double>(position.data(), static_cast<size_t>(dimensions));
      }
      if (master.developmentFunction < 0) {
        view.developed = std::span<const double>(state, count);
      } else {
        world.developedValues(cell.view(), developed);
        view.developed = developed;
      }
      view.age = world.time() - cell.birth();
      view.id = cell.id();
      view.parent = linear ? walk.next(cell, master) : above;
      view.system = master.system >= 0;
      visitor.cell(view);
      if (!view.system) continue;
      visitor.enterPool();
      if (const World* child = world.childOf(view.id)) {
        if (interpreted)
          visitInterpretedWord(*child, visitor);
        else
          visitWord(*child, visitor);
      }
      visitor.leavePool();
    }
  }
}

// Whether the world's word can be streamed to `visitor` by labels, values and run births
// alone, without making its ids again: it is held without them, the visitor reads none,
// and no module in it needs them: none is a system cell (whose pool is found by its id)
// or develops its parameters (with the cell's view), and none printed with its age is
// timeless (such a module keeps no birth of its own in a word without ids:
// docs/COMPACT_WORDS.md, "Timeless modules join runs").
bool labelsAlone(const World& world, bool visitorReadsIds) {
  return !visitorReadsIds && readableWithoutIds(world);
}

// The world's own word (not a homomorphism's image) to `visitor`.
void streamPool(const World& world, bool interpreted, WordVisitor& visitor) {
  const auto same = [](size_t i) { return i; };
  if (labelsAlone(world, visitor.readsIds()))
    stream(world, LabelCursor(world.rootPool().compactWord()), same, interpreted, visitor);
  else
    stream(world, world.rootPool().cursor(), same, interpreted, visitor);
}

// Collects a streamed word into records, nested pools into their system cells.
class WordCollector final : public WordVisitor {
 public:
  void cell(const WordCellView& view) override {
    WordCell entry;
    entry.label = view.label;
    entry.params.assign(view.params.begin(), view.params.end());
    entry.developed.assign(view.developed.begin(), view.developed.end());
    entry.age = view.age;
    entry.timed = view.timed;
    entry.id = view.id;
    entry.parent = view.parent;
    entry.position.assign(view.position.begin(), view.position.end());
    entry.system = view.system;
    current().push_back(std::move(entry));
  }
  void enterPool() override { open_.push_back(&current().back().pool); }
  void leavePool() override { open_.pop_back(); }
  std::vector<WordCell> take() { return std::move(word_); }

 private:
  std::vector<WordCell>& current() { return open_.empty() ? word_ : *open_.back(); }
  std::vector<WordCell> word_;
  std::vector<std::vector<WordCell>*> open_;  // the pools being filled, innermost last
};

}  // namespace

bool readableAsHeld(const World& world, std::span<const uint8_t> needsIds) {
  const Pool& pool = world.rootPool();
  const size_t masters = world.program().masters.size();
  if (!pool.holdsCompactWord() || pool.holdsIds() || needsIds.size() != masters) return false;
  if (std::none_of(needsIds.begin(), needsIds.end(), [](uint8_t needs) { return needs != 0; })) return true;
  // The root system is a master too, and most such masters are in no word: count them.
  const CompactWord& word = pool.compactWord();
  if (word.wideLabels() || masters > 256) return false;
  std::vector<uint64_t> counts(masters);
  countLabels(word.labels8().data(), word.size(), masters, counts.data());
  for (size_t m = 0; m < masters; ++m)
    if (needsIds[m] && counts[m] > 0) return false;
  return true;
}

bool readableWithoutIds(const World& world) {
  const std::vector<MasterCell>& masters = world.program().masters;
  std::vector<uint8_t> needsIds(masters.size());
  for (size_t m = 0; m < masters.size(); ++m) {
    const MasterCell& master = masters[m];
    needsIds[m] =
        master.system >= 0 || master.developmentFunction >= 0 || (master.timedNotation && master.lifetime == kForever);
  }
  return readableAsHeld(world, needsIds);
}

void visitWord(const World& world, WordVisitor& visitor) { streamPool(world, false, visitor); }

void prepareToVisit(const World& world, bool visitorReadsIds) {
  if (!labelsAlone(world, visitorReadsIds)) world.rootPool().ensureIds();
}

void visitInterpretedWord(const World& world, WordVisitor& visitor) {
  if (!world.rootSystem().homomorphism) {
    streamPool(world, true, visitor);
    return;
  }
  const HomomorphismImage image(world);
  stream(world, image.cursor(), [&image](size_t i) { return image.sourceOf(i); }, true, visitor);
}

void visitWord(const std::vector<WordCell>& word, WordVisitor& visitor) {
  for (const WordCell& cell : word) {
    WordCellView view;
    view.label = cell.label;
    view.params = cell.params;
    view.developed = cell.developed;
    view.age = cell.age;
    view.timed = cell.timed;
    view.id = cell.id;
    view.parent = cell.parent;
    view.position = cell.position;
    view.system = cell.system;
    visitor.cell(view);
    if (!cell.system) continue;
    visitor.enterPool();
    visitWord(cell.pool, visitor);
    visitor.leavePool();
  }
}

std::vector<WordCell> captureWord(const World& world) {
  WordCollector collector;
  visitWord(world, collector);
  return collector.take();
}

std::vector<WordCell> captureInterpretedWord(const World& world) {
  WordCollector collector;
  visitInterpretedWord(world, collector);
  return collector.take();
}

}  // namespace ontogen
