#include "core/text_tokens.h"

#include <gtest/gtest.h>

namespace cinepath {
namespace {

TEST(TextTokens, SplitsOnEveryKindOfSpace) {
  const std::vector<std::string_view> expected = {"IMG_1.JPG", "50.8", "-0.13", "12"};
  EXPECT_EQ(WhitespaceTokens("IMG_1.JPG 50.8\t-0.13 \v 12\r"), expected);
  EXPECT_EQ(WhitespaceTokens("  \tIMG_1.JPG\f50.8   -0.13 12"), expected);
}

TEST(TextTokens, EmptyAndBlankLinesHaveNoTokens) {
  EXPECT_TRUE(WhitespaceTokens("").empty());
  EXPECT_TRUE(WhitespaceTokens(" \t\r").empty());
}

TEST(TextTokens, TokensAreViewsIntoTheLine) {
  const std::string_view line = "ply format";
  const auto tokens = WhitespaceTokens(line);
  ASSERT_EQ(tokens.size(), 2u);
  EXPECT_EQ(tokens[1].data(), line.data() + 4);
  EXPECT_FALSE(IsTokenSpace('\n'));  // lines are split before tokens
  EXPECT_TRUE(IsTokenSpace('\v'));
  EXPECT_FALSE(IsTokenSpace('#'));
}

}  // namespace
}  // namespace cinepath
