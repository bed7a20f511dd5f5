#include "batch/batch_run.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <fstream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "interpreters/formats/png_writer.h"
#include "interpreters/interpretation_set.h"
#include "interpreters/output_file.h"
#include "interpreters/sweep/variant_pool.h"

namespace ontogen {

namespace {

// Rank 0's side of the journal: checks a resumed one, drops a line cut short, appends.
struct JournalSetup {
  BatchStatus status = BatchStatus::Done;
  std::string message;
  std::filesystem::path target;  // the file the journal's rows are appended to
  std::vector<SweepRow> rows;
};

// A kill that no handler sees (SIGKILL, a node lost) can leave the temporary of a file
// being written, `.NAME.tmpPID_N` (interpreters/output_file.h); a resumed sweep removes
// them from its folder and the two below it, where its files go.
void removeStaleTemporaries(const std::filesystem::path& dir) {
  auto temporary = [](const std::string& name) {
    const size_t tmp = name.rfind(".tmp");
    if (name.empty() || name[0] != '.' || tmp == std::string::npos || tmp == 0) return false;
    const std::string tail = name.substr(tmp + 4);
    const size_t underscore = tail.find('_');
    auto digits = [](std::string_view text) {
      return !text.empty() && std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
    };
    return underscore != std::string::npos && digits(std::string_view(tail).substr(0, underscore)) &&
           digits(std::string_view(tail).substr(underscore + 1));
  };
  for (const std::filesystem::path& folder : {dir, dir / "thumbnails", dir / "programs"}) {
    std::error_code error;
    std::vector<std::filesystem::path> stale;
    for (std::filesystem::directory_iterator it(folder, error), end; !error && it != end; it.increment(error))
      if (temporary(it->path().filename().string())) stale.push_back(it->path());
    for (const std::filesystem::path& file : stale) std::filesystem::remove(file, error);
  }
}

// The settings that make the variants: the header without what is measured of them.
// Two journals of one identity hold rows of the same variants; rows measured otherwise
// fail their checksums and run again.
std::string identityOf(const std::string& header) {
  nlohmann::json settings = nlohmann::json::parse(header, nullptr, false);
  if (settings.is_discarded() || !settings.is_object()) return header;
  settings.erase("measures");
  settings.erase("columns");
  return settings.dump();
}

JournalSetup openJournal(const BatchDef& def, const std::filesystem::path& path) {
  JournalSetup setup;
  std::error_code error;
  std::filesystem::create_directories(def.dir, error);
  if (error) {
    setup.status = BatchStatus::OutputError;
    setup.message = "cannot create the folder '" + def.dir.string() + "': " + error.message();
    return setup;
  }
  // The journal follows the rule of every output (interpreters/output_file.h): written
  // through a symbolic link, refused when it is no regular file (a FIFO would never end).
  try {
    setup.target = outputTarget(path);
  } catch (const OutputError& bad) {
    setup.status = BatchStatus::OutputError;
    setup.message = bad.what();
    return setup;
  }
  JournalContents contents = readJournal(setup.target, def.columns.size(), def.header);
  // A journal without a whole first line (empty, or its header cut short by a kill)
  // holds no row: it is written anew.
  const bool holdsSweep = contents.exists && !contents.header.empty();
  if (holdsSweep && !def.resume) {
    setup.status = BatchStatus::Refused;
    setup.message = "'" + def.dir.string() +
                    "' holds a sweep already (journal.jsonl); --resume continues it, or choose another --out";
    return setup;
  }
  if (holdsSweep && identityOf(contents.header) != identityOf(def.header)) {
    setup.status = BatchStatus::Refused;
    setup.message = "'" + def.dir.string() +
                    "' holds a sweep of other settings (another program, defines, seeds or run settings); "
                    "--resume continues a sweep only with the command that began it";
    return setup;
  }
  if (holdsSweep) removeStaleTemporaries(def.dir);
  // Only rows that check and say what their variant is are kept; the journal is written
  // again with them alone (the others run again), atomically.
  for (SweepRow& row : contents.rows) {
    if (row.variant >= def.count) continue;
    if (def.leading) {
      const std::vector<std::string> expected = def.leading(row.variant);
      if (row.values.size() < expected.size() || !std::equal(expected.begin(), expected.end(), row.values.begin()))
        continue;
    }
    setup.rows.push_back(std::move(row));
  }
  try {
    writeFileAtomically(path, [&](std::ostream& out) {
      out << def.header << '\n';
      for (const SweepRow& row : setup.rows) out << journalLine(row, def.header) << '\n';
    });
  } catch (const OutputError& bad) {
    setup.status = BatchStatus::OutputError;
    setup.message = bad.what();
  }
  return setup;
}

std::string encodeRows(const std::vector<SweepRow>& rows, const std::string& header) {
  std::string text;
  for (const SweepRow& row : rows) text += journalLine(row, header) + "\n";
  return text;
}

std::vector<SweepRow> decodeRows(const std::string& text, size_t columns, const std::string& header) {
  std::vector<SweepRow> rows;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (auto row = parseJournalLine(line, columns, header)) rows.push_back(std::move(*row));
  return rows;
}

void writeOutputs(const BatchDef& def, const SweepTable& table) {
  writeFileAtomically(def.dir / "results.csv", [&](std::ostream& out) { writeTableCsv(table, out); });
  writeFileAtomically(def.dir / "results.json", [&](std::ostream& out) { writeTableJson(table, out); });
  std::vector<ContactTile> tiles;
  for (const SweepRow& row : table.rows) tiles.push_back(galleryTile(def.thumbnail(row.variant), table, row, def.labelColumns));
  const Image sheet = contactSheet(tiles, def.sheet);
  writeFileAtomically(def.dir / "gallery.png", [&](std::ostream& out) { writePng(sheet, out); });
  writeFileAtomically(def.dir / "gallery.json", [&](std::ostream& out) { writeContactSheetJson(tiles, def.sheet, out); });
}

}  // namespace

ContactTile galleryTile(const std::filesystem::path& thumbnail, const SweepTable& table, const SweepRow& row,
                        size_t labelColumns) {
  std::error_code error;
  const bool exists = std::filesystem::is_regular_file(thumbnail, error);
  ContactTile tile{exists ? thumbnail : std::filesystem::path(), !row.error.empty() && !exists, {}, 0};
  for (size_t c = 0; c < std::min({labelColumns, table.columns.size(), row.values.size()}); ++c)
    tile.label += (tile.label.empty() ? "" : " ") + table.columns[c] + "=" + row.values[c];
  if (exists) tile.pixelsPerUnit = readThumbnailScale(thumbnail);
  return tile;
}

BatchResult runBatch(const BatchDef& def, Cluster& cluster) {
  BatchResult result;
  result.table.columns = def.columns;
  const std::filesystem::path journalPath = def.dir / "journal.jsonl";

  // Rank 0 opens the journal and tells the others which rows are done (or why none run).
  JournalSetup setup;
  if (cluster.leader()) setup = openJournal(def, journalPath);
  const std::string status =
      cluster.broadcast(std::to_string(static_cast<int>(setup.status)) + "\n" + encodeRows(setup.rows, def.header));
  const auto code = static_cast<BatchStatus>(std::stoi(status.substr(0, status.find('\n'))));
  if (code != BatchStatus::Done) {
    result.status = code;
    result.message = setup.message;
    return result;
  }
  std::vector<SweepRow> rows = decodeRows(status.substr(status.find('\n') + 1), def.columns.size(), def.header);
  std::set<uint64_t> finished;
  for (const SweepRow& row : rows) finished.insert(row.variant);
  std::vector<uint64_t> mine;
  uint64_t pending = 0;
  for (uint64_t i = 0; i < def.count; ++i) {
    if (finished.count(i)) continue;
    if (static_cast<int>(pending % static_cast<uint64_t>(cluster.size())) == cluster.rank()) mine.push_back(i);
    ++pending;
  }

  std::ofstream journal;
  if (cluster.leader()) journal.open(setup.target, std::ios::binary | std::ios::app);
  uint64_t failedNow = 0, doneNow = 0;
  for (const SweepRow& row : rows) failedNow += !row.error.empty();
  const auto started = std::chrono::steady_clock::now();
  auto record = [&](const std::string& line) {
    std::optional<SweepRow> row = parseJournalLine(line, def.columns.size(), def.header);
    if (!row || finished.count(row->variant)) return;
    journal << line << '\n' << std::flush;
    finished.insert(row->variant);
    failedNow += !row->error.empty();
    ++doneNow;
    rows.push_back(std::move(*row));
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    const double left = elapsed / static_cast<double>(doneNow) * static_cast<double>(pending - doneNow);
    if (def.progress) def.progress({finished.size(), def.count, failedNow, left});
  };

  auto stopAsked = [&def] { return def.stop && def.stop(); };
  {
    VariantPool pool(def.workers, mine, [&def](uint64_t i) { return journalLine(def.run(i), def.header); });
    bool stopping = false;
    int ranksDone = cluster.leader() ? 1 : 0;  // rank 0 counts itself when its pool is done
    bool sentDone = false;
    for (;;) {
      if (!stopping && stopAsked()) {
        stopping = true;
        pool.stop();
        if (cluster.leader())
          for (int r = 1; r < cluster.size(); ++r) cluster.send(r, ClusterTag::Stop, "");
      }
      for (auto& [index, line] : pool.take(std::chrono::milliseconds(20))) {
        if (cluster.leader())
          record(line);
        else
          cluster.send(0, ClusterTag::Row, line);
      }
      while (std::optional<ClusterMessage> message = cluster.poll()) {
        if (message->tag == ClusterTag::Row && cluster.leader()) record(message->text);
        if (message->tag == ClusterTag::Done && cluster.leader()) ++ranksDone;
        if (message->tag == ClusterTag::Stop && !stopping) {
          stopping = true;
          pool.stop();
        }
      }
      if (!pool.done()) continue;
      if (!cluster.leader()) {
        if (!sentDone) cluster.send(0, ClusterTag::Done, "");
        sentDone = true;
        break;
      }
      if (ranksDone == cluster.size()) break;
    }
    if (cluster.leader() && !journal) {
      result.status = BatchStatus::OutputError;
      result.message = "cannot write '" + journalPath.string() + "'";
    }
    stopping = stopping || stopAsked();
    if (stopping && result.status == BatchStatus::Done) result.status = BatchStatus::Stopped;
  }

  // Rank 0 writes the table and sends it to all (an evolution chooses its next
  // generation from it on every rank).
  std::sort(rows.begin(), rows.end(), [](const SweepRow& a, const SweepRow& b) { return a.variant < b.variant; });
  if (cluster.leader()) {
    result.table.rows = rows;
    try {
      writeOutputs(def, result.table);
    } catch (const OutputError& error) {
      result.status = BatchStatus::OutputError;
      result.message = error.what();
    }
  }
  const std::string table =
      cluster.broadcast(std::to_string(static_cast<int>(result.status)) + "\n" + encodeRows(rows, def.header));
  result.status = static_cast<BatchStatus>(std::stoi(table.substr(0, table.find('\n'))));
  result.table.rows = decodeRows(table.substr(table.find('\n') + 1), def.columns.size(), def.header);
  for (const SweepRow& row : result.table.rows) result.failed += !row.error.empty();
  return result;
}

}  // namespace ontogen
