#include "interpreters/text/word_text.h"

#include <algorithm>
#include <array>
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

// "00" to "99".
constexpr std::array<char, 200> kDigitPairs = [] {
  std::array<char, 200> pairs{};
  for (int i = 0; i < 100; ++i) {
    pairs[static_cast<size_t>(2 * i)] = static_cast<char>('0' + i / 10);
    pairs[static_cast<size_t>(2 * i + 1)] = static_cast<char>('0' + i % 10);
  }
  return pairs;
}();

// The 8 digits of value < 10^8, leading zeros included, in two halves computed apart.
void writeEightDigits(char* to, uint32_t value) {
  const uint32_t high = value / 10000, low = value % 10000;
  std::memcpy(to, &kDigitPairs[2 * (high / 100)], 2);
  std::memcpy(to + 2, &kDigitPairs[2 * (high % 100)], 2);
  std::memcpy(to + 4, &kDigitPairs[2 * (low / 100)], 2);
  std::memcpy(to + 6, &kDigitPairs[2 * (low % 100)], 2);
}

// The digits of value < 10^8 without leading zeros.
char* writeUpToEightDigits(char* to, uint32_t value) {
  const size_t digits = value >= 10000000 ? 8
                        : value >= 1000000 ? 7
                        : value >= 100000  ? 6
                        : value >= 10000   ? 5
                        : value >= 1000    ? 4
                        : value >= 100     ? 3
                        : value >= 10      ? 2
                                           : 1;
  char eight[8];
  writeEightDigits(eight, value);
  std::memcpy(to, eight + 8 - digits, digits);
  return to + digits;
}

// Writes a whole number's digits at `to` (|value| < 10^16, as ids and the whole numbers
// below 2^53 are); returns the end. The ids of a JSON word are most of its numbers.
char* writeInteger(char* to, int64_t value) {
  if (value < 0) *to++ = '-';
  const uint64_t magnitude = value < 0 ? 0 - static_cast<uint64_t>(value) : static_cast<uint64_t>(value);
  if (magnitude < 100000000) return writeUpToEightDigits(to, static_cast<uint32_t>(magnitude));
  to = writeUpToEightDigits(to, static_cast<uint32_t>(magnitude / 100000000));
  writeEightDigits(to, static_cast<uint32_t>(magnitude % 100000000));
  return to + 8;
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

// What a label writes: a space and its label, copied whole (kInline bytes at once) when
// the module has no values and no age, else written by writeModule.
struct LabelText {
  static constexpr size_t kInline = 16;
  std::array<char, kInline> text{};
  uint8_t length = 0;    // bytes of text, space included; 0: written by writeModule
  uint32_t values = 0;   // state values per module
};

// Streams a word held compactly without ids (what visitWord's LabelCursor reads) in
// chunks of its own, handed to the output whole.
class HeldWordText {
 public:
  HeldWordText(const World& world, BufferedOutput& out, int precision)
      : world_(world), out_(out), precision_(precision), chunk_(new char[kChunk + kSlack]) {
    const std::vector<MasterCell>& masters = world.program().masters;
    labels_.resize(masters.size());
    for (size_t m = 0; m < masters.size(); ++m) {
      const MasterCell& master = masters[m];
      LabelText& label = labels_[m];
      label.values = master.stateCount();
      anyTimed_ = anyTimed_ || master.timedNotation;
      if (label.values == 0 && !master.timedNotation && master.label.size() + 1 <= LabelText::kInline) {
        label.text[0] = ' ';
        std::copy(master.label.begin(), master.label.end(), label.text.begin() + 1);
        label.length = static_cast<uint8_t>(master.label.size() + 1);
      }
    }
  }

  void write() {
    const CompactWord& word = world_.rootPool().compactWord();
    if (word.empty()) return;
    at_ = chunk_.get();
    end_ = at_ + kChunk;
    skip_ = 1;  // the first module has no space before it
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
    const MasterCell& master = world_.program().masters[m];
    const size_t room = 1 + moduleRoom(master.label.size(), labels_[m].values);
    if (at_ + room > end_ + kSlack) flush();
    if (at_ + room > end_ + kSlack) {  // larger than a chunk: through a string of its own
      std::string text(room, '\0');
      text[0] = ' ';
      char* last = writeModule(text.data() + 1, master.label, values, labels_[m].values, master.timedNotation, age,
                               precision_);
      out_.write(text.data() + skip_, static_cast<size_t>(last - text.data()) - skip_);
      skip_ = 0;
      return;
    }
    *at_++ = ' ';
    at_ = writeModule(at_, master.label, values, labels_[m].values, master.timedNotation, age, precision_);
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
  int precision_;
  std::unique_ptr<char[]> chunk_;
  char* at_ = nullptr;
  char* end_ = nullptr;
  size_t skip_ = 0;
  std::vector<LabelText> labels_;  // per master
  bool anyTimed_ = false;
};

}  // namespace

void writeWordText(const World& world, BufferedOutput& out, int precision, bool interpreted) {
  const bool image = interpreted && world.rootSystem().homomorphism;
  if (!image && readableWithoutIds(world)) {
    HeldWordText(world, out, precision).write();
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

void WordJsonWriter::cell(const WordCellView& cell) {
  std::string& text = out_.text();
  text += cellsInList_.back()++ ? ",\n" : "\n";
  text.append(2 * cellsInList_.size() + 2, ' ');
  text += labelPrefix(cell.label);
  const size_t paramsAt = text.size();
  appendArray(text, cell.params);
  const size_t paramsEnd = text.size();
  text += ", \"developed\": ";
  if (cell.developed.data() == cell.params.data() && cell.developed.size() == cell.params.size())
    text.append(text, paramsAt, paramsEnd - paramsAt);  // the same values, as just written
  else
    appendArray(text, cell.developed);
  char numbers[3 * kNumberRoom + 64];
  char* to = numbers;
  auto put = [&to](std::string_view piece) { to = std::copy(piece.begin(), piece.end(), to); };
  put(", \"age\": ");
  to = writeExact(to, cell.age);
  put(", \"id\": ");
  to = writeExact(to, idValue(cell.id));
  put(", \"parent\": ");
  if (cell.parent == kNoParent)
    put("-1");
  else
    to = writeExact(to, idValue(cell.parent));
  text.append(numbers, to);
  if (!cell.position.empty()) {
    text += ", \"position\": ";
    appendArray(text, cell.position);
  }
  if (cell.system)
    text += ", \"pool\": ";
  else
    text += '}';
  out_.wrote();
}

void WordJsonWriter::enterPool() { openList(); }

void WordJsonWriter::leavePool() {
  closeList();
  out_.text() += '}';
}

void writeWordJson(std::ostream& out, const std::vector<WordAtTime>& words) {
  BufferedOutput buffered(out);
  WordJsonWriter writer(buffered);
  writer.begin();
  for (const WordAtTime& word : words) {
    writer.beginTime(word.time, &word == words.data());
    visitWord(word.cells, writer);
    writer.endTime();
  }
  writer.end();
}

}  // namespace ontogen
