#include "photogrammetry/mesh/mesh_decimate_for_plan.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>
#include <meshoptimizer.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "core/error.h"
#include "photogrammetry/mesh/mesh_decimate.h"
#include "photogrammetry/mesh/vertex_faces.h"

namespace cinepath::photogrammetry {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double Uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

// Every vertex plus `count` points on the faces, spread by area (seeded; the same points on any machine).
// `faces` gets the face each point lies on (a vertex: the first face using it, -1 for none).
std::vector<Eigen::Vector3d> SampleSurface(const TriangleMesh& mesh, int64_t count, uint32_t seed,
                                           std::vector<int64_t>* faces) {
  std::vector<Eigen::Vector3d> points(mesh.vertices_m.begin(), mesh.vertices_m.end());
  faces->assign(mesh.num_vertices(), -1);
  for (size_t f = mesh.num_faces(); f-- > 0;) {
    for (uint32_t i : mesh.faces[f]) (*faces)[i] = static_cast<int64_t>(f);
  }
  std::vector<double> cumulative(mesh.num_faces());
  double total = 0;
  for (size_t f = 0; f < mesh.num_faces(); ++f) {
    const auto& t = mesh.faces[f];
    const Eigen::Vector3d& a = mesh.vertices_m[t[0]];
    total += 0.5 * (mesh.vertices_m[t[1]] - a).cross(mesh.vertices_m[t[2]] - a).norm();
    cumulative[f] = total;
  }
  if (!(total > 0) || count <= 0) return points;
  std::mt19937_64 rng(seed);
  points.reserve(points.size() + static_cast<size_t>(count));
  faces->reserve(points.size() + static_cast<size_t>(count));
  for (int64_t k = 0; k < count; ++k) {
    const double at = Uniform01(rng) * total;
    const size_t f = std::min<size_t>(mesh.num_faces() - 1,
                                      std::upper_bound(cumulative.begin(), cumulative.end(), at) - cumulative.begin());
    double r1 = Uniform01(rng), r2 = Uniform01(rng);
    if (r1 + r2 > 1) {
      r1 = 1 - r1;
      r2 = 1 - r2;
    }
    const auto& t = mesh.faces[f];
    const Eigen::Vector3d& a = mesh.vertices_m[t[0]];
    points.push_back(a + r1 * (mesh.vertices_m[t[1]] - a) + r2 * (mesh.vertices_m[t[2]] - a));
    faces->push_back(static_cast<int64_t>(f));
  }
  return points;
}

// The region grid over the east/north bounds of the vertices.
struct TileGrid {
  int n = 1;
  Eigen::Vector2d lo = Eigen::Vector2d::Zero();
  Eigen::Vector2d size = Eigen::Vector2d::Ones();

  int Cell(double x, double lo_x, double size_x, int cells) const {
    const int i = static_cast<int>(std::floor((x - lo_x) / size_x));
    return std::clamp(i, 0, cells - 1);
  }
  // Tile of a point on the main grid (n × n).
  int Tile(const Eigen::Vector3d& p) const {
    return Cell(p.y(), lo.y(), size.y(), n) * n + Cell(p.x(), lo.x(), size.x(), n);
  }
  // Tile on the grid shifted by half a tile ((n + 1) × (n + 1)): shifted tile (sx, sy) overlaps main
  // tiles sx - 1 .. sx and sy - 1 .. sy.
  int ShiftedTile(const Eigen::Vector3d& p) const {
    const int sx = std::clamp(static_cast<int>(std::floor((p.x() - lo.x()) / size.x() + 0.5)), 0, n);
    const int sy = std::clamp(static_cast<int>(std::floor((p.y() - lo.y()) / size.y() + 0.5)), 0, n);
    return sy * (n + 1) + sx;
  }
};

TileGrid MakeGrid(const TriangleMesh& mesh, int tiles_per_side) {
  TileGrid g;
  g.n = std::max(1, tiles_per_side);
  Eigen::Vector2d lo(kInf, kInf), hi(-kInf, -kInf);
  for (const auto& v : mesh.vertices_m) {
    lo = lo.cwiseMin(v.head<2>());
    hi = hi.cwiseMax(v.head<2>());
  }
  g.lo = lo;
  g.size = ((hi - lo) / g.n).cwiseMax(Eigen::Vector2d(1e-6, 1e-6));
  return g;
}

Eigen::Vector3d Centroid(const TriangleMesh& mesh, const std::array<uint32_t, 3>& f) {
  return (mesh.vertices_m[f[0]] + mesh.vertices_m[f[1]] + mesh.vertices_m[f[2]]) / 3.0;
}

struct Positions {
  std::vector<float> xyz;  // relative to the bounding-box centre, float for meshoptimizer
  float scale = 1;         // meshopt_simplifyScale: its errors are relative to this
};

Positions MakePositions(const TriangleMesh& mesh) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(kInf), hi = -lo;
  for (const auto& v : mesh.vertices_m) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const Eigen::Vector3d center = 0.5 * (lo + hi);
  Positions p;
  p.xyz.reserve(3 * mesh.num_vertices());
  for (const auto& v : mesh.vertices_m) {
    const Eigen::Vector3d d = v - center;
    p.xyz.insert(p.xyz.end(), {static_cast<float>(d.x()), static_cast<float>(d.y()), static_cast<float>(d.z())});
  }
  p.scale = std::max(1e-30f, meshopt_simplifyScale(p.xyz.data(), mesh.num_vertices(), 3 * sizeof(float)));
  return p;
}

