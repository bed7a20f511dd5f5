#include "interpreters/geometry_set.h"

#include <string>

#include "interpreters/obj_writer.h"
#include "interpreters/output_file.h"
#include "interpreters/turtle_commands.h"

namespace ontogen {

GeometrySet::GeometrySet(const GeometrySetDef& def)
    : def_(def), turtle_(def.turtle), geometry_(def.mesh) {
  checkSvgOptions(def.svg);
}

bool GeometrySet::knows(std::string_view command) const {
  return findTurtleCommand(command) != nullptr;
}

void GeometrySet::beginFrame(const FrameTarget& target) {
  target_ = target;
  turtle_.reset();
  geometry_.clear();
}

void GeometrySet::execute(std::string_view command, std::span<const double> args) {
  turtle_.execute(command, args, geometry_);
}

std::filesystem::path GeometrySet::outputPath(const FrameTarget& target,
                                              std::string_view extension) {
  std::string name = target.stem.empty() ? std::string("geometry") : target.stem;
  if (target.frameCount > 1) {
    std::string number = std::to_string(target.frame);
    if (number.size() < 4) number.insert(0, 4 - number.size(), '0');
    name += "_" + number;
  }
  name += ".";
  name += extension;
  return target.directory / name;
}

std::vector<std::filesystem::path> GeometrySet::endFrame() {
  std::vector<std::filesystem::path> written;
  if (def_.writeSvg) {
    std::filesystem::path path = outputPath(target_, "svg");
    writeFileAtomically(path, [&](std::ostream& out) { writeSvg(geometry_, out, def_.svg); });
    written.push_back(std::move(path));
  }
  if (def_.writeObj) {
    std::filesystem::path path = outputPath(target_, "obj");
    writeFileAtomically(path, [&](std::ostream& out) { writeObj(geometry_, out); });
    written.push_back(std::move(path));
  }
  return written;
}

}  // namespace ontogen
