// Rule 1 of the mesh, "as true as the points", on oblique data with exact truth: `cinepath mesh` on the
// COLMAP reconstructions of the rendered oblique house and cliff scenes of tests/data/photogrammetry/oblique
// (make_oblique.py; PROVENANCE.md there), with the default options, measured against the rendered
// geometry itself (oblique_truth.h). What it asserts (figures in bench/RESULTS.md, "Oblique scenes with
// exact truth"):
// - the run ends with exit 0 (bug 2026-11-27: SIGFPE inside CGAL's Poisson refinement, from points
//   COLMAP left twice; surface_poisson.h, MergeCoincidentPoints);
// - at least 95 % of the mesh's distinct vertex positions within 0.3 m of the true surface, and the 99th
//   percentile within 0.6 m (rule 1; measured 2026-11-28: the house 99.6 %, 0.210 m; the cliff 97.9 %,
//   0.521 m). The trim judges faces against at most
//   4 median point spacings, so the mesh ends where the points thin out (about 50 m from the centre;
//   the ~200 points scattered over the ground beyond carry no surface);
// - the same within 45 m of the orbits' target (radius 32 and 50 m), where they see the scene densely.
// The trim's border fit staying within two point spacings is not met yet (max_border_extension_m 6.9 m
// against 1.2 m): printed, not asserted.
//
// Its own executable (it runs the real `cinepath` binary, ~45 s on the shared machine), label "mesh_truth".
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/json.h"
#include "tests/photogrammetry/oblique_truth.h"
#include "tests/support/command_line.h"

namespace {

namespace fs = std::filesystem;
using cinepath::testing::MakeTempDir;
using cinepath::testing::ReadText;
using cinepath::testing::ShellQuote;

class ObliqueTruth : public ::testing::TestWithParam<const char*> {};

// What each scene must meet: rule 1 itself, the house and the cliff alike (the cliff met it on 2026-11-28,
// when the trim's step 4 learnt to settle vertices onto two planes at an edge: 97.9 % within 0.3 m, p99
// 0.521 m, was 92.4 % and 0.793 m; bench/RESULTS.md, "Sharp edges").
constexpr double kMinShareWithin0_3M = 0.95, kMaxP99M = 0.6;

TEST_P(ObliqueTruth, MeshIsAsTrueAsItsPoints) {
  const fs::path data = fs::path(CINEPATH_TEST_DATA_DIR) / "photogrammetry" / "oblique" / GetParam();
  ASSERT_TRUE(fs::is_directory(data / "sparse")) << data;
  const fs::path tmp = MakeTempDir(std::string("cinepath_oblique_") + GetParam());
  ASSERT_FALSE(tmp.empty());
  const fs::path out = tmp / "scene";
  const std::string command = ShellQuote(CINEPATH_BINARY) + " mesh --colmap " + ShellQuote((data / "sparse").string()) +
                              " --refs " + ShellQuote((data / "refs_gps.txt").string()) + " -o " +
                              ShellQuote(out.string()) + " --no-timestamp 2> " +
                              ShellQuote((tmp / "stderr.txt").string());
  const int rc = std::system(command.c_str());
  ASSERT_EQ(rc, 0) << command << "\n" << ReadText(tmp / "stderr.txt");

  const cinepath::testing::TruthDistances d = cinepath::testing::MeasureAgainstTruth(out, data);
  ASSERT_GT(d.size(), 100u);
  std::printf("%s: %zu vertices; median %.3f m, p90 %.3f m, p99 %.3f m, within 0.3 m %.1f %%\n", GetParam(), d.size(),
              d.Quantile(0.5), d.Quantile(0.9), d.Quantile(0.99), 100 * d.ShareWithin(0.3));
  for (double r : {0.0, 15.0, 25.0, 35.0, 45.0}) {
    const double r_hi = r == 45.0 ? INFINITY : (r == 0.0 ? 15.0 : r + 10.0);
    std::printf("  %4.0f-%-4.0f m from the centre: %6zu vertices, within 0.3 m %.1f %%, p99 %.3f m\n", r, r_hi,
                d.CountIn(r, r_hi), 100 * d.ShareWithin(0.3, r, r_hi), d.Quantile(0.99, r, r_hi));
  }
  std::printf("  within 45 m of the centre: %zu vertices, median %.3f m, p99 %.3f m, within 0.3 m %.1f %%\n",
              d.CountIn(0, 45), d.Quantile(0.5, 0, 45), d.Quantile(0.99, 0, 45), 100 * d.ShareWithin(0.3, 0, 45));
  EXPECT_GE(d.ShareWithin(0.3, 0, 45), kMinShareWithin0_3M);
  EXPECT_LE(d.Quantile(0.99, 0, 45), kMaxP99M);
  EXPECT_GE(d.ShareWithin(0.3), kMinShareWithin0_3M);
  EXPECT_LE(d.Quantile(0.99), kMaxP99M);

  // The trim's border fit: how far a border vertex moved out, against the points' own spacing.
  const cinepath::Json scene = cinepath::Json::parse(ReadText(out / "scene.json"));
  for (const auto& step : scene["surface"]["steps"]) {
    if (step["step"] != "trim") continue;
    const double moved_m = step["max_border_extension_m"].get<double>();
    const double spacing_m = step["median_point_spacing_m"].get<double>();
    std::printf("  trim: max_border_extension_m %.3f, median_point_spacing_m %.3f\n", moved_m, spacing_m);
  }
  fs::remove_all(tmp);
}

INSTANTIATE_TEST_SUITE_P(Scenes, ObliqueTruth, ::testing::Values("house", "cliff"));

}  // namespace
