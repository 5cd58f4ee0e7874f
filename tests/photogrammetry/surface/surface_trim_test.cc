#include "photogrammetry/surface/surface_trim.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "photogrammetry/georef/georeference_model.h"
#include "photogrammetry/io/colmap_reader.h"
#include "photogrammetry/io/refs_file.h"
#include "photogrammetry/pipeline/surface_pipeline.h"
#include "photogrammetry/surface/surface_points.h"
#include "tests/photogrammetry/surface_test_meshes.h"
#include "tests/photogrammetry/test_paths.h"

namespace cinepath::photogrammetry {
namespace {

const Json* FindStep(const Json& report, const std::string& name) {
  for (const Json& step : report["steps"]) {
    if (step["step"] == name) return &step;
  }
  return nullptr;
}

// The vertices on the mesh's border (on an edge used by one face).
std::vector<uint32_t> BorderVertices(const TriangleMesh& mesh) {
  std::map<std::pair<uint32_t, uint32_t>, int> uses;
  for (const auto& f : mesh.faces) {
    for (int c = 0; c < 3; ++c) ++uses[std::minmax(f[c], f[(c + 1) % 3])];
  }
  std::vector<uint32_t> out;
  for (const auto& [edge, n] : uses) {
    if (n == 1) {
      out.push_back(edge.first);
      out.push_back(edge.second);
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// Distance from p to the segment [a, b].
double SegmentDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d d = b - a;
  const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * d)).norm();
}

// The L of testing::LCloud: the floor z = 0 over [0, kWidth] × [0, kDepth] and the wall y = 0 over
// [0, kWidth] × [0, kHeight], facing the floor, with points every kPitch (jittered).
constexpr double kWidth = testing::kLWidthM, kDepth = testing::kLDepthM, kHeight = testing::kLHeightM,
                 kPitch = testing::kLPitchM;
// Where the points end: their last row (kDepth and kHeight are not whole multiples of the pitch; the
// points reach 7.8 m and 4.8 m, give or take their jitter). The L measured below is the data's.
const double kDataWidth = std::floor(kWidth / kPitch + 1e-6) * kPitch;
const double kDataDepth = std::floor(kDepth / kPitch + 1e-6) * kPitch;
const double kDataHeight = std::floor(kHeight / kPitch + 1e-6) * kPitch;

// Distance from p to the union of the two rectangles the points cover.
double DistanceToL(const Eigen::Vector3d& p) {
  const double x = std::clamp(p.x(), 0.0, kDataWidth);
  const Eigen::Vector3d on_floor(x, std::clamp(p.y(), 0.0, kDataDepth), 0.0);
  const Eigen::Vector3d on_wall(x, 0.0, std::clamp(p.z(), 0.0, kDataHeight));
  return std::min((p - on_floor).norm(), (p - on_wall).norm());
}

// Distance from p to the data's border: the outline of the L (every rectangle edge but the shared one).
double DistanceToLBorder(const Eigen::Vector3d& p) {
  using V = Eigen::Vector3d;
  const double w = kDataWidth, d = kDataDepth, h = kDataHeight;
  const std::vector<std::pair<V, V>> edges = {{V(0, 0, 0), V(0, d, 0)}, {V(w, 0, 0), V(w, d, 0)},
                                              {V(0, d, 0), V(w, d, 0)}, {V(0, 0, 0), V(0, 0, h)},
                                              {V(w, 0, 0), V(w, 0, h)}, {V(0, 0, h), V(w, 0, h)}};
  double distance_m = INFINITY;
  for (const auto& [a, b] : edges) distance_m = std::min(distance_m, SegmentDistance(p, a, b));
  return distance_m;
}

// The Poisson surface of an L of two bounded planes ends where the points end, for every seed of the
// surface mesher's first points (each seed gives another valid surface): within one point spacing of
// the data's border, neither past it nor short of it.
TEST(TrimSurfaceToData, PoissonSurfaceOfBoundedPlanesEndsWithinOneSpacingOfTheirBorderWhateverTheSeed) {
  const PointCloud cloud = testing::LCloud();
  double worst_border_spacings = 0;
  for (const unsigned int seed : {PoissonOptions{}.seed, 1u, 2u, 3u, 4u, 5u}) {
    SCOPED_TRACE(seed);
    SurfacePipelineOptions options;
    options.method = SurfaceMethod::kPoisson;
    options.report_times = false;
    options.poisson_seed = seed;
    const SurfacePipelineResult result = BuildSurfaceFromPoints(cloud, options);
    const Json* trim = FindStep(result.report, "trim");
    ASSERT_NE(trim, nullptr);
    const double spacing_m = (*trim)["median_spacing_m"].get<double>();
    // The effective spacing: the larger of the points' (about 1.1 × the pitch) and the Poisson
    // mesher's facet size (CGAL's average spacing over 18 neighbours, about 1.65 × the pitch).
    EXPECT_GT(spacing_m, 1.0 * kPitch);
    EXPECT_LT(spacing_m, 2.0 * kPitch);
    EXPECT_GT((*trim)["faces_far_from_data"].get<int64_t>() + (*trim)["border_faces_unsupported"].get<int64_t>(), 100);
    const TriangleMesh& mesh = result.mesh;
    ASSERT_GT(mesh.num_faces(), 500u);

    // Every vertex lies on the bounded planes, within one spacing (Poisson rounds the crease).
    double worst_m = 0;
    for (const auto& v : mesh.vertices_m) worst_m = std::max(worst_m, DistanceToL(v));
    EXPECT_LT(worst_m, spacing_m) << "spacing " << spacing_m;
    // The border lies near the data's border (no skirt, no hole cut inside).
    const std::vector<uint32_t> border = BorderVertices(mesh);
    ASSERT_GT(border.size(), 50u);
    double worst_border_m = 0;
    Eigen::Vector3d worst_at = Eigen::Vector3d::Zero();
    for (uint32_t i : border) {
      const double d = DistanceToLBorder(mesh.vertices_m[i]);
      if (d > worst_border_m) worst_border_m = d, worst_at = mesh.vertices_m[i];
    }
    const double point_spacing_m = (*trim)["median_point_spacing_m"].get<double>();
    EXPECT_GT(point_spacing_m, 1.0 * kPitch);
    EXPECT_LT(point_spacing_m, 1.3 * kPitch);
    EXPECT_GT((*trim)["border_vertices_pulled"].get<int64_t>(), 0);    // past the points: pulled in
    EXPECT_GT((*trim)["border_vertices_extended"].get<int64_t>(), 0);  // short of a free edge: moved out
    // Within one of the points' own spacings: 0.76-0.84 for these seeds, at most 0.91 over 64 of 65
    // seeds (docs/mesh.md: the 65th surface is torn). Without moving border vertices out to the data,
    // 0.79-1.24 for these seeds: at a free edge (the wall's top, the floor's far side) Poisson rounds
    // the sheet over, and the trim cuts the roll away.
    EXPECT_LT(worst_border_m, point_spacing_m)
        << "point spacing " << point_spacing_m << ", worst at " << worst_at.transpose();
    worst_border_spacings = std::max(worst_border_spacings, worst_border_m / point_spacing_m);
    // And the surface still covers the data: every point has a vertex within about one spacing
    // (0.94-1.08 spacings over these seeds, at most 1.15 over 64 of 65 seeds).
    double worst_cover_m = 0;
    for (const auto& p : cloud.positions_m) {
      double d = INFINITY;
      for (const auto& v : mesh.vertices_m) d = std::min(d, (v - p).norm());
      worst_cover_m = std::max(worst_cover_m, d);
    }
    EXPECT_LT(worst_cover_m, 1.25 * spacing_m);
    std::cerr << "L, seed " << seed << ": spacing " << spacing_m << " m, worst off-plane " << worst_m
              << " m, worst border " << worst_border_m << " m (" << worst_border_m / point_spacing_m
              << " point spacings, at " << worst_at.transpose() << "), worst cover " << worst_cover_m << " m; "
              << DumpJson(*trim) << "\n";
  }
  std::cerr << "worst border over the seeds: " << worst_border_spacings << " point spacings\n";
}

// A height field with outliers injected (in the middle and along the border); no output
// vertex strays from the true surface, on either surface path.
TEST(TrimSurfaceToData, OutliersInAHeightFieldLeaveNoSpike) {
  PointCloud cloud = testing::TerrainCloud(50, 40, 1.0);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> e(0, 49), n(0, 39), offset(2.0, 12.0), border(0, 1.5);
  std::bernoulli_distribution sign(0.5);
  const size_t clean_points = cloud.size();
  for (int i = 0; i < 80; ++i) {
    Eigen::Vector3d p(e(rng), n(rng), 0);
    if (i % 2 == 0) p.x() = i % 4 == 0 ? border(rng) : 49 - border(rng);  // half of them along the border
    p.z() = testing::TerrainHeightM(p.x(), p.y()) + (sign(rng) ? 1 : -1) * offset(rng);
    cloud.positions_m.push_back(p);
    cloud.colors_rgb.push_back({255, 0, 0});
    cloud.reprojection_error_px.push_back(0.8);
    cloud.observers.push_back({0, 1, 2});
  }
  for (SurfaceMethod method : {SurfaceMethod::kHeightField, SurfaceMethod::kPoisson}) {
    SurfacePipelineOptions options;
    options.method = method;
    options.report_times = false;
    const SurfacePipelineResult result = BuildSurfaceFromPoints(cloud, options);
    const Json* filter = FindStep(result.report, "filter_points");
    ASSERT_NE(filter, nullptr);
    const int64_t removed =
        (*filter)["removed_isolated"].get<int64_t>() + (*filter)["removed_off_plane"].get<int64_t>();
    EXPECT_GE(removed, 60) << DumpJson(*filter);  // the rest: the height field's spike test, the trim
    EXPECT_LE(removed, 80 + static_cast<int64_t>(clean_points) / 200) << DumpJson(*filter);  // few true points
    // Tolerance: 0.05 m on the height-field path (its vertices are the points); 0.5 m on the Poisson
    // path, whose facets are 1.7 m here and whose border bends (the outliers were 2 to 12 m off).
    const double tolerance_m = method == SurfaceMethod::kHeightField ? 0.05 : 0.5;
    double worst_m = 0;
    Eigen::Vector3d worst_at = Eigen::Vector3d::Zero();
    for (const auto& v : result.mesh.vertices_m) {
      const double d = std::abs(v.z() - testing::TerrainHeightM(v.x(), v.y()));
      if (d > worst_m) worst_at = v;
      worst_m = std::max(worst_m, d);
    }
    std::cerr << "worst at " << worst_at.transpose() << "\n";
    EXPECT_LT(worst_m, tolerance_m) << SurfaceMethodName(method);
    std::cerr << SurfaceMethodName(method) << ": worst vertical error " << worst_m << " m; " << DumpJson(*filter)
              << "\n"
              << DumpJson(*FindStep(result.report, "trim")) << "\n";
  }
}

// A flat 20 × 20 grid at 1 m, z = 0, and its vertices as the data points.
void FlatGridAndItsPoints(TriangleMesh* mesh, PointCloud* points) {
  *mesh = testing::TerrainGrid(20, 20, 1.0);
  for (auto& v : mesh->vertices_m) {
    v.z() = 0;
    points->positions_m.push_back(v);
  }
}

TEST(TrimSurfaceToData, StretchedBorderTrianglesArePeeledAndSpikesFlattened) {
  // A flat 20 × 20 grid (1 m) plus one stray point 6 m east of its border, joined to it by two long
  // triangles, and one vertex raised 3 m inside.
  TriangleMesh mesh;
  PointCloud points;
  FlatGridAndItsPoints(&mesh, &points);
  const uint32_t stray = static_cast<uint32_t>(mesh.vertices_m.size());
  mesh.vertices_m.emplace_back(25.0, 9.5, 4.0);
  mesh.colors_rgb.push_back({0, 0, 0});
  points.positions_m.push_back(mesh.vertices_m.back());
  mesh.faces.push_back({19 + 9 * 20, stray, 19 + 10 * 20});
  mesh.faces.push_back({19 + 8 * 20, stray, 19 + 9 * 20});
  const uint32_t raised = 10 + 10 * 20;
  mesh.vertices_m[raised].z() = 3.0;
  SurfaceTrimReport report;
  const TriangleMesh out = TrimSurfaceToData(mesh, points, SurfaceTrimOptions{}, &report);
  EXPECT_EQ(report.border_faces_stretched + report.border_faces_unsupported, 2);
  EXPECT_EQ(report.faces_out, 19 * 19 * 2);
  EXPECT_GE(report.spike_vertices_flattened, 1);
  EXPECT_NEAR(report.max_spike_height_m, 3.0 * 6.0 / 7.0, 0.5);
  for (const auto& v : out.vertices_m) EXPECT_LT(std::abs(v.z()), 0.3) << v.transpose();
  EXPECT_EQ(out.colors_rgb.size(), out.num_vertices());
}

// The height-field path's trim: no distance test and no peeling, only ears and strays, a bounded number
// of passes. A flat 20 × 20 grid (1 m) with an ear (one triangle out to a lone point 8 m east), a fan
// (two triangles out to another lone point) and an arm of five stretched quads (12 m long, 1 m wide) out
// to the west, each of its corners a clump of points 0.3 m across, so that the arm is stretched against
// its own data: the ear and the fan go, the arm loses its tip, a few triangles a pass, and not more.
TEST(TrimSurfaceToData, StretchedEarsAndStraysGoInABoundedNumberOfPasses) {
  TriangleMesh mesh;
  PointCloud points;
  FlatGridAndItsPoints(&mesh, &points);
  const size_t grid_faces = mesh.num_faces();
  auto add_vertex = [&](const Eigen::Vector3d& p, bool clump) {
    mesh.vertices_m.push_back(p);
    mesh.colors_rgb.push_back({0, 0, 0});
    points.positions_m.push_back(p);
    for (int k = 0; clump && k < 8; ++k) {
      const double angle = k * M_PI / 4;
      points.positions_m.push_back(p + 0.15 * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0));
    }
    return static_cast<uint32_t>(mesh.vertices_m.size() - 1);
  };
  auto grid = [](uint32_t i, uint32_t j) { return i + 20 * j; };
  const uint32_t ear = add_vertex({27.0, 2.5, -3.0}, false);
  mesh.faces.push_back({grid(19, 2), ear, grid(19, 3)});
  const uint32_t fan = add_vertex({26.0, 9.5, 0.0}, false);
  mesh.faces.push_back({grid(19, 9), fan, grid(19, 10)});
  mesh.faces.push_back({grid(19, 8), fan, grid(19, 9)});
  uint32_t south = grid(0, 14), north = grid(0, 15);
  constexpr int kArmQuads = 5;
  for (int q = 1; q <= kArmQuads; ++q) {
    const uint32_t s = add_vertex({-12.0 * q, 14.0, 0.0}, true), n = add_vertex({-12.0 * q, 15.0, 0.0}, true);
    mesh.faces.push_back({south, n, north});
    mesh.faces.push_back({south, s, n});
    south = s;
    north = n;
  }
  SurfaceTrimOptions options;
  options.far_factor = 0;  // as on the height-field path
  options.border_factor = 0;
  options.border_edge_factor = 0;
  options.spike_factor = 0;
  SurfaceTrimReport report;
  TriangleMesh out = TrimSurfaceToData(mesh, points, options, &report);
  EXPECT_EQ(report.ear_passes, options.max_ear_passes);
  const int64_t arm_cut = report.border_ears_cut - 3;  // the ear and the fan's two triangles go in the first pass
  EXPECT_GE(arm_cut, options.max_ear_passes);          // at least the tip triangle in every pass
  EXPECT_LE(arm_cut, 2 * options.max_ear_passes);      // at most the tip quad in every pass
  EXPECT_EQ(report.faces_out, static_cast<int64_t>(grid_faces + 2 * kArmQuads) - arm_cut);
  for (const auto& v : out.vertices_m) {
    EXPECT_LT(v.x(), 19.5) << "the ear or the fan is left: " << v.transpose();
    EXPECT_GT(v.x(), -12.0 * kArmQuads + 0.5) << "the arm's tip is left: " << v.transpose();
  }
  EXPECT_EQ(out.colors_rgb.size(), out.num_vertices());
  // Switched off, nothing is cut.
  options.max_ear_passes = 0;
  out = TrimSurfaceToData(mesh, points, options, &report);
  EXPECT_EQ(report.faces_out, static_cast<int64_t>(mesh.num_faces()));
  EXPECT_EQ(report.border_ears_cut, 0);
}

// The faces of a grid of vertices stored `rows` per column: two triangles per cell.
void AddGridFaces(TriangleMesh* mesh, uint32_t columns, uint32_t rows) {
  for (uint32_t c = 0; c + 1 < columns; ++c) {
    for (uint32_t k = 0; k + 1 < rows; ++k) {
      const uint32_t a = c * rows + k, b = a + rows;
      mesh->faces.push_back({a, b, b + 1});
      mesh->faces.push_back({a, b + 1, a + 1});
    }
  }
}

// Only step 4 (settle_factor 3, the Poisson path's), every other step off.
SurfaceTrimOptions SettleOnly() {
  SurfaceTrimOptions options;
  options.far_factor = options.border_factor = options.border_edge_factor = options.ear_edge_factor = 0;
  options.border_pull_factor = options.spike_factor = 0;
  options.settle_factor = 3;
  return options;
}

// Step 4: a surface bowed up to 1 m between points that lie on a plane (a sparse ground, 2 m apart) goes
// onto their plane; at a crease (a wall standing on the ground) the points lie on no one plane and the
// vertices there stay.
TEST(TrimSurfaceToData, SettlesABowedSurfaceOntoThePointsPlaneButNotAtACrease) {
  PointCloud points;
  for (int i = 0; i <= 20; ++i) {
    for (int j = 0; j <= 20; ++j) points.positions_m.emplace_back(2.0 * i, 2.0 * j, 0.1 * i);  // a 5.7 % slope
  }
  for (int j = 0; j <= 20; ++j) {
    for (int k = 1; k <= 5; ++k) points.positions_m.emplace_back(40.0, 2.0 * j, 4.0 + 2.0 * k);  // the wall
  }
  TriangleMesh mesh;
  const int n = 41;  // vertices every metre over the ground, bowed up by 1 m in the middle
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double x = i, y = j;
      mesh.vertices_m.emplace_back(x, y, 0.05 * x + std::sin(M_PI * x / 40) * std::sin(M_PI * y / 40));
    }
  }
  AddGridFaces(&mesh, n, n);
  SurfaceTrimOptions options = SettleOnly();
  SurfaceTrimReport report;
  const TriangleMesh out = TrimSurfaceToData(mesh, points, options, &report);
  ASSERT_EQ(out.num_faces(), mesh.num_faces());
  EXPECT_GT(report.settle_vertices_moved, 1000);
  EXPECT_NEAR(report.max_settle_move_m, 1.0, 0.05);
  for (const auto& v : out.vertices_m) {
    if (v.x() > 33) continue;  // within 3 spacings of the crease: the wall's points join the fit there
    EXPECT_NEAR(v.z(), 0.05 * v.x(), 1e-6) << v.transpose();
  }
  // Beside the wall the vertices kept their bow (a vertex 2 m from it, in the middle: 0.1 m of bow left).
  const Eigen::Vector3d& beside = out.vertices_m[38 * n + 20];
  EXPECT_GT(beside.z() - 0.05 * beside.x(), 0.1);
}

