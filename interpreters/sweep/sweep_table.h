#pragma once
// The table of a sweep or of one generation of an evolution: a row per variant in the
// order of their indices, the columns `variant`, one per define (or gene), `seed`, one
// per measure and `error`. Values are kept as the text they are written as (the
// shortest decimal that reads back as the same double), so the journal, the CSV and the
// JSON hold the same digits, and a table rebuilt from a journal after a resume is byte
// for byte the table of an uninterrupted run.
//
// The journal (DIR/journal.jsonl) is what a run appends as variants finish: a first
// line naming the sweep (its settings, so that --resume refuses another sweep's folder),
// then one JSON object per finished row, in the order they finished. Each row carries a
// checksum of itself and of the first line it was written under, so a row changed by
// hand or by a fault, or written under other settings (other measures), reads back as no
// row and is run again; so is a line cut short by a kill.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace ontogen {

/// One variant's row: the values between `variant` and `error`, as written.
struct SweepRow {
  uint64_t variant = 0;
  std::vector<std::string> values;  ///< one per SweepTable::columns; empty: no value (JSON null)
  std::string error;                ///< empty when the run and its measures succeeded
  friend bool operator==(const SweepRow&, const SweepRow&) = default;
};

struct SweepTable {
  std::vector<std::string> columns;  ///< the columns between `variant` and `error`
  std::vector<SweepRow> rows;        ///< sorted by variant
};

/// The shortest decimal text that reads back as value (integers below 2^53 without a
/// point or exponent); empty for NaN and the infinities.
std::string formatValue(double value);

/// RFC 4180: a header line, then a line per row; a field holding a comma, a quote or a
/// line break is quoted, quotes doubled. Lines end in "\n".
void writeTableCsv(const SweepTable& table, std::ostream& out);
/// {"columns": [...], "rows": [{"variant": 0, "<column>": number or null, ..., "error": null or "..."}]}.
void writeTableJson(const SweepTable& table, std::ostream& out);

/// A row as one line of the journal (no line break), with its checksum under `header`
/// (the journal's first line).
std::string journalLine(const SweepRow& row, std::string_view header);
/// The row of a journal line written under `header`; nothing when the line is not one
/// (cut short, another number of columns) or its checksum fails (changed since, or
/// written under another header).
std::optional<SweepRow> parseJournalLine(std::string_view line, size_t columns, std::string_view header);

/// What a journal held.
struct JournalContents {
  bool exists = false;
  std::string header;           ///< its first line; empty when it has no whole first line
  std::vector<SweepRow> rows;   ///< every whole row that checks, in the order written (later duplicates dropped)
  uint64_t rejected = 0;        ///< whole lines after the first that are no row or fail their checksum
};
/// Reads a journal whose rows were written under `header` (its own first line may say
/// otherwise: its rows then fail their checksums); a missing file is an empty
/// JournalContents. The file must be a regular file (interpreters/output_file.h,
/// outputTarget): a FIFO would never end.
JournalContents readJournal(const std::filesystem::path& path, size_t columns, std::string_view header);

}  // namespace ontogen
