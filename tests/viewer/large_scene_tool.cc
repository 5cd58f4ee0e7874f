// Writes a synthetic terrain scene (scene.glb + scene.json) of about N faces for measuring `cinepath view`
// on a large mesh (docs/view.md, "Size and speed"): a jittered grid over rolling hills with 2 cm noise,
// coloured by height, Draco-compressed as `cinepath mesh --draco` writes it.
//   viewer_large_scene FACES OUT_DIR
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>

#include "core/file_io.h"
#include "photogrammetry/gltf/gltf_writer.h"

namespace pg = cinepath::photogrammetry;

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: viewer_large_scene FACES OUT_DIR\n");
    return 2;
  }
  const double faces = std::atof(argv[1]);
  const std::filesystem::path out = argv[2];
  const int side = std::max(2, int(std::lround(std::sqrt(faces / 2.0))) + 1);  // vertices per row
  const double extent_m = 400, step_m = extent_m / (side - 1);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> jitter(-0.3 * step_m, 0.3 * step_m);
  std::normal_distribution<double> noise(0, 0.02);
  pg::TriangleMesh mesh;
  for (int j = 0; j < side; ++j) {
    for (int i = 0; i < side; ++i) {
      const double e = -extent_m / 2 + i * step_m + jitter(rng), n = -extent_m / 2 + j * step_m + jitter(rng);
      const double u = 8 * std::sin(e / 37) * std::cos(n / 53) + 3 * std::sin((e + 2 * n) / 11) + noise(rng);
      mesh.vertices_m.emplace_back(e, n, u);
      const double t = std::clamp((u + 11) / 22, 0.0, 1.0);
      mesh.colors_rgb.push_back({uint8_t(90 + 120 * t), uint8_t(140 + 60 * (1 - t)), uint8_t(70 + 40 * t)});
    }
  }
  for (int j = 0; j + 1 < side; ++j) {
    for (int i = 0; i + 1 < side; ++i) {
      const uint32_t a = j * side + i, b = a + 1, c = a + side, d = c + 1;
      mesh.faces.push_back({a, b, d});
      mesh.faces.push_back({a, d, c});
    }
  }
  pg::GlbWriteOptions options;
  options.draco = true;
  std::filesystem::create_directories(out);
  cinepath::WriteFileAtomic(out / "scene.glb", pg::WriteGlb(mesh, options));
  cinepath::WriteFileAtomic(out / "scene.json",
                            "{\"format\": \"cinepath.scene\", \"version\": 1, \"origin\": {\"lat_deg\": 50.82, "
                            "\"lon_deg\": -0.14, \"height_m\": 50}, \"mesh\": \"scene.glb\"}\n");
  std::printf("%zu vertices, %zu faces\n", mesh.num_vertices(), mesh.num_faces());
  return 0;
}
