#pragma once
// The derivation word as text in the style of paper 000's Table 1 (timed modules as
// `(mov(50), 1)`, untimed ones as `f(50)`, parameters after the development function)
// and as JSON, for `ontogen word`.

#include <ostream>
#include <string>
#include <vector>

#include "core/word.h"

namespace ontogen {

/// Table 1 style text, numbers with `precision` significant digits.
std::string formatWord(const std::vector<WordCell>& word, int precision = 6);

/// Output written through a buffer of its own, handed to the stream in large pieces (a
/// word of millions of cells streams without a record or a string per cell).
class BufferedOutput {
 public:
  explicit BufferedOutput(std::ostream& out) : out_(out) { text_.reserve(kFlushAt + 4096); }
  ~BufferedOutput() { flush(); }
  BufferedOutput(const BufferedOutput&) = delete;
  BufferedOutput& operator=(const BufferedOutput&) = delete;
  std::string& text() { return text_; }
  /// Hands the buffer to the stream when it is full.
  void wrote() {
    if (text_.size() >= kFlushAt) flush();
  }
  void flush();
  /// Writes `size` bytes after what the buffer holds: a large piece goes to the stream
  /// as it is, without a copy.
  void write(const char* data, size_t size);

 private:
  static constexpr size_t kFlushAt = size_t{1} << 16;
  std::ostream& out_;
  std::string text_;
};

/// Streams a word as formatWord writes it.
class WordTextWriter final : public WordVisitor {
 public:
  WordTextWriter(BufferedOutput& out, int precision) : out_(out), precision_(precision) {}
  void cell(const WordCellView& cell) override;
  void enterPool() override;
  void leavePool() override;
  /// Labels, parameters, and ages of timed modules alone.
  bool readsIds() const override { return false; }

 private:
  BufferedOutput& out_;
  int precision_;
  int depth_ = 0;       // pools entered
  bool first_ = true;   // no cell written yet at the top level
};

/// Writes the world's word (`interpreted`: its homomorphism's image) as visitWord or
/// visitInterpretedWord streams it through a WordTextWriter, to the byte. A word held
/// compactly and read without ids (WordVisitor::readsIds) is written as it is held: each
/// label's text made once and copied for its modules, numbers written in place, in
/// chunks handed to the stream whole.
void writeWordText(const World& world, BufferedOutput& out, int precision, bool interpreted = false);

/// Streams the JSON of writeWordJson: begin(), then for each time beginTime(t), the
/// word's cells through the visitor and endTime(), then end().
class WordJsonWriter final : public WordVisitor {
 public:
  explicit WordJsonWriter(BufferedOutput& out) : out_(out) {}
  void begin();
  /// `first`: the first time of the document (a writer may write one time of many).
  void beginTime(double t, bool first);
  void endTime();
  void end();
  void cell(const WordCellView& cell) override;
  void enterPool() override;
  void leavePool() override;

 private:
  void openList();
  void closeList();
  const std::string& labelPrefix(std::string_view label);
  struct LabelPrefix {
    const char* data;
    size_t size;
    std::string prefix;
  };
  static constexpr size_t kLabelPrefixes = 64;  // more labels than a program has masters, as a rule
  BufferedOutput& out_;
  std::vector<LabelPrefix> labels_;
  std::vector<size_t> cellsInList_;  // cells written in each open list, innermost last
};

/// Streams the compact JSON of `ontogen word --json=compact` (docs/LANGUAGE.md, "The
/// word as JSON"): {"form": "compact", "times": [{"t": T, "cells": [...]}, ...]}, where a
/// cell that is its label alone (no values, no age, no position, no pool) is that label as
/// a string, and any other an object of the full form's fields less its defaults:
/// "params" when it has values, "developed" when it differs from "params", "age" when the
/// cell is timed, "position", "pool". No ids, no parents, no ages of untimed cells: a word
/// grown without ids is written as held, without making them again.
class CompactWordJsonWriter final : public WordVisitor {
 public:
  explicit CompactWordJsonWriter(BufferedOutput& out) : out_(out) {}
  void begin();
  /// `first`: the first time of the document.
  void beginTime(double t, bool first);
  /// The world's word (`interpreted`: its homomorphism's image) as the cells of the time
  /// begun, to the byte as visitWord or visitInterpretedWord would stream it through this
  /// writer; a word held compactly without ids is written as it is held, as writeWordText
  /// writes it.
  void writeWord(const World& world, bool interpreted = false);
  void endTime();
  void end();
  void cell(const WordCellView& cell) override;
  void enterPool() override;
  void leavePool() override;
  /// Labels, values, positions, and ages of timed cells alone.
  bool readsIds() const override { return false; }

 private:
  const std::string& quotedLabel(std::string_view label);
  struct QuotedLabel {
    const char* data;
    size_t size;
    std::string quoted;
  };
  static constexpr size_t kQuotedLabels = 64;  // as WordJsonWriter's label prefixes
  BufferedOutput& out_;
  std::vector<QuotedLabel> labels_;
  std::vector<size_t> cellsInList_;  // cells written in each open list, innermost last
};

/// The compact JSON of captured words, as CompactWordJsonWriter streams it.
void writeCompactWordJson(std::ostream& out, const std::vector<WordAtTime>& words);

/// {"times": [{"t": T, "cells": [{"label": ..., "params": [...], "developed": [...],
/// "age": A, "id": I, "parent": P}, ...]}, ...]} (ids' low 53 bits; P is -1 for none), a system cell with "pool": [its cells], numbers in the shortest form that reads back exactly;
/// infinities and NaN as null.
void writeWordJson(std::ostream& out, const std::vector<WordAtTime>& words);

/// A number in the shortest decimal form that reads back to the same double.
std::string formatExact(double value);

}  // namespace ontogen
