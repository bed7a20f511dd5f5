#pragma once
// The derivation word of a world at its current time, as data: labels, parameters before
// and after the development function, ages, ids and parents, nested pools. Its text (in
// the style of paper 000's Table 1) and JSON are in interpreters/text/word_text.h.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/world.h"

namespace ontogen {

struct WordCell {
  std::string label;
  std::vector<double> params;     ///< the actual parameters (state values in declaration order)
  std::vector<double> developed;  ///< after the development function (= params without one)
  double age = 0;                 ///< seconds
  bool timed = false;             ///< written in timed notation: printed as (X, age)
  uint64_t id = 0;      ///< stable id (64 bits; words print the low 53, as rules read it)
  uint64_t parent = ~uint64_t{0};  ///< the id of the cell it hangs from (core/parents.h); all ones: none
  std::vector<double> position;  ///< grid coordinates or spatial x, y, z (empty in a linear pool)
  bool system = false;           ///< a system cell: `pool` holds its system's cells
  std::vector<WordCell> pool;
};

struct WordAtTime {
  double time = 0;
  std::vector<WordCell> cells;
};

/// One cell of a word as it streams past a WordVisitor; the views are valid during the
/// call only.
struct WordCellView {
  std::string_view label;
  std::span<const double> params;
  std::span<const double> developed;
  double age = 0;
  bool timed = false;
  uint64_t id = 0;
  uint64_t parent = ~uint64_t{0};
  std::span<const double> position;
  bool system = false;
};

/// Receives a word cell by cell, in pool order, without a record per cell: what `ontogen
/// word` streams to its output. A system cell is followed by enterPool(), its pool's
/// cells (none when it has no pool yet), and leavePool().
class WordVisitor {
 public:
  virtual ~WordVisitor() = default;
  virtual void cell(const WordCellView& cell) = 0;
  virtual void enterPool() {}
  virtual void leavePool() {}
  /// Whether the visitor reads a cell's id or parent, or the age of a cell that is not in
  /// timed notation. A visitor that reads none of them may be streamed a word held
  /// without ids as it is held, without making its ids again (docs/COMPACT_WORDS.md,
  /// "Words without ids"); those fields are then left unset.
  virtual bool readsIds() const { return true; }
};

/// Whether the world's root word is held without ids (Pool::holdsIds) and no cell of it
/// is of a master m with needsIds[m] set (one entry per master): a reader that reads the
/// ids of those masters' cells alone may then walk the word as it is held
/// (pools/label_cursor.h), without the replay that makes its ids again.
bool readableAsHeld(const World& world, std::span<const uint8_t> needsIds);

/// Whether a reader of no ids may walk the world's word as it is held: readableAsHeld
/// with the masters whose modules need ids marked (system cells, whose pool is found by
/// their id; cells that develop their parameters; timeless ones printed with their ages).
bool readableWithoutIds(const World& world);

/// Streams the world's cells in pool order to `visitor`.
void visitWord(const World& world, WordVisitor& visitor);
/// Does now what visitWord would do first and may fail: the root pool's word held without
/// ids is given them when the visitor (WordVisitor::readsIds) or a module of the word
/// reads them, which may pass the memory limit (LimitError). A caller that writes as it
/// streams calls it before writing anything.
void prepareToVisit(const World& world, bool visitorReadsIds);
/// Streams the interpreted word (captureInterpretedWord) to `visitor`.
void visitInterpretedWord(const World& world, WordVisitor& visitor);
/// Streams a captured word to `visitor`, as visitWord streamed it.
void visitWord(const std::vector<WordCell>& word, WordVisitor& visitor);

/// The world's cells in pool order; a system cell carries its own pool's cells.
std::vector<WordCell> captureWord(const World& world);

/// The word as the interpretation sets read it: the image of the world's word under its
/// L-system's homomorphism (core/homomorphism.h); the word itself without one.
std::vector<WordCell> captureInterpretedWord(const World& world);

}  // namespace ontogen
