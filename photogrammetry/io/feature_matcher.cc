#include "photogrammetry/io/feature_matcher.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <fstream>
#include <string>
#include <thread>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

#include "core/error.h"

namespace cinepath::photogrammetry {
namespace {

namespace fs = std::filesystem;

constexpr int kDims = kSiftDescriptorBytes;
// COLMAP stores a unit descriptor scaled by 512 and rounded: the dot product of two is 512² cos(angle).
constexpr double kDotToCosine = 1.0 / (512.0 * 512.0);
constexpr std::size_t kTileRows = 256;  // rows of the second set per tile: 128 KB of floats

// The nearest and second nearest of one descriptor so far, as dot products (larger is nearer).
// Dot products are integers below 2^24, exact in a float whatever the order of the sums.
struct Nearest {
  float best = 0;
  float second = 0;
  std::int32_t index = -1;
  void Add(float dot, std::int32_t j) {
    if (dot > best) {
      second = best;
      best = dot;
      index = j;
    } else if (dot > second) {
      second = dot;
    }
  }
};

constexpr float kNever = 3.0e38f;       // a second nearest no dot product exceeds (rows past the end)
constexpr std::size_t kBlockRows = 4;   // rows of the first set per block of dot products
constexpr std::size_t kBlockCols = 16;  // rows of the second set per block

// The descriptors as the kernels read them: the first set as rows (padded with zero rows to whole
// blocks), the second as panels of kBlockCols descriptors stored dimension by dimension
// (panel[k * kBlockCols + c]), padded with zero descriptors. Zero rows have dot 0: never nearest.
struct Rows {
  std::size_t count = 0;
  std::vector<float> values;
};

Rows FirstSet(const std::vector<std::uint8_t>& d) {
  Rows rows{d.size() / kDims, {}};
  rows.values.assign(d.begin(), d.end());
  rows.values.resize((rows.count + kBlockRows - 1) / kBlockRows * kBlockRows * kDims, 0.0f);
  return rows;
}

Rows SecondSet(const std::vector<std::uint8_t>& d) {
  Rows rows{d.size() / kDims, {}};
  const std::size_t panels = (rows.count + kBlockCols - 1) / kBlockCols;
  rows.values.assign(panels * kBlockCols * kDims, 0.0f);
  for (std::size_t j = 0; j < rows.count; ++j) {
    float* panel = rows.values.data() + (j / kBlockCols) * kBlockCols * kDims;
    for (int k = 0; k < kDims; ++k) panel[k * kBlockCols + j % kBlockCols] = d[j * kDims + k];
  }
  return rows;
}

// dots[r * kBlockCols + c] = a_r · b_c for a block of four rows and one panel.
void DotsPortable(const float* a, const float* panel, float* dots) {
  for (std::size_t i = 0; i < kBlockRows * kBlockCols; ++i) dots[i] = 0.0f;
  for (int k = 0; k < kDims; ++k) {
    for (std::size_t r = 0; r < kBlockRows; ++r) {
      const float ar = a[r * kDims + k];
      for (std::size_t c = 0; c < kBlockCols; ++c) dots[r * kBlockCols + c] += ar * panel[k * kBlockCols + c];
    }
  }
}

// Which rows and columns of a block have a dot product above their second nearest so far: only those
// can change (Nearest::Add), and most blocks change none. Bit r of row_mask, bit c of col_mask.
void FlagsPortable(const float* dots, const float* row_second, const float* col_second, unsigned* row_mask,
                   unsigned* col_mask) {
  *row_mask = 0;
  *col_mask = 0;
  for (std::size_t r = 0; r < kBlockRows; ++r) {
    for (std::size_t c = 0; c < kBlockCols; ++c) {
      if (dots[r * kBlockCols + c] > row_second[r]) *row_mask |= 1u << r;
      if (dots[r * kBlockCols + c] > col_second[c]) *col_mask |= 1u << c;
    }
  }
}

#if defined(__x86_64__) && defined(__GNUC__)
// The same with AVX and FMA (16 columns as two 8-float registers per row): products and sums of
// integers below 2^24 are exact, so fused or not, in any order, the dots are the same.
__attribute__((target("avx,fma"))) void DotsAvx(const float* a, const float* panel, float* dots) {
  __m256 acc[2 * kBlockRows];
  for (__m256& v : acc) v = _mm256_setzero_ps();
  for (int k = 0; k < kDims; ++k) {
    const __m256 b0 = _mm256_loadu_ps(panel + k * kBlockCols);
    const __m256 b1 = _mm256_loadu_ps(panel + k * kBlockCols + 8);
    for (std::size_t r = 0; r < kBlockRows; ++r) {
      const __m256 ar = _mm256_broadcast_ss(a + r * kDims + k);
      acc[2 * r] = _mm256_fmadd_ps(ar, b0, acc[2 * r]);
      acc[2 * r + 1] = _mm256_fmadd_ps(ar, b1, acc[2 * r + 1]);
    }
  }
  for (std::size_t r = 0; r < kBlockRows; ++r) {
    _mm256_storeu_ps(dots + r * kBlockCols, acc[2 * r]);
    _mm256_storeu_ps(dots + r * kBlockCols + 8, acc[2 * r + 1]);
  }
}
// The same flags as FlagsPortable, eight columns at a time.
__attribute__((target("avx"))) void FlagsAvx(const float* dots, const float* row_second, const float* col_second,
                                             unsigned* row_mask, unsigned* col_mask) {
  *row_mask = 0;
  for (std::size_t r = 0; r < kBlockRows; ++r) {
    const __m256 m = _mm256_max_ps(_mm256_load_ps(dots + r * kBlockCols), _mm256_load_ps(dots + r * kBlockCols + 8));
    if (_mm256_movemask_ps(_mm256_cmp_ps(m, _mm256_set1_ps(row_second[r]), _CMP_GT_OQ)) != 0) *row_mask |= 1u << r;
  }
  for (std::size_t half = 0; half < 2; ++half) {
    __m256 m = _mm256_load_ps(dots + half * 8);
    for (std::size_t r = 1; r < kBlockRows; ++r) m = _mm256_max_ps(m, _mm256_load_ps(dots + r * kBlockCols + half * 8));
    const int bits = _mm256_movemask_ps(_mm256_cmp_ps(m, _mm256_loadu_ps(col_second + half * 8), _CMP_GT_OQ));
    *col_mask = half == 0 ? static_cast<unsigned>(bits) : *col_mask | static_cast<unsigned>(bits) << 8;
  }
}
bool HaveAvx() { return __builtin_cpu_supports("avx") && __builtin_cpu_supports("fma"); }
#else
void DotsAvx(const float* a, const float* panel, float* dots) { DotsPortable(a, panel, dots); }
void FlagsAvx(const float* dots, const float* row_second, const float* col_second, unsigned* row_mask,
              unsigned* col_mask) {
  FlagsPortable(dots, row_second, col_second, row_mask, col_mask);
}
bool HaveAvx() { return false; }
#endif

// The nearest neighbours of every row of `a` among the rows of `b` and, the other way, of every row
// of `b` among the rows of `a`. Rows of `a` see the columns in ascending order, columns the rows.
void NearestBothWays(const Rows& a, const Rows& b, bool use_avx, std::vector<Nearest>* nearest_a,
                     std::vector<Nearest>* nearest_b) {
  nearest_a->assign(a.count, Nearest());
  nearest_b->assign(b.count, Nearest());
  auto dots_of = use_avx ? DotsAvx : DotsPortable;
  auto flags_of = use_avx ? FlagsAvx : FlagsPortable;
  alignas(32) float dots[kBlockRows * kBlockCols];
  float row_second[kBlockRows], col_second[kBlockCols];
  for (std::size_t j0 = 0; j0 < b.count; j0 += kTileRows) {
    const std::size_t j1 = std::min(b.count, j0 + kTileRows);
    for (std::size_t i = 0; i < a.count; i += kBlockRows) {
      const std::size_t rows = std::min(kBlockRows, a.count - i);
      for (std::size_t r = 0; r < kBlockRows; ++r) row_second[r] = r < rows ? (*nearest_a)[i + r].second : kNever;
      for (std::size_t j = j0; j < j1; j += kBlockCols) {
        const std::size_t cols = std::min(kBlockCols, j1 - j);
        for (std::size_t c = 0; c < kBlockCols; ++c) col_second[c] = c < cols ? (*nearest_b)[j + c].second : kNever;
        dots_of(a.values.data() + i * kDims, b.values.data() + j * kDims, dots);
        unsigned row_mask = 0, col_mask = 0;
        flags_of(dots, row_second, col_second, &row_mask, &col_mask);
        for (std::size_t r = 0; r < rows && row_mask != 0; ++r) {
          if ((row_mask >> r & 1u) == 0) continue;
          for (std::size_t c = 0; c < cols; ++c) {
            (*nearest_a)[i + r].Add(dots[r * kBlockCols + c], static_cast<std::int32_t>(j + c));
          }
          row_second[r] = (*nearest_a)[i + r].second;
        }
        for (std::size_t c = 0; c < cols && col_mask != 0; ++c) {
          if ((col_mask >> c & 1u) == 0) continue;
          for (std::size_t r = 0; r < rows; ++r) {
            (*nearest_b)[j + c].Add(dots[r * kBlockCols + c], static_cast<std::int32_t>(i + r));
          }
        }
      }
    }
  }
}

double Angle(float dot) { return std::acos(std::min(1.0, dot * kDotToCosine)); }

// The match of one descriptor, or -1: near enough, and clearly nearer than the second nearest.
std::int32_t Accepted(const Nearest& n, const FeatureMatchOptions& options) {
  if (n.index < 0) return -1;
  const double best = Angle(n.best);
  if (best > options.max_distance) return -1;
  if (best >= options.max_ratio * Angle(n.second)) return -1;
  return n.index;
}

}  // namespace

std::vector<FeatureMatch> MatchSiftDescriptors(const std::vector<std::uint8_t>& descriptors1,
                                               const std::vector<std::uint8_t>& descriptors2,
                                               const FeatureMatchOptions& options) {
  if (descriptors1.size() % kDims != 0 || descriptors2.size() % kDims != 0) {
    throw InternalError("MatchSiftDescriptors: descriptors are not whole rows of 128 bytes");
  }
  const std::size_t n1 = descriptors1.size() / kDims;
  std::vector<Nearest> nearest1, nearest2;
  NearestBothWays(FirstSet(descriptors1), SecondSet(descriptors2), options.use_avx && HaveAvx(), &nearest1, &nearest2);
  std::vector<FeatureMatch> matches;
  for (std::size_t i = 0; i < n1; ++i) {
    const std::int32_t j = Accepted(nearest1[i], options);
    if (j < 0) continue;
    if (options.cross_check &&
        Accepted(nearest2[static_cast<std::size_t>(j)], options) != static_cast<std::int32_t>(i)) {
      continue;
    }
    matches.push_back({static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j)});
  }
  return matches;
}

