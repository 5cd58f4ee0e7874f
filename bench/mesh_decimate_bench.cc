// Decimation and cleaning on one realistic terrain-like mesh of 1–5 M faces: every simplifier
// cinepath has (meshoptimizer, partitioned meshoptimizer, CGAL Garland–Heckbert plane and
// probabilistic, OpenMesh quadric), each timed and checked with the symmetric Hausdorff distance
// (CGAL approximate_Hausdorff_distance both ways, explicit sample count, fixed seed), then the
// --quality presets of the whole surface pipeline. Prints one JSON document (figures for
// bench/RESULTS.md).
//
//   mesh_decimate_bench --list-methods      (the names --methods takes, one per line)
//   mesh_decimate_bench [--faces N] [--ratio R | --ratios R1,R2,...] [--samples S] [--methods a,b,...]
//                       [--qem-endpoints] [--qem-unweighted] [--qem-reach K] [--qem-normal-cos C] [--qem-rcond R]
//                       [--qem-band-rings B] [--qem-band-cell-faces C] [--qem-light-tile-faces T] [--qem-area-floor F]
//                       [--qem-distance-check D] [--qem-check-midpoints 0|1]
//                       [--qem-check-new-edges 0|1] [--qem-light-budget-keep K]
//                       [--qem-spike-pass S] [--qem-refit R]
//                       [--error-goals E1,E2,...]
//                       [--bound [--bound-depth N] [--bound-tolerance M]] [--sample-counts a,b,...]
//                       [--presets] [--export-raw FILE] [--import-raw FILE --label NAME]
//                       [--end-to-end] [--defects] [--threads T]
//
// --samples 0: no Hausdorff measure, the decimation's time alone (for timing runs and profiles).
// --error-goals: each method with an error goal in metres (DecimateOptions::max_error_m) instead of
// a face budget, for the methods that take one (the meshoptimizer methods and qem_tiled).
// --end-to-end: clean → decimate (the first of --methods) → Hausdorff, as `cinepath mesh` runs
// them, each step and the totals in wall and CPU seconds, with input faces per second.
// --defects: punch holes, add floating blobs, duplicate vertices/faces and degenerate faces into
// the terrain, so that cleaning has work to do. --threads: cap TBB's threads (results are the same
// at any count; the JSON output can be compared).
//
// The mesh: 2.5D Delaunay (surface_height_field) of jittered points over fractal rolling terrain
// with rectangular "buildings" and 2 cm measurement noise — irregular triangles and sharp walls
// like a drone photogrammetry mesh, not a benign UV sphere. --export-raw writes it for
// bench/open3d_decimate.py; --import-raw measures the Hausdorff error of a mesh decimated elsewhere.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <memory>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <tbb/global_control.h>
#include <tbb/parallel_invoke.h>

#include "core/heap_pages.h"
#include "core/json.h"
#include "photogrammetry/mesh/mesh_clean.h"
#include "photogrammetry/mesh/mesh_decimate.h"
#include "photogrammetry/mesh/mesh_distance.h"
#include "photogrammetry/pipeline/surface_pipeline.h"
#include "photogrammetry/surface/surface_height_field.h"

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
  uint64_t h =
      static_cast<uint64_t>(x) * 0x9E3779B97F4A7C15ull ^ static_cast<uint64_t>(y) * 0xC2B2AE3D27D4EB4Full ^ seed;
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

