#include "interpreters/text/word_text.h"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cstring>
#include <memory>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/parents.h"
#include "core/salts.h"
#include "pools/label_cursor.h"

namespace ontogen {

namespace {

// 2^53: every whole number below it is a double, and its shortest form is its digits.
constexpr double kExactIntegers = 9007199254740992.0;

// The 8 digits of value < 10^8, leading zeros included, as the bytes of a word, the first
// digit in the lowest byte: the halves, then the pairs, then the digits split in every lane
// of the word at once (a division by a multiplication and a shift each, exact below 10^4,
// 10^2 and 10^1 respectively). Kept in a register, it is stored whole: digits stored a pair
// at a time and read back as one piece stall the store buffer.
static_assert(std::endian::native == std::endian::little, "digits are stored as the bytes of words");
uint64_t eightDigits(uint32_t value) {
  uint64_t lanes = (value / 10000) | (uint64_t{value % 10000} << 32);       // two lanes of 4 digits
  uint64_t high = ((lanes * 10486) >> 20) & 0x0000007F0000007Full;          // each lane / 100
  lanes = high | ((lanes - high * 100) << 16);                               // four lanes of 2 digits
  high = ((lanes * 103) >> 10) & 0x000F000F000F000Full;                      // each lane / 10
  lanes = high | ((lanes - high * 10) << 8);                                 // eight lanes of 1 digit
  return lanes + 0x3030303030303030ull;
}

// The number of decimal digits of value < 10^16 (1 for 0), without a branch a digit: from
// its bit length, corrected by one comparison.
int decimalDigits(uint64_t value) {
  static constexpr uint64_t kPowers[] = {1,         10,         100,         1000,         10000,
                                         100000,    1000000,    10000000,    100000000,    1000000000,
                                         10000000000, 100000000000, 1000000000000, 10000000000000,
                                         100000000000000, 1000000000000000, 10000000000000000};
  const int guess = (64 - std::countl_zero(value | 1)) * 1233 >> 12;  // floor(log10(2^bits)), or one less
  return guess + (value >= kPowers[guess] ? 1 : 0);
}

// Writes a whole number's digits at `to` (|value| < 10^16, as ids and the whole numbers
// below 2^53 are; room for 17 bytes); returns the end. The ids of a JSON word are most of
// its numbers: the digits are made in registers, shifted past the leading zeros and
// stored with one store of 8 or 16 bytes.
char* writeInteger(char* to, int64_t value) {
  if (value < 0) *to++ = '-';
  const uint64_t magnitude = value < 0 ? 0 - static_cast<uint64_t>(value) : static_cast<uint64_t>(value);
  const int digits = decimalDigits(magnitude);
  if (magnitude < 100000000) {
    const uint64_t eight = eightDigits(static_cast<uint32_t>(magnitude)) >> (8 * (8 - digits));
    std::memcpy(to, &eight, 8);
  } else {
    const uint64_t first = eightDigits(static_cast<uint32_t>(magnitude / 100000000));
    const uint64_t last = eightDigits(static_cast<uint32_t>(magnitude % 100000000));
    const int shift = 8 * (16 - digits);  // 0 to 56: the last word's bytes move down by shift
    const uint64_t sixteen[2] = {(first >> shift) | ((last << 1) << (63 - shift)), last >> shift};
    std::memcpy(to, sixteen, 16);
  }
  return to + digits;
}

// %.*g, as printf writes it, without -0, at `to` (room for kNumberRoom bytes); returns the end.
constexpr size_t kNumberRoom = 48;
char* writeShort(char* to, double value, int precision) {
  // Only a program that allows non-finite state has any (core/finite_state.h); NaN's sign
  // means nothing, so it is `nan` alone.
  if (std::isnan(value)) return std::copy_n("nan", 3, to);
  if (value == 0) {
    *to = '0';
    return to + 1;
  }
  // A whole number of at most `precision` digits: %g writes its digits alone.
  static constexpr double kPowers[] = {1e0, 1e1, 1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,
                                       1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16, 1e17};
  // (writeInteger takes fewer than 17 digits.)
  if (precision >= 1 && precision <= 17 && std::abs(value) < std::min(kPowers[precision], 1e16) &&
      value == std::trunc(value))
    return writeInteger(to, static_cast<int64_t>(value));
  return std::to_chars(to, to + kNumberRoom, value, std::chars_format::general, precision).ptr;
}

void appendShort(std::string& text, double value, int precision) {
  char buffer[kNumberRoom];
  text.append(buffer, writeShort(buffer, value, precision));
}

// The shortest form that reads back exactly, null for infinities and NaN, at `to` (room
// for kNumberRoom bytes); returns the end.
char* writeExact(char* to, double value) {
  if (!std::isfinite(value)) return std::copy_n("null", 4, to);
  if (value == 0) {
    *to = '0';
    return to + 1;
  }
  // A whole number: its digits, unless the shortest form is the exponent one, which is
  // shorter only from five trailing zeros on (1e+05 against 100000; a tie goes to the digits).
  if (std::abs(value) < kExactIntegers && value == std::trunc(value)) {
    const auto whole = static_cast<int64_t>(value);
    if (whole % 100000 != 0) return writeInteger(to, whole);
  }
  return std::to_chars(to, to + kNumberRoom, value).ptr;
}

void appendExact(std::string& text, double value) {
  char buffer[kNumberRoom];
  text.append(buffer, writeExact(buffer, value));
}

void appendString(std::string& text, std::string_view value) {
  text += '"';
  for (unsigned char c : value) {
    switch (c) {
      case '"': text += "\\\""; break;
      case '\\': text += "\\\\"; break;
      case '\n': text += "\\n"; break;
      case '\t': text += "\\t"; break;
      default:
        if (c < 0x20) {
          char escaped[8];
          std::snprintf(escaped, sizeof escaped, "\\u%04x", c);
          text += escaped;
        } else {
          text += static_cast<char>(c);
        }
    }
  }
  text += '"';
}

void appendArray(std::string& text, std::span<const double> values) {
  text += '[';
  for (size_t i = 0; i < values.size(); ++i) {
    if (i) text += ", ";
    appendExact(text, values[i]);
  }
  text += ']';
}

}  // namespace

void BufferedOutput::flush() {
  if (text_.empty()) return;
  out_.write(text_.data(), static_cast<std::streamsize>(text_.size()));
  text_.clear();
}

void BufferedOutput::write(const char* data, size_t size) {
  if (text_.size() + size <= kFlushAt) {
    text_.append(data, size);
    return;
  }
  flush();
  out_.write(data, static_cast<std::streamsize>(size));
}

void WordTextWriter::cell(const WordCellView& cell) {
  std::string& text = out_.text();
  if (depth_ > 0 || !first_) text += ' ';
  first_ = false;
  if (cell.timed) text += '(';
  text += cell.label;
  if (!cell.developed.empty()) {
    text += '(';
    for (size_t i = 0; i < cell.developed.size(); ++i) {
      if (i) text += ", ";
      appendShort(text, cell.developed[i], precision_);
    }
    text += ')';
  }
  if (cell.timed) {
    text += ", ";
    appendShort(text, cell.age, precision_);
    text += ')';
  }
  out_.wrote();
}

void WordTextWriter::enterPool() {
  out_.text() += " {";
  ++depth_;
}

void WordTextWriter::leavePool() {
  out_.text() += " }";
  --depth_;
}

namespace {

// A module's text as WordTextWriter::cell writes it, without the space before it, at
// `to`: room for moduleRoom(label, values) bytes. Returns the end.
size_t moduleRoom(size_t label, size_t values) { return label + 8 + values * (kNumberRoom + 2) + kNumberRoom; }
char* writeModule(char* to, std::string_view label, const double* values, size_t count, bool timed, double age,
                  int precision) {
  if (timed) *to++ = '(';
  to = std::copy(label.begin(), label.end(), to);
  if (count > 0) {
    *to++ = '(';
    for (size_t i = 0; i < count; ++i) {
      if (i) to = std::copy_n(", ", 2, to);
      to = writeShort(to, values[i], precision);
    }
    *to++ = ')';
  }
  if (timed) {
    to = std::copy_n(", ", 2, to);
    to = writeShort(to, age, precision);
    *to++ = ')';
  }
  return to;
}

// A cell of the compact JSON whose developed values are its params and which has no
// position and no pool, as CompactWordJsonWriter::cell writes it, at `to`: room for
// compactRoom(quoted, values) bytes. `quoted`: its label as a JSON string. Returns the end.
size_t compactRoom(size_t quoted, size_t values) { return quoted + 40 + values * (kNumberRoom + 2) + kNumberRoom; }
char* writeCompactModule(char* to, std::string_view quoted, const double* values, size_t count, bool timed,
                         double age) {
  if (count == 0 && !timed) return std::copy(quoted.begin(), quoted.end(), to);
  auto put = [&to](std::string_view piece) { to = std::copy(piece.begin(), piece.end(), to); };
  put("{\"label\": ");
  put(quoted);
  if (count > 0) {
    put(", \"params\": [");
    for (size_t i = 0; i < count; ++i) {
      if (i) put(", ");
      to = writeExact(to, values[i]);
    }
    *to++ = ']';
  }
  if (timed) {
    put(", \"age\": ");
    to = writeExact(to, age);
  }
  *to++ = '}';
  return to;
}

std::string quoted(std::string_view label) {
  std::string text;
  appendString(text, label);
  return text;
}

// What a label writes: a separator and its label (the text's space and label, the compact
// JSON's comma and quoted label), copied whole (kInline bytes at once) when the module has
// no values and no age, else written by writeModule or writeCompactModule.
struct LabelText {
  static constexpr size_t kInline = 16;
  std::array<char, kInline> text{};
  uint8_t length = 0;    // bytes of text, separator included; 0: written by writeOne
  uint32_t values = 0;   // state values per module
};

// The forms HeldWord writes: the text of writeWordText, or the cells of the compact JSON.
enum class HeldForm { kText, kCompactJson };

// Streams a word held compactly without ids (what visitWord's LabelCursor reads) in
// chunks of its own, handed to the output whole.
class HeldWord {
 public:
  HeldWord(const World& world, BufferedOutput& out, HeldForm form, int precision)
      : world_(world), out_(out), form_(form), precision_(precision), chunk_(new char[kChunk + kSlack]) {
    const std::vector<MasterCell>& masters = world.program().masters;
    labels_.resize(masters.size());
    written_.resize(masters.size());
    for (size_t m = 0; m < masters.size(); ++m) {
      const MasterCell& master = masters[m];
      LabelText& label = labels_[m];
      label.values = master.stateCount();
      anyTimed_ = anyTimed_ || master.timedNotation;
      written_[m] = form == HeldForm::kText ? master.label : quoted(master.label);
      const std::string& text = written_[m];
      if (label.values == 0 && !master.timedNotation && text.size() + 1 <= LabelText::kInline) {
        label.text[0] = form == HeldForm::kText ? ' ' : ',';
        std::copy(text.begin(), text.end(), label.text.begin() + 1);
        label.length = static_cast<uint8_t>(text.size() + 1);
      }
    }
  }

