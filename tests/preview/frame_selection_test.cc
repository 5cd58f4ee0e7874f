#include "preview/frame_selection.h"

#include <set>

#include <gtest/gtest.h>

#include "core/error.h"

namespace cinepath::preview {
namespace {

TEST(FrameSelection, RangeIsInclusiveAndEveryStartsAtItsFirstFrame) {
  FrameSelection selection;
  selection.range = ParseFrameRange("3-11");
  selection.every = 4;
  EXPECT_EQ(SelectFrames(20, selection), (std::vector<size_t>{3, 7, 11}));
  selection.range = ParseFrameRange("5");
  selection.every = 1;
  EXPECT_EQ(SelectFrames(20, selection), (std::vector<size_t>{5}));
}

TEST(FrameSelection, ShardsAreDisjointAndMakeTheWhole) {
  FrameSelection whole;
  whole.every = 3;
  const std::vector<size_t> all = SelectFrames(100, whole);
  for (size_t count : {1u, 2u, 3u, 7u}) {
    std::set<size_t> seen;
    size_t total = 0;
    for (size_t i = 0; i < count; ++i) {
      FrameSelection shard = whole;
      shard.shard = ParseShard(std::to_string(i) + "/" + std::to_string(count));
      for (size_t k : SelectFrames(100, shard)) {
        seen.insert(k);
        ++total;
      }
    }
    EXPECT_EQ(total, all.size()) << count << " shards";
    EXPECT_EQ(std::vector<size_t>(seen.begin(), seen.end()), all) << count << " shards";
  }
}

TEST(FrameSelection, RefusesRangesOutsideThePlanAndMalformedFlags) {
  FrameSelection selection;
  selection.range = FrameRange{5, 20};
  EXPECT_THROW(SelectFrames(20, selection), InputError);
  EXPECT_THROW(ParseFrameRange("9-3"), InputError);
  EXPECT_THROW(ParseFrameRange("a-3"), InputError);
  EXPECT_THROW(ParseFrameRange("-3"), InputError);
  EXPECT_THROW(ParseShard("2/2"), InputError);
  EXPECT_THROW(ParseShard("0/0"), InputError);
  EXPECT_THROW(ParseShard("1"), InputError);
  EXPECT_THROW(SelectFrames(0, FrameSelection{}), InputError);
}

}  // namespace
}  // namespace cinepath::preview
