#pragma once
// The ontogen executable run from a test as a user runs it: its exit code, what it wrote
// to stdout and stderr, and its peak resident size. The command-line tests share these
// rather than each spawning it its own way.

#include <sys/types.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace ontogen::test {

/// How a run of ontogen ended.
struct OntogenRun {
  int exitCode = -1;  ///< -1: ended by a signal, or could not start
  std::string out;
  std::string err;
  uint64_t peakKib = 0;  ///< the process's peak resident size (ru_maxrss), KiB
};

/// Runs ontogen with `args` (no shell: each is one argument), its stdout and stderr
/// written to stdout.txt and stderr.txt in `dir` and read back.
OntogenRun runOntogen(const std::filesystem::path& dir, std::vector<std::string> args);

/// Runs `PREFIX ontogen ARGS` through /bin/sh, so ARGS may quote and redirect and PREFIX
/// may be a `ulimit -v N; ` or a `timeout 60 `. Its stdout and stderr go to files in
/// `dir`, or, with no `dir`, in a folder of this test process under the build tree.
OntogenRun runOntogenShell(const std::string& args, const std::string& prefix = "",
                           const std::filesystem::path& dir = {});

/// Starts ontogen with `args` (no shell) and returns its process id, for a test that
/// signals it: SIGINT and SIGTERM have their default actions in it whatever this process
/// inherited (a background job ignores SIGINT). Its output goes where this process's
/// goes. -1 when it could not start.
pid_t startOntogen(std::vector<std::string> args);

}  // namespace ontogen::test
