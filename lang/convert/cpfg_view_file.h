#pragma once
// Which view file cpfg reads with an L-system file. cpfg takes it from its command line,
// `cpfg [options] plant.l view.v [anim.a]`: the second file named. The Virtual Laboratory
// keeps that command in the object's `specifications` file (`cpfg -M plant.mat plant.l
// view.v anim.a`), so the view file need not share the L-system's name. Without such a
// command the converter looks for the file of the L-system's name with `.v`.

#include <optional>
#include <string>
#include <string_view>

namespace ontogen::convert {

/// The view file that the `cpfg` commands of a `specifications` text give with the
/// L-system file `lsystemName` (a file name, no folder): the second file of each command
/// whose first file is `lsystemName`, cpfg's options and their arguments skipped. Nothing
/// when no command names it, or when commands name it with different view files.
std::optional<std::string> viewFileInSpecifications(std::string_view specifications, std::string_view lsystemName);

}  // namespace ontogen::convert
