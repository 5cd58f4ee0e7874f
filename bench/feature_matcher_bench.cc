// cinepath's SIFT matcher (photogrammetry/io/feature_matcher.h) on a COLMAP database: time and match
// count at each thread count given, and whether every count gives the same matches.
//   feature_matcher_bench DATABASE.db [MATCH_LIST.txt] [THREADS ...]   (default threads: 1 2)
// The match list (colmap matches_importer --match_type raw) is written from the first thread count.
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "photogrammetry/io/colmap_database.h"
#include "photogrammetry/io/feature_matcher.h"

namespace {

double CpuSeconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

double Since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

int main(int argc, char** argv) {
  using namespace cinepath::photogrammetry;
  if (argc < 2) {
    std::fprintf(stderr, "usage: feature_matcher_bench DATABASE.db [MATCH_LIST.txt] [THREADS ...]\n");
    return 2;
  }
  const std::string list = argc > 2 ? argv[2] : "";
  std::vector<int> thread_counts;
  for (int i = 3; i < argc; ++i) thread_counts.push_back(std::atoi(argv[i]));
  if (thread_counts.empty()) thread_counts = {1, 2};

  auto start = std::chrono::steady_clock::now();
  std::vector<ColmapImageFeatures> images = ReadColmapFeatures(argv[1]);
  size_t descriptors = 0;
  for (const auto& image : images) descriptors += image.num_keypoints();
  const size_t blanked = BlankBorderDescriptors(&images);
  std::printf("read %zu images, %zu descriptors (%zu at the border blanked) in %.3f s\n", images.size(), descriptors,
              blanked, Since(start));

  std::vector<ImagePairMatches> first;
  bool same = true;
  for (int threads : thread_counts) {
    FeatureMatchOptions options;
    options.num_threads = threads;
    const double cpu0 = CpuSeconds();
    start = std::chrono::steady_clock::now();
    std::vector<ImagePairMatches> pairs = MatchAllPairs(images, options);
    const double wall = Since(start), cpu = CpuSeconds() - cpu0;
    size_t matches = 0;
    for (const auto& p : pairs) matches += p.matches.size();
    std::printf("%d thread(s): %zu pairs, %zu matches, %.2f s wall, %.2f s CPU\n", threads, pairs.size(), matches, wall,
                cpu);
    if (first.empty()) {
      first = pairs;
      if (!list.empty()) WriteColmapRawMatches(list, images, pairs);
    } else {
      for (size_t p = 0; p < pairs.size(); ++p) same = same && pairs[p].matches == first[p].matches;
    }
  }
  std::printf("same matches at every thread count: %s\n", same ? "yes" : "NO");
  return same ? 0 : 1;
}
