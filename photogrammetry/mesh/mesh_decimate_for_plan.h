// `cinepath mesh --for-plan plan.json`: simplify each part of the surface only as far as the plan's
// cameras can tell (docs/mesh.md, "Detail where the cameras look").
//
// Regions are a fixed grid of tiles over the mesh's east/north bounding box (tiles_per_side², the same
// tiles on any machine). Each tile's allowed error is max_error_px × the finest metres-per-pixel over
// the points of the tile that a plan frame sees (view_dependent_budget.h: the closest frame, with its
// focal length and resolution); a tile no frame sees gets the coarsest budget any seen tile gets, in
// metres.
//
// Simplification, with an error goal and no face goal, by one of two simplifiers:
//   qem_tiled (the default): quadric collapse with optimal placement (internal::DecimateQemTiled) with
//      a goal per vertex: its own budget (max_error_px × its metres per pixel in its finest view, or the
//      unseen budget) × its tile's factor. Its error is the RMS distance of the placed point to the
//      planes merged into it, which falls short of the largest distance, so the search starts at 1/4.
//   meshoptimizer (meshopt_simplify, the simplifier before 2026-11-26; kept for comparison), a goal per
//      tile, in two passes:
//   1. every tile on its own, in parallel, its cut edges and the mesh's outer border locked, to its goal;
//   2. a second grid shifted by half a tile, so that the cuts of pass 1 lie inside its tiles, each tile
//      to the smallest goal of the (up to 4) pass-1 tiles it overlaps;
// Then, with either:
//   3. measure: points on the original surface (every vertex plus `measure_samples` random points on
//      the faces, spread by area, seeded), each one's distance to the simplified mesh divided by its
//      metres-per-pixel = its worst projected error in pixels over every frame that sees it (unseen
//      points: the distance against the unseen budget).
// Either simplifier's error is its own estimate (and meshoptimizer's passes 1 and 2 add up), so each
// tile's goal (allowed × a factor) is searched over the rounds: ×4 while its points stay within aim ×
// the bound, ×1/4 while over, then bisected; then each tile takes the largest factor found within. A
// tile still over after that (its factor halved, then zeroed, a round each) first freezes, for up to
// face_freeze_rounds rounds, the faces under its measured points over the bound and the faces around
// their corners; a tile still over after those is frozen whole. Frozen faces come out as they went in:
// qem_tiled gives their corners a goal of 0, which it never touches; with meshoptimizer they are left
// out of pass 1, and out of pass 2's input, so that its edge with them is an open border that
// meshopt_SimplifyLockBorder keeps in place. The rounds go on, freezing, until every tile is within or
// frozen. meshoptimizer 0.18 makes collapses it rates at ~zero error that move the surface by
// centimetres, so a goal of 0 is no bound; a frozen tile is (its points lie on faces of the output). A
// point is the tile's of the face it lies on (a vertex: of its first face), so that freezing the tile
// of a point over the bound puts the point back on the output. The outer border of an open mesh stays
// in place. Deterministic at any thread count.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/json.h"
#include "photogrammetry/mesh/triangle_mesh.h"
#include "photogrammetry/mesh/view_dependent_budget.h"

namespace cinepath::photogrammetry {

enum class ForPlanSimplifier {
  kQemTiled,       // quadric collapse with optimal placement and an error goal per vertex (the default)
  kMeshoptimizer,  // meshopt_simplify with an error goal per tile, in two passes (steps 1 and 2 above)
};
const char* ForPlanSimplifierName(ForPlanSimplifier simplifier);

struct ForPlanOptions {
  std::vector<PlanCamera> cameras;                              // CamerasFromPlan
  std::string plan_source;                                      // the plan file, for the report
  double max_error_px = 0.5;                                    // --max-error-px
  ForPlanSimplifier simplifier = ForPlanSimplifier::kQemTiled;  // see above
  int tiles_per_side = 16;                                      // the region grid
  int64_t measure_samples = 200000;  // random points on the original faces (every vertex is measured too)
  uint32_t seed = 1;
  // The search aims at aim × the bound on the measured points: the error between them can be a little
  // larger (an independent sampling of the test mesh found 2 % more than the measured points).
  double aim = 0.9;
  // A tile over the bound after the search keeps its original faces. false: it gets an error goal of 0
  // instead, which meshoptimizer 0.18 can overshoot (the bound is then not met; for the tests and the
  // benchmark, to show what freezing buys).
  bool freeze = true;
  // Before a whole tile is frozen: this many rounds that freeze only the faces under its points over
  // the bound, with the faces around their corners (0: whole tiles at once).
  int face_freeze_rounds = 8;
  int max_rounds = 10;  // search rounds (max_rounds - 3, at least 1) + 1 settling round; then freezing rounds

