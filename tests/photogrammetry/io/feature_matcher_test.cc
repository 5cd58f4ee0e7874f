#include "photogrammetry/io/feature_matcher.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "tests/support/command_line.h"
#include "tests/support/input_error.h"

namespace cinepath::photogrammetry {
namespace {

namespace fs = std::filesystem;
constexpr int kDims = kSiftDescriptorBytes;
using Descriptor = std::vector<double>;  // unit length

// A random unit descriptor with non-negative, uneven entries (as SIFT's are): random ones are far
// apart (most pairs more than 0.7 rad).
Descriptor RandomDescriptor(std::mt19937* rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Descriptor d(kDims);
  for (double& v : d) v = std::pow(u(*rng), 6.0);
  const double norm = std::sqrt(std::inner_product(d.begin(), d.end(), d.begin(), 0.0));
  for (double& v : d) v /= norm;
  return d;
}

// `d` moved towards a random direction: the angle between them grows with `amount`.
Descriptor Perturbed(const Descriptor& d, double amount, std::mt19937* rng) {
  const Descriptor w = RandomDescriptor(rng);
  Descriptor out(kDims);
  for (int k = 0; k < kDims; ++k) out[k] = d[k] + amount * w[k];
  const double norm = std::sqrt(std::inner_product(out.begin(), out.end(), out.begin(), 0.0));
  for (double& v : out) v /= norm;
  return out;
}

// As COLMAP stores them: 512 × the unit vector, rounded, at most 255.
std::vector<std::uint8_t> Bytes(const std::vector<Descriptor>& ds) {
  std::vector<std::uint8_t> out;
  for (const Descriptor& d : ds) {
    for (double v : d) out.push_back(static_cast<std::uint8_t>(std::min(255.0, std::round(512.0 * v))));
  }
  return out;
}

double AngleOfBytes(const std::vector<std::uint8_t>& a, size_t i, const std::vector<std::uint8_t>& b, size_t j) {
  long dot = 0;
  for (int k = 0; k < kDims; ++k) dot += a[i * kDims + k] * b[j * kDims + k];
  return std::acos(std::min(1.0, dot / (512.0 * 512.0)));
}

// The rules written the plain way: every distance, nearest and second nearest, both ways.
std::vector<FeatureMatch> NaiveMatches(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b,
                                       const FeatureMatchOptions& options) {
  const size_t na = a.size() / kDims, nb = b.size() / kDims;
  auto nearest = [&](const std::vector<std::uint8_t>& x, size_t i, const std::vector<std::uint8_t>& y, size_t ny) {
    double best = M_PI, second = M_PI;
    long index = -1;
    for (size_t j = 0; j < ny; ++j) {
      const double angle = AngleOfBytes(x, i, y, j);
      if (angle < best)
        second = best, best = angle, index = static_cast<long>(j);
      else if (angle < second)
        second = angle;
    }
    if (index < 0 || best > options.max_distance || best >= options.max_ratio * std::min(second, M_PI / 2)) return -1L;
    return index;
  };
  std::vector<FeatureMatch> out;
  for (size_t i = 0; i < na; ++i) {
    const long j = nearest(a, i, b, nb);
    if (j < 0) continue;
    if (options.cross_check && nearest(b, static_cast<size_t>(j), a, na) != static_cast<long>(i)) continue;
    out.push_back({static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j)});
  }
  return out;
}

TEST(FeatureMatcher, FindsTheKnownNearestNeighbours) {
  std::mt19937 rng(1);
  std::vector<Descriptor> first, second;
  for (int i = 0; i < 40; ++i) first.push_back(RandomDescriptor(&rng));
  // The second set: the first one's descriptors, slightly moved, in another order, among 60 others.
  std::vector<int> order(40);
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), rng);
  for (int i = 0; i < 60; ++i) second.push_back(RandomDescriptor(&rng));
  for (int i = 0; i < 40; ++i) second.insert(second.begin() + 2 * i, Perturbed(first[order[i]], 0.05, &rng));
  const std::vector<FeatureMatch> matches = MatchSiftDescriptors(Bytes(first), Bytes(second), FeatureMatchOptions());
  ASSERT_EQ(matches.size(), 40u);
  for (int i = 0; i < 40; ++i) {
    const auto at = std::find(order.begin(), order.end(), static_cast<int>(matches[i].index1));
    EXPECT_EQ(matches[i].index1, static_cast<std::uint32_t>(i));  // by ascending index1
    EXPECT_EQ(matches[i].index2, static_cast<std::uint32_t>(2 * (at - order.begin())));
  }
}

