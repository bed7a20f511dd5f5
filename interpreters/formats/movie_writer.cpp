#include "interpreters/formats/movie_writer.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "interpreters/formats/png_writer.h"
#include "interpreters/interpretation_set.h"
#include "interpreters/output_file.h"

extern char** environ;

namespace ontogen {

bool ffmpegAvailable() {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return false;
  std::string_view rest(path);
  while (!rest.empty()) {
    std::size_t colon = rest.find(':');
    std::filesystem::path candidate = std::filesystem::path(rest.substr(0, colon)) / "ffmpeg";
    if (::access(candidate.c_str(), X_OK) == 0) return true;
    if (colon == std::string_view::npos) break;
    rest.remove_prefix(colon + 1);
  }
  return false;
}

MovieWriter::MovieWriter(std::filesystem::path path, double framesPerSecond)
    : path_(std::move(path)), framesPerSecond_(framesPerSecond) {
  folder_ = path_.parent_path() / ("." + path_.stem().string() + ".mp4-frames");
}

MovieWriter::~MovieWriter() {
  if (registered_) {
    std::error_code ignored;
    std::filesystem::remove_all(folder_, ignored);
  }
}

void MovieWriter::addFrame(const Image& image) {
  if (!registered_) {
    registered_ = std::make_unique<RegisteredTemporary>(folder_, RegisteredTemporary::Kind::Folder);
    std::error_code error;
    std::filesystem::create_directories(folder_, error);
    if (error) throw OutputError("cannot create " + folder_.string() + ": " + error.message());
  }
  std::string number = std::to_string(frames_++);
  number.insert(0, number.size() < 6 ? 6 - number.size() : 0, '0');
  writeFileAtomically(folder_ / ("frame_" + number + ".png"), [&](std::ostream& out) { writePng(image, out); });
}

void MovieWriter::finish() {
  // Written through a link, refusing what is not a regular file, as every output is.
  const std::filesystem::path target = outputTarget(path_);
  const std::filesystem::path temporary = target.string() + ".partial.mp4";
  const std::string rate = std::to_string(framesPerSecond_);
  const std::string input = (folder_ / "frame_%06d.png").string();
  const std::string output = temporary.string();
  // Even sizes: H.264 in yuv420p needs them.
  std::vector<std::string> args = {"ffmpeg", "-y", "-loglevel", "error", "-framerate", rate, "-i", input,
                                   "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264", "-pix_fmt", "yuv420p",
                                   "-f", "mp4", output};
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);
  const RegisteredTemporary registered(temporary);  // removed on SIGINT and SIGTERM too
  pid_t pid = 0;
  int status = 0;
  const bool ok = frames_ > 0 && ::posix_spawnp(&pid, "ffmpeg", nullptr, nullptr, argv.data(), environ) == 0 &&
                  ::waitpid(pid, &status, 0) == pid && WIFEXITED(status) && WEXITSTATUS(status) == 0;
  std::error_code ignored;
  std::filesystem::remove_all(folder_, ignored);
  registered_.reset();
  frames_ = 0;
  if (!ok) {
    std::filesystem::remove(temporary, ignored);
    throw OutputError("ffmpeg could not make " + path_.string());
  }
  std::error_code error;
  std::filesystem::rename(temporary, target, error);
  if (error) throw OutputError("cannot rename " + temporary.string() + " to " + path_.string() + ": " + error.message());
}

}  // namespace ontogen
