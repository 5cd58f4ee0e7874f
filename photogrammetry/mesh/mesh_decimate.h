// Mesh decimation to a face budget (or an error bound), with the simplifiers measured in
// bench/mesh_decimate_bench.cc: meshoptimizer, a partitioned parallel meshoptimizer (the fastest,
// ~30× faster than CGAL), CGAL Garland–Heckbert (plane — the final preset: the most accurate at light
// budgets — and probabilistic plane policies), OpenMesh's quadric Decimater, and qem_tiled (draft and
// standard presets, and error goals): quadric collapse with optimal placement in parallel tiles
// (mesh_decimate_qem.cc; below OpenMesh's error from 10 % to 80 % of the bench terrain, 19–30×
// faster, bench/RESULTS.md). The outer border of an open (terrain) mesh is kept in place by every
// method.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "photogrammetry/mesh/triangle_mesh.h"

namespace cinepath::photogrammetry {

enum class DecimationMethod {
  kMeshoptimizer,                     // meshopt_simplify (quadric collapse), border locked
  kMeshoptimizerPartitioned,          // tiles simplified in parallel (borders locked), then one global pass
  kCgalGarlandHeckbert,               // CGAL SMS edge_collapse, GarlandHeckbert_plane_policies
  kCgalGarlandHeckbertProbabilistic,  // GarlandHeckbert_probabilistic_plane_policies
  kOpenMeshQuadric,                   // OpenMesh DecimaterT + ModQuadricT
  kQemTiled,  // quadric collapse with optimal placement, tiles in parallel then a pass over the whole
};
const char* DecimationMethodName(DecimationMethod method);
// Every method, in a fixed order (mesh_decimate_bench --list-methods prints their names).
std::vector<DecimationMethod> AllDecimationMethods();
// Parses the names DecimationMethodName gives; throws InputError naming `where`.
DecimationMethod ParseDecimationMethod(const std::string& text, const std::string& where);

namespace internal {
// kQemTiled's settings (mesh_decimate_qem.cc); the defaults are the measured best.
struct QemOptions {
  bool optimal_placement = true;  // false: the endpoint with the lower error (a half-edge collapse)
  bool area_weighted = true;      // plane quadrics weighted by face area (else one per face)
  double placement_reach = 2.0;   // the quadric minimum is used within this many edge lengths of the edge
  double min_normal_cos = 0.5;    // a collapse may turn no remaining face's normal further than this
  int tiles = 256;                // fixed grid of tiles (same mesh on any machine); small tiles fit the cache
  // Eigenvalues of the quadric at most this fraction of its largest leave their direction at the edge's
  // midpoint (the quadric does not pin it down); bench/RESULTS.md has the measured choice.
  double placement_rcond = 1e-3;
  // The pass after the tiles works on the faces within ceil(final_band_rings / √keep) rings of the
  // tiles' cuts (its outer border locked), where the tiles left the full density; keep is the budget's
  // share of the faces (the lighter the budget, the coarser the tiles' faces next to the band, and the
  // wider it must be to take their share). 0 = on every merged face.
  double final_band_rings = 4;
  // The band pass runs in parallel on cells (a grid shifted by half a tile) that each keep about this
  // many faces; a band that would keep fewer than four times this, or 0, is simplified as one piece.
  // The cells' locked cuts cost some accuracy on small meshes (docs/mesh.md, bench/RESULTS.md).
  double band_cell_faces = 4000;
  // Two terms for the light budgets, where the Hausdorff error comes down to a few spots of noisy ground
  // (bench/RESULTS.md, "Decimation against the peers", 2026-11-28). Both apply with a face budget that
  // keeps at least `light_budget_keep` of the faces; below it (and with error goals) neither does,
  // since there they were measured to help on one mesh and to hurt on another.
  double light_budget_keep = 0.6;
  // At those light budgets the tiles hold about this many faces each (fewer than `tiles` on a mesh
  // under tiles × this), when the mesh holds at least 4 × 4 such tiles: the band around the cuts,
  // simplified a second time, is then a smaller share of the mesh (on 500 k faces 36 % with 64 tiles,
  // 65 % with 256), about 9 % faster at 80 %, and as close or closer by the certified bound on every
  // mesh of 100 k-1 M faces measured (bench/RESULTS.md, run X). A smaller mesh keeps the fine grid,
  // whose band covers it whole: a second pass over every face, cheap there, and on the unit tests'
  // 51 k-face ground with buildings more accurate than 3 × 3 or 4 × 4 tiles. Not below
  // light_budget_keep, where fewer tiles were measured less accurate. 0 = always `tiles`.
  double light_budget_tile_faces = 8000;
  // Each face's plane weighs its area plus this many times the median face area of its tile, so that a
  // vertex whose faces are small (close, noisy points) is not collapsed away for their small area
  // alone; below 0: the budget's share of the faces. 0 = area only.
  double area_floor = -1;
  // A collapse costs at least this many times its planes' weight × the squared distance from the
  // edge's two vertices to the faces around the new point (the quadric's cost is a mean over its
  // planes; the Hausdorff error is a maximum). 0 = the quadric alone.
  double distance_check = 0.6;
  // ... and that distance also from the midpoints of the two vertices' edges: the farthest input
  // points were inside faces whose corners the collapses left on the surface (bench/RESULTS.md, run V).
  bool distance_check_midpoints = true;
  // ... and the other way: the midpoints of the new edges to the faces before the collapse, where
  // slivers across a crease stood off the input with their corners on it (bench/RESULTS.md, run Z).
  bool distance_check_new_edges = true;
  // The spike pass, with a face budget that keeps less than `light_budget_keep` of the faces: once the
  // budget is met, the input vertices the output left farther than this share of the largest such
  // distance are pinned (locked as the cuts are), and the tiles that hold one run again with the band
  // pass, so that other collapses meet the budget (bench/RESULTS.md, run M). 0 = off.
  double spike_pass = 0.8;
  // The re-fit, with a face budget that keeps less than `light_budget_keep` of the faces: the output vertices farther
  // from the input (measured against the input faces merged into them) than this share of the largest such distance are
  // moved towards the input when that lowers the distances around them (docs/mesh.md). 0 = off.
  double refit = 0.8;
};
}  // namespace internal

struct DecimateOptions {
  DecimationMethod method = DecimationMethod::kMeshoptimizerPartitioned;
  int64_t target_faces = 0;  // > 0: stop at (about) this many faces
  // > 0 (meshoptimizer methods: also) stop before the simplifier's own error estimate exceeds this
  // distance in metres; qem_tiled takes it instead of a face budget (its estimate: a collapse's RMS
  // distance to the planes merged into it). The pipeline checks the result with a Hausdorff measurement.
  double max_error_m = 0;
  int partitions = 16;  // kMeshoptimizerPartitioned: tiles (fixed: same mesh on any machine)
  internal::QemOptions qem;
};

struct DecimateStats {
  int64_t faces_in = 0, faces_out = 0, vertices_in = 0, vertices_out = 0;
  double simplifier_error_m = -1;  // the simplifier's own error estimate when it gives one
};

// Vertices no face uses are dropped; colours follow their vertices. Deterministic for any thread
// count (partitions are fixed by geometry, not by threads).
TriangleMesh DecimateMesh(const TriangleMesh& mesh, const DecimateOptions& options, DecimateStats* stats = nullptr);

namespace internal {
// In mesh_decimate_cgal.cc (the CGAL translation unit).
TriangleMesh DecimateCgal(const TriangleMesh& mesh, int64_t target_faces, bool probabilistic);
// In mesh_decimate_qem.cc. With `goal_error_m` (one per vertex) there is no face budget: every
// collapse is made whose error (the root of its quadric's area-weighted mean: its point's RMS distance
// to the planes of the faces merged into it) is within the smaller goal of its two vertices, and the
// vertex kept takes that goal; a vertex whose goal is 0 is never moved or removed (nor, when all its
// corners have goal 0, is a face). The measured error of the result is the caller's to check.
TriangleMesh DecimateQemTiled(const TriangleMesh& mesh, int64_t target_faces, int partitions, const QemOptions& options,
                              const std::vector<double>* goal_error_m = nullptr);
// In mesh_decimate.cc: the mesh of the triangles `indices` (three vertex ids each) of `mesh`, with the
// vertices they use, in their input order, and their colours.
TriangleMesh FromKeptIndices(const TriangleMesh& mesh, const std::vector<uint32_t>& indices);
}  // namespace internal

}  // namespace cinepath::photogrammetry
