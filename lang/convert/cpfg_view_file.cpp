#include "lang/convert/cpfg_view_file.h"

#include <array>
#include <vector>

#include "lang/convert/line_reader.h"

namespace ontogen::convert {

namespace {

std::vector<std::string_view> wordsOf(std::string_view text) {
  std::vector<std::string_view> words;
  size_t at = 0;
  while (at < text.size()) {
    while (at < text.size() && (text[at] == ' ' || text[at] == '\t')) ++at;
    size_t stop = at;
    while (stop < text.size() && text[stop] != ' ' && text[stop] != '\t') ++stop;
    if (stop > at) words.push_back(text.substr(at, stop - at));
    at = stop;
  }
  return words;
}

// How many words after it cpfg's option `option` takes (its command-line reader).
int argumentsOf(std::string_view option) {
  // An image or string to save: `-rgb file`, `-str file`, ...
  static constexpr std::array<std::string_view, 17> kSaved = {"-rgb", "-png", "-bmp", "-gif", "-jpg", "-pbm",
                                                              "-tiff", "-ras", "-tga", "-rle", "-ray", "-ps",
                                                              "-str", "-vv", "-strb", "-gls", "-obj"};
  for (std::string_view saved : kSaved)
    if (option == saved) return 1;
  if (option.size() < 2) return 0;
  switch (option[1]) {
    case 'b':  // -b file (batch)
    case 'C':  // -C setup
    case 'S':  // -S socket
    case 'e':  // -e environment
    case 'M':  // -M[N] materials
    case 'P':  // -P preprocessor
      return 1;
    case 'm':  // -m[N] colour map; -mb (a menu bar) takes none
      return option == "-mb" ? 0 : 1;
    case 'r':
      return option == "-rmode" ? 1 : 0;
    case 'w':  // -wt title; -wnb; -wr, -wpr, -wp x y; -w x y (the window's size)
      if (option == "-wt") return 1;
      if (option == "-wnb" || option == "-wnm") return 0;
      return 2;
    default:
      return 0;
  }
}

}  // namespace

std::optional<std::string> viewFileInSpecifications(std::string_view specifications, std::string_view lsystemName) {
  std::optional<std::string> found;
  for (const Line& line : splitLines(specifications)) {
    const std::vector<std::string_view> words = wordsOf(specifications.substr(line.begin, line.end - line.begin));
    if (words.empty() || words[0] != "cpfg") continue;
    std::vector<std::string_view> files;
    for (size_t i = 1; i < words.size(); ++i) {
      if (words[i][0] == '-')
        i += static_cast<size_t>(argumentsOf(words[i]));
      else
        files.push_back(words[i]);
    }
    if (files.size() < 2 || files[0] != lsystemName) continue;
    if (found && *found != files[1]) return std::nullopt;  // two commands, two views
    found = std::string(files[1]);
  }
  return found;
}

}  // namespace ontogen::convert
