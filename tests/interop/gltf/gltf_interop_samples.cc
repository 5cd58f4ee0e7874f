// Writes the GLBs the interop tests check with outside tools, and manifest.json with what each
// must decode to: every kind of GLB cinepath writes (plain, coloured, Draco, a full surface pipeline
// run from points and from a given mesh).
//   gltf_interop_samples OUTDIR
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "../../photogrammetry/surface_test_meshes.h"
#include "../../photogrammetry/texture_test_scenes.h"
#include "core/json.h"
#include "photogrammetry/gltf/gltf_writer.h"
#include "photogrammetry/pipeline/surface_pipeline.h"
#include "photogrammetry/texture/mesh_texture.h"

namespace pg = cinepath::photogrammetry;

namespace {

void Write(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: gltf_interop_samples OUTDIR\n");
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  std::filesystem::create_directories(dir);
  cinepath::Json manifest = cinepath::Json::array();
  auto add = [&](const std::string& name, const std::string& bytes, const pg::TriangleMesh& mesh, bool draco,
                 bool texture = false) {
    Write(dir / name, bytes);
    manifest.push_back({{"file", name},
                        {"vertices", mesh.num_vertices()},
                        {"faces", mesh.num_faces()},
                        {"colors", mesh.has_colors()},
                        {"draco", draco},
                        {"texture", texture}});
  };
  const cinepath::Json extras = cinepath::Json::parse(
      R"({"origin": {"lat_deg": 50.8225, "lon_deg": -0.1372, "height_m": 47.5}, "frame": "ENU"})");

  pg::TriangleMesh grid = pg::testing::TerrainGrid(120, 80, 0.5);
  pg::GlbWriteOptions plain;
  plain.extras = extras;
  add("grid_colors.glb", pg::WriteGlb(grid, plain), grid, false);
  pg::GlbWriteOptions draco = plain;
  draco.draco = true;
  add("grid_colors_draco.glb", pg::WriteGlb(grid, draco), grid, true);
  pg::TriangleMesh uncoloured = grid;
  uncoloured.colors_rgb.clear();
  add("grid_plain.glb", pg::WriteGlb(uncoloured, plain), uncoloured, false);
  add("grid_plain_draco.glb", pg::WriteGlb(uncoloured, draco), uncoloured, true);

  pg::SurfacePipelineOptions options;
  options.report_times = false;
  options.gltf_extras = extras;
  options.target_faces = 4000;
  const pg::PointCloud cloud = pg::testing::TerrainCloud(100, 80, 0.7);
  const pg::SurfacePipelineResult from_points = pg::BuildSurfaceFromPoints(cloud, options);
  add("pipeline_points.glb", from_points.glb, from_points.mesh, false);
  options.draco = true;
  const pg::SurfacePipelineResult from_points_draco = pg::BuildSurfaceFromPoints(cloud, options);
  add("pipeline_points_draco.glb", from_points_draco.glb, from_points_draco.mesh, true);

  // A ground textured from a synthetic photo (mesh_texture.h): TEXCOORD_0, a JPEG baseColorTexture,
  // COLOR_0 kept; and the same with Draco (texture coordinates compressed too).
  namespace tt = pg::testing;
  const pg::TriangleMesh ground = tt::GroundGrid(24, 0.5);
  const pg::ColmapCamera camera = tt::Camera(int(pg::CameraModelId::kSimpleRadial), {420, 320, 240, -0.05}, 640, 480);
  const pg::ColmapImage image = tt::NadirImage({5, 6, 14}, "nadir.jpg");
  pg::MeshTextureOptions texture_options;
  texture_options.texture_px = 512;
  texture_options.report_times = false;
  const pg::TexturedMesh textured = pg::TextureMesh(
      ground, {pg::TextureView(image, camera)}, {tt::RenderPlanePhoto(image, camera, 0, tt::Checker)}, texture_options);
  const pg::GlbTexture texture{textured.texcoords, textured.image_bytes, textured.mime_type};
  add("ground_textured.glb", pg::WriteGlb(textured.mesh, &texture, plain), textured.mesh, false, true);
  add("ground_textured_draco.glb", pg::WriteGlb(textured.mesh, &texture, draco), textured.mesh, true, true);

  Write(dir / "manifest.json", cinepath::DumpJson(manifest));
  return 0;
}
