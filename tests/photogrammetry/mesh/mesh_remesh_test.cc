#include "photogrammetry/mesh/mesh_remesh.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "core/error.h"
#include "photogrammetry/mesh/mesh_distance.h"
#include "tests/photogrammetry/surface_test_meshes.h"

namespace cinepath::photogrammetry {
namespace {

// Lengths of the edges with no end on the outer border (the border is kept as it is, so its edges
// keep the input's length when that is shorter than the target).
std::vector<double> InteriorEdgeLengths(const TriangleMesh& mesh, const Eigen::AlignedBox3d& box) {
  auto on_border = [&](uint32_t v) {
    const Eigen::Vector3d& p = mesh.vertices_m[v];
    return std::abs(p.x() - box.min().x()) < 1e-9 || std::abs(p.x() - box.max().x()) < 1e-9 ||
           std::abs(p.y() - box.min().y()) < 1e-9 || std::abs(p.y() - box.max().y()) < 1e-9;
  };
  std::vector<std::pair<uint32_t, uint32_t>> edges;
  for (const auto& f : mesh.faces) {
    for (int k = 0; k < 3; ++k) {
      edges.emplace_back(std::min(f[k], f[(k + 1) % 3]), std::max(f[k], f[(k + 1) % 3]));
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<double> lengths;
  for (const auto& [a, b] : edges) {
    if (!on_border(a) && !on_border(b)) {
      lengths.push_back((mesh.vertices_m[a] - mesh.vertices_m[b]).norm());
    }
  }
  return lengths;
}

TEST(RemeshIsotropic, EdgesApproachTheTargetAndTheSurfaceStaysPut) {
  // 30 m × 30 m rolling terrain, 1 m grid (edges 1 m and 1.41 m): remesh to 0.6 m and to 2.5 m.
  const TriangleMesh grid = testing::TerrainGrid(31, 31, 1.0);
  for (double target_m : {0.6, 2.5}) {
    RemeshOptions options;
    options.target_edge_m = target_m;
    RemeshReport report;
    const TriangleMesh out = RemeshIsotropic(grid, options, &report);
    ASSERT_GT(out.num_faces(), 0u);
    EXPECT_EQ(report.faces_out, static_cast<int64_t>(out.num_faces()));
    Eigen::AlignedBox3d in_box;
    for (const auto& v : grid.vertices_m) in_box.extend(v);
    std::vector<double> lengths = InteriorEdgeLengths(out, in_box);
    ASSERT_GT(lengths.size(), 50u);
    std::sort(lengths.begin(), lengths.end());
    const double median = lengths[lengths.size() / 2];
    EXPECT_GT(median, 0.8 * target_m) << target_m;
    EXPECT_LT(median, 4.0 / 3.0 * target_m) << target_m;
    const auto in_band = std::count_if(lengths.begin(), lengths.end(),
                                       [&](double l) { return l >= 0.7 * target_m && l <= 1.4 * target_m; });
    EXPECT_GT(static_cast<double>(in_band) / lengths.size(), 0.7) << target_m;
    EXPECT_GT(report.edges_in_band_fraction, 0.5) << target_m;  // all edges, border included
    // Finer target → more faces than the input; coarser → fewer.
    if (target_m < 1.0) EXPECT_GT(out.num_faces(), grid.num_faces());
    if (target_m > 2.0) EXPECT_LT(out.num_faces(), grid.num_faces());
    // The surface stays within a few centimetres of the input (gentle terrain), the border put.
    HausdorffOptions hausdorff;
    hausdorff.samples_per_mesh = 20000;
    EXPECT_LT(ApproximateHausdorff(grid, out, hausdorff).symmetric_m, 0.05) << target_m;
    Eigen::AlignedBox3d out_box;
    for (const auto& v : out.vertices_m) out_box.extend(v);
    EXPECT_NEAR(out_box.min().x(), in_box.min().x(), 1e-9);
    EXPECT_NEAR(out_box.max().y(), in_box.max().y(), 1e-9);
    ASSERT_EQ(out.colors_rgb.size(), out.num_vertices());
    // Deterministic.
    EXPECT_EQ(RemeshIsotropic(grid, options).faces, out.faces);
  }
}

TEST(RemeshIsotropic, RejectsBadOptionsAndEmptyMeshes) {
  RemeshOptions options;
  options.target_edge_m = 0;
  EXPECT_THROW(options.Check(), InputError);
  options.target_edge_m = NAN;
  EXPECT_THROW(options.Check(), InputError);
  options.target_edge_m = 1.0;
  EXPECT_THROW(RemeshIsotropic(TriangleMesh{}, options), InputError);
}

}  // namespace
}  // namespace cinepath::photogrammetry
