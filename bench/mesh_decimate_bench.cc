// Decimation and cleaning on one realistic terrain-like mesh of 1–5 M faces: every simplifier
// cinepath has (meshoptimizer, partitioned meshoptimizer, CGAL Garland–Heckbert plane and
// probabilistic, OpenMesh quadric), each timed and checked with the symmetric Hausdorff distance
// (CGAL approximate_Hausdorff_distance both ways, explicit sample count, fixed seed), then the
// --quality presets of the whole surface pipeline. Prints one JSON document (figures for
// bench/RESULTS.md).
//
//   mesh_decimate_bench [--faces N] [--ratio R] [--samples S] [--methods a,b,...]
//                       [--presets] [--export-raw FILE] [--import-raw FILE --label NAME]
//
// The mesh: 2.5D Delaunay (surface_height_field) of jittered points over fractal rolling terrain
// with rectangular "buildings" and 2 cm measurement noise — irregular triangles and sharp walls
// like a drone photogrammetry mesh, not a benign UV sphere. --export-raw writes it for
// bench/open3d_decimate.py; --import-raw measures the Hausdorff error of a mesh decimated elsewhere.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "core/json.h"
#include "photogrammetry/mesh_clean.h"
#include "photogrammetry/mesh_decimate.h"
#include "photogrammetry/mesh_distance.h"
#include "photogrammetry/surface_height_field.h"
#include "photogrammetry/surface_pipeline.h"

namespace pg = cinepath::photogrammetry;
using cinepath::Json;

namespace {

double Seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Process CPU time (all threads): on a shared machine wall-clock time depends on the neighbours,
// CPU time much less. Both are reported.
double CpuSeconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

// Smooth value noise on an integer lattice (deterministic hash), summed over octaves.
double Lattice(int64_t x, int64_t y, uint32_t seed) {
  uint64_t h = static_cast<uint64_t>(x) * 0x9E3779B97F4A7C15ull ^
               static_cast<uint64_t>(y) * 0xC2B2AE3D27D4EB4Full ^ seed;
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdull;
  h ^= h >> 33;
  return static_cast<double>(h % 1000000) / 1000000.0 * 2.0 - 1.0;
}

double ValueNoise(double x, double y, uint32_t seed) {
  const int64_t ix = static_cast<int64_t>(std::floor(x)), iy = static_cast<int64_t>(std::floor(y));
  const double fx = x - ix, fy = y - iy;
  const double sx = fx * fx * (3 - 2 * fx), sy = fy * fy * (3 - 2 * fy);
  const double a = Lattice(ix, iy, seed), b = Lattice(ix + 1, iy, seed);
  const double c = Lattice(ix, iy + 1, seed), d = Lattice(ix + 1, iy + 1, seed);
  return (a + (b - a) * sx) + ((c + (d - c) * sx) - (a + (b - a) * sx)) * sy;
}

double TerrainM(double e, double n) {
  double z = 0, amplitude = 12.0, frequency = 1.0 / 120.0;
  for (int octave = 0; octave < 6; ++octave) {
    z += amplitude * ValueNoise(e * frequency, n * frequency, 17u + octave);
    amplitude *= 0.45;
    frequency *= 2.1;
  }
  // Buildings: a 40 m block grid, about a third of the blocks hold a 6–18 m box.
  const int64_t bx = static_cast<int64_t>(std::floor(e / 40.0));
  const int64_t by = static_cast<int64_t>(std::floor(n / 40.0));
  const double r = Lattice(bx, by, 99u);
  if (r > 0.35) {
    const double u = e - bx * 40.0, v = n - by * 40.0;
    if (u > 8 && u < 32 && v > 10 && v < 30) z += 6.0 + 12.0 * (r - 0.35);
  }
  return z;
}

pg::TriangleMesh MakeTerrainMesh(int64_t target_faces) {
  // A Delaunay triangulation of n points has about 2n faces.
  const int64_t points = target_faces / 2;
  const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(points))));
  const double spacing_m = 0.5;
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> jitter(-0.45, 0.45);
  std::normal_distribution<double> noise(0.0, 0.02);
  pg::PointCloud cloud;
  cloud.positions_m.reserve(static_cast<size_t>(side) * side);
  for (int j = 0; j < side; ++j) {
    for (int i = 0; i < side; ++i) {
      const double e = (i + jitter(rng)) * spacing_m, n = (j + jitter(rng)) * spacing_m;
      cloud.positions_m.emplace_back(e, n, TerrainM(e, n) + noise(rng));
      const uint8_t shade = static_cast<uint8_t>(100 + 10 * std::fmod(TerrainM(e, n), 10.0));
      cloud.colors_rgb.push_back({shade, static_cast<uint8_t>(shade / 2 + 60), 90});
    }
  }
  pg::HeightFieldOptions options;
  options.max_points = 0;
  options.spike_min_m = 1e9;  // keep the walls
  options.max_edge_factor = 0;
  return pg::HeightFieldSurface(cloud, options, nullptr);
}

