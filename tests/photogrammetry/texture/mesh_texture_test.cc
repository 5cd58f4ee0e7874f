#include "photogrammetry/texture/mesh_texture.h"

#include <cmath>

#include <gtest/gtest.h>

#include "photogrammetry/gltf/gltf_writer.h"
#include "scene/glb_reader.h"
#include "tests/photogrammetry/texture_test_scenes.h"

namespace cinepath::photogrammetry {
namespace {

using testing::Camera;
using testing::Checker;
using testing::GroundGrid;
using testing::NadirImage;
using testing::RenderPlanePhoto;

// PSNR (dB) of the atlas against the ground's true colours, over the texels of textured faces whose
// centre lies more than `edge_m` from a square's border (the photo blurs the borders at its own scale).
double AtlasPsnr(const TexturedMesh& t, double edge_m) {
  double sum = 0;
  int64_t n = 0;
  const double size = t.atlas.width;
  for (const auto& face : t.mesh.faces) {
    if (t.mesh.colors_rgb[face[0]][0] != 255) continue;  // a vertex-colour face
    Eigen::Vector2d uv[3];
    for (int k = 0; k < 3; ++k) uv[k] = t.texcoords[face[k]].cast<double>() * size;
    const double det = (uv[1] - uv[0]).x() * (uv[2] - uv[0]).y() - (uv[1] - uv[0]).y() * (uv[2] - uv[0]).x();
    const int x0 = int(std::floor(std::min({uv[0].x(), uv[1].x(), uv[2].x()})));
    const int x1 = int(std::ceil(std::max({uv[0].x(), uv[1].x(), uv[2].x()})));
    const int y0 = int(std::floor(std::min({uv[0].y(), uv[1].y(), uv[2].y()})));
    const int y1 = int(std::ceil(std::max({uv[0].y(), uv[1].y(), uv[2].y()})));
    for (int y = y0; y < y1; ++y) {
      for (int x = x0; x < x1; ++x) {
        const Eigen::Vector2d p(x + 0.5, y + 0.5);
        const double l1 = ((p - uv[0]).x() * (uv[2] - uv[0]).y() - (p - uv[0]).y() * (uv[2] - uv[0]).x()) / det;
        const double l2 = ((uv[1] - uv[0]).x() * (p - uv[0]).y() - (uv[1] - uv[0]).y() * (p - uv[0]).x()) / det;
        if (l1 < 0 || l2 < 0 || l1 + l2 > 1) continue;
        const Eigen::Vector3d w = (1 - l1 - l2) * t.mesh.vertices_m[face[0]] + l1 * t.mesh.vertices_m[face[1]] +
                                  l2 * t.mesh.vertices_m[face[2]];
        const double fx = w.x() - std::floor(w.x()), fy = w.y() - std::floor(w.y());
        if (std::min({fx, 1 - fx, fy, 1 - fy}) < edge_m) continue;
        const Eigen::Vector3f truth = Checker(w);
        const uint8_t* texel = t.atlas.At(x, y);
        for (int k = 0; k < 3; ++k) sum += std::pow(double(texel[k]) - truth[k], 2);
        n += 3;
      }
    }
  }
  EXPECT_GT(n, 3000);
  return 10 * std::log10(255.0 * 255.0 / std::max(sum / double(n), 1e-6));
}

// A radial-distortion camera 9 m above an 8 x 8 m checkerboard (the corners 0.6 focal lengths off axis,
// where the distortion moves them by about 12 px), its photo rendered exactly.
struct CheckerScene {
  TriangleMesh mesh = GroundGrid(16, 0.5);
  ColmapCamera camera = Camera(int(CameraModelId::kSimpleRadial), {420, 320, 240, -0.12}, 640, 480);
  ColmapImage image = NadirImage({4.1, 3.9, 9}, "nadir.png");
  RgbImage photo = RenderPlanePhoto(image, camera, 0, Checker);
};

TEST(MeshTexture, BakedTextureReproducesTheCheckerboardThroughTheDistortion) {
  const CheckerScene s;
  MeshTextureOptions options;
  options.texture_px = 512;
  const TexturedMesh t = TextureMesh(s.mesh, {TextureView(s.image, s.camera)}, {s.photo}, options);
  EXPECT_EQ(t.report["faces_textured"], int64_t(s.mesh.num_faces()));
  EXPECT_EQ(t.report["photos_used"], 1);
  EXPECT_EQ(t.mesh.num_faces(), s.mesh.num_faces());
  EXPECT_GT(AtlasPsnr(t, 0.08), 30.0);
}

TEST(MeshTexture, IgnoringTheDistortionWouldShowInThePsnr) {
  // The same photo textured through a camera that forgets the distortion: the measure above must see it.
  CheckerScene s;
  ColmapCamera pinhole = s.camera;
  pinhole.params[3] = 0;
  MeshTextureOptions options;
  options.texture_px = 512;
  const double right = AtlasPsnr(TextureMesh(s.mesh, {TextureView(s.image, s.camera)}, {s.photo}, options), 0.08);
  const double wrong = AtlasPsnr(TextureMesh(s.mesh, {TextureView(s.image, pinhole)}, {s.photo}, options), 0.08);
  EXPECT_LT(wrong, right - 8.0) << right << " dB with the distortion, " << wrong << " without";
}

TEST(MeshTexture, FacesNoPhotoSeesKeepTheirVertexColour) {
  // A camera that sees only part of the ground: the rest keeps its vertex colour (COLOR_0) on white texels.
  const TriangleMesh mesh = GroundGrid(16, 0.5);
  const ColmapCamera camera = Camera(int(CameraModelId::kPinhole), {300, 300, 160, 120}, 320, 240);
  const ColmapImage image = NadirImage({2, 2, 4}, "corner.png");
  const RgbImage photo = RenderPlanePhoto(image, camera, 0, Checker);
  MeshTextureOptions options;
  options.texture_px = 256;
  const TexturedMesh t = TextureMesh(mesh, {TextureView(image, camera)}, {photo}, options);
  const int64_t textured = t.report["faces_textured"];
  EXPECT_GT(textured, 0);
  EXPECT_LT(textured, int64_t(mesh.num_faces()));
  EXPECT_EQ(t.report["faces_vertex_color"], int64_t(mesh.num_faces()) - textured);
  int vertex_colour_faces = 0;
  for (const auto& face : t.mesh.faces) {
    const auto c = t.mesh.colors_rgb[face[0]];
    if (c[0] == 255) continue;
    ++vertex_colour_faces;
    EXPECT_EQ(c, (std::array<uint8_t, 3>{10, 200, 30}));
    const Eigen::Vector2f uv = t.texcoords[face[0]] * float(t.atlas.width);
    const uint8_t* texel = t.atlas.At(int(uv.x()), int(uv.y()));
    EXPECT_EQ(texel[0], 255);
    EXPECT_EQ(texel[1], 255);
  }
  EXPECT_EQ(vertex_colour_faces, int64_t(mesh.num_faces()) - textured);
}

TEST(MeshTexture, ExposureGainsLevelTwoPhotosOfDifferentBrightness) {
  const TriangleMesh mesh = GroundGrid(16, 0.5);
  const ColmapCamera camera = Camera(int(CameraModelId::kPinhole), {400, 400, 320, 240}, 640, 480);
  const ColmapImage a = NadirImage({3, 4, 12}, "a.png"), b = NadirImage({5, 4, 12}, "b.png");
  const auto grey = [](const Eigen::Vector3d& p) {
    return Eigen::Vector3f(Checker(p) * 0.5f + Eigen::Vector3f::Constant(60));
  };
  const RgbImage pa = RenderPlanePhoto(a, camera, 0, grey, 1.0f), pb = RenderPlanePhoto(b, camera, 0, grey, 1.5f);
  MeshTextureOptions options;
  options.texture_px = 256;
  const TexturedMesh t = TextureMesh(mesh, {TextureView(a, camera), TextureView(b, camera)}, {pa, pb}, options);
  const Json& gains = t.report["photo_gains"];
  for (int k = 0; k < 3; ++k) {
    const double ratio = gains[1]["gain_rgb"][k].get<double>() / gains[0]["gain_rgb"][k].get<double>();
    EXPECT_NEAR(ratio, 1 / 1.5, 0.03) << k;
  }
  EXPECT_LT(t.report["exposure"]["rms_linear_after"].get<double>(),
            0.2 * t.report["exposure"]["rms_linear_before"].get<double>());
}

TEST(MeshTexture, TheSameBytesAtAnyThreadCountAndRun) {
  const CheckerScene s;
  MeshTextureOptions options;
  options.texture_px = 256;
  options.report_times = false;
  const TexturedMesh t1 = TextureMesh(s.mesh, {TextureView(s.image, s.camera)}, {s.photo}, options);
  const TexturedMesh t2 = TextureMesh(s.mesh, {TextureView(s.image, s.camera)}, {s.photo}, options);
  EXPECT_EQ(t1.image_bytes, t2.image_bytes);
  EXPECT_EQ(t1.report, t2.report);
}

TEST(MeshTexture, GlbCarriesTheTextureAndTexcoordsWithAndWithoutDraco) {
  const CheckerScene s;
  MeshTextureOptions options;
  options.texture_px = 256;
  options.format = TextureFormat::kPng;
  const TexturedMesh t = TextureMesh(s.mesh, {TextureView(s.image, s.camera)}, {s.photo}, options);
  const GlbTexture texture{t.texcoords, t.image_bytes, t.mime_type};
  for (bool draco : {false, true}) {
    GlbWriteOptions glb;
    glb.draco = draco;
    const scene::SceneMesh read = scene::ReadGlbBytes(WriteGlb(t.mesh, &texture, glb), "test.glb");
    ASSERT_EQ(read.images.size(), 1u) << draco;
    EXPECT_EQ(read.images[0].mime_type, "image/png");
    EXPECT_EQ(std::string(read.images[0].encoded.begin(), read.images[0].encoded.end()), t.image_bytes);
    ASSERT_EQ(read.materials.size(), 1u);
    EXPECT_EQ(read.materials[0].base_color_image, 0);
    ASSERT_TRUE(read.has_texcoords());
    ASSERT_TRUE(read.has_colors());
    ASSERT_EQ(read.num_faces(), t.mesh.num_faces());
    // Every vertex read back has the texture coordinates of a written vertex at its position (Draco may
    // reorder faces and vertices).
    double worst = 0;
    for (size_t i = 0; i < read.num_vertices(); ++i) {
      double best = 1e9;
      for (size_t j = 0; j < t.mesh.num_vertices(); ++j) {
        if ((read.positions_enu_m[i] - t.mesh.vertices_m[j]).norm() > 1e-3) continue;
        best = std::min(best, double((read.texcoords[i] - t.texcoords[j]).norm()));
      }
      worst = std::max(worst, best);
    }
    EXPECT_LT(worst, draco ? 1.0 / 16384 : 1e-7) << draco;
  }
}

}  // namespace
}  // namespace cinepath::photogrammetry