// meshopt_simplify on the faces `indices` (global vertex indices) with a compact vertex buffer (its
// cost follows the vertex count it is given), border locked, no face goal, the error goal in metres.
// `scratch` maps global → local indices (one entry per global vertex; never cleared).
std::vector<uint32_t> SimplifyFaces(const Positions& positions, const std::vector<uint32_t>& indices,
                                    double goal_error_m, std::vector<uint32_t>& scratch) {
  if (indices.empty()) return {};
  std::vector<uint32_t> global(indices);
  std::sort(global.begin(), global.end());
  global.erase(std::unique(global.begin(), global.end()), global.end());
  std::vector<float> local_xyz(3 * global.size());
  for (size_t k = 0; k < global.size(); ++k) {
    scratch[global[k]] = static_cast<uint32_t>(k);
    std::copy_n(positions.xyz.begin() + 3 * static_cast<size_t>(global[k]), 3, local_xyz.begin() + 3 * k);
  }
  std::vector<uint32_t> local(indices.size());
  for (size_t k = 0; k < indices.size(); ++k) local[k] = scratch[indices[k]];
  std::vector<uint32_t> out(local.size());
  float result_error = 0;
  const size_t count =
      meshopt_simplify(out.data(), local.data(), local.size(), local_xyz.data(), global.size(), 3 * sizeof(float), 0,
                       static_cast<float>(goal_error_m / positions.scale), meshopt_SimplifyLockBorder, &result_error);
  out.resize(count);
  for (uint32_t& i : out) i = global[i];
  return out;
}

// Simplifies the faces of each tile to its goal, in parallel; returns the kept faces in tile order.
std::vector<uint32_t> SimplifyTiles(const Positions& positions, const std::vector<std::vector<uint32_t>>& tiles,
                                    const std::vector<double>& goal_error_m, size_t num_vertices) {
  tbb::enumerable_thread_specific<std::vector<uint32_t>> scratch([&] { return std::vector<uint32_t>(num_vertices); });
  std::vector<std::vector<uint32_t>> kept(tiles.size());
  tbb::parallel_for(size_t{0}, tiles.size(),
                    [&](size_t t) { kept[t] = SimplifyFaces(positions, tiles[t], goal_error_m[t], scratch.local()); });
  std::vector<uint32_t> merged;
  for (const auto& k : kept) merged.insert(merged.end(), k.begin(), k.end());
  return merged;
}

