// scene.glb as `cinepath mesh` writes it (photogrammetry/gltf/gltf_writer.h), plain and Draco, read back.
#include <gtest/gtest.h>

#include "photogrammetry/gltf/gltf_writer.h"
#include "scene/glb_reader.h"

namespace cinepath::scene {
namespace {

photogrammetry::TriangleMesh Terrain() {
  photogrammetry::TriangleMesh m;
  const int n = 20;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      m.vertices_m.emplace_back(i * 2.5 - 25, j * 2.5 - 25, -38 + 0.1 * i);
      m.colors_rgb.push_back({static_cast<uint8_t>(10 * i), static_cast<uint8_t>(10 * j), 128});
    }
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      m.faces.push_back({a, b, d});
      m.faces.push_back({a, d, c});
    }
  }
  return m;
}

void ExpectSameMesh(const photogrammetry::TriangleMesh& written, const SceneMesh& read, double tolerance_m) {
  ASSERT_EQ(read.num_faces(), written.num_faces());
  ASSERT_EQ(read.num_vertices(), written.num_vertices());
  ASSERT_TRUE(read.has_colors());
  // Draco reorders points and faces: every written vertex has a read one within the tolerance, and
  // the surface area is the same.
  for (const Eigen::Vector3d& a : written.vertices_m) {
    double best = 1e9;
    for (const Eigen::Vector3d& b : read.positions_enu_m) best = std::min(best, (a - b).norm());
    ASSERT_LT(best, tolerance_m);
  }
  auto area = [](const auto& positions, const auto& faces) {
    double total = 0;
    for (const auto& f : faces)
      total += 0.5 * (positions[f[1]] - positions[f[0]]).cross(positions[f[2]] - positions[f[0]]).norm();
    return total;
  };
  EXPECT_NEAR(area(read.positions_enu_m, read.faces), area(written.vertices_m, written.faces), 1e-3);
  // COLOR_0 is linear: sRGB 128 -> 0.2158.
  for (const Eigen::Vector3f& c : read.colors_linear) ASSERT_NEAR(c.z(), 0.21586, 2e-3);
}

TEST(GlbRoundTrip, PlainGlb) {
  const photogrammetry::TriangleMesh m = Terrain();
  ExpectSameMesh(m, ReadGlbBytes(photogrammetry::WriteGlb(m, {}), "plain.glb"), 1e-5);
}

TEST(GlbRoundTrip, DracoGlbDecodesWithinTheQuantization) {
  const photogrammetry::TriangleMesh m = Terrain();
  photogrammetry::GlbWriteOptions options;
  options.draco = true;
  // 16-bit positions over a 50 m box: 50 / 65535 = 0.8 mm steps.
  ExpectSameMesh(m, ReadGlbBytes(photogrammetry::WriteGlb(m, options), "draco.glb"), 2e-3);
}

}  // namespace
}  // namespace cinepath::scene