// Defects a photogrammetry mesh has: small holes (faces dropped in 1–2 m discs), floating blobs,
// duplicated vertices and faces, zero-area faces. Deterministic.
void AddDefects(pg::TriangleMesh& mesh) {
  std::mt19937_64 rng(7);
  Eigen::Vector3d lo = mesh.vertices_m.front(), hi = lo;
  for (const auto& v : mesh.vertices_m) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  // Holes: 1 per 400 m² (in the interior), radius 0.6–1.2 m.
  const double area = (hi.x() - lo.x()) * (hi.y() - lo.y());
  const int holes = static_cast<int>(area / 400.0);
  std::uniform_real_distribution<double> ux(lo.x() + 5, hi.x() - 5), uy(lo.y() + 5, hi.y() - 5);
  std::uniform_real_distribution<double> ur(0.6, 1.2);
  std::vector<Eigen::Vector3d> centres;
  std::vector<double> radii;
  for (int h = 0; h < holes; ++h) {
    centres.emplace_back(ux(rng), uy(rng), 0);
    radii.push_back(ur(rng));
  }
  const double cell = 20.0;
  const int gx = static_cast<int>((hi.x() - lo.x()) / cell) + 1;
  std::vector<std::vector<int>> grid(static_cast<size_t>(gx) * (static_cast<int>((hi.y() - lo.y()) / cell) + 1));
  for (int h = 0; h < holes; ++h) {
    grid[static_cast<int>((centres[h].y() - lo.y()) / cell) * gx + static_cast<int>((centres[h].x() - lo.x()) / cell)]
        .push_back(h);
  }
  std::vector<std::array<uint32_t, 3>> kept;
  kept.reserve(mesh.faces.size());
  for (const auto& f : mesh.faces) {
    const Eigen::Vector3d c = (mesh.vertices_m[f[0]] + mesh.vertices_m[f[1]] + mesh.vertices_m[f[2]]) / 3.0;
    const int cx = static_cast<int>((c.x() - lo.x()) / cell), cy = static_cast<int>((c.y() - lo.y()) / cell);
    bool in_hole = false;
    for (int dy = -1; dy <= 1 && !in_hole; ++dy) {
      for (int dx = -1; dx <= 1 && !in_hole; ++dx) {
        const int x = cx + dx, y = cy + dy;
        if (x < 0 || y < 0 || x >= gx || static_cast<size_t>(y * gx + x) >= grid.size()) continue;
        for (int h : grid[y * gx + x]) {
          if ((c.head<2>() - centres[h].head<2>()).norm() < radii[h]) in_hole = true;
        }
      }
    }
    if (!in_hole) kept.push_back(f);
  }
  mesh.faces.swap(kept);
  // Floating blobs: 1 per 2,000 m², 3×3-vertex patches 5–15 m above the ground.
  const int blobs = static_cast<int>(area / 2000.0);
  std::uniform_real_distribution<double> uz(5, 15);
  for (int b = 0; b < blobs; ++b) {
    const double x0 = ux(rng), y0 = uy(rng), z0 = uz(rng) + TerrainM(x0, y0);
    const uint32_t base = static_cast<uint32_t>(mesh.vertices_m.size());
    for (int j = 0; j < 3; ++j) {
      for (int i = 0; i < 3; ++i) {
        mesh.vertices_m.emplace_back(x0 + 0.3 * i, y0 + 0.3 * j, z0 + 0.05 * i * j);
        if (mesh.has_colors()) mesh.colors_rgb.push_back({200, 200, 200});
      }
    }
    for (uint32_t j = 0; j < 2; ++j) {
      for (uint32_t i = 0; i < 2; ++i) {
        const uint32_t a = base + j * 3 + i;
        mesh.faces.push_back({a, a + 1, a + 4});
        mesh.faces.push_back({a, a + 4, a + 3});
      }
    }
  }
  // Duplicates: every 1,000th face repeated (reversed), every 1,000th vertex copied and used by
  // one of its faces; a zero-area face every 5,000 faces.
  const size_t faces = mesh.faces.size();
  std::vector<int64_t> copy_of(mesh.vertices_m.size(), -1);
  for (size_t i = 0; i < faces; i += 1000) {
    const auto f = mesh.faces[i];
    mesh.faces.push_back({f[0], f[2], f[1]});
  }
  for (size_t i = 500; i < faces; i += 1000) {
    auto& f = mesh.faces[i];
    if (copy_of[f[0]] < 0) {
      copy_of[f[0]] = static_cast<int64_t>(mesh.vertices_m.size());
      mesh.vertices_m.push_back(mesh.vertices_m[f[0]]);
      if (mesh.has_colors()) mesh.colors_rgb.push_back(mesh.colors_rgb[f[0]]);
    }
    f[0] = static_cast<uint32_t>(copy_of[f[0]]);
  }
  for (size_t i = 250; i < faces; i += 5000) {
    const auto f = mesh.faces[i];
    mesh.faces.push_back({f[0], f[1], f[0]});
  }
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

// FNV-1a over the vertex bits and the faces: equal digests = byte-identical meshes.
std::string Digest(const pg::TriangleMesh& mesh) {
  uint64_t h = 0xcbf29ce484222325ull;
  auto add = [&](const void* data, size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
  };
  for (const auto& v : mesh.vertices_m) add(v.data(), 24);
  for (const auto& f : mesh.faces) add(f.data(), 12);
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return text;
}

std::vector<std::string> Split(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream stream(text);
  for (std::string part; std::getline(stream, part, ',');) parts.push_back(part);
  return parts;
}

}  // namespace

