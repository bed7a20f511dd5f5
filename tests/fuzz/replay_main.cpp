// A plain driver for a fuzz target, for builds without libFuzzer: runs the target on
// every file given, or on every file below the folders given, once each, and says how
// many it ran. A crash fails the test that runs it; so the ordinary tests replay the
// regression corpus (tests/fuzz/regressions/) and the seeds on every run.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace {

void runFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::filesystem::path> files;
  for (int i = 1; i < argc; ++i) {
    const std::filesystem::path path = argv[i];
    if (std::filesystem::is_directory(path)) {
      for (const auto& entry : std::filesystem::recursive_directory_iterator(path))
        if (entry.is_regular_file()) files.push_back(entry.path());
    } else if (std::filesystem::is_regular_file(path)) {
      files.push_back(path);
    } else {
      std::cerr << "replay: no such file or folder: " << path << "\n";
      return 1;
    }
  }
  std::sort(files.begin(), files.end());  // the same order on every run
  for (const auto& file : files) runFile(file);
  std::cout << "replay: ran " << files.size() << " inputs\n";
  return 0;
}