// A cliff's profile in (y, z): ground at z = 3 up to y = 15, the face up to z = 11, the plateau beyond.
// `fillet_m` > 0 rounds both edges (the foot concave, the top convex) with arcs of that radius, as a smooth
// surface does (0.44 m off the nearer plane at the arcs' middles). Sampled every `step_m` along the profile, from y = 5
// to y = 25.
std::vector<Eigen::Vector2d> CliffProfile(double fillet_m, double step_m) {
  const double r = fillet_m;
  std::vector<Eigen::Vector2d> path;  // dense polyline, then resampled
  for (double y = 5; y < 15 - r; y += 0.01) path.emplace_back(y, 3.0);
  for (double t = 0; r > 0 && t < M_PI / 2; t += 0.005)
    path.emplace_back(15 - r + r * std::sin(t), 3 + r - r * std::cos(t));
  for (double z = 3 + r; z < 11 - r; z += 0.01) path.emplace_back(15.0, z);
  for (double t = 0; r > 0 && t < M_PI / 2; t += 0.005)
    path.emplace_back(15 + r - r * std::cos(t), 11 - r + r * std::sin(t));
  for (double y = 15 + r; y <= 25; y += 0.01) path.emplace_back(y, 11.0);
  std::vector<Eigen::Vector2d> out{path.front()};
  double run = 0;
  for (size_t k = 1; k < path.size(); ++k) {
    run += (path[k] - path[k - 1]).norm();
    if (run >= step_m) {
      out.push_back(path[k]);
      run = 0;
    }
  }
  return out;
}