namespace {

// The command line (each flag is documented in the header comment).
struct BenchArgs {
  int64_t faces = 2500000;
  double ratio = 0.1;
  int64_t samples = 1000000;
  std::string methods =
      "meshoptimizer,meshoptimizer_partitioned,cgal_garland_heckbert_probabilistic,"
      "cgal_garland_heckbert,openmesh_quadric";
  std::string ratios;       // --ratios a,b,...: the decimation table at each budget (overrides --ratio)
  std::string error_goals;  // --error-goals e1,e2,...: error goals in metres instead of face budgets
  bool presets = false, end_to_end = false, defects = false;
  pg::internal::QemOptions qem;
  int partitions = 0;                       // > 0: tiles of both tiled methods (default: each method's own)
  bool bound = false;                       // --bound: also bound the true Hausdorff distance (both directions)
  pg::HausdorffBoundOptions bound_options;  // --bound-depth N, --bound-tolerance M (metres, and 0 relative)
  std::string sample_counts;                // --sample-counts a,b,...: the sampled estimate at each count (convergence)
  int threads = 0;
  std::string export_raw, import_raw, label = "external";
};

// Fills `args` from the command line; an exit code when the run ends here (--list-methods, a bad flag).
std::optional<int> ParseArgs(int argc, char** argv, BenchArgs& args) {
  int64_t& faces = args.faces;
  double& ratio = args.ratio;
  int64_t& samples = args.samples;
  std::string& methods = args.methods;
  std::string& ratios = args.ratios;
  std::string& error_goals = args.error_goals;
  bool& presets = args.presets;
  bool& end_to_end = args.end_to_end;
  bool& defects = args.defects;
  pg::internal::QemOptions& qem = args.qem;
  int& partitions = args.partitions;
  bool& bound = args.bound;
  std::string& sample_counts = args.sample_counts;
  int& threads = args.threads;
  std::string& export_raw = args.export_raw;
  std::string& import_raw = args.import_raw;
  std::string& label = args.label;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
    if (arg == "--list-methods") {
      for (pg::DecimationMethod m : pg::AllDecimationMethods()) std::printf("%s\n", pg::DecimationMethodName(m));
      return 0;
    } else if (arg == "--faces")
      faces = std::stoll(next());
    else if (arg == "--ratios")
      ratios = next();
    else if (arg == "--error-goals")
      error_goals = next();
    else if (arg == "--bound")
      bound = true;
    else if (arg == "--bound-depth")
      args.bound_options.max_depth = std::stoi(next());
    else if (arg == "--bound-tolerance") {
      args.bound_options.tolerance_m = std::stod(next());
      args.bound_options.relative_tolerance = 0;
    } else if (arg == "--sample-counts")
      sample_counts = next();
    else if (arg == "--partitions")
      partitions = std::stoi(next());
    else if (arg == "--qem-endpoints")
      qem.optimal_placement = false;
    else if (arg == "--qem-unweighted")
      qem.area_weighted = false;
    else if (arg == "--qem-reach")
      qem.placement_reach = std::stod(next());
    else if (arg == "--qem-normal-cos")
      qem.min_normal_cos = std::stod(next());
    else if (arg == "--qem-rcond")
      qem.placement_rcond = std::stod(next());
    else if (arg == "--qem-band-rings")
      qem.final_band_rings = std::stod(next());
    else if (arg == "--qem-band-cell-faces")
      qem.band_cell_faces = std::stod(next());
    else if (arg == "--qem-light-tile-faces")
      qem.light_budget_tile_faces = std::stod(next());
    else if (arg == "--qem-area-floor")
      qem.area_floor = std::stod(next());
    else if (arg == "--qem-distance-check")
      qem.distance_check = std::stod(next());
    else if (arg == "--qem-check-midpoints")
      qem.distance_check_midpoints = std::stoi(next()) != 0;
    else if (arg == "--qem-check-new-edges")
      qem.distance_check_new_edges = std::stoi(next()) != 0;
    else if (arg == "--qem-light-budget-keep")
      qem.light_budget_keep = std::stod(next());
    else if (arg == "--qem-spike-pass")
      qem.spike_pass = std::stod(next());
    else if (arg == "--qem-refit")
      qem.refit = std::stod(next());
    else if (arg == "--ratio")
      ratio = std::stod(next());
    else if (arg == "--samples")
      samples = std::stoll(next());
    else if (arg == "--methods")
      methods = next();
    else if (arg == "--presets")
      presets = true;
    else if (arg == "--end-to-end")
      end_to_end = true;
    else if (arg == "--defects")
      defects = true;
    else if (arg == "--threads")
      threads = std::stoi(next());
    else if (arg == "--export-raw")
      export_raw = next();
    else if (arg == "--import-raw")
      import_raw = next();
    else if (arg == "--label")
      label = next();
    else {
      std::fprintf(stderr, "unknown argument %s\n", arg.c_str());
      return 2;
    }
  }
  return std::nullopt;
}

