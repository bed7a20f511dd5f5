#include "tests/apps/ontogen_process.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <sstream>

extern char** environ;

namespace ontogen::test {

namespace fs = std::filesystem;

namespace {

std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<char*> argumentVector(std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);
  return argv;
}

// Runs `program` with `args` (args[0] its name), stdout and stderr into files of `dir`,
// and waits for it.
OntogenRun spawnAndWait(const char* program, std::vector<std::string> args, const fs::path& dir) {
  fs::create_directories(dir);
  std::vector<char*> argv = argumentVector(args);
  const fs::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&files, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  OntogenRun result;
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, program, &files, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&files);
  if (spawned != 0) return result;
  int status = 0;
  rusage usage{};
  if (wait4(pid, &status, 0, &usage) != pid) return result;
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = readFile(out);
  result.err = readFile(err);
  result.peakKib = static_cast<uint64_t>(usage.ru_maxrss);
  return result;
}

}  // namespace

OntogenRun runOntogen(const fs::path& dir, std::vector<std::string> args) {
  args.insert(args.begin(), ONTOGEN_EXECUTABLE);
  return spawnAndWait(ONTOGEN_EXECUTABLE, std::move(args), dir);
}

OntogenRun runOntogenShell(const std::string& args, const std::string& prefix, const fs::path& dir) {
  // One folder per process: ctest runs tests in parallel processes.
  const fs::path files =
      dir.empty() ? fs::path(ONTOGEN_BINARY_DIR) / "ontogen_process" / std::to_string(getpid()) : dir;
  return spawnAndWait("/bin/sh", {"sh", "-c", prefix + ONTOGEN_EXECUTABLE + " " + args}, files);
}

pid_t startOntogen(std::vector<std::string> args) {
  args.insert(args.begin(), ONTOGEN_EXECUTABLE);
  std::vector<char*> argv = argumentVector(args);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t defaults;
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGINT);
  sigaddset(&defaults, SIGTERM);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGDEF);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, ONTOGEN_EXECUTABLE, nullptr, &attributes, argv.data(), environ);
  posix_spawnattr_destroy(&attributes);
  return spawned == 0 ? pid : -1;
}

}  // namespace ontogen::test