TEST(FeatureMatcher, TheRatioTestRejectsAmbiguousNeighbours) {
  std::mt19937 rng(2);
  const Descriptor x = RandomDescriptor(&rng);
  // Two candidates about as near as each other: no match at 0.8, the nearer one when the ratio is 1.
  const std::vector<std::uint8_t> first = Bytes({x});
  const std::vector<std::uint8_t> second = Bytes({Perturbed(x, 0.2, &rng), Perturbed(x, 0.2, &rng)});
  const double a0 = AngleOfBytes(first, 0, second, 0), a1 = AngleOfBytes(first, 0, second, 1);
  ASSERT_GT(std::min(a0, a1), 0.8 * std::max(a0, a1)) << a0 << " " << a1;
  FeatureMatchOptions options;
  options.cross_check = false;
  EXPECT_TRUE(MatchSiftDescriptors(first, second, options).empty());
  options.max_ratio = 1.0;
  const std::vector<FeatureMatch> matches = MatchSiftDescriptors(first, second, options);
  ASSERT_EQ(matches.size(), 1u);
  EXPECT_EQ(matches[0].index2, a0 < a1 ? 0u : 1u);
}

TEST(FeatureMatcher, TheMaximumDistanceRejectsFarNeighbours) {
  std::mt19937 rng(3);
  const Descriptor x = RandomDescriptor(&rng);
  const std::vector<std::uint8_t> first = Bytes({x});
  const std::vector<std::uint8_t> second = Bytes({Perturbed(x, 1.5, &rng)});
  const double angle = AngleOfBytes(first, 0, second, 0);
  ASSERT_GT(angle, 0.7);
  EXPECT_TRUE(MatchSiftDescriptors(first, second, FeatureMatchOptions()).empty());
  FeatureMatchOptions options;
  options.max_distance = angle + 0.01;
  EXPECT_EQ(MatchSiftDescriptors(first, second, options).size(), 1u);
}

TEST(FeatureMatcher, CrossCheckKeepsOnlyMutualNearestNeighbours) {
  std::mt19937 rng(4);
  const Descriptor x = RandomDescriptor(&rng);
  // x and a moved copy of it both find x as their nearest; x's nearest is x, not the copy.
  const std::vector<std::uint8_t> first = Bytes({x, Perturbed(x, 0.25, &rng)});
  const std::vector<std::uint8_t> second = Bytes({x, RandomDescriptor(&rng), RandomDescriptor(&rng)});
  FeatureMatchOptions options;
  options.cross_check = false;
  EXPECT_EQ(MatchSiftDescriptors(first, second, options), (std::vector<FeatureMatch>{{0, 0}, {1, 0}}));
  options.cross_check = true;
  EXPECT_EQ(MatchSiftDescriptors(first, second, options), (std::vector<FeatureMatch>{{0, 0}}));
}

// Sizes that are not whole blocks (4 rows, 16 columns) nor whole tiles (256 columns), with matches
// and near misses: the blocked kernels (AVX or portable) give what the plain rules give.
TEST(FeatureMatcher, TheBlockedKernelsGiveWhatThePlainRulesGive) {
  std::mt19937 rng(5);
  std::vector<Descriptor> first, second;
  for (int i = 0; i < 301; ++i) first.push_back(RandomDescriptor(&rng));
  for (int i = 0; i < 517; ++i) {
    second.push_back(i % 2 == 0 ? Perturbed(first[(i * 7) % 301], 0.1 + 0.002 * (i % 200), &rng)
                                : RandomDescriptor(&rng));
  }
  const std::vector<std::uint8_t> a = Bytes(first), b = Bytes(second);
  for (bool cross_check : {true, false}) {
    FeatureMatchOptions options;
    options.cross_check = cross_check;
    const std::vector<FeatureMatch> expected = NaiveMatches(a, b, options);
    EXPECT_GT(expected.size(), 30u);
    EXPECT_EQ(MatchSiftDescriptors(a, b, options), expected);
    options.use_avx = false;
    EXPECT_EQ(MatchSiftDescriptors(a, b, options), expected);
    EXPECT_EQ(MatchSiftDescriptors(b, a, options), NaiveMatches(b, a, options));
  }
}

TEST(FeatureMatcher, EmptySetsHaveNoMatches) {
  std::mt19937 rng(6);
  const std::vector<std::uint8_t> some = Bytes({RandomDescriptor(&rng)});
  EXPECT_TRUE(MatchSiftDescriptors({}, some, FeatureMatchOptions()).empty());
  EXPECT_TRUE(MatchSiftDescriptors(some, {}, FeatureMatchOptions()).empty());
}

