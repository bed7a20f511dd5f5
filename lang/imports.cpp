#include "lang/imports.h"

#include <algorithm>
#include <filesystem>
#include <iterator>
#include <set>

#include "lang/parser.h"
#include "lang/source_reader.h"

namespace ontogen {

namespace {
namespace fs = std::filesystem;

template <typename T>
void prepend(std::vector<T>& into, std::vector<T>&& items) {
  into.insert(into.begin(), std::make_move_iterator(items.begin()), std::make_move_iterator(items.end()));
}

template <typename T>
void append(std::vector<T>& into, std::vector<T>&& items) {
  into.insert(into.end(), std::make_move_iterator(items.begin()), std::make_move_iterator(items.end()));
}

class ImportResolver {
 public:
  ImportResolver(DiagnosticSink& sink, uint64_t maxBytes) : sink_(sink), maxBytes_(maxBytes) {}

  ParsedProgram run(std::shared_ptr<const SourceFile> main) {
    ParsedProgram result;
    std::error_code error;
    seen_.insert(fs::weakly_canonical(main->name(), error).string());
    result.tree = load(main, result.sources);
    return result;
  }

 private:
  // Parses one file, then merges in what it imports.
  ast::Program load(std::shared_ptr<const SourceFile> file, std::vector<std::shared_ptr<const SourceFile>>& sources) {
    sink_.retain(file);
    sources.push_back(file);
    usedBytes_ += file->text().size();
    ast::Program tree = parse(*file, sink_);
    const fs::path base = fs::path(file->name()).parent_path();
    ast::Program imported;
    for (const ast::Import& import : tree.imports) {
      const fs::path path = base / import.path;
      std::error_code error;
      const std::string key = fs::weakly_canonical(path, error).string();
      if (!seen_.insert(key).second) continue;
      SourceText read = readSourceFile(path, maxBytes_ - std::min(maxBytes_, usedBytes_));
      if (!read.text) {
        sink_.error(import.span, "cannot import '" + import.path + "': " + read.error);
        continue;
      }
      ast::Program library = load(std::make_shared<const SourceFile>(path.string(), std::move(*read.text)), sources);
      append(imported.defines, std::move(library.defines));
      append(imported.equivs, std::move(library.equivs));
      append(imported.settings, std::move(library.settings));
      append(imported.functions, std::move(library.functions));
      append(imported.cells, std::move(library.cells));
      append(imported.systems, std::move(library.systems));
    }
    prepend(tree.defines, std::move(imported.defines));
    prepend(tree.equivs, std::move(imported.equivs));
    prepend(tree.settings, std::move(imported.settings));
    prepend(tree.functions, std::move(imported.functions));
    prepend(tree.cells, std::move(imported.cells));
    append(tree.systems, std::move(imported.systems));
    return tree;
  }

  DiagnosticSink& sink_;
  const uint64_t maxBytes_;  // of the program and its imports together
  uint64_t usedBytes_ = 0;
  std::set<std::string> seen_;
};
}  // namespace

ParsedProgram parseWithImports(std::shared_ptr<const SourceFile> main, DiagnosticSink& sink, uint64_t maxSourceBytes) {
  return ImportResolver(sink, maxSourceBytes).run(std::move(main));
}

}  // namespace ontogen