  void write() {
    const CompactWord& word = world_.rootPool().compactWord();
    if (word.empty()) return;
    at_ = chunk_.get();
    end_ = at_ + kChunk;
    skip_ = 1;  // the first module has no separator before it
    if (anyTimed_)
      writeWithAges(word);
    else if (word.wideLabels())
      writeLabels(word, word.labels16());
    else
      writeLabels(word, word.labels8());
    flush();
  }

 private:
  // Every module's whole text is this far below the end of a chunk or goes to
  // writeModule with room checked.
  static constexpr size_t kChunk = size_t{1} << 16;
  static constexpr size_t kSlack = LabelText::kInline;

  // No module is timed: labels and values alone, no births.
  template <typename Label>
  void writeLabels(const CompactWord& word, std::span<const Label> labels) {
    const double* values = word.values().data();
    const LabelText* table = labels_.data();
    char* at = at_;
    char* const end = end_;
    for (const Label m : labels) {
      const LabelText& label = table[m];
      if (label.length > 0) [[likely]] {
        std::memcpy(at, label.text.data(), LabelText::kInline);
        at += label.length;
        if (at >= end) [[unlikely]] {
          at_ = at;
          flush();
          at = at_;
        }
        continue;
      }
      at_ = at;
      writeOne(m, values, 0);
      at = at_;
      values += label.values;
    }
    at_ = at;
  }

