// Names in messages (scene/NameList.h): a few shown, the rest counted with grouped digits.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "rill/rt/scene/NameList.h"

namespace rt {
namespace {

TEST(NameList, AFewNamesThenHowManyMore) {
  EXPECT_EQ(name_list({}), "");
  EXPECT_EQ(name_list({"a"}), "a");
  EXPECT_EQ(name_list({"a", "b", "c", "d", "e"}), "a, b, c, d, e");
  EXPECT_EQ(name_list({"a", "b", "c", "d", "e", "f"}), "a, b, c, d, e and 1 more");
  std::vector<std::string> many(20000, "n");
  EXPECT_EQ(name_list(many), "n, n, n, n, n and 19,995 more");
  EXPECT_EQ(name_list({"a", "b", "c"}, 2), "a, b and 1 more");
  // Each name is clipped like any user string in a message (Scene.h: clipped).
  EXPECT_EQ(name_list({std::string(100, 'x'), "tab\there"}),
            std::string(80, 'x') + "... (100 bytes), tab\\x09here");
}

TEST(NameList, CountsGroupTheirThousands) {
  EXPECT_EQ(grouped(0), "0");
  EXPECT_EQ(grouped(999), "999");
  EXPECT_EQ(grouped(1000), "1,000");
  EXPECT_EQ(grouped(19995), "19,995");
  EXPECT_EQ(grouped(1234567), "1,234,567");
}

}  // namespace
}  // namespace rt
