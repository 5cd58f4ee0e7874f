#include "photogrammetry/texture_view_selection.h"

#include <random>

#include <gtest/gtest.h>

#include "scene/ray_caster.h"
#include "texture_test_scenes.h"

namespace cinepath::photogrammetry {
namespace {

using testing::Camera;
using testing::GroundGrid;
using testing::LookAtImage;
using testing::NadirImage;

scene::SceneMesh AsScene(const TriangleMesh& mesh) {
  scene::SceneMesh s;
  s.positions_enu_m = mesh.vertices_m;
  s.faces = mesh.faces;
  return s;
}

const ColmapCamera kCamera = Camera(int(CameraModelId::kPinhole), {500, 500, 400, 300}, 800, 600);

TEST(TextureViewSelection, PrefersTheCloserAndTheMoreFrontalView) {
  const TriangleMesh mesh = GroundGrid(8, 1.0);
  const scene::RayCaster caster(AsScene(mesh));
  const std::vector<TextureView> views = {
      TextureView(NadirImage({4, 4, 40}, "far"), kCamera),
      TextureView(LookAtImage({4, -8, 8}, {4, 4, 0}, "oblique"), kCamera),
      TextureView(NadirImage({4, 4, 12}, "close"), kCamera),
  };
  ViewSelectionOptions options;
  options.smoothing_iterations = 0;
  const ViewSelection s = SelectViews(mesh, views, caster, options);
  EXPECT_EQ(s.faces_seen, int64_t(mesh.num_faces()));
  for (size_t f = 0; f < mesh.num_faces(); ++f) {
    ASSERT_EQ(s.candidates[f].size(), 3u) << f;
    EXPECT_EQ(s.label[f], 2) << f;
    // The oblique view (about as close) scores below the close nadir one, the far view lowest.
    EXPECT_GT(s.candidates[f][2].quality, s.candidates[f][1].quality);
    EXPECT_GT(s.candidates[f][2].quality, s.candidates[f][0].quality);
  }
}

TEST(TextureViewSelection, AnOccludedFaceIsNotTexturedFromTheCameraThatCannotSeeIt) {
  // Ground 8 x 8 m, and a 2 x 2 m roof 3 m above its middle; a close camera straight above the roof and
  // a farther one off to the side that sees under it.
  TriangleMesh mesh = GroundGrid(8, 1.0);
  const TriangleMesh roof = GroundGrid(2, 1.0, 3.0, 3.0, 3.0);
  const uint32_t base = uint32_t(mesh.num_vertices());
  const size_t ground_faces = mesh.num_faces();
  for (const auto& v : roof.vertices_m) mesh.vertices_m.push_back(v);
  for (const auto& c : roof.colors_rgb) mesh.colors_rgb.push_back(c);
  for (const auto& f : roof.faces) mesh.faces.push_back({f[0] + base, f[1] + base, f[2] + base});
  const scene::RayCaster caster(AsScene(mesh));
  const std::vector<TextureView> views = {TextureView(NadirImage({4, 4, 10}, "above"), kCamera),
                                          TextureView(LookAtImage({4, -14, 6}, {4, 4, 0}, "side"), kCamera)};
  const ViewSelection s = SelectViews(mesh, views, caster);
  int under_roof = 0;
  for (size_t f = 0; f < ground_faces; ++f) {
    const auto& t = mesh.faces[f];
    const Eigen::Vector3d c = (mesh.vertices_m[t[0]] + mesh.vertices_m[t[1]] + mesh.vertices_m[t[2]]) / 3;
    const bool hidden_from_above = c.x() > 3 && c.x() < 5 && c.y() > 3 && c.y() < 5;
    if (!hidden_from_above) continue;
    ++under_roof;
    EXPECT_NE(s.label[f], 0) << f;
    for (const FaceView& v : s.candidates[f]) EXPECT_NE(v.view, 0) << f;
  }
  EXPECT_EQ(under_roof, 8);
  // The roof itself and the open ground are textured from above.
  EXPECT_EQ(s.label[ground_faces], 0);
  EXPECT_EQ(s.label[0], 0);
}

TEST(TextureViewSelection, SmoothingRemovesIsolatedSwitchesAndCountsSeams) {
  // Two nadir views at nearly the same place over a bumpy ground: which is the more frontal flips from
  // face to face by a hair; smoothing merges the faces into fewer, larger charts.
  TriangleMesh mesh = GroundGrid(12, 1.0);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> bump(-0.15, 0.15);
  for (auto& v : mesh.vertices_m) v.z() += bump(rng);
  const scene::RayCaster caster(AsScene(mesh));
  const std::vector<TextureView> views = {TextureView(NadirImage({5.9, 6, 20}, "a"), kCamera),
                                          TextureView(NadirImage({6.1, 6, 20}, "b"), kCamera)};
  ViewSelectionOptions options;
  const ViewSelection s = SelectViews(mesh, views, caster, options);
  EXPECT_GT(s.seam_edges_before, 0);
  EXPECT_LT(s.seam_edges_after, s.seam_edges_before / 2);
  EXPECT_GE(s.iterations_run, 1);
}

}  // namespace
}  // namespace cinepath::photogrammetry
