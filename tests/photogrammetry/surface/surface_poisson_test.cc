#include "photogrammetry/surface/surface_poisson.h"

#include <cmath>
#include <csignal>
#include <random>
#include <vector>

#include <thread>

#include <CGAL/Random.h>
#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "core/error.h"
#include "tests/photogrammetry/surface_test_meshes.h"

namespace cinepath::photogrammetry {
namespace {

// Points on a sphere (Fibonacci lattice) of radius r about c, seen by 6 cameras outside it.
PointCloud SphereCloud(int n, double r, const Eigen::Vector3d& c) {
  PointCloud cloud;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / n;
    const double rho = std::sqrt(1.0 - z * z);
    cloud.positions_m.push_back(c + r * Eigen::Vector3d(rho * std::cos(golden * i), rho * std::sin(golden * i), z));
    cloud.colors_rgb.push_back({static_cast<uint8_t>(z > 0 ? 250 : 10), 100, 100});
  }
  for (int axis = 0; axis < 3; ++axis) {
    for (double s : {-1.0, 1.0}) {
      Eigen::Vector3d d = Eigen::Vector3d::Zero();
      d[axis] = s * 5 * r;
      cloud.camera_centers_m.push_back(c + d);
    }
  }
  // Each point is observed by the cameras on its side.
  for (const auto& p : cloud.positions_m) {
    std::vector<uint32_t> seen;
    for (uint32_t k = 0; k < cloud.camera_centers_m.size(); ++k) {
      if ((cloud.camera_centers_m[k] - c).dot(p - c) > 0) seen.push_back(k);
    }
    cloud.observers.push_back(seen);
  }
  return cloud;
}

double SignedVolume(const TriangleMesh& mesh) {
  double v = 0;
  for (const auto& f : mesh.faces) {
    v += mesh.vertices_m[f[0]].dot(mesh.vertices_m[f[1]].cross(mesh.vertices_m[f[2]])) / 6.0;
  }
  return v;
}

TEST(PoissonSurface, ReconstructsASphereOrientedOutwardFromEstimatedNormals) {
  const Eigen::Vector3d center(10, 20, 5);
  const PointCloud cloud = SphereCloud(3000, 4.0, center);
  PoissonReport report;
  TriangleMesh mesh = PoissonSurface(cloud, PoissonOptions{}, &report);
  EXPECT_TRUE(report.normals_estimated);
  EXPECT_EQ(report.points, 3000);
  EXPECT_GT(mesh.num_faces(), 500u);
  for (const auto& v : mesh.vertices_m) EXPECT_NEAR((v - center).norm(), 4.0, 0.2);
  // Outward normals: a closed surface's signed volume about the centre is +4/3 π r³.
  for (auto& v : mesh.vertices_m) v -= center;
  EXPECT_NEAR(SignedVolume(mesh), 4.0 / 3.0 * M_PI * 64.0, 0.1 * 4.0 / 3.0 * M_PI * 64.0);
  ASSERT_EQ(mesh.colors_rgb.size(), mesh.num_vertices());
}

// The same bytes whatever state CGAL's default random generator is in (it is seeded from the wall clock)
// and on another thread (where it is a fresh, clock-seeded generator).
TEST(PoissonSurface, SameMeshWhateverTheRandomStateAndThread) {
  const PointCloud cloud = SphereCloud(2000, 3.0, Eigen::Vector3d(1, 2, 3));
  CGAL::get_default_random() = CGAL::Random(1);
  const TriangleMesh a = PoissonSurface(cloud, PoissonOptions{}, nullptr);
  CGAL::get_default_random() = CGAL::Random(987654321);
  const TriangleMesh b = PoissonSurface(cloud, PoissonOptions{}, nullptr);
  TriangleMesh c;
  std::thread([&] { c = PoissonSurface(cloud, PoissonOptions{}, nullptr); }).join();
  ASSERT_GT(a.num_faces(), 100u);
  for (const TriangleMesh* other : std::vector<const TriangleMesh*>{&b, &c}) {
    ASSERT_EQ(other->num_faces(), a.num_faces());
    ASSERT_EQ(other->num_vertices(), a.num_vertices());
    EXPECT_TRUE(other->faces == a.faces);
    for (size_t i = 0; i < a.num_vertices(); ++i) ASSERT_EQ(other->vertices_m[i], a.vertices_m[i]) << i;
  }
}

// The same bytes whatever the heap looks like: CGAL orders its triangulations' handles by address
// unless told otherwise, and where a block lands depends on what was allocated and freed before (in
// a real run: by the threads of every parallel step, in whatever order they were scheduled). Each
// round leaves the heap with another pattern of holes and live blocks before reconstructing.
// (The L of two planes: a sphere's surface came out the same from any heap even before.)
TEST(PoissonSurface, SameMeshWhateverTheHeapLooksLike) {
  const PointCloud cloud = testing::LCloud();
  const TriangleMesh first = PoissonSurface(cloud, PoissonOptions{}, nullptr);
  ASSERT_GT(first.num_faces(), 100u);
  std::vector<std::vector<char>> kept;
  for (unsigned round = 1; round <= 4; ++round) {
    SCOPED_TRACE(round);
    std::mt19937 rng(round);
    std::vector<std::vector<char>> blocks;
    for (int i = 0; i < 3000; ++i) blocks.emplace_back(16 + rng() % 40000);
    for (size_t i = 0; i < blocks.size(); ++i) {
      if (rng() % 3 == 0) kept.push_back(std::move(blocks[i]));  // some stay alive across the call
    }
    blocks.clear();  // the rest leave holes
    const TriangleMesh again = PoissonSurface(cloud, PoissonOptions{}, nullptr);
    ASSERT_EQ(again.num_faces(), first.num_faces());
    ASSERT_EQ(again.num_vertices(), first.num_vertices());
    EXPECT_TRUE(again.faces == first.faces);
    for (size_t i = 0; i < first.num_vertices(); ++i) ASSERT_EQ(again.vertices_m[i], first.vertices_m[i]) << i;
  }
}

TEST(PoissonSurface, NormalsFlippedInTheInputAreTurnedTowardTheCameras) {
  const Eigen::Vector3d center(0, 0, 0);
  PointCloud cloud = SphereCloud(2000, 3.0, center);
  for (const auto& p : cloud.positions_m) cloud.normals.push_back(-(p - center).normalized());
  PoissonReport report;
  const TriangleMesh mesh = PoissonSurface(cloud, PoissonOptions{}, &report);
  EXPECT_FALSE(report.normals_estimated);
  EXPECT_EQ(report.normals_flipped_toward_cameras, 2000);
  EXPECT_GT(SignedVolume(mesh), 0.0);
}

TEST(PoissonSurface, TrimsTheSurfaceFarFromThePoints) {
  // A hemisphere of points: Poisson closes it; trimming removes the invented lower half.
  PointCloud cloud = SphereCloud(4000, 3.0, Eigen::Vector3d::Zero());
  PointCloud upper;
  upper.camera_centers_m = cloud.camera_centers_m;
  for (size_t i = 0; i < cloud.size(); ++i) {
    if (cloud.positions_m[i].z() < 0.3) continue;
    upper.positions_m.push_back(cloud.positions_m[i]);
    upper.observers.push_back(cloud.observers[i]);
  }
  PoissonReport report;
  const TriangleMesh mesh = PoissonSurface(upper, PoissonOptions{}, &report);
  EXPECT_GT(report.faces_trimmed, 0);
  for (const auto& v : mesh.vertices_m) EXPECT_GT(v.z(), -1.0);
}

TEST(PoissonSurface, RejectsTinyClouds) {
  PointCloud cloud;
  for (int i = 0; i < 5; ++i) cloud.positions_m.emplace_back(i, i * i, 0);
  EXPECT_THROW(PoissonSurface(cloud, PoissonOptions{}, nullptr), InputError);
}

// Clouds that span no volume: CGAL's Poisson solver, called on them, fails a precondition (a plane),
// reads outside its triangulation (a line, one point: SIGSEGV, measured with CGAL 5.5) or divides by zero.
// They are refused before the solver is called, with the cause named.
PointCloud FlatCloud(int dimension) {
  PointCloud cloud;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-10, 10);
  for (int i = 0; i < 200; ++i) {
    const double x = u(rng), y = u(rng);
    if (dimension == 0) cloud.positions_m.emplace_back(1.5, -2.5, 3.0);
    if (dimension == 1) cloud.positions_m.emplace_back(x, 2 * x + 1, -x);
    // A tilted plane, exactly representable: z = x + 2y with x, y multiples of 1/8.
    if (dimension == 2) {
      const double a = std::round(8 * x) / 8, b = std::round(8 * y) / 8;
      cloud.positions_m.emplace_back(a, b, a + 2 * b);
    }
    cloud.normals.emplace_back(0, 0, 1);
  }
  return cloud;
}

