#include "interpreters/formats/look.h"

#include <array>

namespace ontogen {

namespace {

// light: the page most documentation sits on; the floor shadow grounds the model.
// dark: for dark pages and screens; surfaces lit more, as dark surroundings make colours
//   read darker.
// paper: for print: warm paper, colours muted and washed towards it, no floor (a drawing
//   rather than a photograph), lines drawn nearly black, as in ink.
const std::array<Look, 3> kLooks{
    Look{},
    Look{.name = "dark",
         .background = {28, 30, 34},
         .ambient = 0.3,
         .fill = 0.3,
         .key = 0.85,
         .specular = 0.12,
         .floorShadow = 0.5,
         .lineShade = 1.0},
    Look{.name = "paper",
         .background = {244, 238, 224},
         .ambient = 0.35,
         .fill = 0.35,
         .key = 0.6,
         .specular = 0,
         .floorShadow = 0,
         .saturation = 0.55,
         .wash = 0.2,
         .lineShade = 0.25},
};

}  // namespace

std::vector<std::string_view> lookNames() {
  std::vector<std::string_view> names;
  for (const Look& look : kLooks) names.push_back(look.name);
  return names;
}

std::optional<Look> findLook(std::string_view name) {
  for (const Look& look : kLooks)
    if (look.name == name) return look;
  return std::nullopt;
}

std::string lookList() {
  std::string list;
  for (const Look& look : kLooks) list += (list.empty() ? "" : ", ") + std::string(look.name);
  return list;
}

}  // namespace ontogen
