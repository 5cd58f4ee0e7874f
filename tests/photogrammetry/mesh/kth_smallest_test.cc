#include "photogrammetry/mesh/kth_smallest.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace cinepath::photogrammetry {
namespace {

float ByNthElement(const std::vector<std::vector<float>>& lists, size_t k) {
  std::vector<float> joined;
  for (const auto& list : lists) joined.insert(joined.end(), list.begin(), list.end());
  std::nth_element(joined.begin(), joined.begin() + static_cast<std::ptrdiff_t>(k), joined.end());
  return joined[k];
}

// Lists of every size (empty ones among them) holding zeros, repeats, tiny and huge values and
// infinity: every k gives std::nth_element's value, bit for bit.
TEST(KthSmallest, MatchesNthElementOnTheJoinedLists) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<std::vector<float>> lists(1 + rng() % 9);
    size_t total = 0;
    for (auto& list : lists) {
      list.resize(rng() % 300);
      for (float& v : list) {
        switch (rng() % 6) {
          case 0: v = 0.0f; break;
          case 1: v = static_cast<float>(rng() % 4); break;  // repeats
          case 2: v = std::ldexp(unit(rng), -120); break;    // subnormal and tiny
          case 3: v = std::ldexp(unit(rng), 100); break;
          case 4: v = INFINITY; break;
          default: v = unit(rng);
        }
      }
      total += list.size();
    }
    for (size_t k = 0; k < total; k += 1 + total / 40) {
      const float expected = ByNthElement(lists, k), got = KthSmallest(lists, k);
      EXPECT_EQ(std::memcmp(&expected, &got, sizeof got), 0)
          << trial << " k " << k << ": " << got << " vs " << expected;
    }
    if (total > 0) EXPECT_EQ(KthSmallest(lists, total - 1), ByNthElement(lists, total - 1));
  }
}

// Values that share their upper bits and differ only in the last round's ten.
TEST(KthSmallest, SeparatesValuesOneUlpApart) {
  std::vector<std::vector<float>> lists(2);
  float v = 1.0f;
  for (int i = 0; i < 50; ++i) {
    lists[i % 2].push_back(v);
    v = std::nextafter(v, 2.0f);
  }
  std::reverse(lists[0].begin(), lists[0].end());
  for (size_t k = 0; k < 50; ++k) EXPECT_EQ(KthSmallest(lists, k), ByNthElement(lists, k)) << k;
  EXPECT_EQ(KthSmallest(lists, 0), 1.0f);
}

}  // namespace
}  // namespace cinepath::photogrammetry