// --import-raw: another tool's decimation of the same input, measured as ours are.
Json MeasureExternal(const pg::TriangleMesh& input, const BenchArgs& args, const pg::HausdorffOptions& hausdorff) {
  const std::string& label = args.label;
  const pg::TriangleMesh other = ReadRaw(args.import_raw);
  const auto start = std::chrono::steady_clock::now();
  const pg::HausdorffDistance d = pg::ApproximateHausdorff(input, other, hausdorff);
  std::fprintf(stderr, "%s: %zu faces  hausdorff %.4f m\n", label.c_str(), other.num_faces(), d.symmetric_m);
  Json result;
  result["external"] = {{"label", label},
                        {"faces_out", other.num_faces()},
                        {"hausdorff_m", d.symmetric_m},
                        {"hausdorff_in_to_out_m", d.a_to_b_m},
                        {"hausdorff_out_to_in_m", d.b_to_a_m},
                        {"hausdorff_s", Seconds(start)}};
  return result;
}

// --end-to-end: clean, decimate and measure with one method, each phase timed (wall and CPU).
Json MeasureEndToEnd(const pg::TriangleMesh& input, const BenchArgs& args, int64_t target,
                     const pg::HausdorffOptions& hausdorff) {
  const std::string& methods = args.methods;
  const pg::internal::QemOptions& qem = args.qem;
  const int& partitions = args.partitions;
  auto start = std::chrono::steady_clock::now();
  const std::vector<std::string> names = Split(methods);
  pg::DecimateOptions options;
  options.method =
      pg::ParseDecimationMethod(names.empty() ? std::string("meshoptimizer_partitioned") : names.front(), "--methods");
  options.target_faces = target;
  options.qem = qem;
  if (partitions > 0) options.partitions = options.qem.tiles = partitions;
  Json e2e;
  start = std::chrono::steady_clock::now();
  double cpu0 = CpuSeconds();
  pg::MeshCleanReport report;
  const pg::TriangleMesh cleaned = pg::CleanMesh(input, pg::MeshCleanOptions{}, &report);
  const double clean_s = Seconds(start), clean_cpu = CpuSeconds() - cpu0;
  start = std::chrono::steady_clock::now();
  cpu0 = CpuSeconds();
  const pg::TriangleMesh out = pg::DecimateMesh(cleaned, options);
  const double decimate_s = Seconds(start), decimate_cpu = CpuSeconds() - cpu0;
  start = std::chrono::steady_clock::now();
  cpu0 = CpuSeconds();
  std::unique_ptr<pg::MeshDistanceIndex> cleaned_index_ptr, out_index_ptr;
  tbb::parallel_invoke([&] { cleaned_index_ptr = std::make_unique<pg::MeshDistanceIndex>(cleaned, "cleaned"); },
                       [&] { out_index_ptr = std::make_unique<pg::MeshDistanceIndex>(out, "decimated"); });
  const pg::MeshDistanceIndex& cleaned_index = *cleaned_index_ptr;
  const pg::MeshDistanceIndex& out_index = *out_index_ptr;
  const double index_s = Seconds(start), index_cpu = CpuSeconds() - cpu0;
  auto phase = std::chrono::steady_clock::now();
  double phase_cpu = CpuSeconds();
  pg::HausdorffDistance d;
  d.a_to_b_m = cleaned_index.MaxDistanceTo(out_index, hausdorff, &d.samples_a);
  const double in_to_out_s = Seconds(phase), in_to_out_cpu = CpuSeconds() - phase_cpu;
  phase = std::chrono::steady_clock::now();
  phase_cpu = CpuSeconds();
  d.b_to_a_m = out_index.MaxDistanceTo(cleaned_index, hausdorff, &d.samples_b);
  const double out_to_in_s = Seconds(phase), out_to_in_cpu = CpuSeconds() - phase_cpu;
  d.symmetric_m = std::max(d.a_to_b_m, d.b_to_a_m);
  const double hausdorff_s = Seconds(start), hausdorff_cpu = CpuSeconds() - cpu0;
  std::fprintf(stderr,
               "hausdorff phases: trees %.2f s (cpu %.2f), input->output %.2f s (cpu %.2f), "
               "output->input %.2f s (cpu %.2f)\n",
               index_s, index_cpu, in_to_out_s, in_to_out_cpu, out_to_in_s, out_to_in_cpu);
  const double n = static_cast<double>(input.num_faces());
  e2e["method"] = pg::DecimationMethodName(options.method);
  e2e["clean"] = {
      {"seconds", clean_s}, {"cpu_seconds", clean_cpu}, {"report", report.ToJson()}, {"digest", Digest(cleaned)}};
  e2e["decimate"] = {
      {"seconds", decimate_s}, {"cpu_seconds", decimate_cpu}, {"faces_out", out.num_faces()}, {"digest", Digest(out)}};
  e2e["hausdorff"] = {{"seconds", hausdorff_s},
                      {"cpu_seconds", hausdorff_cpu},
                      {"hausdorff_m", d.symmetric_m},
                      {"in_to_out_m", d.a_to_b_m},
                      {"out_to_in_m", d.b_to_a_m},
                      {"points_measured", d.samples_a + d.samples_b},
                      {"trees_seconds", index_s},
                      {"trees_cpu_seconds", index_cpu},
                      {"in_to_out_cpu_seconds", in_to_out_cpu},
                      {"out_to_in_cpu_seconds", out_to_in_cpu}};
  const double cd = clean_s + decimate_s, cd_cpu = clean_cpu + decimate_cpu;
  e2e["clean_decimate"] = {{"seconds", cd}, {"cpu_seconds", cd_cpu}, {"input_faces_per_s", n / cd}};
  e2e["clean_decimate_hausdorff"] = {{"seconds", cd + hausdorff_s},
                                     {"cpu_seconds", cd_cpu + hausdorff_cpu},
                                     {"input_faces_per_s", n / (cd + hausdorff_s)}};
  std::fprintf(stderr,
               "end-to-end %s: clean %.2f s (cpu %.2f)  decimate %.2f s (cpu %.2f) -> %zu faces  "
               "hausdorff %.4f m %.2f s (cpu %.2f)  clean+decimate %.2f M faces/s, with hausdorff "
               "%.2f M faces/s\n",
               e2e["method"].get<std::string>().c_str(), clean_s, clean_cpu, decimate_s, decimate_cpu, out.num_faces(),
               d.symmetric_m, hausdorff_s, hausdorff_cpu, n / cd / 1e6, n / (cd + hausdorff_s) / 1e6);
  return e2e;
}

