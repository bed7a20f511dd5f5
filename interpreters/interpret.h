#pragma once
// Walks a developed world in pool order and realises each cell through an
// interpretation set: a cell with an `interpret SET { ... }` block runs its
// instructions (arguments evaluated over its state, age and the time); otherwise a cell
// whose symbol (or equiv) is a command of the set runs that command with its developed
// parameters (paper 000: λ' = g · λ). Development and interpretation stay decoupled.

#include <filesystem>
#include <vector>

#include "core/world.h"
#include "interpreters/interpretation_set.h"

namespace ontogen {

/// Interprets the world's current word as one frame; returns the files the set wrote.
std::vector<std::filesystem::path> interpretFrame(const World& world, InterpretationSet& set,
                                                  const FrameTarget& target);

/// Feeds the world's current word to the set (between beginFrame and endFrame).
void interpretWord(const World& world, InterpretationSet& set);

}  // namespace ontogen
