// The distance of a cinepath mesh to the exact surface of a synthetic scene, for bench/oblique_truth.sh:
//   mesh_vs_truth OUT_DIR TRUTH_DIR [--dump CSV]
// (OUT_DIR: `cinepath mesh -o`'s folder, scene.glb and scene.json; TRUTH_DIR: truth.ply and truth.json)
// prints one line: vertices, median, p90, p99, share within 0.3 m (all distinct vertex positions), then
// the same by horizontal distance from the centre (tests/photogrammetry/oblique_truth.h). --dump writes every
// vertex (truth frame, metres) with its distance and ring radius as CSV, to see where the error sits.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <string>

#include "tests/photogrammetry/oblique_truth.h"

int main(int argc, char** argv) {
  const bool dump = argc == 5 && std::string(argv[3]) == "--dump";
  if (argc != 3 && !dump) {
    std::fprintf(stderr, "usage: mesh_vs_truth OUT_DIR TRUTH_DIR [--dump CSV]\n");
    return 2;
  }
  try {
    const auto d = cinepath::testing::MeasureAgainstTruth(argv[1], argv[2]);
    std::printf("all: vertices %zu median %.3f p90 %.3f p99 %.3f within_0.3m %.1f%%\n", d.size(), d.Quantile(0.5),
                d.Quantile(0.9), d.Quantile(0.99), 100 * d.ShareWithin(0.3));
    if (dump) {
      std::FILE* csv = std::fopen(argv[4], "w");
      if (!csv) throw std::runtime_error(std::string("cannot write ") + argv[4]);
      std::fprintf(csv, "x_m,y_m,z_m,distance_m,radius_m\n");
      for (size_t i = 0; i < d.size(); ++i) {
        const auto& p = d.position_m[i];
        std::fprintf(csv, "%.4f,%.4f,%.4f,%.4f,%.3f\n", p.x(), p.y(), p.z(), d.distance_m[i], d.radius_m[i]);
      }
      std::fclose(csv);
    }
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
