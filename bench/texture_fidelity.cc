// How the textured mesh looks from where the photos were taken: renders scene.glb from each registered
// camera of scene.json (its pose, and its COLMAP camera model with the distortion: each pixel's ray is
// the pixel undistorted, camera_models.h) and compares the render with the photo itself, over the
// pixels the mesh covers: PSNR of the 8-bit sRGB values and the normalised cross-correlation of their
// luma. The render is unlit (flat): base colour = COLOR_0 x baseColorTexture (bilinear), as glTF defines
// it, so a vertex-coloured GLB is measured the same way.
//
// --leave-one-out PX: the mesh of scene.glb (give a vertex-coloured one, `mesh --no-texture`) textured
// in this process (photogrammetry/texture/mesh_texture.h, a PX-texel atlas) from every photo but k, then
// rendered from camera k: a view the texture has not seen. (The atlas is used as baked, before its JPEG
// encoding.)
//
//   texture_fidelity SCENE_DIR IMAGES_DIR [--only IMAGE] [--step N] [--leave-one-out PX]
// prints one tab-separated line per camera: image, covered pixels, PSNR dB, NCC.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "core/file_io.h"
#include "core/json.h"
#include "photogrammetry/georef/camera_models.h"
#include "photogrammetry/io/photo_image.h"
#include "photogrammetry/texture/mesh_texture.h"
#include "scene/glb_reader.h"
#include "scene/ray_caster.h"

namespace {

using namespace cinepath;
namespace pg = cinepath::photogrammetry;

pg::RgbImage Decode(const std::string& name, const uint8_t* data, size_t size) {
  std::unique_ptr<OIIO::ImageInput> input;
  OIIO::Filesystem::IOMemReader reader(const_cast<uint8_t*>(data), size);
  input = data ? OIIO::ImageInput::open(name, nullptr, &reader) : OIIO::ImageInput::open(name);
  if (!input) throw std::runtime_error(name + ": " + OIIO::geterror());
  const OIIO::ImageSpec& spec = input->spec();
  std::vector<uint8_t> pixels(size_t(spec.width) * spec.height * spec.nchannels);
  if (!input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, pixels.data())) {
    throw std::runtime_error(name + ": " + input->geterror());
  }
  pg::RgbImage image;
  image.width = spec.width;
  image.height = spec.height;
  image.rgb.resize(size_t(spec.width) * spec.height * 3);
  for (size_t i = 0; i < size_t(spec.width) * spec.height; ++i) {
    for (int k = 0; k < 3; ++k) image.rgb[3 * i + k] = pixels[i * spec.nchannels + (k % spec.nchannels)];
  }
  return image;
}

float ToSrgb(float x) {
  x = std::clamp(x, 0.0f, 1.0f);
  return x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1 / 2.4f) - 0.055f;
}

struct Camera {
  std::string name;
  int model_id = 0;
  std::vector<double> params;
  int width = 0, height = 0;
  Eigen::Matrix3d world_from_camera;
  Eigen::Vector3d centre;
};

Camera CameraFromJson(const Json& camera) {
  Camera c;
  c.name = camera["image"];
  c.model_id = *pg::CameraModelIdFromName(camera["distortion"]["model"].get<std::string>());
  c.params.assign(size_t(pg::CameraModelNumParams(c.model_id)), 0.0);
  const auto focal = pg::CameraModelFocalIndices(c.model_id);
  c.params[size_t(focal[0])] = camera["focal_px"];
  if (focal.size() > 1) c.params[size_t(focal[1])] = camera.value("focal_y_px", camera["focal_px"].get<double>());
  const auto principal = pg::CameraModelPrincipalPointIndices(c.model_id);
  c.params[size_t(principal[0])] = camera["principal_point_px"][0];
  c.params[size_t(principal[1])] = camera["principal_point_px"][1];
  const auto extra = pg::CameraModelExtraIndices(c.model_id);
  for (size_t k = 0; k < extra.size(); ++k) c.params[size_t(extra[k])] = camera["distortion"]["params"][k];
  c.width = camera["width_px"];
  c.height = camera["height_px"];
  const auto& q = camera["world_from_camera"];
  c.world_from_camera =
      Eigen::Quaterniond(q[0].get<double>(), q[1].get<double>(), q[2].get<double>(), q[3].get<double>())
          .normalized()
          .toRotationMatrix();
  c.centre = Eigen::Vector3d(camera["position_enu_m"][0].get<double>(), camera["position_enu_m"][1].get<double>(),
                             camera["position_enu_m"][2].get<double>());
  return c;
}

pg::TextureView ViewFromCamera(const Camera& c) {
  pg::ColmapImage image;
  image.name = c.name;
  image.camera_id = 1;
  image.cam_from_world_rotation = Eigen::Quaterniond(c.world_from_camera.transpose());
  image.cam_from_world_translation = -c.world_from_camera.transpose() * c.centre;
  pg::ColmapCamera camera;
  camera.camera_id = 1;
  camera.model_id = c.model_id;
  camera.params = c.params;
  camera.width_px = uint64_t(c.width);
  camera.height_px = uint64_t(c.height);
  return pg::TextureView(image, camera);
}

// What the render of a face point shows: colours and texture coordinates per vertex, faces in the order of
// the mesh the ray caster holds.
struct Look {
  const std::vector<std::array<uint32_t, 3>>* faces;
  const std::vector<Eigen::Vector3f>* colors_linear;  // may be empty
  const std::vector<Eigen::Vector2f>* texcoords;      // may be empty
  const pg::RgbImage* texture;                        // may be null
};

struct Score {
  int64_t covered = 0;
  double psnr = 0, ncc = 0;
};

