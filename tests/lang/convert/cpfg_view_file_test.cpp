// The view file cpfg reads with an L-system, from the cpfg commands of a vlab object's
// `specifications` (lang/convert/cpfg_view_file.cpp).

#include "lang/convert/cpfg_view_file.h"

#include <gtest/gtest.h>

namespace ontogen::convert {
namespace {

TEST(CpfgViewFile, TheSecondFileOfTheCommandNamingTheLsystemFirst) {
  // As vlab's objects write it: a menu item, then the command on a line of its own.
  const std::string specifications =
      "lamp.l\nview.v\nignore:\n*\nmodel:\n\tgenerate:\n\t\tcpfg -a -M materials.mat lamp.l view.v anim.a\n"
      "L-system:\n\tEDIT lamp.l\n";
  EXPECT_EQ(viewFileInSpecifications(specifications, "lamp.l"), "view.v");
  EXPECT_EQ(viewFileInSpecifications(specifications, "other.l"), std::nullopt);
}

TEST(CpfgViewFile, OptionsAndTheirArgumentsAreSkipped) {
  // -w takes two numbers, -m2 and -e a file, -str a file to save, -g none.
  EXPECT_EQ(viewFileInSpecifications("cpfg -w 300 500 -m2 sedge.map2 -e a.e -g -str out.str male.l male.v\n", "male.l"),
            "male.v");
  EXPECT_EQ(viewFileInSpecifications("cpfg -wp 1 2 -wt title -mb -rmode expl p.l v.v\n", "p.l"), "v.v");
  // A file between the options is read as cpfg reads it: the first named is the L-system.
  EXPECT_EQ(viewFileInSpecifications("cpfg p.l -M p.mat p.v\n", "p.l"), "p.v");
}

TEST(CpfgViewFile, NoViewWhenNoCommandGivesOneOrTwoDisagree) {
  EXPECT_EQ(viewFileInSpecifications("cpfg plant.l\n", "plant.l"), std::nullopt);    // no second file
  EXPECT_EQ(viewFileInSpecifications("lpfg plant.l a.v\n", "plant.l"), std::nullopt); // not cpfg
  EXPECT_EQ(viewFileInSpecifications("cpfg plant.l a.v\ncpfg plant.l b.v\n", "plant.l"), std::nullopt);
  EXPECT_EQ(viewFileInSpecifications("cpfg plant.l a.v x.a\ncpfg -g plant.l a.v\n", "plant.l"), "a.v");
}

}  // namespace
}  // namespace ontogen::convert