void WriteRaw(const pg::TriangleMesh& mesh, const std::string& path) {
  std::ofstream out(path, std::ios::binary);
  const uint64_t nv = mesh.num_vertices(), nf = mesh.num_faces();
  out.write(reinterpret_cast<const char*>(&nv), 8);
  out.write(reinterpret_cast<const char*>(&nf), 8);
  for (const auto& v : mesh.vertices_m) out.write(reinterpret_cast<const char*>(v.data()), 24);
  for (const auto& f : mesh.faces) out.write(reinterpret_cast<const char*>(f.data()), 12);
}

pg::TriangleMesh ReadRaw(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  uint64_t nv = 0, nf = 0;
  in.read(reinterpret_cast<char*>(&nv), 8);
  in.read(reinterpret_cast<char*>(&nf), 8);
  pg::TriangleMesh mesh;
  mesh.vertices_m.resize(nv);
  mesh.faces.resize(nf);
  for (auto& v : mesh.vertices_m) in.read(reinterpret_cast<char*>(v.data()), 24);
  for (auto& f : mesh.faces) in.read(reinterpret_cast<char*>(f.data()), 12);
  if (!in) {
    std::fprintf(stderr, "cannot read %s\n", path.c_str());
    std::exit(1);
  }
  return mesh;
}

std::vector<std::string> Split(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream stream(text);
  for (std::string part; std::getline(stream, part, ',');) parts.push_back(part);
  return parts;
}

}  // namespace