// Passes 1 and 2 with the main tiles' goals. The faces of a frozen tile and the frozen faces go through
// both passes untouched: left out of pass 1, and out of pass 2's input (their edge with the rest is then
// an open border, which meshopt_SimplifyLockBorder keeps in place); they come last, in input order.
std::vector<uint32_t> SimplifyTwoPasses(const TriangleMesh& mesh, const Positions& positions, const TileGrid& grid,
                                        const std::vector<double>& goal_error_m, const std::vector<char>& frozen,
                                        const std::vector<char>& face_frozen) {
  const int n = grid.n;
  std::vector<std::vector<uint32_t>> tiles(static_cast<size_t>(n) * n);
  std::vector<uint32_t> untouched;
  for (size_t k = 0; k < mesh.faces.size(); ++k) {
    const auto& f = mesh.faces[k];
    const int t = grid.Tile(Centroid(mesh, f));
    auto& tile = frozen[t] || face_frozen[k] ? untouched : tiles[t];
    tile.insert(tile.end(), f.begin(), f.end());
  }
  const std::vector<uint32_t> pass1 = SimplifyTiles(positions, tiles, goal_error_m, mesh.num_vertices());

  const int m = n + 1;
  std::vector<std::vector<uint32_t>> shifted(static_cast<size_t>(m) * m);
  for (size_t k = 0; k + 2 < pass1.size(); k += 3) {
    const Eigen::Vector3d c =
        (mesh.vertices_m[pass1[k]] + mesh.vertices_m[pass1[k + 1]] + mesh.vertices_m[pass1[k + 2]]) / 3.0;
    auto& tile = shifted[grid.ShiftedTile(c)];
    tile.insert(tile.end(), pass1.begin() + k, pass1.begin() + k + 3);
  }
  // Each shifted tile to the smallest goal of the main tiles it overlaps that are not frozen.
  std::vector<double> shifted_goal(shifted.size(), kInf);
  for (int sy = 0; sy < m; ++sy) {
    for (int sx = 0; sx < m; ++sx) {
      double& goal = shifted_goal[static_cast<size_t>(sy) * m + sx];
      for (int iy = std::max(0, sy - 1); iy <= std::min(n - 1, sy); ++iy) {
        for (int ix = std::max(0, sx - 1); ix <= std::min(n - 1, sx); ++ix) {
          const size_t t = static_cast<size_t>(iy) * n + ix;
          if (!frozen[t]) goal = std::min(goal, goal_error_m[t]);
        }
      }
      if (std::isinf(goal)) goal = 0;  // no faces come from a frozen tile; no goal needed
    }
  }
  std::vector<uint32_t> out = SimplifyTiles(positions, shifted, shifted_goal, mesh.num_vertices());
  out.insert(out.end(), untouched.begin(), untouched.end());
  return out;
}

// The same with quadric collapse (internal::DecimateQemTiled with an error goal per vertex): each
// vertex's goal is its own budget (max_error_px × its metres per pixel in its finest view, or the
// unseen budget) × its tile's factor; the corners of a frozen tile's faces and of the frozen faces get
// a goal of 0, which the simplifier never touches, so those faces come out as they went in.
TriangleMesh SimplifyQem(const TriangleMesh& mesh, const TileGrid& grid, const std::vector<int>& vertex_tile,
                         const std::vector<double>& vertex_allowed_m, const std::vector<double>& factor,
                         const std::vector<char>& frozen, const std::vector<char>& face_frozen) {
  std::vector<double> goal_m(mesh.num_vertices());
  for (size_t v = 0; v < goal_m.size(); ++v) goal_m[v] = vertex_allowed_m[v] * factor[vertex_tile[v]];
  for (size_t k = 0; k < mesh.faces.size(); ++k) {
    if (!face_frozen[k] && !frozen[grid.Tile(Centroid(mesh, mesh.faces[k]))]) continue;
    for (uint32_t v : mesh.faces[k]) goal_m[v] = 0;
  }
  const internal::QemOptions qem;
  return internal::DecimateQemTiled(mesh, 0, qem.tiles, qem, &goal_m);
}

}  // namespace

const char* ForPlanSimplifierName(ForPlanSimplifier simplifier) {
  return simplifier == ForPlanSimplifier::kMeshoptimizer ? "meshoptimizer" : "qem_tiled";
}

