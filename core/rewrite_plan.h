#pragma once
// How a linear word is rewritten, decided in one place. Every way of rewriting a word
// writes the bytes the serial pass writes (records, ids, births, values, statistics) on
// any thread count; they differ only in speed and in what they need of the rules. The
// development gathers the facts (the word's kind and size, what the rules allow, the
// threads asked for, what earlier rewrites learnt) and planRewrite picks the strategy and
// the threads it runs on; an executor then runs it, and the world's statistics count the
// rewrites each strategy made (WorldStats::rewrites), so a test sees which ran.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace ontogen {

/// One way of rewriting a linear word; the comment says why it exists.
enum class RewriteStrategy : uint8_t {
  Serial,         ///< records, cell by cell: the reference, and every word the others cannot take
  CompactSerial,  ///< compact word in one pass: small words, and choices that vary (counting would choose twice)
  TableAlone,     ///< compact word walked by its table in one pass without counting (Koch, Thue-Morse, one thread)
  OneForOne,      ///< compact word whose modules each write one: slices know their place without counting (a signal)
  Parts,          ///< compact word whose choices vary, on many cores: parts written apart, then copied in
  TableBounds,    ///< compact word walked by its table by slices placed by bounds: the count saved (Koch, many cores)
  CompactSlices,  ///< compact word counted then written by slices: the general pass of a compact word
};

/// The number of strategies (the size of WorldStats::rewrites).
inline constexpr size_t kRewriteStrategyCount = 7;

/// The strategy's name, as statistics print it ("serial", "table-alone", ...).
std::string_view rewriteStrategyName(RewriteStrategy strategy);

/// Whether the strategy rewrites a compact word (docs/COMPACT_WORDS.md) rather than records.
constexpr bool rewritesCompactWords(RewriteStrategy strategy) {
  return strategy >= RewriteStrategy::CompactSerial;
}

/// Rewrites made by each strategy, indexed by RewriteStrategy.
using RewriteCounts = std::array<uint64_t, kRewriteStrategyCount>;

/// The strategies that rewrote words and how often, as `--stats` prints them:
/// "table-alone 5, compact-slices 2" (strategies that made none left out; "" if none did).
std::string formatRewriteCounts(const RewriteCounts& counts);

/// What a system's rules allow, found once from the program (ParallelRewrite).
struct RewriteShape {
  bool compact = false;       ///< the word may be kept compact between steps
  bool byTable = false;       ///< every master does one thing when it expires (pools/table_rewrite.h)
  bool choiceVaries = false;  ///< some label-only master's choice depends on the cell
  bool oneForOne = false;     ///< every rule that acts writes one successor
  bool withValues = false;    ///< the compact word holds state values
  bool anyState = false;      ///< some master has state values
  bool batched = false;       ///< some master's successors' values are evaluated in batches
};

/// Which pass of the development asks.
enum class RewritePass : uint8_t {
  Records,  ///< a word of records: the serial pass, context-free or instant by instant
  Compact,  ///< a compact word at one instant
};

/// The facts planRewrite decides by.
struct RewriteFacts {
  RewriteShape shape;
  RewritePass pass = RewritePass::Records;
  size_t size = 0;              ///< modules of the word
  unsigned threads = 1;         ///< threads the world may use (WorldDef::threads)
  bool withoutIds = false;      ///< the table's words are written without ids (ParallelRewrite::writesWithoutIds)
  bool growthKnown = false;     ///< a compact rewrite of this development grew a word already
  bool boundsMissed = false;    ///< slices placed by bounds once wrote less than the bounds
  bool inPlaceRefused = false;  ///< OneForOne's bounds did not fit the limits this time
  /// For tests only (WorldDef::testRewriteStrategy): the strategy to take wherever it applies.
  std::optional<RewriteStrategy> forced;
};

/// A plan: the strategy, and the threads it runs on: 1 for Serial, CompactSerial and
/// TableAlone, the world's (RewriteFacts::threads) for the others.
struct RewritePlan {
  RewriteStrategy strategy = RewriteStrategy::Serial;
  unsigned threads = 1;
};

/// The unforced plan rewrites words smaller than this on one thread: threads would cost more than they save.
inline constexpr size_t kMinimumSliceCells = size_t{1} << 15;

/// Whether `strategy` can rewrite a word of these facts (what it needs of the rules and
/// of the word, not whether it pays).
bool rewriteApplies(RewriteStrategy strategy, const RewriteFacts& facts);

/// The strategy for a word of these facts: the forced one where it applies, else the
/// fastest that applies; and its threads, decided here alone.
RewritePlan planRewrite(const RewriteFacts& facts);

/// Whether a development whose rules have `shape` keeps its word compact in this step
/// (else it takes the records' passes); the compact strategies apply only then.
bool keepsWordCompact(const RewriteShape& shape, bool slices, bool lineage,
                      const std::optional<RewriteStrategy>& forced);

/// Whether the table's words are written without their ids (WorldDef::wordsWithoutIds):
/// only where every strategy the word may take can write them so.
bool writesWordsWithoutIds(const RewriteShape& shape, bool wordsWithoutIds,
                           const std::optional<RewriteStrategy>& forced);

}  // namespace ontogen