// The cleaning step alone.
Json MeasureClean(const pg::TriangleMesh& input) {
  const auto start = std::chrono::steady_clock::now();
  const double cpu0 = CpuSeconds();
  pg::MeshCleanReport report;
  const pg::TriangleMesh cleaned = pg::CleanMesh(input, pg::MeshCleanOptions{}, &report);
  const double s = Seconds(start);
  std::fprintf(stderr, "clean: %.2f s\n", s);
  return {{"seconds", s},
          {"cpu_seconds", CpuSeconds() - cpu0},
          {"faces_per_s", input.num_faces() / s},
          {"faces_out", cleaned.num_faces()}};
}

// Every method at every budget (a face ratio, or an error goal), with its Hausdorff distance to the input.
Json DecimationTable(const pg::TriangleMesh& input, const BenchArgs& args, const pg::HausdorffOptions& hausdorff) {
  const double& ratio = args.ratio;
  const std::string& methods = args.methods;
  const std::string& ratios = args.ratios;
  const std::string& error_goals = args.error_goals;
  const pg::internal::QemOptions& qem = args.qem;
  const int& partitions = args.partitions;
  const bool& bound = args.bound;
  const std::string& sample_counts = args.sample_counts;
  auto start = std::chrono::steady_clock::now();
  Json rows = Json::array();
  std::unique_ptr<pg::MeshDistanceIndex> input_index;  // built once, for every method
  std::vector<double> budgets;
  for (const std::string& r : Split(error_goals.empty() ? ratios : error_goals)) budgets.push_back(std::stod(r));
  if (budgets.empty()) budgets.push_back(ratio);
  const bool goals = !error_goals.empty();
  for (double budget : budgets)
    for (const std::string& name : Split(methods)) {
      pg::DecimateOptions options;
      options.method = pg::ParseDecimationMethod(name, "--methods");
      if (goals) {
        options.max_error_m = budget;
      } else {
        options.target_faces = static_cast<int64_t>(std::llround(budget * input.num_faces()));
      }
      options.qem = qem;
      if (partitions > 0) options.partitions = options.qem.tiles = partitions;
      start = std::chrono::steady_clock::now();
      const double cpu0 = CpuSeconds();
      const pg::TriangleMesh out = pg::DecimateMesh(input, options);
      const double s = Seconds(start);
      const double cpu = CpuSeconds() - cpu0;
      Json row = {{"method", name},
                  {goals ? "error_goal_m" : "ratio", budget},
                  {"target_faces", options.target_faces},
                  {"digest", Digest(out)},
                  {"seconds", s},
                  {"cpu_seconds", cpu},
                  {"input_faces_per_s", input.num_faces() / s},
                  {"faces_out", out.num_faces()}};
      if (hausdorff.samples_per_mesh <= 0) {  // --samples 0: the time alone (profiles, timing runs)
        std::fprintf(stderr, "%6g%s %-36s %8.3f s (cpu %.3f s) %9zu faces\n", goals ? budget : 100 * budget,
                     goals ? " m" : " %", name.c_str(), s, cpu, out.num_faces());
        rows.push_back(row);
        continue;
      }
      start = std::chrono::steady_clock::now();
      if (!input_index) input_index = std::make_unique<pg::MeshDistanceIndex>(input, "input");
      const pg::MeshDistanceIndex out_index(out, "output");
      const pg::HausdorffDistance d = pg::ApproximateHausdorff(*input_index, out_index, hausdorff);
      const double hs = Seconds(start);
      Json extra = Json::object();
      if (bound) {
        start = std::chrono::steady_clock::now();
        const pg::HausdorffBoundOptions& bound_options = args.bound_options;
        const pg::HausdorffInterval in_out = input_index->BoundDistanceTo(out_index, d.a_to_b_m, bound_options);
        const pg::HausdorffInterval out_in = out_index.BoundDistanceTo(*input_index, d.b_to_a_m, bound_options);
        const double bs = Seconds(start);
        std::fprintf(stderr,
                     "      bound: in->out [%.4f, %.4f] (%lld unresolved), out->in [%.4f, %.4f] (%lld unresolved); "
                     "symmetric [%.4f, %.4f], %lld points, %.1f s\n",
                     in_out.lower_m, in_out.upper_m, static_cast<long long>(in_out.unresolved_triangles),
                     out_in.lower_m, out_in.upper_m, static_cast<long long>(out_in.unresolved_triangles),
                     std::max(in_out.lower_m, out_in.lower_m), std::max(in_out.upper_m, out_in.upper_m),
                     static_cast<long long>(in_out.points_measured + out_in.points_measured), bs);
        extra["bound"] = {
            {"lower_m", std::max(in_out.lower_m, out_in.lower_m)},
            {"upper_m", std::max(in_out.upper_m, out_in.upper_m)},
            {"in_to_out",
             {{"lower_m", in_out.lower_m}, {"upper_m", in_out.upper_m}, {"unresolved", in_out.unresolved_triangles}}},
            {"out_to_in",
             {{"lower_m", out_in.lower_m}, {"upper_m", out_in.upper_m}, {"unresolved", out_in.unresolved_triangles}}},
            {"points_measured", in_out.points_measured + out_in.points_measured},
            {"seconds", bs}};
      }
      if (!sample_counts.empty()) {
        Json table = Json::array();
        for (const std::string& count : Split(sample_counts)) {
          for (bool vertices : {false, true}) {
            pg::HausdorffOptions h = hausdorff;
            h.samples_per_mesh = std::stoll(count);
            h.sample_vertices = vertices;
            start = std::chrono::steady_clock::now();
            const pg::HausdorffDistance e = pg::ApproximateHausdorff(*input_index, out_index, h);
            std::fprintf(stderr, "      %9lld samples%s: %.4f m (%.1f s)\n", static_cast<long long>(h.samples_per_mesh),
                         vertices ? " + vertices" : "           ", e.symmetric_m, Seconds(start));
            table.push_back(
                {{"samples_per_mesh", h.samples_per_mesh}, {"vertices", vertices}, {"hausdorff_m", e.symmetric_m}});
          }
        }
        extra["convergence"] = table;
      }
      std::fprintf(
          stderr,
          "%6g%s %-36s %8.2f s (cpu %.2f s) %9zu faces  hausdorff %.4f m (in->out %.4f, out->in %.4f; %.1f s)\n",
          goals ? budget : 100 * budget, goals ? " m" : " %", name.c_str(), s, cpu, out.num_faces(), d.symmetric_m,
          d.a_to_b_m, d.b_to_a_m, hs);
      row["hausdorff_m"] = d.symmetric_m;
      row["hausdorff_in_to_out_m"] = d.a_to_b_m;
      row["hausdorff_out_to_in_m"] = d.b_to_a_m;
      row["hausdorff_s"] = hs;
      rows.push_back(row);
      for (auto it = extra.begin(); it != extra.end(); ++it) rows.back()[it.key()] = it.value();
    }
  return rows;
}