void ForPlanOptions::Check() const {
  if (cameras.empty()) throw InputError(Located(plan_source.empty() ? "for_plan" : plan_source, "no camera"));
  if (!(max_error_px > 0 && std::isfinite(max_error_px))) {
    throw InputError("max_error_px: must be a finite number > 0");
  }
  if (tiles_per_side < 1 || tiles_per_side > 1024) throw InputError("tiles_per_side: must be in 1..1024");
  if (measure_samples < 0) throw InputError("measure_samples: must be >= 0");
  if (max_rounds < 1) throw InputError("max_rounds: must be >= 1");
  if (!(aim > 0 && aim <= 1)) throw InputError("aim: must be in (0, 1]");
}

ProjectedErrorProbe::ProjectedErrorProbe(const TriangleMesh& original, const std::vector<PlanCamera>& cameras,
                                         int64_t face_samples, uint32_t seed)
    : points_(SampleSurface(original, face_samples, seed, &faces_)), views_(FinestViews(points_, cameras)) {
  for (const PointView& v : views_) points_seen_ += v.seen() ? 1 : 0;
}

namespace {

// Distances from many points to a mesh: a CGAL AABB tree with its k-d tree of vertices as the hint
// of every closest-point query (built by the first query, before the parallel ones).
using CgalKernel = CGAL::Simple_cartesian<double>;
using CgalTriangles = std::vector<CgalKernel::Triangle_3>;
using CgalTree = CGAL::AABB_tree<
    CGAL::AABB_traits<CgalKernel, CGAL::AABB_triangle_primitive<CgalKernel, CgalTriangles::const_iterator>>>;

std::vector<double> DistancesToMesh(const std::vector<Eigen::Vector3d>& points, const TriangleMesh& mesh) {
  std::vector<double> distance(points.size(), 0.0);
  CgalTriangles triangles;
  triangles.reserve(mesh.num_faces());
  auto point = [](const Eigen::Vector3d& v) { return CgalKernel::Point_3(v.x(), v.y(), v.z()); };
  for (const auto& f : mesh.faces) {
    const CgalKernel::Triangle_3 t(point(mesh.vertices_m[f[0]]), point(mesh.vertices_m[f[1]]),
                                   point(mesh.vertices_m[f[2]]));
    if (!t.is_degenerate()) triangles.push_back(t);
  }
  if (triangles.empty() || points.empty()) return distance;
  CgalTree tree(triangles.cbegin(), triangles.cend());
  tree.accelerate_distance_queries();
  distance[0] = std::sqrt(tree.squared_distance(point(points[0])));
  tbb::parallel_for(size_t{1}, points.size(),
                    [&](size_t i) { distance[i] = std::sqrt(tree.squared_distance(point(points[i]))); });
  return distance;
}

}  // namespace

std::vector<double> ProjectedErrorProbe::DistancesM(const TriangleMesh& simplified) const {
  return DistancesToMesh(points_, simplified);
}

double ProjectedErrorProbe::WorstPx(const TriangleMesh& simplified, int* worst_point) const {
  const std::vector<double> distance = DistancesM(simplified);
  double worst = 0;
  int at = -1;
  for (size_t i = 0; i < distance.size(); ++i) {
    if (!views_[i].seen()) continue;
    const double px = distance[i] / views_[i].metres_per_px;
    if (px > worst) {
      worst = px;
      at = static_cast<int>(i);
    }
  }
  if (worst_point) *worst_point = at;
  return worst;
}