std::size_t BlankBorderDescriptors(std::vector<ColmapImageFeatures>* images) {
  std::size_t blanked = 0;
  for (ColmapImageFeatures& image : *images) {
    const std::size_t columns = static_cast<std::size_t>(image.keypoint_columns);
    for (std::size_t i = 0; i < image.num_keypoints() && columns >= 2; ++i) {
      const float* k = image.keypoints.data() + i * columns;
      // (x, y), (x, y, scale, orientation) or (x, y, a11, a12, a21, a22): the scale is |first column of A|.
      const double scale = columns == 4 ? k[2] : columns == 6 ? std::hypot(k[2], k[4]) : 1.0;
      const double margin = 0.5 + 2.0 * std::max(1.0, scale);
      if (k[0] >= margin && k[1] >= margin && k[0] <= image.width_px - margin && k[1] <= image.height_px - margin) {
        continue;
      }
      std::fill_n(image.descriptors.begin() + static_cast<std::ptrdiff_t>(i * kDims), kDims, std::uint8_t{0});
      ++blanked;
    }
  }
  return blanked;
}

std::vector<ImagePairMatches> MatchAllPairs(const std::vector<ColmapImageFeatures>& images,
                                            const FeatureMatchOptions& options) {
  std::vector<ImagePairMatches> pairs;
  for (std::size_t i = 0; i < images.size(); ++i) {
    for (std::size_t j = i + 1; j < images.size(); ++j) pairs.push_back({i, j, {}});
  }
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t threads = std::min<std::size_t>(
      pairs.size(), options.num_threads > 0 ? static_cast<std::size_t>(options.num_threads) : cores);
  // Each pair's matches depend on that pair alone, and go to that pair's slot: the same at any count.
  std::atomic<std::size_t> next{0};
  auto work = [&] {
    for (std::size_t p = next++; p < pairs.size(); p = next++) {
      pairs[p].matches =
          MatchSiftDescriptors(images[pairs[p].image1].descriptors, images[pairs[p].image2].descriptors, options);
    }
  };
  std::vector<std::thread> pool;
  for (std::size_t t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  return pairs;
}

void WriteColmapRawMatches(const fs::path& path, const std::vector<ColmapImageFeatures>& images,
                           const std::vector<ImagePairMatches>& pairs) {
  for (const ColmapImageFeatures& image : images) {
    if (image.name.find_first_of(" \t\r\n") != std::string::npos) {
      throw InputError(Located(image.name,
                               "an image name with white space cannot go through COLMAP's match list "
                               "(rename the photo)"));
    }
  }
  const fs::path tmp = path.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    for (const ImagePairMatches& pair : pairs) {
      out << images[pair.image1].name << ' ' << images[pair.image2].name << '\n';
      for (const FeatureMatch& m : pair.matches) out << m.index1 << ' ' << m.index2 << '\n';
      out << '\n';
    }
    out.flush();
    if (!out) throw RuntimeError(Located(tmp.string(), "cannot be written"));
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) throw RuntimeError(Located(path.string(), "cannot be written (" + ec.message() + ")"));
}

}  // namespace cinepath::photogrammetry