// --presets: the surface pipeline's draft, standard and final on the input.
Json PresetTable(const pg::TriangleMesh& input) {
  Json table = Json::array();
  for (cinepath::Quality quality :
       {cinepath::Quality::kDraft, cinepath::Quality::kStandard, cinepath::Quality::kFinal}) {
    pg::SurfacePipelineOptions options;
    options.quality = quality;
    const auto start = std::chrono::steady_clock::now();
    const double cpu0 = CpuSeconds();
    const pg::SurfacePipelineResult r = pg::BuildSurfaceFromMesh(input, nullptr, options);
    const double s = Seconds(start);
    const double cpu = CpuSeconds() - cpu0;
    std::fprintf(stderr, "preset %-8s %8.2f s  %9zu faces  hausdorff %.4f m\n", cinepath::QualityName(quality), s,
                 r.mesh.num_faces(), r.report["output"]["hausdorff_m"].get<double>());
    table.push_back({{"quality", cinepath::QualityName(quality)},
                     {"seconds", s},
                     {"cpu_seconds", cpu},
                     {"faces_out", r.mesh.num_faces()},
                     {"hausdorff_m", r.report["output"]["hausdorff_m"]},
                     {"glb_bytes", r.glb.size()},
                     {"steps", r.report["steps"]}});
  }
  return table;
}

}  // namespace