namespace {

void CheckMeshForPlan(const TriangleMesh& mesh) {
  for (const auto& f : mesh.faces) {
    for (uint32_t i : f) {
      if (i >= mesh.num_vertices()) throw InputError("decimate: vertex index out of range");
    }
  }
  if (mesh.has_colors() && mesh.colors_rgb.size() != mesh.num_vertices()) {
    throw InputError("decimate: colours: one per vertex expected");
  }
}

// The budgets: each tile's allowed error is its finest seen point's (max_error_px at that point's
// metres per pixel); tiles no frame sees get the coarsest budget a seen tile gets, in metres.
// point_tile: the tile of each measured point (its face's, whose faces go through that tile's
// simplification).
std::vector<ForPlanTile> TileBudgets(const TriangleMesh& mesh, const TileGrid& grid, const ProjectedErrorProbe& probe,
                                     const ForPlanOptions& options, std::vector<int>* point_tile, ForPlanReport* r) {
  const std::vector<Eigen::Vector3d>& points = probe.points();
  const std::vector<PointView>& views = probe.views();
  const int n = grid.n;
  std::vector<ForPlanTile> tiles(static_cast<size_t>(n) * n);
  for (size_t t = 0; t < tiles.size(); ++t) {
    tiles[t].ix = static_cast<int>(t % n);
    tiles[t].iy = static_cast<int>(t / n);
    tiles[t].allowed_error_m = kInf;
  }
  point_tile->resize(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const int64_t face = probe.faces()[i];
    const int t = face >= 0 ? grid.Tile(Centroid(mesh, mesh.faces[static_cast<size_t>(face)])) : grid.Tile(points[i]);
    (*point_tile)[i] = t;
    const PointView& v = views[i];
    if (!v.seen()) continue;
    const double allowed = options.max_error_px * v.metres_per_px;
    if (allowed < tiles[t].allowed_error_m) {
      ForPlanTile& tile = tiles[t];
      tile.seen = true;
      tile.allowed_error_m = allowed;
      tile.camera_sample = options.cameras[v.camera].sample_index;
      tile.camera_time_s = options.cameras[v.camera].time_s;
      tile.depth_m = v.depth_m;
    }
  }
  for (const auto& f : mesh.faces) ++tiles[grid.Tile(Centroid(mesh, f))].faces_in;
  r->min_allowed_error_m = kInf;
  r->max_allowed_error_m = 0;
  for (const ForPlanTile& t : tiles) {
    if (!t.seen) continue;
    r->min_allowed_error_m = std::min(r->min_allowed_error_m, t.allowed_error_m);
    r->max_allowed_error_m = std::max(r->max_allowed_error_m, t.allowed_error_m);
  }
  r->unseen_allowed_error_m = r->max_allowed_error_m;
  for (ForPlanTile& t : tiles) {
    if (!t.seen) t.allowed_error_m = r->unseen_allowed_error_m;
  }
  return tiles;
}

// The search's state per tile (DecimateForPlan's comment).
struct TileSearch {
  std::vector<double> factor, within, over;
  std::vector<char> frozen, face_frozen;
  std::vector<int> stage;  // settling steps taken: halved, zeroed, faces frozen (rounds)

