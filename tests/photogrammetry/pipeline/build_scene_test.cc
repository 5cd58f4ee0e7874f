// BuildScene with a dense cloud (`--points`) or a mesh (`--mesh`) given in the COLMAP model's frame: the
// input is carried into ENU by the affine map the sparse model's points fit (photogrammetry/pipeline/
// build_scene.cc, FitAffineBetweenModels), and lands where the georeferenced sparse points are.
#include "photogrammetry/pipeline/build_scene.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>

#include "core/error.h"
#include "photogrammetry/io/colmap_reader.h"
#include "tests/photogrammetry/test_paths.h"

namespace cinepath::photogrammetry {
namespace {

namespace fs = std::filesystem;

fs::path Brighton6() { return testing::TestDataDir() / "photogrammetry" / "brighton6_colmap"; }

SceneBuildOptions Brighton6Options() {
  SceneBuildOptions options;
  options.colmap_dir = (Brighton6() / "sparse").string();
  options.refs_path = (Brighton6() / "refs_gps.txt").string();
  options.texture = false;
  options.timestamps = false;
  return options;
}

std::vector<Eigen::Vector3d> ModelPoints(const ColmapModel& model) {
  std::vector<Eigen::Vector3d> points;
  for (const auto& [id, p] : model.points3d) {
    if (p.track.size() >= 2) points.push_back(p.xyz);
  }
  return points;
}

// An ASCII PLY: the vertices, and the triangles when there are any.
void WritePly(const fs::path& path, const std::vector<Eigen::Vector3d>& vertices,
              const std::vector<Eigen::Vector3i>& triangles) {
  std::ofstream out(path);
  out << "ply\nformat ascii 1.0\nelement vertex " << vertices.size()
      << "\nproperty double x\nproperty double y\nproperty double z\n";
  if (!triangles.empty()) out << "element face " << triangles.size() << "\nproperty list uchar int vertex_indices\n";
  out << "end_header\n";
  out.precision(17);
  for (const auto& v : vertices) out << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
  for (const auto& t : triangles) out << "3 " << t.x() << ' ' << t.y() << ' ' << t.z() << '\n';
}

// The sparse-only scene's bounding box, the reference where a dense input must land.
struct Box {
  Eigen::Vector3d min, max;
};
Box OutputBox(const Json& scene) {
  const auto& out = scene["surface"]["output"];
  Box b;
  for (int k = 0; k < 3; ++k) {
    b.min[k] = out["bbox_min_m"][k].get<double>();
    b.max[k] = out["bbox_max_m"][k].get<double>();
  }
  return b;
}

TEST(BuildScene, ADenseCloudInTheModelsFrameLandsOnTheSparseScene) {
  const fs::path tmp = fs::temp_directory_path() / "cinepath_build_scene_points";
  fs::create_directories(tmp);
  const ColmapModel model = ReadColmapModel(Brighton6() / "sparse");
  WritePly(tmp / "dense.ply", ModelPoints(model), {});

  const Box sparse = OutputBox(BuildScene(Brighton6Options()).scene);
  SceneBuildOptions options = Brighton6Options();
  options.points_path = (tmp / "dense.ply").string();
  const Json scene = BuildScene(options).scene;
  const double rms_m = scene["input"]["enu_from_input_affine_rms_m"].get<double>();
  std::printf("dense input: affine rms %.4f m\n", rms_m);
  EXPECT_LT(rms_m, 0.5);
  EXPECT_FALSE(scene["input"].contains("enu_from_input_similarity_only"));
  // The same points as the sparse run: the surface stands where it stood, within a metre.
  const Box dense = OutputBox(scene);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(dense.min[k], sparse.min[k], 1.0) << "axis " << k;
    EXPECT_NEAR(dense.max[k], sparse.max[k], 1.0) << "axis " << k;
  }
  fs::remove_all(tmp);
}

TEST(BuildScene, AMeshInTheModelsFrameLandsOnTheSparseScene) {
  // A 6 x 6 grid on the plane of the model's points (its two widest directions), over their extent.
  const fs::path tmp = fs::temp_directory_path() / "cinepath_build_scene_mesh";
  fs::create_directories(tmp);
  const std::vector<Eigen::Vector3d> points = ModelPoints(ReadColmapModel(Brighton6() / "sparse"));
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : points) mean += p;
  mean /= double(points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const auto& p : points) covariance += (p - mean) * (p - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> axes(covariance);
  const Eigen::Vector3d u = axes.eigenvectors().col(2), v = axes.eigenvectors().col(1);
  double u_lo = 0, u_hi = 0, v_lo = 0, v_hi = 0;
  for (const auto& p : points) {
    u_lo = std::min(u_lo, (p - mean).dot(u)), u_hi = std::max(u_hi, (p - mean).dot(u));
    v_lo = std::min(v_lo, (p - mean).dot(v)), v_hi = std::max(v_hi, (p - mean).dot(v));
  }
  const int n = 6;
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      vertices.push_back(mean + (u_lo + (u_hi - u_lo) * i / (n - 1)) * u + (v_lo + (v_hi - v_lo) * j / (n - 1)) * v);
    }
  }
  for (int j = 0; j + 1 < n; ++j) {
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i;
      triangles.emplace_back(a, a + 1, a + n + 1);
      triangles.emplace_back(a, a + n + 1, a + n);
    }
  }
  WritePly(tmp / "mesh.ply", vertices, triangles);

  const Box sparse = OutputBox(BuildScene(Brighton6Options()).scene);
  SceneBuildOptions options = Brighton6Options();
  options.mesh_path = (tmp / "mesh.ply").string();
  const Json scene = BuildScene(options).scene;
  EXPECT_LT(scene["input"]["enu_from_input_affine_rms_m"].get<double>(), 0.5);
  // The plane through the points: in ENU it spans the sparse scene's extent, at its heights.
  const Box mesh = OutputBox(scene);
  std::printf("mesh input: bbox [%.1f %.1f %.1f]-[%.1f %.1f %.1f], sparse [%.1f %.1f %.1f]-[%.1f %.1f %.1f]\n",
              mesh.min.x(), mesh.min.y(), mesh.min.z(), mesh.max.x(), mesh.max.y(), mesh.max.z(), sparse.min.x(),
              sparse.min.y(), sparse.min.z(), sparse.max.x(), sparse.max.y(), sparse.max.z());
  for (int k = 0; k < 2; ++k) {
    EXPECT_LT(mesh.min[k], sparse.min[k] + 10) << "axis " << k;
    EXPECT_GT(mesh.max[k], sparse.max[k] - 10) << "axis " << k;
  }
  EXPECT_GT(mesh.max.z(), sparse.min.z() - 2);
  EXPECT_LT(mesh.min.z(), sparse.max.z() + 2);
  fs::remove_all(tmp);
}

}  // namespace
}  // namespace cinepath::photogrammetry
