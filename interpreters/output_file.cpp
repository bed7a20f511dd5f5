#include "interpreters/output_file.h"

#include "interpreters/temporary_files.h"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <string>
#include <system_error>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace ontogen {

namespace {

// Tries this many names before giving up: collisions need another writer racing for the
// same target, so a handful of names is plenty.
constexpr int kNameAttempts = 100;

// Links followed before giving up: the kernel's own limit (Linux's MAXSYMLINKS is 40).
constexpr int kMaxLinks = 40;

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what, int error) {
  std::string message = "cannot write '" + path.string() + "': " + what;
  if (error != 0) message += std::string(what.empty() ? "" : ": ") + std::strerror(error);
  throw OutputError(message);
}

/// What a file that is not a regular file is, for the message refusing it.
std::string kindOf(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

/// Creates a new, empty file beside target with a name no one else uses, with the
/// permissions a new file gets (0666 less the umask), and returns its path; failures
/// name path, the output asked for. The name is
/// registered before the file is made (temporary_files.h), so a signal removes it.
std::filesystem::path createTemporary(const std::filesystem::path& target, const std::filesystem::path& path,
                                      RegisteredTemporary& registered) {
  static std::atomic<unsigned> counter{0};
  std::filesystem::path directory = target.parent_path();
  for (int attempt = 0; attempt < kNameAttempts; ++attempt) {
    std::string name = "." + target.filename().string() + ".tmp" + std::to_string(::getpid()) +
                       "_" + std::to_string(counter++);
    std::filesystem::path temporary = directory / name;
    registered.hold(temporary);
    int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) {
      ::close(fd);
      return temporary;
    }
    registered.release();
    if (errno != EEXIST) fail(path, "", errno);
  }
  fail(path, "no free temporary name", EEXIST);
}

}  // namespace

std::filesystem::path outputTarget(const std::filesystem::path& path) {
  std::filesystem::path target = path;
  for (int links = 0;; ++links) {
    struct stat status {};
    if (::lstat(target.c_str(), &status) != 0) {
      if (errno == ENOENT) return target;  // a new file (a missing folder fails when it is made)
      fail(path, "", errno);
    }
    if (S_ISREG(status.st_mode)) return target;
    if (!S_ISLNK(status.st_mode)) {
      const std::string through = target == path ? "" : " (through its link, '" + target.string() + "')";
      fail(path, "it is " + kindOf(status.st_mode) + through + "; ontogen writes only regular files", 0);
    }
    if (links == kMaxLinks) fail(path, "", ELOOP);
    std::error_code error;
    const std::filesystem::path link = std::filesystem::read_symlink(target, error);
    if (error) fail(path, "cannot read the link: " + error.message(), 0);
    target = link.is_absolute() ? link : target.parent_path() / link;
  }
}

void writeFileAtomically(const std::filesystem::path& path,
                         const std::function<void(std::ostream&)>& write) {
  if (path.filename().empty()) fail(path, "not a file name", 0);
  const std::filesystem::path target = outputTarget(path);
  // Registered until it is renamed or removed, so that SIGINT and SIGTERM remove it too.
  RegisteredTemporary registered;
  const std::filesystem::path temporary = createTemporary(target, path, registered);
  auto discard = [&] {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
  };
  try {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) fail(path, "cannot open the temporary file", errno);
    errno = 0;  // so that a failure below reports the error of the failing write
    write(out);
    out.flush();
    if (!out) fail(path, "write error", errno);
    out.close();
    if (!out) fail(path, "write error on close", errno);
    // A file written again keeps its permissions (a private file stays private).
    struct stat old {};
    if (::stat(target.c_str(), &old) == 0 && S_ISREG(old.st_mode) && ::chmod(temporary.c_str(), old.st_mode & 07777) != 0)
      fail(path, "cannot keep the permissions", errno);
  } catch (...) {
    discard();
    throw;
  }
  std::error_code error;
  std::filesystem::rename(temporary, target, error);
  if (error) {
    discard();
    throw OutputError("cannot write '" + path.string() + "': " + error.message());
  }
}

}  // namespace ontogen
