// SIFT descriptor matching of our own, for `cinepath mesh --images`: brute force over every pair of
// images, the same rules as COLMAP's GPU matcher (descriptors as unit vectors, the distance is the
// angle between them; ratio test, maximum distance, cross-check), and the same result at any thread
// count. COLMAP's own CPU matcher (FLANN's randomized kd-trees) gives different matches every run;
// these matches go to `colmap matches_importer --match_type raw`, which verifies them geometrically.
//
// The dot products are exact integer sums of the 8-bit descriptors (COLMAP scales unit descriptors
// to 512), held in floats (exact below 2^24) and computed in blocks, with AVX+FMA where the processor
// has them (chosen at run time); the order of the output is fixed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "photogrammetry/io/colmap_database.h"

namespace cinepath::photogrammetry {

struct FeatureMatchOptions {
  double max_ratio = 0.8;     // best distance / second best distance must be below this
  double max_distance = 0.7;  // radians between the two unit descriptors
  bool cross_check = true;    // keep a match only when each descriptor is the other's nearest
  int num_threads = 0;        // image pairs matched at once; 0: every core
  bool use_avx = true;        // AVX+FMA where the processor has them; false: portable loops (same matches)
};

struct FeatureMatch {
  std::uint32_t index1 = 0;  // row in the first image's descriptors
  std::uint32_t index2 = 0;  // row in the second image's descriptors
  bool operator==(const FeatureMatch& o) const { return index1 == o.index1 && index2 == o.index2; }
};

// Matches between two sets of SIFT descriptors (rows of kSiftDescriptorBytes bytes), by ascending
// index1.
std::vector<FeatureMatch> MatchSiftDescriptors(const std::vector<std::uint8_t>& descriptors1,
                                               const std::vector<std::uint8_t>& descriptors2,
                                               const FeatureMatchOptions& options);

struct ImagePairMatches {
  std::size_t image1 = 0;  // indices into the features given, image1 < image2
  std::size_t image2 = 0;
  std::vector<FeatureMatch> matches;
};

// COLMAP 3.8's CPU extractor (VLFeat) computes the descriptor of a keypoint that lies past the last
// pixel row or column of its octave's image (the coarser octaves of an image whose size is not a
// multiple of their step lose up to 2^octave - 1 px at the bottom and right) from memory outside the
// image: its bytes change from run to run, even on one thread (brighton9: 1-2 of ~5,000 keypoints in
// 5 of 9 photos, all within 0.5 + 2 scale of the border). Blanks (zeroes) the descriptor of every
// keypoint within 0.5 + 2 max(1, scale) px of its image's border, so that it is never matched and no
// other match depends on it. Returns how many were blanked (~1 % on brighton9).
std::size_t BlankBorderDescriptors(std::vector<ColmapImageFeatures>* images);

// Every pair of images (exhaustive), in the order (0,1), (0,2), … (1,2), …; pairs with no match are kept.
std::vector<ImagePairMatches> MatchAllPairs(const std::vector<ColmapImageFeatures>& images,
                                            const FeatureMatchOptions& options);

// Writes the matches in the text format of `colmap matches_importer --match_type raw`: per pair a
// line with the two image names, one line "index1 index2" per match, then an empty line. Atomic
// (a temporary file renamed). RuntimeError when it cannot be written.
void WriteColmapRawMatches(const std::filesystem::path& path, const std::vector<ColmapImageFeatures>& images,
                           const std::vector<ImagePairMatches>& pairs);

}  // namespace cinepath::photogrammetry