Score Measure(const scene::RayCaster& caster, const Look& look, const Camera& camera, const pg::RgbImage& photo,
              int step) {
  double sq = 0, sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
  int64_t covered = 0;
  const double luma[3] = {0.2126, 0.7152, 0.0722};
  for (int y = 0; y < photo.height; y += step) {
    for (int x = 0; x < photo.width; x += step) {
      double u = 0, v = 0;
      if (!pg::PixelToNormalized(camera.model_id, camera.params, x + 0.5, y + 0.5, &u, &v)) continue;
      const auto hit = caster.Intersect(camera.centre, camera.world_from_camera * Eigen::Vector3d(u, v, 1));
      if (!hit) continue;
      const auto& f = (*look.faces)[hit->face];
      const float bu = float(hit->u), bv = float(hit->v), bw = 1 - bu - bv;
      Eigen::Vector3f color = Eigen::Vector3f::Ones();
      if (!look.colors_linear->empty()) {
        const auto& c = *look.colors_linear;
        color = bw * c[f[0]] + bu * c[f[1]] + bv * c[f[2]];
      }
      if (look.texture && !look.texcoords->empty()) {
        const auto& t = *look.texcoords;
        const Eigen::Vector2f uv = bw * t[f[0]] + bu * t[f[1]] + bv * t[f[2]];
        color = color.cwiseProduct(
            pg::SampleLinear(*look.texture, uv.x() * look.texture->width, uv.y() * look.texture->height));
      }
      const uint8_t* p = photo.At(x, y);
      double la = 0, lb = 0;
      for (int k = 0; k < 3; ++k) {
        const double a = 255.0 * ToSrgb(color[k]), b = p[k];
        sq += (a - b) * (a - b);
        la += luma[k] * a;
        lb += luma[k] * b;
      }
      sa += la;
      sb += lb;
      saa += la * la;
      sbb += lb * lb;
      sab += la * lb;
      ++covered;
    }
  }
  Score s;
  s.covered = covered;
  const double n = double(covered);
  s.psnr = 10 * std::log10(255.0 * 255.0 / (sq / (3 * n)));
  const double cov = sab / n - (sa / n) * (sb / n);
  s.ncc = cov / std::sqrt((saa / n - (sa / n) * (sa / n)) * (sbb / n - (sb / n) * (sb / n)));
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: texture_fidelity SCENE_DIR IMAGES_DIR [--only IMAGE] [--step N] [--leave-one-out PX]\n";
    return 2;
  }
  const std::filesystem::path scene_dir = argv[1], images_dir = argv[2];
  std::string only;
  int step = 1, leave_one_out_px = 0;
  for (int i = 3; i + 1 < argc; i += 2) {
    if (std::string(argv[i]) == "--only") only = argv[i + 1];
    if (std::string(argv[i]) == "--step") step = std::max(1, std::atoi(argv[i + 1]));
    if (std::string(argv[i]) == "--leave-one-out") leave_one_out_px = std::atoi(argv[i + 1]);
  }
  const Json scene = Json::parse(ReadFileToString(scene_dir / "scene.json"));
  const scene::SceneMesh mesh = scene::ReadGlbFile(scene_dir / "scene.glb");
  const scene::RayCaster caster(mesh);
  pg::RgbImage texture;
  for (const auto& m : mesh.materials) {
    if (m.base_color_image >= 0 && mesh.has_texcoords()) {
      const auto& img = mesh.images[size_t(m.base_color_image)];
      texture = Decode(img.mime_type == "image/png" ? "t.png" : "t.jpg", img.encoded.data(), img.encoded.size());
    }
  }
  std::vector<Camera> cameras;
  std::vector<pg::RgbImage> photos;
  for (const Json& camera : scene["cameras"]) {
    cameras.push_back(CameraFromJson(camera));
    photos.push_back(Decode((images_dir / cameras.back().name).string(), nullptr, 0));
  }

  pg::TriangleMesh triangles;  // for --leave-one-out
  if (leave_one_out_px > 0) {
    triangles.vertices_m = mesh.positions_enu_m;
    triangles.faces = mesh.faces;
    for (const auto& c : mesh.colors_linear) {
      triangles.colors_rgb.push_back({pg::SrgbFromLinear(c[0]), pg::SrgbFromLinear(c[1]), pg::SrgbFromLinear(c[2])});
    }
  }
  for (size_t k = 0; k < cameras.size(); ++k) {
    if (!only.empty() && cameras[k].name != only) continue;
    Score s;
    if (leave_one_out_px > 0) {
      std::vector<pg::TextureView> views;
      std::vector<pg::RgbImage> others;
      for (size_t j = 0; j < cameras.size(); ++j) {
        if (j == k) continue;
        views.push_back(ViewFromCamera(cameras[j]));
        others.push_back(photos[j]);
      }
      pg::MeshTextureOptions options;
      options.texture_px = leave_one_out_px;
      const pg::TexturedMesh textured = pg::TextureMesh(triangles, views, others, options);
      std::vector<Eigen::Vector3f> colors;
      for (const auto& c : textured.mesh.colors_rgb) {
        colors.emplace_back(pg::LinearFromSrgb(c[0]), pg::LinearFromSrgb(c[1]), pg::LinearFromSrgb(c[2]));
      }
      s = Measure(caster, Look{&textured.mesh.faces, &colors, &textured.texcoords, &textured.atlas}, cameras[k],
                  photos[k], step);
    } else {
      s = Measure(caster, Look{&mesh.faces, &mesh.colors_linear, &mesh.texcoords, texture.empty() ? nullptr : &texture},
                  cameras[k], photos[k], step);
    }
    std::printf("%s\t%lld\t%.2f\t%.4f\n", cameras[k].name.c_str(), static_cast<long long>(s.covered), s.psnr, s.ncc);
    std::fflush(stdout);
  }
  return 0;
}