std::vector<ColmapImageFeatures> FourImages() {
  std::mt19937 rng(7);
  std::vector<Descriptor> scene;
  for (int i = 0; i < 200; ++i) scene.push_back(RandomDescriptor(&rng));
  std::vector<ColmapImageFeatures> images;
  for (int image = 0; image < 4; ++image) {
    std::vector<Descriptor> seen;
    for (int i = image * 30; i < image * 30 + 100; ++i) seen.push_back(Perturbed(scene[i], 0.08, &rng));
    ColmapImageFeatures f;
    f.image_id = static_cast<std::uint32_t>(image + 1);
    f.name = "img" + std::to_string(image) + ".jpg";
    f.descriptors = Bytes(seen);
    images.push_back(f);
  }
  return images;
}

TEST(FeatureMatcher, EveryPairInAFixedOrderAndTheSameAtAnyThreadCount) {
  const std::vector<ColmapImageFeatures> images = FourImages();
  FeatureMatchOptions options;
  options.num_threads = 1;
  const std::vector<ImagePairMatches> one = MatchAllPairs(images, options);
  ASSERT_EQ(one.size(), 6u);
  const std::vector<std::pair<size_t, size_t>> order = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  for (size_t p = 0; p < one.size(); ++p) {
    EXPECT_EQ(std::make_pair(one[p].image1, one[p].image2), order[p]);
    EXPECT_EQ(one[p].matches,
              MatchSiftDescriptors(images[order[p].first].descriptors, images[order[p].second].descriptors, options));
  }
  // Images i and j share 100 - 30 (j - i) scene descriptors.
  EXPECT_EQ(one[0].matches.size(), 70u);
  EXPECT_EQ(one[2].matches.size(), 10u);
  for (int threads : {2, 3, 0}) {
    options.num_threads = threads;
    const std::vector<ImagePairMatches> many = MatchAllPairs(images, options);
    ASSERT_EQ(many.size(), one.size());
    for (size_t p = 0; p < one.size(); ++p) EXPECT_EQ(many[p].matches, one[p].matches) << threads << " threads";
  }
}

TEST(FeatureMatcher, BorderKeypointsAreBlankedAndNeverMatched) {
  std::mt19937 rng(8);
  std::vector<Descriptor> seen;
  for (int i = 0; i < 5; ++i) seen.push_back(RandomDescriptor(&rng));
  ColmapImageFeatures image;
  image.width_px = 800;
  image.height_px = 450;
  image.keypoint_columns = 6;
  // (x, y, scale): inside; on the last row; 7 px from the bottom at scale 3.7 (margin 7.9 px); the
  // same 7 px from the bottom at scale 1 (margin 2.5 px); past the left edge.
  const double keypoints[5][3] = {{400, 200, 2}, {300, 449.8, 1}, {789, 443, 3.7}, {789, 443, 1}, {0.3, 100, 1}};
  for (const auto& k : keypoints) {
    for (double v : {k[0], k[1], k[2], 0.0, 0.0, k[2]}) image.keypoints.push_back(static_cast<float>(v));
  }
  image.descriptors = Bytes(seen);
  ColmapImageFeatures copy = image;
  std::vector<ColmapImageFeatures> images = {image, copy};
  EXPECT_EQ(BlankBorderDescriptors(&images), 6u);
  for (int i = 0; i < 5; ++i) {
    const bool kept = i == 0 || i == 3;
    const auto begin = images[0].descriptors.begin() + i * kDims;
    EXPECT_EQ(std::count(begin, begin + kDims, 0) == kDims, !kept) << i;
  }
  EXPECT_EQ(MatchSiftDescriptors(images[0].descriptors, images[1].descriptors, FeatureMatchOptions()),
            (std::vector<FeatureMatch>{{0, 0}, {3, 3}}));
}

TEST(FeatureMatcher, WritesCOLMAPsRawMatchList) {
  std::vector<ColmapImageFeatures> images(3);
  images[0].name = "a.jpg";
  images[1].name = "sub/b.jpg";
  images[2].name = "c.jpg";
  const std::vector<ImagePairMatches> pairs = {{0, 1, {{3, 4}, {5, 1}}}, {0, 2, {}}, {1, 2, {{0, 0}}}};
  const fs::path dir = cinepath::testing::MakeTempDir("cinepath_raw_matches");
  ASSERT_FALSE(dir.empty());
  WriteColmapRawMatches(dir / "matches.txt", images, pairs);
  EXPECT_EQ(cinepath::testing::ReadText(dir / "matches.txt"),
            "a.jpg sub/b.jpg\n3 4\n5 1\n\na.jpg c.jpg\n\nsub/b.jpg c.jpg\n0 0\n\n");
  EXPECT_FALSE(fs::exists(dir / "matches.txt.tmp"));
  images[2].name = "c d.jpg";
  const std::string message =
      cinepath::testing::InputErrorMessage([&] { WriteColmapRawMatches(dir / "matches.txt", images, pairs); });
  EXPECT_NE(message.find("c d.jpg: an image name with white space"), std::string::npos) << message;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace cinepath::photogrammetry
