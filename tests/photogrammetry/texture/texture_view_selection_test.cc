#include "photogrammetry/texture/texture_view_selection.h"

#include <random>

#include <gtest/gtest.h>

#include "photogrammetry/io/photo_image.h"
#include "scene/ray_caster.h"
#include "tests/photogrammetry/texture_test_scenes.h"

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

// Four photos of a wall-like ground; the closest (the best by quality) has a "tree" in front of the middle
// 4 x 4 m that the mesh does not hold. Occlusion by the mesh cannot see it; the photo-consistency check
// does: no face under the tree is textured from that photo, and every face outside it still may be.
TEST(TextureViewSelection, APhotoThatDisagreesWithTheOthersDoesNotTextureTheFace) {
  const TriangleMesh mesh = GroundGrid(8, 1.0);
  const scene::RayCaster caster(AsScene(mesh));
  const std::vector<ColmapImage> images = {NadirImage({4, 4, 10}, "tree"), NadirImage({2, 3, 16}, "a"),
                                           NadirImage({6, 5, 16}, "b"), NadirImage({4, 2, 18}, "c")};
  const auto in_tree = [](const Eigen::Vector3d& p) { return p.x() > 2 && p.x() < 6 && p.y() > 2 && p.y() < 6; };
  std::vector<TextureView> views;
  std::vector<RgbImage> photos;
  for (size_t i = 0; i < images.size(); ++i) {
    views.emplace_back(images[i], kCamera);
    photos.push_back(testing::RenderPlanePhoto(images[i], kCamera, 0.0, [&](const Eigen::Vector3d& p) {
      if (i == 0 && in_tree(p)) return Eigen::Vector3f(40, 110, 30);  // foliage
      return testing::Checker(p);
    }));
  }
  const FaceColorFn face_color = [&](uint32_t f, int v, Eigen::Vector3f* rgb) {
    const auto& t = mesh.faces[f];
    const Eigen::Vector3d c = (mesh.vertices_m[t[0]] + mesh.vertices_m[t[1]] + mesh.vertices_m[t[2]]) / 3;
    Eigen::Vector2d px;
    if (!views[size_t(v)].Project(c, &px)) return false;
    *rgb = SampleLinear(photos[size_t(v)], px.x(), px.y());
    return true;
  };
  ViewSelectionOptions options;
  options.smoothing_iterations = 0;
  const ViewSelection without = SelectViews(mesh, views, caster, options);
  const ViewSelection with = SelectViews(mesh, views, caster, options, &face_color);
  int under_tree = 0;
  for (size_t f = 0; f < mesh.num_faces(); ++f) {
    const auto& t = mesh.faces[f];
    const Eigen::Vector3d c = (mesh.vertices_m[t[0]] + mesh.vertices_m[t[1]] + mesh.vertices_m[t[2]]) / 3;
    ASSERT_EQ(without.candidates[f].size(), 4u) << f;
    EXPECT_EQ(without.label[f], 0) << f;  // the closest photo wins everywhere on quality alone
    if (in_tree(c)) {
      ++under_tree;
      EXPECT_NE(with.label[f], 0) << f;
      EXPECT_EQ(with.candidates[f].size(), 3u) << f;
    } else {
      EXPECT_EQ(with.candidates[f].size(), 4u) << f;
      EXPECT_EQ(with.label[f], 0) << f;
    }
  }
  EXPECT_EQ(under_tree, 32);
  EXPECT_EQ(with.views_inconsistent, 32);
  EXPECT_EQ(with.faces_with_inconsistent_views, 32);
}

// With two photos there is no majority: nothing is dropped, whatever they show.
TEST(TextureViewSelection, TwoDisagreeingPhotosAreBothKept) {
  std::vector<FaceView> candidates = {{0, 1.0f}, {1, 1.0f}};
  const FaceColorFn face_color = [](uint32_t, int v, Eigen::Vector3f* rgb) {
    *rgb = v == 0 ? Eigen::Vector3f(0.9f, 0.9f, 0.9f) : Eigen::Vector3f(0.0f, 0.3f, 0.0f);
    return true;
  };
  EXPECT_EQ(RemoveInconsistentViews(0, &candidates, face_color, PhotoConsistencyOptions{}), 0);
  EXPECT_EQ(candidates.size(), 2u);
}

}  // namespace
}  // namespace cinepath::photogrammetry