  TileSearch(size_t num_tiles, size_t num_faces, double start_factor)
      : factor(num_tiles, start_factor),
        within(num_tiles, 0.0),
        over(num_tiles, kInf),
        frozen(num_tiles, 0),
        face_frozen(num_faces, 0),
        stage(num_tiles, 0) {}
  bool any_frozen() const {
    return std::find(frozen.begin(), frozen.end(), 1) != frozen.end() ||
           std::find(face_frozen.begin(), face_frozen.end(), 1) != face_frozen.end();
  }
};

// One round's measurement of `out`: each tile's share of its budget (the worst of its points), the
// tiles' goals and worst projected errors, and the report's worst figures. Returns the points' distances.
std::vector<double> MeasureRound(const TriangleMesh& out, const ProjectedErrorProbe& probe,
                                 const std::vector<int>& point_tile, const std::vector<double>& point_allowed_m,
                                 const std::vector<double>& goal, const TileSearch& search,
                                 const ForPlanOptions& options, std::vector<ForPlanTile>* tiles,
                                 std::vector<double>* share, ForPlanReport* r) {
  const std::vector<PointView>& views = probe.views();
  const std::vector<double> distance = probe.DistancesM(out);
  std::fill(share->begin(), share->end(), 0.0);
  for (size_t i = 0; i < probe.points().size(); ++i) {
    (*share)[point_tile[i]] = std::max((*share)[point_tile[i]], distance[i] / point_allowed_m[i]);
  }
  r->worst_projected_px = 0;
  r->worst_unseen_error_m = 0;
  int worst_point = -1;
  for (size_t t = 0; t < tiles->size(); ++t) {
    (*tiles)[t].goal_error_m = search.frozen[t] ? 0.0 : goal[t];
    (*tiles)[t].worst_projected_px = 0;
  }
  for (size_t i = 0; i < probe.points().size(); ++i) {
    if (!views[i].seen()) {
      r->worst_unseen_error_m = std::max(r->worst_unseen_error_m, distance[i]);
      continue;
    }
    const double px = distance[i] / views[i].metres_per_px;
    (*tiles)[point_tile[i]].worst_projected_px = std::max((*tiles)[point_tile[i]].worst_projected_px, px);
    if (px > r->worst_projected_px) {
      r->worst_projected_px = px;
      worst_point = static_cast<int>(i);
    }
  }
  r->worst_camera_sample = worst_point >= 0 ? options.cameras[views[worst_point].camera].sample_index : -1;
  r->worst_camera_drone = worst_point >= 0 ? options.cameras[views[worst_point].camera].drone : std::string();
  return distance;
}

// A settling round: a tile still over has its factor halved, then zeroed; then, for up to
// face_freeze_rounds rounds, the faces under its points over the bound are frozen with the faces around
// their corners; then the whole tile is frozen (a goal of 0 is no bound with meshoptimizer 0.18).
// Returns whether anything changed (when nothing did, no tile is over or none has a step left).
bool SettleRound(const TriangleMesh& mesh, const ProjectedErrorProbe& probe, const VertexFaces& around,
                 const std::vector<int>& point_tile, const std::vector<double>& point_allowed_m,
                 const std::vector<double>& distance, const std::vector<double>& share, const ForPlanOptions& options,
                 TileSearch* search) {
  bool changed = false;
  std::vector<char> freeze_faces_in(share.size(), 0);
  for (size_t t = 0; t < share.size(); ++t) {
    if (share[t] <= 1.0 || search->frozen[t]) continue;
    int& stage = search->stage[t];
    if (stage < 2 && search->factor[t] > 0) {
      search->factor[t] = stage == 0 ? search->factor[t] * 0.5 : 0.0;
      ++stage;
      changed = true;
    } else if (options.freeze && std::max(stage, 2) - 2 < options.face_freeze_rounds) {
      stage = std::max(stage, 2) + 1;
      freeze_faces_in[t] = 1;
      changed = true;  // (a round that froze no new face is repeated once per step; it then goes whole)
    } else if (options.freeze) {
      search->frozen[t] = 1;
      changed = true;
    }
  }
  for (size_t i = 0; i < probe.points().size(); ++i) {
    const int64_t face = probe.faces()[i];
    if (face < 0 || !freeze_faces_in[point_tile[i]] || distance[i] <= point_allowed_m[i]) continue;
    for (uint32_t corner : mesh.faces[static_cast<size_t>(face)]) {
      around.ForEach(corner, [&](uint32_t k) {
        if (!search->face_frozen[k]) {
          search->face_frozen[k] = 1;
          changed = true;
        }
      });
    }
  }
  return changed;
}

// A search round: factors grow ×4 while a tile stays within, shrink ×1/4 while over, then bisect
// (geometrically) between the largest factor seen within and the smallest seen over; with settle_now,
// each tile takes its largest factor seen within.
void SearchRound(const std::vector<double>& share, bool settle_now, TileSearch* s) {
  for (size_t t = 0; t < share.size(); ++t) {
    if (share[t] <= 1.0) {
      s->within[t] = std::max(s->within[t], s->factor[t]);
    } else {
      s->over[t] = std::min(s->over[t], s->factor[t]);
    }
    if (settle_now) {
      s->factor[t] = s->within[t];
    } else if (std::isinf(s->over[t])) {
      s->factor[t] = std::min(s->factor[t] * 4, 1024.0);
    } else if (s->within[t] == 0) {
      s->factor[t] = s->factor[t] / 4;
    } else {
      s->factor[t] = std::sqrt(s->within[t] * s->over[t]);
    }
  }
}

// The report's closing figures: faces out per tile, frozen tiles and faces, tile counts.
void FinishForPlanReport(const TriangleMesh& mesh, const TriangleMesh& out, const TileGrid& grid,
                         const TileSearch& search, const ForPlanOptions& options, std::vector<ForPlanTile>* tiles,
                         ForPlanReport* r) {
  r->bound_met = r->worst_projected_px <= options.max_error_px && r->worst_unseen_error_m <= r->unseen_allowed_error_m;
  for (const auto& f : out.faces) ++(*tiles)[grid.Tile(Centroid(out, f))].faces_out;
  r->faces_out = static_cast<int64_t>(out.num_faces());
  for (size_t t = 0; t < tiles->size(); ++t) (*tiles)[t].frozen = search.frozen[t] != 0;
  for (size_t k = 0; k < mesh.num_faces(); ++k) {
    if (!search.face_frozen[k]) continue;
    const int t = grid.Tile(Centroid(mesh, mesh.faces[k]));
    if (search.frozen[t]) continue;
    ++(*tiles)[t].faces_frozen;
    ++r->faces_frozen;
  }
  for (const ForPlanTile& t : *tiles) {
    if (t.faces_in == 0 && t.faces_out == 0) continue;
    (t.seen ? r->tiles_seen : r->tiles_unseen) += 1;
    r->tiles_frozen += t.frozen ? 1 : 0;
    r->tiles.push_back(t);
  }
}

}  // namespace

