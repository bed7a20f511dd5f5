#include "model/program.h"

namespace ontogen {

int Program::findMaster(std::string_view label, int scope) const {
  int global = -1;
  for (size_t i = 0; i < masters.size(); ++i) {
    if (masters[i].label != label) continue;
    if (masters[i].scope == scope) return static_cast<int>(i);
    if (masters[i].scope == -1) global = static_cast<int>(i);
  }
  return global;
}

}  // namespace ontogen