  // Some module is timed: its age is the time since its run's birth, as LabelCursor gives it.
  void writeWithAges(const CompactWord& word) {
    const double time = world_.time();
    for (LabelCursor cell(word); !cell.done(); cell.next()) {
      const uint32_t m = cell.master();
      const LabelText& label = labels_[m];
      if (label.length > 0) {
        std::memcpy(at_, label.text.data(), LabelText::kInline);
        at_ += label.length;
        if (at_ >= end_) flush();
      } else {
        writeOne(m, cell.state(), time - cell.birth());
      }
    }
  }

  void writeOne(uint32_t m, const double* values, double age) {
    const bool timed = world_.program().masters[m].timedNotation;
    const std::string& label = written_[m];
    const size_t count = labels_[m].values;
    const bool text = form_ == HeldForm::kText;
    const size_t room = 1 + (text ? moduleRoom(label.size(), count) : compactRoom(label.size(), count));
    auto writeAt = [&](char* to) {
      *to++ = text ? ' ' : ',';
      return text ? writeModule(to, label, values, count, timed, age, precision_)
                  : writeCompactModule(to, label, values, count, timed, age);
    };
    if (at_ + room > end_ + kSlack) flush();
    if (at_ + room > end_ + kSlack) {  // larger than a chunk: through a string of its own
      std::string piece(room, '\0');
      char* last = writeAt(piece.data());
      out_.write(piece.data() + skip_, static_cast<size_t>(last - piece.data()) - skip_);
      skip_ = 0;
      return;
    }
    at_ = writeAt(at_);
    if (at_ >= end_) flush();
  }