TriangleMesh DecimateForPlan(const TriangleMesh& mesh, const ForPlanOptions& options, ForPlanReport* report) {
  options.Check();
  CheckMeshForPlan(mesh);
  ForPlanReport r;
  r.max_error_px = options.max_error_px;
  r.simplifier = options.simplifier;
  r.aim = options.aim;
  r.faces_in = static_cast<int64_t>(mesh.num_faces());
  const TileGrid grid = MakeGrid(mesh, options.tiles_per_side);
  const size_t num_tiles = static_cast<size_t>(grid.n) * grid.n;
  r.tiles_per_side = grid.n;
  r.grid_min_m = grid.lo;
  r.tile_size_m = grid.size;

  const ProjectedErrorProbe probe(mesh, options.cameras, options.measure_samples, options.seed);
  const std::vector<PointView>& views = probe.views();
  r.points_measured = static_cast<int64_t>(probe.points().size());
  r.points_seen = probe.points_seen();
  if (r.points_seen == 0) {
    throw InputError(Located(options.plan_source.empty() ? "for_plan" : options.plan_source,
                             "no frame of the plan sees the mesh (is the plan made on this scene?)"));
  }
  std::vector<int> point_tile;
  std::vector<ForPlanTile> tiles = TileBudgets(mesh, grid, probe, options, &point_tile, &r);
  // Each point's share of its budget: distance / (aim × allowed), within when <= 1. The search aims
  // under the bound (aim < 1): the measured points are samples, and the error between them can be
  // a little larger.
  std::vector<double> point_allowed_m(views.size());
  for (size_t i = 0; i < views.size(); ++i) {
    point_allowed_m[i] =
        options.aim * (views[i].seen() ? options.max_error_px * views[i].metres_per_px : r.unseen_allowed_error_m);
  }
  // The quadric simplifier's per-vertex budgets (the points begin with the vertices).
  std::vector<int> vertex_tile(point_tile.begin(), point_tile.begin() + static_cast<ptrdiff_t>(mesh.num_vertices()));
  std::vector<double> vertex_allowed_m(mesh.num_vertices());
  for (size_t v = 0; v < vertex_allowed_m.size(); ++v) vertex_allowed_m[v] = point_allowed_m[v] / options.aim;

  // The search, per tile, for the largest goal (allowed error × factor) whose points stay within
  // their budget (SearchRound). Then each tile takes its largest factor seen within (0 where none was),
  // and the rounds go on (SettleRound) until every tile is within or frozen. Steps only go forward, so
  // this ends.
  const bool quadric = options.simplifier == ForPlanSimplifier::kQemTiled;
  const Positions positions = quadric ? Positions{} : MakePositions(mesh);
  // The search starts where each simplifier's goal is about the measured error: meshoptimizer's goals
  // are met with room (the box scene settles at factors 3–15), the quadric's RMS distance to its planes
  // falls short of the largest distance (factors 0.2–0.7).
  TileSearch search(num_tiles, mesh.num_faces(), quadric ? 0.25 : 1.0);
  // Faces around each vertex, to freeze the faces next to a point over the bound with its own.
  const VertexFaces around(mesh.num_vertices(), mesh.faces);
  TriangleMesh out;
  std::vector<double> share(num_tiles);
  bool settling = false;
  for (int round = 0;; ++round) {
    std::vector<double> goal(num_tiles);
    for (size_t t = 0; t < num_tiles; ++t) goal[t] = tiles[t].allowed_error_m * search.factor[t];
    out = quadric
              ? SimplifyQem(mesh, grid, vertex_tile, vertex_allowed_m, search.factor, search.frozen, search.face_frozen)
              : internal::FromKeptIndices(
                    mesh, SimplifyTwoPasses(mesh, positions, grid, goal, search.frozen, search.face_frozen));
    r.rounds = round + 1;
    if (search.any_frozen()) ++r.freeze_rounds;
    const std::vector<double> distance =
        MeasureRound(out, probe, point_tile, point_allowed_m, goal, search, options, &tiles, &share, &r);
    if (settling) {
      if (!SettleRound(mesh, probe, around, point_tile, point_allowed_m, distance, share, options, &search)) break;
      continue;
    }
    const bool settle_now = round + 1 >= options.max_rounds - 3;
    SearchRound(share, settle_now, &search);
    if (settle_now) settling = true;
  }
  FinishForPlanReport(mesh, out, grid, search, options, &tiles, &r);
  if (report) *report = std::move(r);
  return out;
}

