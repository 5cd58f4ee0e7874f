#include "shots/shot_type.h"

#include <gtest/gtest.h>

namespace cinepath::shots {
namespace {

TEST(ShotType, NamesAndAliasesRoundTrip) {
  EXPECT_EQ(ShotTypeNames().size(), 11u);
  for (auto name : ShotTypeNames()) EXPECT_EQ(ShotTypeName(*ShotTypeFromName(name)), name);
  EXPECT_EQ(ShotTypeFromName("TRACK"), ShotType::kDolly);
  EXPECT_EQ(ShotTypeFromName("REVEAL"), ShotType::kCrane);
  EXPECT_EQ(ShotTypeFromName("FREE"), ShotType::kKeyframes);
  EXPECT_FALSE(ShotTypeFromName("orbit").has_value());  // names are upper case
}

}  // namespace
}  // namespace cinepath::shots
