// What `#letters` costs (lang/parser_cells.cpp, splitLetterRun): the bytes the parser allocates
// grow with the text, not with its square. A run of 32,000 letters once took 1 GB (each
// piece copied the whole run's text). Counted by the bytes asked of operator new in this
// executable, which holds this test alone.

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <string>

#include "lang/parser.h"

namespace {
std::atomic<uint64_t> allocatedBytes{0};
}  // namespace

void* operator new(std::size_t bytes) {
  allocatedBytes.fetch_add(bytes, std::memory_order_relaxed);
  if (void* block = std::malloc(bytes == 0 ? 1 : bytes)) return block;
  throw std::bad_alloc();
}
// GCC takes the replaced operators' free for a mismatch with the operator new it pairs.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
void operator delete(void* block) noexcept { std::free(block); }
void operator delete(void* block, std::size_t) noexcept { std::free(block); }
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

namespace ontogen {
namespace {

// Bytes allocated while `text` is parsed (without errors).
uint64_t bytesToParse(const std::string& text) {
  SourceFile file("letters.cell", text);
  DiagnosticSink sink;
  const uint64_t before = allocatedBytes.load();
  const ast::Program program = parse(file, sink);
  const uint64_t bytes = allocatedBytes.load() - before;
  EXPECT_FALSE(sink.hasErrors()) << formatDiagnostics(sink);
  return bytes;
}

std::string axiomOf(const std::string& run) { return "lsystem a {\n #letters\n axiom " + run + "\n F -> F\n}\n"; }
std::string successorOf(const std::string& run) { return "lsystem a {\n #letters\n axiom F\n F -> " + run + "\n}\n"; }

TEST(LettersCost, ARunOfLettersCostsBytesInProportionToItsLength) {
  for (auto* program : {&axiomOf, &successorOf}) {
    const uint64_t single = bytesToParse(program(std::string(16000, 'F')));
    const uint64_t twice = bytesToParse(program(std::string(32000, 'F')));
    // Twice the letters, twice the bytes (and a little): the square would give four times.
    EXPECT_LT(twice, single * 5 / 2) << single << " bytes, then " << twice;
    // A few hundred bytes a module: its token and its node.
    EXPECT_LT(twice, uint64_t{32000} * 1024) << twice;
  }
}

TEST(LettersCost, ManyShortRunsCostBytesInProportionToTheirCount) {
  std::string single, twice;
  for (int i = 0; i < 8000; ++i) single += "FF+";
  twice = single + single;
  const uint64_t one = bytesToParse(axiomOf(single));
  const uint64_t two = bytesToParse(axiomOf(twice));
  EXPECT_LT(two, one * 5 / 2) << one << " bytes, then " << two;
}

}  // namespace
}  // namespace ontogen