  void Check() const;  // InputError naming the field
};

struct ForPlanTile {
  int ix = 0, iy = 0;                   // column (east) and row (north)
  int64_t faces_in = 0, faces_out = 0;  // faces whose centroid lies in the tile
  bool seen = false;
  int camera_sample = -1;  // the plan sample whose camera sees the tile the finest
  double camera_time_s = 0;
  double depth_m = 0;             // that camera's depth of the finest-seen point
  double allowed_error_m = 0;     // max_error_px × its metres per pixel (unseen: the coarsest budget)
  double goal_error_m = 0;        // the error goal meshoptimizer got in the last round (allowed × 2^-k)
  double worst_projected_px = 0;  // over the measured points of the tile
  bool frozen = false;            // over the bound after the search: its original faces, untouched
  int64_t faces_frozen = 0;       // in a tile not frozen whole: faces kept as they were (see face_freeze_rounds)
};

struct ForPlanReport {
  ForPlanSimplifier simplifier = ForPlanSimplifier::kQemTiled;
  int tiles_per_side = 0;
  Eigen::Vector2d grid_min_m = Eigen::Vector2d::Zero();  // east/north of the grid's corner
  Eigen::Vector2d tile_size_m = Eigen::Vector2d::Zero();
  std::vector<ForPlanTile> tiles;  // row-major (iy, ix), only tiles holding faces
  double max_error_px = 0;
  double aim = 0;
  double min_allowed_error_m = 0;  // over seen tiles: the error a uniform simplification must keep
  double max_allowed_error_m = 0;  // over seen tiles
  double unseen_allowed_error_m = 0;
  int64_t tiles_seen = 0, tiles_unseen = 0;
  int64_t tiles_frozen = 0;
  int64_t faces_frozen = 0;  // frozen on their own, in tiles not frozen whole
  int64_t faces_in = 0, faces_out = 0;
  int64_t points_measured = 0;  // vertices + face samples of the original mesh
  int64_t points_seen = 0;      // of those, seen by some frame
  double worst_projected_px = 0;
  int worst_camera_sample = -1;
  std::string worst_camera_drone;   // that sample's drone, in a plan of several (else empty)
  double worst_unseen_error_m = 0;  // over the points no frame sees (their budget: unseen_allowed_error_m)
  int rounds = 0;
  int freeze_rounds = 0;  // of those, the rounds run with some tile or face frozen
  bool bound_met = false;
  Json ToJson() const;
};

TriangleMesh DecimateForPlan(const TriangleMesh& mesh, const ForPlanOptions& options, ForPlanReport* report = nullptr);

// The measurement of step 3, on its own (the benchmark measures a uniform simplification with it):
// every vertex of `original` and `face_samples` points on its faces, each with its finest view, built once.
class ProjectedErrorProbe {
 public:
  ProjectedErrorProbe(const TriangleMesh& original, const std::vector<PlanCamera>& cameras, int64_t face_samples,
                      uint32_t seed);
  // Each point's distance (m) to `simplified` (exact closest-point queries, CGAL AABB tree).
  std::vector<double> DistancesM(const TriangleMesh& simplified) const;
  // The worst projected error (px) of `simplified` over the seen points (and which point).
  double WorstPx(const TriangleMesh& simplified, int* worst_point = nullptr) const;

  const std::vector<Eigen::Vector3d>& points() const { return points_; }  // vertices, then face samples
  const std::vector<PointView>& views() const { return views_; }          // one per point
  // The face of `original` each point lies on (a vertex: the first face using it; -1 for none).
  const std::vector<int64_t>& faces() const { return faces_; }
  int64_t points_seen() const { return points_seen_; }

 private:
  std::vector<int64_t> faces_;  // before points_: SampleSurface fills it
  std::vector<Eigen::Vector3d> points_;
  std::vector<PointView> views_;
  int64_t points_seen_ = 0;
};

}  // namespace cinepath::photogrammetry