TEST(PoissonSurface, CloudsThatSpanNoVolumeAreRefusedBeforeTheSolver) {
  const char* expected[] = {"coincide", "one line", "one plane"};
  for (int dimension = 0; dimension < 3; ++dimension) {
    const PointCloud cloud = FlatCloud(dimension);
    const auto problem = PoissonInputProblem(cloud);
    ASSERT_TRUE(problem.has_value()) << dimension;
    EXPECT_NE(problem->find(expected[dimension]), std::string::npos) << *problem;
    try {
      PoissonSurface(cloud, PoissonOptions{}, nullptr);
      ADD_FAILURE() << "no error for dimension " << dimension;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(expected[dimension]), std::string::npos) << e.what();
    }
  }
}

TEST(PoissonSurface, APlaneOffByOneMillimetreIsAVolume) {
  PointCloud cloud = FlatCloud(2);
  cloud.positions_m[17].z() += 1e-3;
  EXPECT_FALSE(PoissonInputProblem(cloud).has_value());
  EXPECT_FALSE(PoissonInputProblem(SphereCloud(100, 2.0, Eigen::Vector3d(1, 2, 3))).has_value());
}

// Bug 2026-11-27: `cinepath mesh` died of SIGFPE inside CGAL's Poisson refinement on the oblique house
// (COLMAP left 191 points twice, and some 4e-16 m apart), and on facade photos. Two points a few ulps
// apart make cells whose rounded circumcentre falls outside their own sphere; CGAL's refinement inserts it
// anyway, corrupts its triangulation and divides by zero in an exact circumcentre (surface_poisson.h,
// MergeCoincidentPoints). A small noisy ground of 100 points (a hash, no random generator: the same
// doubles everywhere) with one point repeated 1 ulp away, in six variants: CGAL 5.5 divides by zero on
// variants 1 and 5.
PointCloud GroundWithANearDuplicate(int variant) {
  auto hash = [](double x) {
    const double h = std::sin(x) * 43758.5453;
    return h - std::floor(h);
  };
  PointCloud cloud;
  for (int i = 0; i < 100; ++i) {
    const double x = 20 * hash(i * 12.9898 + variant) - 10, y = 20 * hash(i * 78.233 + variant) - 10;
    cloud.positions_m.emplace_back(x, y, -28 + 0.02 * (hash(i * 39.346) - 0.5));
    cloud.normals.emplace_back(0, 0, 1);
  }
  const Eigen::Vector3d p = cloud.positions_m[37];
  cloud.positions_m.emplace_back(std::nextafter(p.x(), INFINITY), p.y(), p.z());
  cloud.normals.emplace_back(0, 0, 1);
  return cloud;
}

