#include "lang/convert/written_number.h"

#include "lang/expression_compiler.h"
#include "lang/parser.h"

namespace ontogen::convert {

std::optional<double> writtenNumber(const std::string& expression) {
  if (expression.find('\n') != std::string::npos) return std::nullopt;
  SourceFile file("(converted)", "#define value (" + expression + ")\n");
  DiagnosticSink sink;
  const ast::Program tree = parse(file, sink);
  if (sink.hasErrors() || tree.defines.size() != 1 || !tree.defines[0].value) return std::nullopt;
  NameLookup names;
  names.constant = [](std::string_view) -> std::optional<double> { return std::nullopt; };
  return evaluateConstant(*tree.defines[0].value, names, sink, "the value");
}

}  // namespace ontogen::convert
