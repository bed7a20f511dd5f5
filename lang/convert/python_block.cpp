#include "lang/convert/python_block.h"

#include "lang/convert/foreign_text.h"

namespace ontogen::convert {

namespace {

class BlockReader {
 public:
  BlockReader(const ForeignSyntax& syntax, std::string_view text, const std::vector<BodyLine>& lines)
      : syntax_(syntax), text_(text), lines_(lines) {}

  std::vector<PythonStatement> read() {
    std::vector<PythonStatement> body = block(lines_.empty() ? 0 : lines_.front().indent);
    if (at_ < lines_.size()) syntax_.fail(lines_[at_].begin, lines_[at_].end, "unexpected indentation", false);
    return body;
  }

 private:
  bool starts(uint32_t b, uint32_t e, std::string_view word) const { return startsWithKeyword(text_, b, e, word); }

  // The statements of the lines at `indent`, from the next one.
  std::vector<PythonStatement> block(int indent) {
    std::vector<PythonStatement> result;
    while (at_ < lines_.size() && lines_[at_].indent >= indent) {
      if (lines_[at_].indent > indent) syntax_.fail(lines_[at_].begin, lines_[at_].end, "unexpected indentation", false);
      const BodyLine line = lines_[at_++];
      uint32_t b = line.begin, e = line.end;
      syntax_.trim(b, e);
      const bool elif = starts(b, e, "elif"), otherwise = starts(b, e, "else");
      if (elif || otherwise) {
        if (result.empty() || !result.back().isIf() || !result.back().branches.back().testEnd)
          syntax_.fail(b, e, "'elif' or 'else' without its 'if'", false);
        result.back().branches.push_back(compound(b + 4, e, indent, otherwise));
        continue;
      }
      PythonStatement stmt;
      stmt.begin = b;
      stmt.end = e;
      if (starts(b, e, "if")) {
        stmt.branches.push_back(compound(b + 2, e, indent, false));
      } else if (starts(b, e, "for") && opensBody(b, e, indent)) {
        stmt.loop = true;
        stmt.branches.push_back(compound(b + 3, e, indent, false));
      } else if (e > b && text_[e - 1] == ':' && at_ < lines_.size() && lines_[at_].indent > indent) {
        // `while`, `with`, `try` ... (and a `for` whose header has no ':'): the lines of its
        // block are its own, so that the reader refuses the statement at its keyword.
        while (at_ < lines_.size() && lines_[at_].indent > indent) ++at_;
      }
      result.push_back(std::move(stmt));
    }
    return result;
  }

  // Whether the line [b, e) at `indent` has a ':' followed by a statement on it or by an
  // indented block below.
  bool opensBody(uint32_t b, uint32_t e, int indent) const {
    const uint32_t colon = syntax_.find(b, e, ":");
    if (colon == e) return false;
    return colon + 1 < e || (at_ < lines_.size() && lines_[at_].indent > indent);
  }

  // `TEST: statement` or `TEST:` and an indented block; `otherwise`: an `else`.
  PythonBranch compound(uint32_t b, uint32_t e, int indent, bool otherwise) {
    PythonBranch branch;
    const uint32_t colon = syntax_.find(b, e, ":");
    if (colon == e) syntax_.fail(b, e, "expected ':' after the test", false);
    uint32_t tb = b, te = colon;
    syntax_.trim(tb, te);
    if (otherwise && tb != te) syntax_.fail(tb, te, "expected ':' after 'else'", false);
    if (!otherwise && tb == te) syntax_.fail(b, colon + 1, "expected a test before ':'", false);
    if (!otherwise) {
      branch.testBegin = tb;
      branch.testEnd = te;
    }
    uint32_t sb = colon + 1, se = e;
    syntax_.trim(sb, se);
    if (sb < se) {
      branch.body.push_back(PythonStatement{sb, se, {}});
      return branch;
    }
    if (at_ >= lines_.size() || lines_[at_].indent <= indent) syntax_.fail(b, e, "a test without a body", false);
    branch.body = block(lines_[at_].indent);
    return branch;
  }

  const ForeignSyntax& syntax_;
  std::string_view text_;
  const std::vector<BodyLine>& lines_;
  size_t at_ = 0;
};

}  // namespace

bool startsWithKeyword(std::string_view text, uint32_t begin, uint32_t end, std::string_view word) {
  if (end - begin < word.size() || text.compare(begin, word.size(), word) != 0) return false;
  return begin + word.size() == end || !chars::isNameChar(text[begin + word.size()]);
}

std::optional<PythonAssignment> readAssignment(std::string_view text, uint32_t begin, uint32_t end) {
  uint32_t at = begin;
  while (at < end && chars::isNameChar(text[at])) ++at;
  if (at == begin || !chars::isLetter(text[begin])) return std::nullopt;
  uint32_t op = at;
  while (op < end && chars::isSpace(text[op])) ++op;
  char kind = 0;
  if (op < end && text[op] == '=' && (op + 1 >= end || text[op + 1] != '='))
    kind = '=';
  else if (op + 1 < end && text[op + 1] == '=' && std::string_view("+-*/").find(text[op]) != std::string_view::npos)
    kind = text[op];
  if (!kind) return std::nullopt;
  return PythonAssignment{std::string(text.substr(begin, at - begin)), kind, op + (kind == '=' ? 1u : 2u)};
}

std::set<std::string, std::less<>> assignedNames(std::string_view text, const std::vector<PythonStatement>& statements) {
  std::set<std::string, std::less<>> names;
  for (const PythonStatement& stmt : statements) {
    if (std::optional<PythonAssignment> assignment = readAssignment(text, stmt.begin, stmt.end))
      names.insert(std::move(assignment->name));
    if (stmt.isFor()) {  // the loop's variable
      const PythonBranch& header = stmt.branches.front();
      uint32_t at = header.testBegin;
      while (at < header.testEnd && chars::isNameChar(text[at])) ++at;
      if (at > header.testBegin) names.emplace(text.substr(header.testBegin, at - header.testBegin));
    }
    for (const PythonBranch& branch : stmt.branches) names.merge(assignedNames(text, branch.body));
  }
  return names;
}

std::vector<PythonStatement> readPythonBlock(const ForeignSyntax& syntax, std::string_view text,
                                             const std::vector<BodyLine>& lines) {
  return BlockReader(syntax, text, lines).read();
}

std::vector<BodyLine> logicalLines(std::string_view text, uint32_t begin, uint32_t end) {
  std::vector<BodyLine> lines;
  uint32_t at = begin;
  while (at < end) {
    uint32_t lineEnd = at;
    while (lineEnd < end && text[lineEnd] != '\n') ++lineEnd;
    uint32_t first = at;
    int indent = 0;
    while (first < lineEnd && (text[first] == ' ' || text[first] == '\t' || text[first] == '\r')) {
      indent += text[first] == '\t' ? 8 - indent % 8 : text[first] == ' ' ? 1 : 0;
      ++first;
    }
    if (first == lineEnd) {
      at = lineEnd + 1;
      continue;
    }
    // Continue while a parenthesis is open (brackets and braces are modules of a word).
    int depth = 0;
    uint32_t stop = first;
    for (;;) {
      for (; stop < end && text[stop] != '\n'; ++stop) {
        if (text[stop] == '(') ++depth;
        if (text[stop] == ')') --depth;
      }
      if (depth <= 0 || stop >= end) break;
      ++stop;
    }
    lines.push_back({first, stop, indent});
    at = stop + 1;
  }
  return lines;
}

}  // namespace ontogen::convert