  void flush() {
    const size_t written = static_cast<size_t>(at_ - chunk_.get());
    if (written > skip_) {
      out_.write(chunk_.get() + skip_, written - skip_);
      skip_ = 0;
    }
    at_ = chunk_.get();
  }

  const World& world_;
  BufferedOutput& out_;
  HeldForm form_;
  int precision_;
  std::unique_ptr<char[]> chunk_;
  char* at_ = nullptr;
  char* end_ = nullptr;
  size_t skip_ = 0;
  std::vector<LabelText> labels_;  // per master
  std::vector<std::string> written_;  // per master: its label as the form writes it
  bool anyTimed_ = false;
};

}  // namespace

void writeWordText(const World& world, BufferedOutput& out, int precision, bool interpreted) {
  const bool image = interpreted && world.rootSystem().homomorphism;
  if (!image && readableWithoutIds(world)) {
    HeldWord(world, out, HeldForm::kText, precision).write();
    return;
  }
  WordTextWriter writer(out, precision);
  if (interpreted)
    visitInterpretedWord(world, writer);
  else
    visitWord(world, writer);
}

std::string formatWord(const std::vector<WordCell>& word, int precision) {
  std::ostringstream text;
  {
    BufferedOutput out(text);
    WordTextWriter writer(out, precision);
    visitWord(word, writer);
  }
  return text.str();
}

std::string formatExact(double value) {
  std::string text;
  appendExact(text, value);
  return text;
}

void WordJsonWriter::begin() { out_.text() += "{\"times\": ["; }

void WordJsonWriter::beginTime(double t, bool first) {
  std::string& text = out_.text();
  text += first ? "\n  " : ",\n  ";
  text += "{\"t\": ";
  appendExact(text, t);
  text += ", \"cells\": ";
  openList();
}

void WordJsonWriter::endTime() {
  closeList();
  out_.text() += '}';
  out_.wrote();
}

void WordJsonWriter::end() {
  out_.text() += "\n]}\n";
  out_.flush();
}

void WordJsonWriter::openList() {
  out_.text() += '[';
  cellsInList_.push_back(0);
}

// The list's closing bracket on a line of its own, at the indentation of what holds it.
void WordJsonWriter::closeList() {
  std::string& text = out_.text();
  if (cellsInList_.back() > 0) {
    text += '\n';
    text.append(2 * cellsInList_.size(), ' ');
  }
  text += ']';
  cellsInList_.pop_back();
}

// `{"label": "X", "params": ` of a label, escaped once: the labels of a world's word are
// its masters' strings, a few of them, each met again and again.
const std::string& WordJsonWriter::labelPrefix(std::string_view label) {
  for (const LabelPrefix& known : labels_)
    if (known.data == label.data() && known.size == label.size()) return known.prefix;
  std::string prefix = "{\"label\": ";
  appendString(prefix, label);
  prefix += ", \"params\": ";
  // A captured word's labels are strings of its own cells: keep a bounded few.
  if (labels_.size() >= kLabelPrefixes) labels_.pop_back();
  labels_.push_back({label.data(), label.size(), std::move(prefix)});
  return labels_.back().prefix;
}

namespace {

// Values as a JSON array at `to` (room for 2 + values.size() * (kNumberRoom + 2) bytes);
// returns the end.
char* writeArray(char* to, std::span<const double> values) {
  *to++ = '[';
  for (size_t i = 0; i < values.size(); ++i) {
    if (i) to = std::copy_n(", ", 2, to);
    to = writeExact(to, values[i]);
  }
  *to++ = ']';
  return to;
}

// The room fullCell takes for `cell` after its label's prefix and indentation.
size_t fullCellRoom(const WordCellView& cell) {
  return (cell.params.size() + cell.developed.size() + cell.position.size()) * (kNumberRoom + 2) + 3 * kNumberRoom + 128;
}

// A cell of the full JSON as WordJsonWriter::cell writes it, at `to`: its separator, line
// and indentation, `prefix` (its label's), its values, age, id and parent. Returns the end.
char* writeFullCell(char* to, const WordCellView& cell, std::string_view prefix, size_t indent, bool comma) {
  auto put = [&to](std::string_view piece) { to = std::copy(piece.begin(), piece.end(), to); };
  if (comma) *to++ = ',';
  *to++ = '\n';
  to = std::fill_n(to, indent, ' ');
  put(prefix);
  const char* paramsAt = to;
  to = writeArray(to, cell.params);
  const std::string_view params(paramsAt, static_cast<size_t>(to - paramsAt));
  put(", \"developed\": ");
  if (cell.developed.data() == cell.params.data() && cell.developed.size() == cell.params.size())
    put(params);  // the same values, as just written
  else
    to = writeArray(to, cell.developed);
  put(", \"age\": ");
  to = writeExact(to, cell.age);
  put(", \"id\": ");
  to = writeExact(to, idValue(cell.id));
  put(", \"parent\": ");
  if (cell.parent == kNoParent)
    put("-1");
  else
    to = writeExact(to, idValue(cell.parent));
  if (!cell.position.empty()) {
    put(", \"position\": ");
    to = writeArray(to, cell.position);
  }
  if (cell.system)
    put(", \"pool\": ");
  else
    *to++ = '}';
  return to;
}

// The words at their times as one JSON document, in either form.
template <class Writer>
void writeWordsAsJson(std::ostream& out, const std::vector<WordAtTime>& words) {
  BufferedOutput buffered(out);
  Writer writer(buffered);
  writer.begin();
  for (const WordAtTime& word : words) {
    writer.beginTime(word.time, &word == words.data());
    visitWord(word.cells, writer);
    writer.endTime();
  }
  writer.end();
}

}  // namespace

// Each cell is written in one piece: on the stack when it fits, as most do, else straight
// into the buffer made large enough for it.
void WordJsonWriter::cell(const WordCellView& cell) {
  const std::string& prefix = labelPrefix(cell.label);
  const size_t indent = 2 * cellsInList_.size() + 2;
  const bool comma = cellsInList_.back()++ > 0;
  const size_t room = 2 + indent + prefix.size() + fullCellRoom(cell);
  std::string& text = out_.text();
  constexpr size_t kOnStack = 1024;
  if (room <= kOnStack) {
    char piece[kOnStack];
    text.append(piece, writeFullCell(piece, cell, prefix, indent, comma));
  } else {
    const size_t at = text.size();
    text.resize(at + room);
    char* last = writeFullCell(text.data() + at, cell, prefix, indent, comma);
    text.resize(static_cast<size_t>(last - text.data()));
  }
  out_.wrote();
}

void WordJsonWriter::enterPool() { openList(); }

void WordJsonWriter::leavePool() {
  closeList();
  out_.text() += '}';
}

void writeWordJson(std::ostream& out, const std::vector<WordAtTime>& words) {
  writeWordsAsJson<WordJsonWriter>(out, words);
}

void CompactWordJsonWriter::begin() { out_.text() += "{\"form\": \"compact\", \"times\": ["; }

void CompactWordJsonWriter::beginTime(double t, bool first) {
  std::string& text = out_.text();
  text += first ? "\n  " : ",\n  ";
  text += "{\"t\": ";
  appendExact(text, t);
  text += ", \"cells\": [";
  cellsInList_.push_back(0);
}

void CompactWordJsonWriter::writeWord(const World& world, bool interpreted) {
  const bool image = interpreted && world.rootSystem().homomorphism;
  if (!image && readableWithoutIds(world)) {
    const size_t modules = world.rootPool().compactWord().size();
    // The held word's first module takes no comma: it must open the list.
    if (cellsInList_.back() == 0) {
      HeldWord(world, out_, HeldForm::kCompactJson, 0).write();
      cellsInList_.back() = modules;
      return;
    }
  }
  if (interpreted)
    visitInterpretedWord(world, *this);
  else
    visitWord(world, *this);
}

void CompactWordJsonWriter::endTime() {
  out_.text() += "]}";
  cellsInList_.pop_back();
  out_.wrote();
}

void CompactWordJsonWriter::end() {
  out_.text() += "\n]}\n";
  out_.flush();
}

const std::string& CompactWordJsonWriter::quotedLabel(std::string_view label) {
  for (const QuotedLabel& known : labels_)
    if (known.data == label.data() && known.size == label.size()) return known.quoted;
  if (labels_.size() >= kQuotedLabels) labels_.pop_back();
  labels_.push_back({label.data(), label.size(), quoted(label)});
  return labels_.back().quoted;
}

void CompactWordJsonWriter::cell(const WordCellView& cell) {
  std::string& text = out_.text();
  if (cellsInList_.back()++ > 0) text += ',';
  const std::string& label = quotedLabel(cell.label);
  const bool developedIsParams =
      cell.developed.size() == cell.params.size() &&
      std::equal(cell.params.begin(), cell.params.end(), cell.developed.begin(),
                 [](double a, double b) { return std::bit_cast<uint64_t>(a) == std::bit_cast<uint64_t>(b); });
  if (developedIsParams && cell.position.empty() && !cell.system) {
    const size_t at = text.size();
    text.resize(at + compactRoom(label.size(), cell.params.size()));
    char* last = writeCompactModule(text.data() + at, label, cell.params.data(), cell.params.size(), cell.timed, cell.age);
    text.resize(static_cast<size_t>(last - text.data()));
  } else {
    text += "{\"label\": ";
    text += label;
    if (!cell.params.empty()) {
      text += ", \"params\": ";
      appendArray(text, cell.params);
    }
    if (!developedIsParams) {
      text += ", \"developed\": ";
      appendArray(text, cell.developed);
    }
    if (cell.timed) {
      text += ", \"age\": ";
      appendExact(text, cell.age);
    }
    if (!cell.position.empty()) {
      text += ", \"position\": ";
      appendArray(text, cell.position);
    }
    text += cell.system ? ", \"pool\": " : "}";
  }
  out_.wrote();
}

void CompactWordJsonWriter::enterPool() {
  out_.text() += '[';
  cellsInList_.push_back(0);
}

void CompactWordJsonWriter::leavePool() {
  out_.text() += "]}";
  cellsInList_.pop_back();
}

void writeCompactWordJson(std::ostream& out, const std::vector<WordAtTime>& words) {
  writeWordsAsJson<CompactWordJsonWriter>(out, words);
}

}  // namespace ontogen
