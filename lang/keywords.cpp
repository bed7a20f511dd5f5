#include "lang/keywords.h"

#include <array>

namespace ontogen {

namespace {

using Kind = KeywordKind;

constexpr std::array kKeywords = {
    Keyword{"cell", Kind::Declaration, "cell NAME(params) { ... }: a kind of cell, its rules and interpretation"},
    Keyword{"lsystem", Kind::Declaration, "lsystem NAME { ... }: a system written as L-system productions"},
    Keyword{"system", Kind::Declaration, "system NAME { ... }: a system of cells in a pool"},
    Keyword{"import", Kind::Declaration, "import \"file.cell\": the cells and systems of another file"},
    Keyword{"axiom", Kind::Statement, "axiom WORD: the cells a system starts with"},
    Keyword{"pool", Kind::Statement, "pool linear | grid(w, h) | spatial(r) OPTIONS: where a system's cells live"},
    Keyword{"fill", Kind::Statement, "fill A(e): a cell at every site of a grid"},
    Keyword{"at", Kind::Statement, "at(x, y) A(e): a cell at one site of a grid"},
    Keyword{"rules", Kind::Statement, "rules { ... }: a cell's state updates and rewriting rules"},
    Keyword{"rate", Kind::Statement, "rate(x) = e: x changes continuously at e per second"},
    Keyword{"terminal", Kind::Statement, "terminal: -> W: what a cell becomes at its terminal age"},
    Keyword{"lifetime", Kind::Statement, "lifetime T; a cell's terminal age, seconds (also read as a value)"},
    Keyword{"interpret", Kind::Statement, "interpret SET [A(p)] { ... }: instructions of an interpretation set"},
    Keyword{"equiv", Kind::Statement, "equiv A B: A and B are one module to context matching"},
    Keyword{"ignore", Kind::Statement, "ignore: A B: modules context matching skips"},
    Keyword{"consider", Kind::Statement, "consider: A B: the only modules context matching sees"},
    Keyword{"g", Kind::Statement, "g A(tau, beta) = e: a development function of a module"},
    Keyword{"develop", Kind::Statement, "develop A(tau, beta) = e: a development function (the long spelling of g)"},
    Keyword{"production", Kind::Statement, "production: the section of productions (L-Py's layout)"},
    Keyword{"decomposition", Kind::Statement, "decomposition: productions applied at once, to a depth"},
    Keyword{"homomorphism", Kind::Statement, "homomorphism: productions applied only to the word interpreted"},
    Keyword{"interpretation", Kind::Statement, "interpretation: the homomorphism's section, as L-Py names it"},
    Keyword{"maximum", Kind::Statement, "maximum depth: N: how deep decomposition and homomorphism go"},
    Keyword{"depth", Kind::Statement, "maximum depth: N"},
    Keyword{"group", Kind::Statement, "group N: the productions that follow belong to group N"},
    Keyword{"use", Kind::Statement, "use group N: the group of productions in force"},
    Keyword{"scale", Kind::Statement, "scale N: A B: the scale of modules A and B; contexts match at scales"},
    Keyword{"level", Kind::Statement, "level N: A B: the level of modules A and B; contexts match at levels"},
    Keyword{"me", Kind::Reference, "the cell itself: me.x, me.age, me.parent"},
    Keyword{"parent", Kind::Reference, "the enclosing cell: parent.x"},
    Keyword{"root", Kind::Reference, "the outermost enclosing cell: root.x"},
    Keyword{"age", Kind::Reference, "the cell's age, seconds (tau, τ)"},
    Keyword{"tau", Kind::Reference, "the cell's age, seconds"},
    Keyword{"τ", Kind::Reference, "the cell's age, seconds"},
    Keyword{"lifetime", Kind::Reference, "the cell's terminal age, seconds (beta, β)"},
    Keyword{"beta", Kind::Reference, "the cell's terminal age, seconds"},
    Keyword{"β", Kind::Reference, "the cell's terminal age, seconds"},
    Keyword{"time", Kind::Reference, "the global time of the development, seconds"},
    Keyword{"status", Kind::Reference, "the cell's status: birth (1) in the instant it appears, alive (2) after"},
    Keyword{"id", Kind::Reference, "the cell's stable id"},
};

}  // namespace

std::span<const Keyword> keywords() { return kKeywords; }

std::string_view keywordKindName(KeywordKind kind) {
  switch (kind) {
    case KeywordKind::Declaration:
      return "declaration";
    case KeywordKind::Statement:
      return "statement";
    case KeywordKind::Reference:
      return "reference";
  }
  return "?";
}

}  // namespace ontogen