// The distance from (y, z) to the sharp profile.
double DistanceToCliff(const Eigen::Vector2d& q) {
  auto segment = [&](Eigen::Vector2d a, Eigen::Vector2d b) {
    const Eigen::Vector2d d = b - a;
    const double t = std::clamp((q - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
    return (q - (a + t * d)).norm();
  };
  return std::min({segment({5, 3}, {15, 3}), segment({15, 3}, {15, 11}), segment({15, 11}, {25, 11})});
}

// Step 4 with settle_creases: a surface whose cliff edges are rounded (arcs of 1.5 m, up to 0.44 m off
// the sharp profile, as Poisson rounds them) goes onto the two planes its points define at each edge, the foot's and
// the top's; without it, the rounded vertices stay (the points there lie on no one plane).
TEST(TrimSurfaceToData, SettlesARoundedCliffEdgeOntoItsTwoPlanes) {
  const std::vector<Eigen::Vector2d> rounded = CliffProfile(1.5, 0.5), sharp = CliffProfile(0, 0.5);
  const int columns = 21;  // x = 0 .. 10 every 0.5 m
  TriangleMesh mesh;
  for (int c = 0; c < columns; ++c) {
    for (const auto& q : rounded) mesh.vertices_m.emplace_back(0.5 * c, q.x(), q.y());
  }
  AddGridFaces(&mesh, columns, static_cast<uint32_t>(rounded.size()));
  PointCloud points;
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 0.02);
  for (int c = 0; c < columns; ++c) {
    for (const auto& q : sharp) {
      points.positions_m.emplace_back(0.5 * c + 0.25 + noise(rng), q.x() + noise(rng), q.y() + noise(rng));
    }
  }
  auto worst_and_share = [&](const TriangleMesh& m) {
    double worst_m = 0;
    int near = 0, measured = 0;
    for (const auto& v : m.vertices_m) {
      if (v.x() < 2 || v.x() > 8 || v.y() < 8 || v.y() > 22) continue;  // away from the sheet's borders
      const double d = DistanceToCliff({v.y(), v.z()});
      worst_m = std::max(worst_m, d);
      near += d <= 0.1;
      ++measured;
    }
    return std::make_pair(worst_m, static_cast<double>(near) / measured);
  };
  EXPECT_GT(worst_and_share(mesh).first, 0.4);  // r (1 - cos 45°) = 0.44 m at the arcs' middles
  SurfaceTrimOptions options = SettleOnly();
  SurfaceTrimReport report;
  const TriangleMesh plane_only = TrimSurfaceToData(mesh, points, options, &report);
  EXPECT_GT(worst_and_share(plane_only).first, 0.4);
  options.settle_creases = true;
  const TriangleMesh out = TrimSurfaceToData(mesh, points, options, &report);
  ASSERT_EQ(out.num_faces(), mesh.num_faces());
  const auto [worst_m, share] = worst_and_share(out);
  std::cerr << "rounded cliff: worst " << worst_m << " m, within 0.1 m " << share << "; "
            << report.settle_crease_vertices_moved << " vertices onto two planes\n";
  EXPECT_LT(worst_m, 0.15);
  EXPECT_GT(share, 0.95);
  EXPECT_GT(report.settle_crease_vertices_moved, 50);
}

TEST(FilterPoints, KeepsAnOutlierFreeTerrainAndSaysWhyItDropsPoints) {
  PointCloud cloud = testing::TerrainCloud(40, 40, 1.0);
  PointFilterReport report;
  PointCloud out = FilterPoints(cloud, PointFilterOptions{}, &report);
  EXPECT_EQ(report.removed_isolated + report.removed_off_plane, 0);
  EXPECT_EQ(out.size(), cloud.size());
  // One point 2 m above the ground, one 30 m away from everything.
  cloud.positions_m.push_back({20.3, 20.6, testing::TerrainHeightM(20.3, 20.6) + 2.0});
  cloud.positions_m.push_back({70, 70, 0});
  for (int i = 0; i < 2; ++i) {
    cloud.colors_rgb.push_back({0, 0, 0});
    cloud.reprojection_error_px.push_back(0.5);
    cloud.observers.push_back({0, 1, 2});
  }
  out = FilterPoints(cloud, PointFilterOptions{}, &report);
  EXPECT_EQ(report.removed_off_plane, 1);
  EXPECT_EQ(report.removed_isolated, 1);
  EXPECT_NEAR(report.max_off_plane_m, 2.0, 0.3);
  EXPECT_EQ(out.size(), cloud.size() - 2);
  EXPECT_EQ(report.ToJson()["criteria"]["neighbours"], 16);
}

// The same border check on the bundled Brighton Beach sample (the fixture copy of its
// default COLMAP model): every vertex of the output's border lies within one local point spacing
// of the data's border. A point is on the data's border when the directions (east, north) to its
// neighbours within three median spacings leave an empty sector wider than 90° (the angle criterion
// of PCL's BoundaryEstimation).
TEST(TrimSurfaceToData, BrightonBeachBorderStaysWithinOneSpacingOfThePointsBorder) {
  const ColmapModel model = ReadColmapModel(testing::TestDataDir() / "colmap" / "brighton_sparse_default");
  const auto refs = ReadReferencesFile(testing::TestDataDir() / "colmap" / "brighton_refs_gps.txt");
  ModelGeoreferenceOptions georeference;
  georeference.focal_prior_px[1] = 3.61 / 6.317 * 1600;  // EXIF: 3.61 mm on a 6.317 mm sensor, 1600 px
  const ModelGeoreference geo = GeoreferenceModel(model, refs, georeference);
  const PointCloud cloud = PointCloudFromModel(geo.model_enu);
  SurfacePipelineOptions options;
  options.quality = Quality::kDraft;
  options.report_times = false;
  const SurfacePipelineResult result = BuildSurfaceFromPoints(cloud, options);
  const PointCloud points = FilterPoints(cloud, PointFilterOptions{}, nullptr);  // what was surfaced

  // Local spacing (the trim step's: mean distance to the 6 nearest points) and the data's border.
  const size_t n = points.size();
  std::vector<double> spacing(n);
  std::vector<std::vector<std::pair<double, uint32_t>>> near(n);
  std::vector<std::pair<double, uint32_t>> all;
  for (size_t i = 0; i < n; ++i) {
    all.clear();
    for (uint32_t j = 0; j < n; ++j) {
      if (j != i) all.emplace_back((points.positions_m[j] - points.positions_m[i]).head<2>().norm(), j);
    }
    std::partial_sort(all.begin(), all.begin() + 6, all.end());
    double sum = 0;
    for (int m = 0; m < 6; ++m) sum += all[m].first;
    spacing[i] = sum / 6;
    for (const auto& a : all) {
      if (a.first < 20.0) near[i].push_back(a);  // wider than 3 median spacings (about 1 m here)
    }
  }
  std::vector<double> sorted = spacing;
  std::nth_element(sorted.begin(), sorted.begin() + n / 2, sorted.end());
  const double median_spacing_m = sorted[n / 2];
  std::vector<char> on_border(n, 0);
  for (size_t i = 0; i < n; ++i) {
    std::vector<double> angles;
    for (const auto& [d, j] : near[i]) {
      if (d > 3 * median_spacing_m) continue;
      const Eigen::Vector2d dir = (points.positions_m[j] - points.positions_m[i]).head<2>();
      angles.push_back(std::atan2(dir.y(), dir.x()));
    }
    std::sort(angles.begin(), angles.end());
    double gap = angles.empty() ? 2 * M_PI : 2 * M_PI - (angles.back() - angles.front());
    for (size_t m = 1; m < angles.size(); ++m) gap = std::max(gap, angles[m] - angles[m - 1]);
    on_border[i] = gap > M_PI / 2;
  }
  const std::vector<uint32_t> border = BorderVertices(result.mesh);
  ASSERT_GT(border.size(), 20u);
  size_t beyond = 0;
  double worst_ratio = 0;
  for (uint32_t b : border) {
    const Eigen::Vector2d p = result.mesh.vertices_m[b].head<2>();
    double best = INFINITY;
    for (size_t i = 0; i < n; ++i) {
      if (on_border[i]) best = std::min(best, (points.positions_m[i].head<2>() - p).norm() / spacing[i]);
    }
    worst_ratio = std::max(worst_ratio, best);
    if (best > 1.0) ++beyond;  // measured 2026-11-26: every one is a point of the data's border (0)
  }
  std::cerr << DumpJson(*FindStep(result.report, "filter_points")) << DumpJson(*FindStep(result.report, "trim"));
  std::cerr << "Brighton: " << border.size() << " border vertices, " << beyond
            << " farther than one local spacing from the points' border (worst " << worst_ratio
            << " spacings); median spacing " << median_spacing_m << " m\n";
  EXPECT_EQ(beyond, 0u);

  // No stretched ear is left: a face with two edges on the border whose longest edge exceeds 4 local
  // spacings (the spacing of the point nearest each corner; the largest of the three). The sample had
  // one, 10.4 m long, hanging from the arm of points over the water.
  std::map<std::pair<uint32_t, uint32_t>, int> edge_uses;
  for (const auto& f : result.mesh.faces) {
    for (int k = 0; k < 3; ++k) ++edge_uses[std::minmax(f[k], f[(k + 1) % 3])];
  }
  auto corner_spacing = [&](const Eigen::Vector3d& q) {
    size_t best = 0;
    for (size_t i = 1; i < n; ++i) {
      if ((points.positions_m[i] - q).squaredNorm() < (points.positions_m[best] - q).squaredNorm()) best = i;
    }
    return spacing[best];
  };
  double worst_ear_ratio = 0;
  for (const auto& f : result.mesh.faces) {
    int open = 0;
    double longest = 0, s = 0;
    for (int k = 0; k < 3; ++k) {
      open += edge_uses[std::minmax(f[k], f[(k + 1) % 3])] == 1;
      longest = std::max(longest, (result.mesh.vertices_m[f[k]] - result.mesh.vertices_m[f[(k + 1) % 3]]).norm());
      s = std::max(s, corner_spacing(result.mesh.vertices_m[f[k]]));
    }
    if (open >= 2) worst_ear_ratio = std::max(worst_ear_ratio, longest / s);
  }
  std::cerr << "Brighton: the most stretched ear left is " << worst_ear_ratio << " local spacings long\n";
  EXPECT_LT(worst_ear_ratio, 4.0);
}

}  // namespace
}  // namespace cinepath::photogrammetry