int main(int argc, char** argv) {
  int64_t faces = 2500000;
  double ratio = 0.1;
  int64_t samples = 1000000;
  std::string methods = "meshoptimizer,meshoptimizer_partitioned,cgal_garland_heckbert_probabilistic,"
                        "cgal_garland_heckbert,openmesh_quadric";
  bool presets = false;
  std::string export_raw, import_raw, label = "external";
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
    if (arg == "--faces") faces = std::stoll(next());
    else if (arg == "--ratio") ratio = std::stod(next());
    else if (arg == "--samples") samples = std::stoll(next());
    else if (arg == "--methods") methods = next();
    else if (arg == "--presets") presets = true;
    else if (arg == "--export-raw") export_raw = next();
    else if (arg == "--import-raw") import_raw = next();
    else if (arg == "--label") label = next();
    else {
      std::fprintf(stderr, "unknown argument %s\n", arg.c_str());
      return 2;
    }
  }

  Json result;
  auto start = std::chrono::steady_clock::now();
  const pg::TriangleMesh input = MakeTerrainMesh(faces);
  result["input"] = {{"faces", input.num_faces()},
                     {"vertices", input.num_vertices()},
                     {"generate_s", Seconds(start)}};
  std::fprintf(stderr, "input: %zu faces, %zu vertices\n", input.num_faces(),
               input.num_vertices());
  if (!export_raw.empty()) WriteRaw(input, export_raw);
  const int64_t target = static_cast<int64_t>(std::llround(ratio * input.num_faces()));
  result["target_faces"] = target;
  result["hausdorff_samples_per_mesh"] = samples;
  pg::HausdorffOptions hausdorff;
  hausdorff.samples_per_mesh = samples;

  if (!import_raw.empty()) {
    const pg::TriangleMesh other = ReadRaw(import_raw);
    start = std::chrono::steady_clock::now();
    const pg::HausdorffDistance d = pg::ApproximateHausdorff(input, other, hausdorff);
    std::fprintf(stderr, "%s: %zu faces  hausdorff %.4f m\n", label.c_str(), other.num_faces(),
                 d.symmetric_m);
    result["external"] = {{"label", label},
                          {"faces_out", other.num_faces()},
                          {"hausdorff_m", d.symmetric_m},
                          {"hausdorff_in_to_out_m", d.a_to_b_m},
                          {"hausdorff_out_to_in_m", d.b_to_a_m},
                          {"hausdorff_s", Seconds(start)}};
    std::printf("%s", cinepath::DumpJson(result).c_str());
    return 0;
  }

  {
    start = std::chrono::steady_clock::now();
    const double cpu0 = CpuSeconds();
    pg::MeshCleanReport report;
    const pg::TriangleMesh cleaned = pg::CleanMesh(input, pg::MeshCleanOptions{}, &report);
    const double s = Seconds(start);
    result["clean"] = {{"seconds", s},
                       {"cpu_seconds", CpuSeconds() - cpu0},
                       {"faces_per_s", input.num_faces() / s},
                       {"faces_out", cleaned.num_faces()}};
    std::fprintf(stderr, "clean: %.2f s\n", s);
  }

  Json rows = Json::array();
  for (const std::string& name : Split(methods)) {
    pg::DecimateOptions options;
    options.method = pg::ParseDecimationMethod(name, "--methods");
    options.target_faces = target;
    start = std::chrono::steady_clock::now();
    const double cpu0 = CpuSeconds();
    const pg::TriangleMesh out = pg::DecimateMesh(input, options);
    const double s = Seconds(start);
    const double cpu = CpuSeconds() - cpu0;
    start = std::chrono::steady_clock::now();
    const pg::HausdorffDistance d = pg::ApproximateHausdorff(input, out, hausdorff);
    const double hs = Seconds(start);
    std::fprintf(stderr, "%-36s %8.2f s (cpu %.2f s) %9zu faces  hausdorff %.4f m (%.1f s)\n",
                 name.c_str(), s, cpu, out.num_faces(), d.symmetric_m, hs);
    rows.push_back({{"method", name},
                    {"seconds", s},
                    {"cpu_seconds", cpu},
                    {"input_faces_per_s", input.num_faces() / s},
                    {"faces_out", out.num_faces()},
                    {"hausdorff_m", d.symmetric_m},
                    {"hausdorff_in_to_out_m", d.a_to_b_m},
                    {"hausdorff_out_to_in_m", d.b_to_a_m},
                    {"hausdorff_s", hs}});
  }
  result["decimation"] = rows;

  if (presets) {
    Json table = Json::array();
    for (pg::Quality quality : {pg::Quality::kDraft, pg::Quality::kStandard, pg::Quality::kFinal}) {
      pg::SurfacePipelineOptions options;
      options.quality = quality;
      start = std::chrono::steady_clock::now();
      const double cpu0 = CpuSeconds();
      const pg::SurfacePipelineResult r = pg::BuildSurfaceFromMesh(input, nullptr, options);
      const double s = Seconds(start);
      const double cpu = CpuSeconds() - cpu0;
      std::fprintf(stderr, "preset %-8s %8.2f s  %9zu faces  hausdorff %.4f m\n",
                   pg::QualityName(quality), s, r.mesh.num_faces(),
                   r.report["output"]["hausdorff_m"].get<double>());
      table.push_back({{"quality", pg::QualityName(quality)},
                       {"seconds", s},
                       {"cpu_seconds", cpu},
                       {"faces_out", r.mesh.num_faces()},
                       {"hausdorff_m", r.report["output"]["hausdorff_m"]},
                       {"glb_bytes", r.glb.size()},
                       {"steps", r.report["steps"]}});
    }
    result["presets"] = table;
  }
  std::printf("%s", cinepath::DumpJson(result).c_str());
  return 0;
}