TEST(PoissonSurfaceDeathTest, PointsOneUlpApartMadeCgalDivideByZero) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  PoissonOptions unguarded;
  unguarded.coincident_distance_ratio = 0;
  auto run = [&] {
    for (int variant = 0; variant < 6; ++variant) PoissonSurface(GroundWithANearDuplicate(variant), unguarded, nullptr);
  };
#if !defined(NDEBUG) && !defined(CGAL_NDEBUG)
  // A build with CGAL's own assertions (make sanitize) stops at the corrupted triangulation before the
  // division: the same input, refused one step earlier.
  try {
    run();
    ADD_FAILURE() << "CGAL's assertions let the corrupted triangulation through";
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("surface mesher failed"), std::string::npos) << e.what();
  }
#elif defined(__SANITIZE_ADDRESS__)
  EXPECT_DEATH(run(), "FPE");  // AddressSanitizer reports the signal itself
#else
  EXPECT_EXIT(run(), ::testing::KilledBySignal(SIGFPE), "");  // GMP's division by zero raises SIGFPE
#endif
}

TEST(PoissonSurface, PointsOneUlpApartAreMergedAndTheSolverRuns) {
  for (int variant = 0; variant < 6; ++variant) {
    PoissonReport report;
    const TriangleMesh mesh = PoissonSurface(GroundWithANearDuplicate(variant), PoissonOptions{}, &report);
    EXPECT_GT(mesh.num_faces(), 0u) << variant;
    EXPECT_EQ(report.coincident_points_merged, 1) << variant;
    EXPECT_EQ(report.points, 100) << variant;
    EXPECT_GT(report.coincident_distance_m, 0) << variant;
    EXPECT_LT(report.coincident_distance_m, 1e-3) << variant;
  }
}

TEST(MergeCoincidentPoints, EachPointWithinTheToleranceOfAnEarlierOneGoesToIt) {
  const std::vector<Eigen::Vector3d> p = {{0, 0, 0}, {1, 0, 0}, {0, 0, 0}, {1e-7, 0, 0}, {1, 1e-5, 0}, {5, 5, 5}};
  const std::vector<uint32_t> into = MergeCoincidentPoints(p, 1e-6);
  EXPECT_EQ(into, (std::vector<uint32_t>{0, 1, 0, 0, 4, 5}));
  EXPECT_EQ(MergeCoincidentPoints(p, 0), (std::vector<uint32_t>{0, 1, 2, 3, 4, 5}));
}

}  // namespace
}  // namespace cinepath::photogrammetry