int main(int argc, char** argv) {
  cinepath::PrepareHeapForLargeBuffers(cinepath::kCommandHeapReserveBytes);  // as `cinepath mesh` does
  BenchArgs args;
  if (const auto exit_code = ParseArgs(argc, argv, args)) return *exit_code;
  const int64_t& faces = args.faces;
  const double& ratio = args.ratio;
  const int64_t& samples = args.samples;
  const bool& defects = args.defects;
  const int& threads = args.threads;
  const std::string& export_raw = args.export_raw;
  std::unique_ptr<tbb::global_control> thread_cap;
  if (threads > 0) {
    thread_cap = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                       static_cast<size_t>(threads));
  }
  Json result;
  const auto start = std::chrono::steady_clock::now();
  const pg::TriangleMesh input = [&] {
    pg::TriangleMesh mesh = MakeTerrainMesh(faces);
    if (defects) AddDefects(mesh);
    return mesh;
  }();
  result["input"] = {{"faces", input.num_faces()},
                     {"defects", defects},
                     {"threads_cap", threads},
                     {"vertices", input.num_vertices()},
                     {"generate_s", Seconds(start)}};
  std::fprintf(stderr, "input: %zu faces, %zu vertices\n", input.num_faces(), input.num_vertices());
  if (!export_raw.empty()) WriteRaw(input, export_raw);
  const int64_t target = static_cast<int64_t>(std::llround(ratio * input.num_faces()));
  result["target_faces"] = target;
  result["hausdorff_samples_per_mesh"] = samples;
  pg::HausdorffOptions hausdorff;
  hausdorff.samples_per_mesh = samples;

  if (!args.import_raw.empty()) {
    result.update(MeasureExternal(input, args, hausdorff));
    std::printf("%s", cinepath::DumpJson(result).c_str());
    return 0;
  }
  if (args.end_to_end) {
    result["end_to_end"] = MeasureEndToEnd(input, args, target, hausdorff);
    std::printf("%s", cinepath::DumpJson(result).c_str());
    return 0;
  }
  result["clean"] = MeasureClean(input);
  result["decimation"] = DecimationTable(input, args, hausdorff);
  if (args.presets) result["presets"] = PresetTable(input);
  std::printf("%s", cinepath::DumpJson(result).c_str());
  return 0;
}
