#include "interpreters/sweep/sweep_table.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>

#include "lang/variation.h"

namespace ontogen {

std::string formatValue(double value) { return std::isfinite(value) ? shortestNumber(value) : std::string(); }

namespace {

void csvField(std::ostream& out, std::string_view field) {
  if (field.find_first_of(",\"\r\n") == std::string_view::npos) {
    out << field;
    return;
  }
  out << '"';
  for (char c : field) {
    if (c == '"') out << '"';
    out << c;
  }
  out << '"';
}

}  // namespace

void writeTableCsv(const SweepTable& table, std::ostream& out) {
  out << "variant";
  for (const std::string& column : table.columns) {
    out << ',';
    csvField(out, column);
  }
  out << ",error\n";
  for (const SweepRow& row : table.rows) {
    out << row.variant;
    for (const std::string& value : row.values) out << ',' << value;
    out << ',';
    csvField(out, row.error);
    out << '\n';
  }
}

void writeTableJson(const SweepTable& table, std::ostream& out) {
  // Written by hand around the values so that each keeps its digits: nlohmann would print
  // a double again, in its own shortest form (the same value, perhaps other digits).
  out << "{\"columns\": " << nlohmann::json(table.columns).dump() << ", \"rows\": [";
  for (size_t r = 0; r < table.rows.size(); ++r) {
    const SweepRow& row = table.rows[r];
    out << (r ? ",\n  " : "\n  ") << "{\"variant\": " << row.variant;
    for (size_t c = 0; c < table.columns.size(); ++c) {
      out << ", " << nlohmann::json(table.columns[c]).dump() << ": ";
      const std::string& value = c < row.values.size() ? row.values[c] : std::string();
      out << (value.empty() ? std::string("null") : value);
    }
    out << ", \"error\": " << (row.error.empty() ? std::string("null") : nlohmann::json(row.error).dump()) << "}";
  }
  out << (table.rows.empty() ? "]}\n" : "\n]}\n");
}

namespace {

// FNV-1a, 64 bits, of the header, a line break and the row's JSON without its check, in
// hexadecimal: catches a row edited or damaged, and a row moved from under another header.
std::string rowChecksum(std::string_view header, const nlohmann::json& row) {
  uint64_t hash = 1469598103934665603ull;
  auto add = [&hash](std::string_view text) {
    for (unsigned char c : text) {
      hash ^= c;
      hash *= 1099511628211ull;
    }
  };
  add(header);
  add("\n");
  add(row.dump());
  char buffer[20];
  std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(hash));
  return buffer;
}

}  // namespace

std::string journalLine(const SweepRow& row, std::string_view header) {
  nlohmann::json line;
  line["variant"] = row.variant;
  line["values"] = row.values;
  line["error"] = row.error;
  line["check"] = rowChecksum(header, line);
  return line.dump();
}

std::optional<SweepRow> parseJournalLine(std::string_view text, size_t columns, std::string_view header) {
  nlohmann::json line = nlohmann::json::parse(text, nullptr, false);
  if (line.is_discarded() || !line.is_object()) return std::nullopt;
  const auto check = line.find("check");
  if (check == line.end() || !check->is_string()) return std::nullopt;
  const std::string written = check->get<std::string>();
  line.erase("check");
  if (line.size() != 3 || rowChecksum(header, line) != written) return std::nullopt;
  const auto variant = line.find("variant");
  const auto values = line.find("values");
  const auto error = line.find("error");
  if (variant == line.end() || values == line.end() || error == line.end()) return std::nullopt;
  if (!variant->is_number_unsigned() || !values->is_array() || !error->is_string() || values->size() != columns)
    return std::nullopt;
  SweepRow row;
  row.variant = variant->get<uint64_t>();
  for (const auto& value : *values) {
    if (!value.is_string()) return std::nullopt;
    const std::string number = value.get<std::string>();
    // A value is what formatValue wrote: a JSON number or nothing.
    if (!number.empty() && !nlohmann::json::parse(number, nullptr, false).is_number()) return std::nullopt;
    row.values.push_back(number);
  }
  row.error = error->get<std::string>();
  return row;
}

JournalContents readJournal(const std::filesystem::path& path, size_t columns, std::string_view header) {
  JournalContents contents;
  std::ifstream in(path, std::ios::binary);
  if (!in) return contents;
  contents.exists = true;
  std::ostringstream all;
  all << in.rdbuf();
  const std::string text = all.str();
  std::set<uint64_t> seen;
  size_t at = 0;
  bool first = true;
  while (at < text.size()) {
    const size_t end = text.find('\n', at);
    if (end == std::string::npos) break;  // a line cut short: no newline yet
    const std::string_view line(text.data() + at, end - at);
    if (first) {
      contents.header = std::string(line);
      first = false;
    } else if (std::optional<SweepRow> row = parseJournalLine(line, columns, header)) {
      if (seen.insert(row->variant).second) contents.rows.push_back(std::move(*row));
    } else {
      ++contents.rejected;
    }
    at = end + 1;
  }
  return contents;
}

}  // namespace ontogen