Json ForPlanReport::ToJson() const {
  auto round = [](double v, int d) { return std::isfinite(v) ? Json(RoundToDecimals(v, d)) : Json(nullptr); };
  Json j = Json::object();
  j["max_error_px"] = max_error_px;
  j["simplifier"] = ForPlanSimplifierName(simplifier);
  j["aim"] = aim;
  j["occlusion"] = "none: a point inside a frame's frustum counts as seen";
  j["unseen_budget"] = "the coarsest budget of a seen tile";
  j["faces_in"] = faces_in;
  j["faces_out"] = faces_out;
  j["worst_projected_px"] = round(worst_projected_px, 4);
  j["worst_camera_sample"] = worst_camera_sample;
  if (!worst_camera_drone.empty()) j["worst_camera_drone"] = worst_camera_drone;
  j["worst_unseen_error_m"] = round(worst_unseen_error_m, 6);
  j["bound_met"] = bound_met;
  j["tiles_frozen"] = tiles_frozen;
  j["faces_frozen"] = faces_frozen;
  j["rounds"] = rounds;
  j["freeze_rounds"] = freeze_rounds;
  j["frozen"] =
      "over the bound after the search: first the faces under the points over it and around them, "
      "then the whole tile, keep their original faces";
  j["points_measured"] = points_measured;
  j["points_seen"] = points_seen;
  j["min_allowed_error_m"] = round(min_allowed_error_m, 6);
  j["max_allowed_error_m"] = round(max_allowed_error_m, 6);
  j["unseen_allowed_error_m"] = round(unseen_allowed_error_m, 6);
  Json grid = Json::object();
  grid["tiles_per_side"] = tiles_per_side;
  grid["min_m"] = Json::array({round(grid_min_m.x(), 4), round(grid_min_m.y(), 4)});
  grid["tile_size_m"] = Json::array({round(tile_size_m.x(), 4), round(tile_size_m.y(), 4)});
  grid["tiles_seen"] = tiles_seen;
  grid["tiles_unseen"] = tiles_unseen;
  j["grid"] = std::move(grid);
  Json list = Json::array();
  for (const ForPlanTile& t : tiles) {
    Json e = Json::object();
    e["ix"] = t.ix;
    e["iy"] = t.iy;
    e["faces_in"] = t.faces_in;
    e["faces_out"] = t.faces_out;
    e["seen"] = t.seen;
    e["camera_sample"] = t.seen ? Json(t.camera_sample) : Json(nullptr);
    e["camera_time_s"] = t.seen ? round(t.camera_time_s, 6) : Json(nullptr);
    e["depth_m"] = t.seen ? round(t.depth_m, 4) : Json(nullptr);
    e["allowed_error_m"] = round(t.allowed_error_m, 6);
    e["goal_error_m"] = round(t.goal_error_m, 6);
    e["worst_projected_px"] = round(t.worst_projected_px, 4);
    e["frozen"] = t.frozen;
    e["faces_frozen"] = t.faces_frozen;
    list.push_back(std::move(e));
  }
  j["tiles"] = std::move(list);
  return j;
}

}  // namespace cinepath::photogrammetry
