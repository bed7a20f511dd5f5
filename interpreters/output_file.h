#pragma once
// Writing an output file so that readers never see half of it: the content goes to a
// temporary file beside the target, which is renamed over the target only once it has
// been written and flushed without error.
//
// An output owns only the file it writes. A target that is a symbolic link is written
// through the link: the temporary goes beside the file the link points to and is renamed
// over that file, so the link stays a link. A target that exists and is not a regular
// file (a folder, FIFO, device or socket) is refused, never replaced.

#include <filesystem>
#include <functional>
#include <ostream>

#include "interpreters/interpretation_set.h"

namespace ontogen {

/// The file an output to `path` writes: `path`, or when it is a symbolic link the file it
/// points to (followed link by link; a relative link is read from the link's folder).
/// Throws OutputError naming `path` when that file exists and is not a regular file, or
/// the links loop or cannot be read.
std::filesystem::path outputTarget(const std::filesystem::path& path);

/// Calls write with a stream on a new temporary file beside outputTarget(path), flushes it
/// and renames it over that file, replacing an old regular file (whose permissions the new
/// one keeps) and refusing anything else. On any failure (cannot create, write
/// error, write throws, cannot rename) the temporary is removed and path is untouched;
/// failures of the file system throw OutputError naming path and the reason (strerror),
/// exceptions from write propagate as they are.
void writeFileAtomically(const std::filesystem::path& path,
                         const std::function<void(std::ostream&)>& write);

}  // namespace ontogen
