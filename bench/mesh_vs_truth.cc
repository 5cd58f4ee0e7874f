// The distance of a cinepath mesh to the exact surface of a synthetic scene, for bench/oblique_truth.sh:
//   mesh_vs_truth OUT_DIR TRUTH_DIR
// (OUT_DIR: `cinepath mesh -o`'s folder, scene.glb and scene.json; TRUTH_DIR: truth.ply and truth.json)
// prints one line: vertices, median, p90, p99, share within 0.3 m (all distinct vertex positions), then
// the same by horizontal distance from the centre (tests/photogrammetry/oblique_truth.h).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "tests/photogrammetry/oblique_truth.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: mesh_vs_truth OUT_DIR TRUTH_DIR\n");
    return 2;
  }
  try {
    const auto d = cinepath::testing::MeasureAgainstTruth(argv[1], argv[2]);
    std::printf("all: vertices %zu median %.3f p90 %.3f p99 %.3f within_0.3m %.1f%%\n", d.size(), d.Quantile(0.5),
                d.Quantile(0.9), d.Quantile(0.99), 100 * d.ShareWithin(0.3));
    const double rings[][2] = {{0, 15}, {15, 25}, {25, 35}, {35, 45}, {45, INFINITY}};
    for (const auto& r : rings) {
      std::printf("ring %.0f-%.0f m: vertices %zu median %.3f p99 %.3f within_0.3m %.1f%%\n", r[0], r[1],
                  d.CountIn(r[0], r[1]), d.Quantile(0.5, r[0], r[1]), d.Quantile(0.99, r[0], r[1]),
                  100 * d.ShareWithin(0.3, r[0], r[1]));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mesh_vs_truth: %s\n", e.what());
    return 1;
  }
  return 0;
}
