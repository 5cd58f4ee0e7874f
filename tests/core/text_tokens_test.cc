#include "core/text_tokens.h"

#include <string>
#include <utility>

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

TEST(TextTokens, DataLinesSkipBlanksAndCommentsAndKeepTheirNumbers) {
  std::vector<std::pair<size_t, std::string>> seen;
  auto collect = [&](std::string_view line, size_t number, const std::vector<std::string_view>& tokens) {
    seen.emplace_back(number, std::string(line) + "|" + std::to_string(tokens.size()));
  };
  ForEachDataLine("# header\na 1\n\n  \t\n  # indented comment\nb 2 3\r\nlast", collect);
  const std::vector<std::pair<size_t, std::string>> expected = {{2, "a 1|2"}, {6, "b 2 3\r|3"}, {7, "last|1"}};
  EXPECT_EQ(seen, expected);
  seen.clear();
  ForEachDataLine("x\n", collect);  // a final newline adds no line
  ForEachDataLine("", collect);
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0].first, 1u);
}

}  // namespace
}  // namespace cinepath
