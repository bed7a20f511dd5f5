// The C++ side of bench/python_vs_cpp.py: grows a program through the library's API
// and reads its word into columns (id, parent, age, label index, parameters), what
// World.arrays() gives Python, timing the growth and the read apart in processor seconds
// (user and system: on a shared machine wall time mostly measures the others),
// repetition by repetition, as one JSON line each.
//
//   python_vs_cpp_baseline FILE.cell UNTIL REPETITIONS THREADS

#include <sys/resource.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "core/word.h"
#include "core/world.h"
#include "interpreters/set_registry.h"
#include "lang/compiler.h"

namespace {

using namespace ontogen;

// The word's columns, cell by cell in pool order, as a C++ program would collect them.
class Columns final : public WordVisitor {
 public:
  explicit Columns(size_t cells) {
    ids.reserve(cells);
    parents.reserve(cells);
    ages.reserve(cells);
    labels.reserve(cells);
  }
  void cell(const WordCellView& cell) override {
    constexpr uint64_t kIdBits = (uint64_t{1} << 53) - 1;
    ids.push_back(cell.id & kIdBits);
    parents.push_back(cell.parent == ~uint64_t{0} ? -1 : static_cast<int64_t>(cell.parent & kIdBits));
    ages.push_back(cell.age);
    params.insert(params.end(), cell.params.begin(), cell.params.end());
    // A label is one string for the program's life: its address names it.
    if (cell.label.data() != last_.data()) {
      auto [found, added] = index_.try_emplace(cell.label.data(), static_cast<int32_t>(names.size()));
      if (added) names.emplace_back(cell.label);
      last_ = cell.label;
      lastIndex_ = found->second;
    }
    labels.push_back(lastIndex_);
  }
  std::vector<uint64_t> ids;
  std::vector<int64_t> parents;
  std::vector<double> ages;
  std::vector<int32_t> labels;
  std::vector<std::string> names;
  std::vector<double> params;

 private:
  std::unordered_map<const char*, int32_t> index_;
  std::string_view last_;
  int32_t lastIndex_ = 0;
};

// Processor seconds of the process so far, user and system (where fresh pages are zeroed).
double processSeconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 5) {
    std::cerr << "usage: python_vs_cpp_baseline FILE.cell UNTIL REPETITIONS THREADS\n";
    return 2;
  }
  std::ifstream in(argv[1], std::ios::binary);
  if (!in) {
    std::cerr << "python_vs_cpp_baseline: cannot read " << argv[1] << "\n";
    return 2;
  }
  std::ostringstream text;
  text << in.rdbuf();
  const double until = std::stod(argv[2]);
  const int repetitions = std::stoi(argv[3]);
  const auto threads = static_cast<unsigned>(std::stoul(argv[4]));

  for (int repetition = 0; repetition < repetitions; ++repetition) {
    const double start = processSeconds();
    DiagnosticSink sink;
    CompileOptions options;
    options.commandSets = commandSets();
    std::shared_ptr<const Program> program = compileSource(argv[1], text.str(), sink, options);
    if (!program) {
      std::cerr << formatDiagnostics(sink);
      return 1;
    }
    WorldDef def;
    def.seed = 0;
    def.threads = threads;
    def.environment = queryEnvironmentOf(*program);
    World world(program, def);
    world.advanceTo(until, program->dt);
    const double grow = processSeconds() - start;
    const double readStart = processSeconds();
    Columns columns(static_cast<size_t>(world.totalCells()));
    visitWord(world, columns);
    const double read = processSeconds() - readStart;
    std::printf("{\"grow\": %.6f, \"read\": %.6f, \"cells\": %zu, \"labels\": %zu}\n", grow, read,
                columns.ids.size(), columns.names.size());
    std::fflush(stdout);
  }
  return 0;
}
