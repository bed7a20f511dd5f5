#pragma once
// Writing an output file so that readers never see half of it: the content goes to a
// temporary file beside the target, which is renamed over the target only once it has
// been written and flushed without error.

#include <filesystem>
#include <functional>
#include <ostream>

#include "interpreters/interpretation_set.h"

namespace ontogen {

/// Calls write with a stream on a new temporary file in path's directory, flushes it and
/// renames it to path, replacing any old file. On any failure (cannot create, write
/// error, write throws, cannot rename) the temporary is removed and path is untouched;
/// failures of the file system throw OutputError naming path and the reason (strerror),
/// exceptions from write propagate as they are.
void writeFileAtomically(const std::filesystem::path& path,
                         const std::function<void(std::ostream&)>& write);

}  // namespace ontogen
