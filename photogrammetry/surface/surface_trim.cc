#include "photogrammetry/surface/surface_trim.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "photogrammetry/mesh/vertex_faces.h"
#include "photogrammetry/surface/cgal_point_search_internal.h"
#include "photogrammetry/surface/surface_crease.h"
#include "photogrammetry/surface/vertex_moves_internal.h"

namespace cinepath::photogrammetry {
namespace {

constexpr int kSmoothingNeighbours = 16;

template <typename F>
void ForEachIndex(size_t n, F&& f) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 512), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) f(i);
  });
}

double Median(std::vector<double> values) {
  if (values.empty()) return 0;
  const size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + mid, values.end());
  return values[mid];
}

uint64_t EdgeKey(uint32_t a, uint32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<uint64_t>(a) << 32) | b;
}

// The faces' edges, each with an id, and for every edge the faces around it.
struct EdgeTable {
  std::vector<std::array<uint32_t, 3>> face_edges;  // edge ids of face f (edge c: corners c, c + 1)
  std::vector<uint32_t> offsets;                    // faces of edge e: faces[offsets[e] .. offsets[e + 1])
  std::vector<uint32_t> faces;

  explicit EdgeTable(const std::vector<std::array<uint32_t, 3>>& mesh_faces) {
    std::vector<std::pair<uint64_t, uint32_t>> entries;
    entries.reserve(3 * mesh_faces.size());
    for (uint32_t f = 0; f < mesh_faces.size(); ++f) {
      for (int c = 0; c < 3; ++c) entries.emplace_back(EdgeKey(mesh_faces[f][c], mesh_faces[f][(c + 1) % 3]), f);
    }
    std::sort(entries.begin(), entries.end());
    face_edges.resize(mesh_faces.size());
    faces.reserve(entries.size());
    for (size_t i = 0; i < entries.size();) {
      const uint32_t id = static_cast<uint32_t>(offsets.size());
      offsets.push_back(static_cast<uint32_t>(faces.size()));
      size_t j = i;
      for (; j < entries.size() && entries[j].first == entries[i].first; ++j) {
        const uint32_t f = entries[j].second;
        faces.push_back(f);
        for (int c = 0; c < 3; ++c) {
          if (EdgeKey(mesh_faces[f][c], mesh_faces[f][(c + 1) % 3]) == entries[i].first) face_edges[f][c] = id;
        }
      }
      i = j;
    }
    offsets.push_back(static_cast<uint32_t>(faces.size()));
  }
  size_t num_edges() const { return offsets.size() - 1; }
};

// The direction, from border vertex i, away from the faces on its border edges: for each such edge, the
// unit vector in the face's plane, perpendicular to the edge, pointing away from the face's third corner;
// summed (not normalised).
Eigen::Vector3d OutwardAt(const TriangleMesh& mesh, const std::vector<std::array<uint32_t, 3>>& border_edges_of_face,
                          const std::vector<std::vector<uint32_t>>& border_faces, uint32_t i) {
  Eigen::Vector3d out = Eigen::Vector3d::Zero();
  const auto& v = mesh.vertices_m;
  for (uint32_t f : border_faces[i]) {
    const auto& t = mesh.faces[f];
    for (int c = 0; c < 3; ++c) {
      if (!border_edges_of_face[f][c]) continue;
      const uint32_t a = t[c], b = t[(c + 1) % 3], k = t[(c + 2) % 3];
      if (a != i && b != i) continue;
      const Eigen::Vector3d d = (v[b] - v[a]).normalized();
      const Eigen::Vector3d w = (v[k] - v[a]) - (v[k] - v[a]).dot(d) * d;
      if (w.norm() > 0) out -= w.normalized();
    }
  }
  return out;
}

// Step 2c, the border fit. For each border vertex (on an edge of one face), against the data points
// near it:
// - Short of the data (the surface ends before the points do): when the points within
//   border_extend_factor × spacing lie on a plane (RMS off it under a third of a spacing) and some of
//   them, in a band one spacing either side of the vertex, lie more than border_pull_factor × spacing
//   past it (along the border's outward direction in that plane), the vertex goes onto the plane, out to
//   the farthest of them. Poisson rounds a sheet over at a free edge; the trim cuts the roll away and
//   the surface would otherwise end more than a spacing short (1.24 measured on the L test).
// - Past the data: a vertex farther from its nearest data point than border_pull_factor × that point's
//   spacing is moved straight toward the point until it is that far.
// The spacing is the points' own (not floored by min_spacing_m). The moves are made together; a vertex
// whose move would turn a face around it by more than 60° (or flatten it) tries half of it, up to three
// times, and then stays where it was; the check is repeated until no face turns (each round only
// shortens moves or takes them back).
void FitBorderToData(TriangleMesh& mesh, const PointCloud& points, const internal::PointSearch& search,
                     const std::vector<double>& point_spacing, const SurfaceTrimOptions& options,
                     SurfaceTrimReport* report) {
  const size_t n = mesh.num_vertices();
  std::vector<char> on_border(n, 0);
  std::vector<std::array<uint32_t, 3>> border_edge_of_face(mesh.faces.size(), {0, 0, 0});
  std::vector<std::vector<uint32_t>> border_faces(n);
  {
    const EdgeTable edges(mesh.faces);
    for (uint32_t f = 0; f < mesh.faces.size(); ++f) {
      for (int c = 0; c < 3; ++c) {
        const uint32_t e = edges.face_edges[f][c];
        if (edges.offsets[e + 1] - edges.offsets[e] != 1) continue;  // not an edge of one face
        border_edge_of_face[f][c] = 1;
        for (uint32_t i : {mesh.faces[f][c], mesh.faces[f][(c + 1) % 3]}) {
          on_border[i] = 1;
          if (border_faces[i].empty() || border_faces[i].back() != f) border_faces[i].push_back(f);
        }
      }
    }
  }
  constexpr int kFitNeighbours = 48;
  const bool extend = options.border_extend_factor > 0;
  std::vector<Eigen::Vector3d> target = mesh.vertices_m;
  std::vector<char> moved(n, 0);  // 1 pulled in, 2 extended out
  ForEachIndex(n, [&](size_t i) {
    if (!on_border[i]) return;
    const Eigen::Vector3d& p = mesh.vertices_m[i];
    const auto near = search.Nearest(p, extend ? kFitNeighbours : 1);
    const double d = std::sqrt(near.front().first), s = point_spacing[near.front().second];
    const double keep_m = options.border_pull_factor * s;
    if (extend && d <= keep_m + s) {
      // The points near the vertex and near the surface's plane there (not those of another surface
      // meeting this one at a crease).
      Eigen::Vector3d surface_normal = Eigen::Vector3d::Zero();
      for (uint32_t f : border_faces[i]) {
        const auto& t = mesh.faces[f];
        const auto& v = mesh.vertices_m;
        surface_normal += (v[t[1]] - v[t[0]]).cross(v[t[2]] - v[t[0]]);
      }
      if (surface_normal.norm() > 0) surface_normal.normalize();
      std::vector<Eigen::Vector3d> around;
      const double radius_m = options.border_extend_factor * s;
      for (const auto& [d2, j] : near) {
        const Eigen::Vector3d& q = points.positions_m[j];
        if (d2 <= radius_m * radius_m && std::abs((q - p).dot(surface_normal)) <= s) around.push_back(q);
      }
      const internal::FittedPlane plane = internal::FitPlane(around);
      double off_plane_m2 = 0;
      for (const auto& q : around) off_plane_m2 += std::pow((q - plane.centroid).dot(plane.normal), 2);
      if (plane.valid && around.size() >= 8 && off_plane_m2 < around.size() * std::pow(s / 3, 2)) {
        Eigen::Vector3d out = OutwardAt(mesh, border_edge_of_face, border_faces, static_cast<uint32_t>(i));
        out -= out.dot(plane.normal) * plane.normal;
        if (out.norm() > 0.5) {  // the border's outward direction lies near the data's plane
          out.normalize();
          const Eigen::Vector3d along = plane.normal.cross(out);
          const Eigen::Vector3d foot = p - (p - plane.centroid).dot(plane.normal) * plane.normal;
          double past_m = 0;
          const Eigen::Vector3d* farthest = nullptr;
          for (const auto& q : around) {
            if (std::abs((q - foot).dot(along)) > s || !((q - foot).dot(out) > past_m)) continue;
            past_m = (q - foot).dot(out);
            farthest = &q;
          }
          if (past_m > keep_m) {
            // At the farthest point itself, less its offset along the border: the height is the point's,
            // not the fitted plane's (a plane tilted by a few degrees is a metre off ten metres out).
            target[i] = *farthest - (*farthest - foot).dot(along) * along;
            moved[i] = 2;
            return;
          }
        }
      }
    }
    if (!(d > keep_m)) return;
    const Eigen::Vector3d& q = points.positions_m[near.front().second];
    target[i] = q + (p - q) * (keep_m / d);
    moved[i] = 1;
  });
  std::vector<int> halvings;
  report->border_pulls_refused += internal::KeepFacesFromTurning(mesh, target, moved, halvings);
  for (size_t i = 0; i < n; ++i) {
    if (!moved[i]) continue;
    report->border_moves_shortened += halvings[i] > 0;
    const double move_m = (target[i] - mesh.vertices_m[i]).norm();
    if (moved[i] == 1) {
      ++report->border_vertices_pulled;
      report->max_border_pull_m = std::max(report->max_border_pull_m, move_m);
    } else {
      ++report->border_vertices_extended;
      report->max_border_extension_m = std::max(report->max_border_extension_m, move_m);
    }
    mesh.vertices_m[i] = target[i];
  }
}

// Step 4: each vertex with data points under it (its nearest point within settle_factor × that point's
// spacing) goes along the normal of the plane of those points (within settle_factor × spacing, at
// least 8; where fewer lie that close, as in a thin outer ring, the 8 nearest within twice that) onto
// that plane, when they lie on one (RMS off it under a third of a spacing). With settle_creases the
// points are first fitted robustly (surface_crease.h): where they hold an edge (two planes, as at a
// cliff's top edge or foot) the vertex goes to the nearest point of the two half-planes, and where one
// plane carries most of them and a few strays would tilt a least-squares plane, onto that plane; a move
// longer than the radius is not made. A vertex without points under it stays. Poisson's implicit surface
// is a smooth average of the points: where they are thin (an orbit's outer ring, spacing of metres), it
// bows metres away from them between the points, and it rounds every sharp edge. Moves are made
// together, with step 2c's guard against faces turning.
void SettleOntoData(TriangleMesh& mesh, const PointCloud& points, const internal::PointSearch& search,
                    const std::vector<double>& point_spacing, const SurfaceTrimOptions& options,
                    SurfaceTrimReport* report) {
  constexpr int kSettleNeighbours = 24, kCreaseNeighbours = 48;
  const size_t n = mesh.num_vertices();
  std::vector<Eigen::Vector3d> target = mesh.vertices_m;
  std::vector<char> moved(n, 0);  // 1 onto a plane, 2 onto a crease
  ForEachIndex(n, [&](size_t i) {
    const Eigen::Vector3d& p = mesh.vertices_m[i];
    const auto near = search.Nearest(p, options.settle_creases ? kCreaseNeighbours : kSettleNeighbours);
    const double s = point_spacing[near.front().second];
    const double radius_m = options.settle_factor * s;
    if (!(s > 0) || std::sqrt(near.front().first) > radius_m) return;
    std::vector<Eigen::Vector3d> around;  // nearest first
    for (const auto& [d2, j] : near) {
      if (d2 <= radius_m * radius_m) around.push_back(points.positions_m[j]);
    }
    // Thin points (an orbit's outer ring, where the spacing is capped): the 8 nearest within twice the radius.
    for (size_t k = around.size(); around.size() < 8 && k < near.size(); ++k) {
      if (near[k].first <= 4 * radius_m * radius_m) around.push_back(points.positions_m[near[k].second]);
    }
    if (around.size() < 8) return;
    if (options.settle_creases) {
      // Two planes, or one robust plane (a least-squares plane through the points at an edge can pass the
      // RMS test tilted half-way between the two surfaces).
      CreaseFitOptions crease;
      crease.tolerance_m = s / 3;
      const CreaseFit fit = FitCrease(around, p, crease, 0x5eed0000ULL + i);
      if (fit.planes > 0) {
        const Eigen::Vector3d x = NearestOnCrease(fit, p);
        if ((x - p).norm() > radius_m || x == p) return;
        target[i] = x;
        moved[i] = static_cast<char>(fit.planes);
        return;
      }
    }
    around.resize(std::min<size_t>(around.size(), kSettleNeighbours));
    const internal::FittedPlane plane = internal::FitPlane(around);
    if (!plane.valid) return;
    double off_plane_m2 = 0;
    for (const auto& q : around) off_plane_m2 += std::pow((q - plane.centroid).dot(plane.normal), 2);
    if (!(off_plane_m2 < around.size() * std::pow(s / 3, 2))) return;
    const double h = (p - plane.centroid).dot(plane.normal);
    if (h == 0) return;
    target[i] = p - h * plane.normal;
    moved[i] = 1;
  });
  std::vector<int> halvings;
  report->settle_moves_refused += internal::KeepFacesFromTurning(mesh, target, moved, halvings);
  for (size_t i = 0; i < n; ++i) {
    if (!moved[i]) continue;
    ++report->settle_vertices_moved;
    report->settle_crease_vertices_moved += moved[i] == 2;
    report->max_settle_move_m = std::max(report->max_settle_move_m, (target[i] - mesh.vertices_m[i]).norm());
    mesh.vertices_m[i] = target[i];
  }
}

// The local spacing of every data point: `spacing` floored by the surface's resolution (min_spacing_m) sets
// the distance tests (steps 1 and 2); `point_spacing`, the points' own, sets the border fit and the settling
// (steps 2c and 4). Both are capped at max_spacing_ratio × the median.
struct DataSpacing {
  std::vector<double> spacing;
  std::vector<double> point_spacing;
};

// The mean distance from each point to its k nearest others (0 for a non-finite point or a lone one).
std::vector<double> MeanNeighbourDistances(const PointCloud& points, const internal::PointSearch& search, int k) {
  std::vector<double> spacing(points.size(), 0.0);
  if (search.size() <= 1) return spacing;
  ForEachIndex(points.size(), [&](size_t i) {
    if (!points.positions_m[i].allFinite()) return;
    double sum = 0;
    int count = 0;
    for (const auto& [d2, j] : search.Nearest(points.positions_m[i], k + 1)) {
      if (j == i || count == k) continue;
      sum += std::sqrt(d2);
      ++count;
    }
    spacing[i] = count > 0 ? sum / count : 0.0;
  });
  return spacing;
}

// Smoothed: the median over each point's 16 nearest points (a clump of near-duplicate points or a lone
// stray point does not set the scale of its area).
std::vector<double> SmoothedSpacings(const PointCloud& points, const internal::PointSearch& search,
                                     const std::vector<double>& spacing) {
  std::vector<double> smoothed(points.size(), 0.0);
  ForEachIndex(points.size(), [&](size_t i) {
    if (!points.positions_m[i].allFinite()) return;
    std::vector<double> around;
    for (const auto& hit : search.Nearest(points.positions_m[i], kSmoothingNeighbours)) {
      around.push_back(spacing[hit.second]);
    }
    smoothed[i] = Median(around);
  });
  return smoothed;
}

double MedianOverFinitePoints(const PointCloud& points, const std::vector<double>& values) {
  std::vector<double> finite;
  for (size_t i = 0; i < points.size(); ++i) {
    if (points.positions_m[i].allFinite()) finite.push_back(values[i]);
  }
  return Median(finite);
}

DataSpacing MeasureDataSpacing(const PointCloud& points, const internal::PointSearch& search,
                               const SurfaceTrimOptions& options, SurfaceTrimReport* report) {
  DataSpacing s;
  s.point_spacing =
      SmoothedSpacings(points, search, MeanNeighbourDistances(points, search, std::max(1, options.spacing_neighbours)));
  s.spacing.resize(points.size());
  for (size_t i = 0; i < points.size(); ++i) s.spacing[i] = std::max(s.point_spacing[i], options.min_spacing_m);
  report->median_spacing_m = MedianOverFinitePoints(points, s.spacing);
  report->median_point_spacing_m = MedianOverFinitePoints(points, s.point_spacing);
  // The spacing that sets a criterion is at most max_spacing_ratio × the median: where the points thin
  // out to metres apart, a face that far from all of them has no point under it.
  if (options.max_spacing_ratio > 0 && report->median_point_spacing_m > 0) {
    const double cap_m = options.max_spacing_ratio * report->median_point_spacing_m;
    for (size_t i = 0; i < points.size(); ++i) {
      if (s.point_spacing[i] > cap_m || s.spacing[i] > std::max(cap_m, options.min_spacing_m)) {
        ++report->spacings_capped;
      }
      s.point_spacing[i] = std::min(s.point_spacing[i], cap_m);
      s.spacing[i] = std::min(s.spacing[i], std::max(cap_m, options.min_spacing_m));
    }
  }
  return s;
}

// How far each face (its vertices and centroid) is from the data, and its longest edge, in local spacings.
struct FaceSupport {
  std::vector<double> support_ratio;
  std::vector<double> edge_ratio;
};

FaceSupport MeasureFaceSupport(const TriangleMesh& mesh, const internal::PointSearch& search,
                               const std::vector<double>& spacing) {
  FaceSupport support{std::vector<double>(mesh.num_faces(), 0.0), std::vector<double>(mesh.num_faces(), 0.0)};
  if (search.size() == 0) return support;
  const auto& v = mesh.vertices_m;
  auto ratio_at = [&](const Eigen::Vector3d& q, double* s_out) {
    const auto nearest = search.Nearest(q, 1).front();
    const double s = std::max(spacing[nearest.second], 1e-9);
    if (s_out) *s_out = s;
    return std::sqrt(nearest.first) / s;
  };
  std::vector<double> vertex_ratio(v.size(), 0.0), vertex_spacing(v.size(), 0.0);
  ForEachIndex(v.size(), [&](size_t i) { vertex_ratio[i] = ratio_at(v[i], &vertex_spacing[i]); });
  ForEachIndex(mesh.num_faces(), [&](size_t f) {
    const auto& t = mesh.faces[f];
    const Eigen::Vector3d centroid = (v[t[0]] + v[t[1]] + v[t[2]]) / 3.0;
    double ratio = ratio_at(centroid, nullptr), s = 0, longest = 0;
    for (int c = 0; c < 3; ++c) {
      ratio = std::max(ratio, vertex_ratio[t[c]]);
      s = std::max(s, vertex_spacing[t[c]]);
      longest = std::max(longest, (v[t[c]] - v[t[(c + 1) % 3]]).norm());
    }
    support.support_ratio[f] = ratio;
    support.edge_ratio[f] = longest / s;
  });
  return support;
}

// Step 1: the faces far from the data, anywhere.
void CutFarFaces(const FaceSupport& support, double far_factor, std::vector<char>* alive, SurfaceTrimReport* report) {
  for (size_t f = 0; f < alive->size(); ++f) {
    if (support.support_ratio[f] > far_factor) {
      (*alive)[f] = 0;
      ++report->faces_far_from_data;
    }
  }
}

// The faces still kept and, for every edge, how many kept faces share it: a kept face with an edge no
// other kept face shares is on the border.
class KeptFaces {
 public:
  KeptFaces(const std::vector<std::array<uint32_t, 3>>& faces, std::vector<char>* alive)
      : edges(faces), alive(*alive), alive_around_(edges.num_edges(), 0) {
    for (size_t f = 0; f < faces.size(); ++f) {
      if (!this->alive[f]) continue;
      for (uint32_t e : edges.face_edges[f]) ++alive_around_[e];
    }
  }
  int BorderEdges(uint32_t f) const {
    int count = 0;
    for (uint32_t e : edges.face_edges[f]) count += alive_around_[e] == 1;
    return count;
  }
  bool OnBorder(uint32_t f) const { return BorderEdges(f) > 0; }
  void Remove(uint32_t f) {
    alive[f] = 0;
    for (uint32_t e : edges.face_edges[f]) --alive_around_[e];
  }

  const EdgeTable edges;
  std::vector<char>& alive;

 private:
  std::vector<uint32_t> alive_around_;
};

// The kept faces that share an edge with one of `removed`, sorted, each once.
std::vector<uint32_t> KeptNeighbours(const KeptFaces& kept, const std::vector<uint32_t>& removed) {
  std::vector<uint32_t> next;
  for (uint32_t f : removed) {
    for (uint32_t e : kept.edges.face_edges[f]) {
      for (uint32_t i = kept.edges.offsets[e]; i < kept.edges.offsets[e + 1]; ++i) {
        if (kept.alive[kept.edges.faces[i]]) next.push_back(kept.edges.faces[i]);
      }
    }
  }
  std::sort(next.begin(), next.end());
  next.erase(std::unique(next.begin(), next.end()), next.end());
  return next;
}

// Step 2: border peeling, one ring of unsupported or stretched border faces per pass.
void PeelBorder(KeptFaces& kept, const FaceSupport& support, const SurfaceTrimOptions& options,
                SurfaceTrimReport* report) {
  auto unsupported = [&](uint32_t f) {
    return options.border_factor > 0 && support.support_ratio[f] > options.border_factor;
  };
  auto stretched = [&](uint32_t f) {
    return options.border_edge_factor > 0 && support.edge_ratio[f] > options.border_edge_factor;
  };
  std::vector<uint32_t> candidates;
  for (uint32_t f = 0; f < kept.alive.size(); ++f) {
    if (kept.alive[f] && kept.OnBorder(f)) candidates.push_back(f);
  }
  while (!candidates.empty() && report->border_passes < options.max_border_passes) {
    std::vector<uint32_t> removed;
    for (uint32_t f : candidates) {
      if (!kept.alive[f] || !kept.OnBorder(f)) continue;
      if (unsupported(f)) {
        ++report->border_faces_unsupported;
      } else if (stretched(f)) {
        ++report->border_faces_stretched;
      } else {
        continue;
      }
      removed.push_back(f);
    }
    if (removed.empty()) break;
    ++report->border_passes;
    for (uint32_t f : removed) kept.Remove(f);
    candidates = KeptNeighbours(kept, removed);
  }
}

// Step 2b: stretched ears and stray border vertices, all measured on the same border in each pass.
void CutStretchedEars(const TriangleMesh& mesh, KeptFaces& kept, const std::vector<double>& edge_ratio,
                      const SurfaceTrimOptions& options, SurfaceTrimReport* report) {
  const size_t num_faces = mesh.num_faces();
  const VertexFaces around(mesh.vertices_m.size(), mesh.faces);
  auto stretched_ear = [&](uint32_t f) { return edge_ratio[f] > options.ear_edge_factor; };
  // A border vertex with one or two faces, both stretched: a stray point the surface reached out to.
  // (Not more faces: in an arm of stretched triangles every vertex would be a stray, and the cut would
  // run its whole length in one pass.)
  auto stray = [&](uint32_t i) {
    int count = 0;
    bool border = false;
    for (uint32_t k = around.offsets[i]; k < around.offsets[i + 1]; ++k) {
      const uint32_t f = around.faces[k];
      if (!kept.alive[f]) continue;
      if (!stretched_ear(f) || ++count > 2) return false;
      border = border || kept.OnBorder(f);
    }
    return count > 0 && border;
  };
  while (report->ear_passes < options.max_ear_passes) {
    std::vector<char> cut(num_faces, 0);
    for (uint32_t f = 0; f < num_faces; ++f) {
      if (!kept.alive[f] || !stretched_ear(f)) continue;
      const auto& t = mesh.faces[f];
      cut[f] = kept.BorderEdges(f) >= 2 || stray(t[0]) || stray(t[1]) || stray(t[2]);
    }
    const int64_t count = std::count(cut.begin(), cut.end(), 1);
    if (count == 0) break;
    ++report->ear_passes;
    report->border_ears_cut += count;
    for (uint32_t f = 0; f < num_faces; ++f) {
      if (cut[f]) kept.Remove(f);
    }
  }
}

// The kept faces, with the vertices they use (in their original order).
TriangleMesh KeptMesh(const TriangleMesh& mesh, const std::vector<char>& alive) {
  const auto& v = mesh.vertices_m;
  TriangleMesh out;
  std::vector<int64_t> remap(v.size(), -1);
  for (size_t f = 0; f < mesh.num_faces(); ++f) {
    if (!alive[f]) continue;
    for (uint32_t i : mesh.faces[f]) remap[i] = 0;
  }
  for (size_t i = 0; i < v.size(); ++i) {
    if (remap[i] < 0) continue;
    remap[i] = static_cast<int64_t>(out.vertices_m.size());
    out.vertices_m.push_back(v[i]);
    if (mesh.has_colors()) out.colors_rgb.push_back(mesh.colors_rgb[i]);
  }
  for (size_t f = 0; f < mesh.num_faces(); ++f) {
    if (!alive[f]) continue;
    const auto& t = mesh.faces[f];
    out.faces.push_back(
        {static_cast<uint32_t>(remap[t[0]]), static_cast<uint32_t>(remap[t[1]]), static_cast<uint32_t>(remap[t[2]])});
  }
  return out;
}

// Every vertex's 1-ring: the vertices it shares a face with, sorted, each once.
std::vector<std::vector<uint32_t>> VertexRings(const TriangleMesh& mesh) {
  std::vector<std::vector<uint32_t>> ring(mesh.vertices_m.size());
  for (const auto& t : mesh.faces) {
    for (int c = 0; c < 3; ++c) {
      ring[t[c]].push_back(t[(c + 1) % 3]);
      ring[t[c]].push_back(t[(c + 2) % 3]);
    }
  }
  for (auto& r : ring) {
    std::sort(r.begin(), r.end());
    r.erase(std::unique(r.begin(), r.end()), r.end());
  }
  return ring;
}

// One pass of step 3: where vertex i stands out of the plane of its ring (the 2-ring when the ring is too
// small to span a plane, as at a border corner), its foot on that plane in (*moved)[i] and its height in
// (*height)[i]; every vertex measured on the same positions.
void MeasureSpikes(const TriangleMesh& mesh, const std::vector<std::vector<uint32_t>>& ring,
                   const SurfaceTrimOptions& options, std::vector<Eigen::Vector3d>* moved,
                   std::vector<double>* height) {
  ForEachIndex(mesh.vertices_m.size(), [&](size_t i) {
    std::vector<uint32_t> around = ring[i];
    if (around.size() < 4) {
      for (uint32_t j : ring[i]) around.insert(around.end(), ring[j].begin(), ring[j].end());
      std::sort(around.begin(), around.end());
      around.erase(std::unique(around.begin(), around.end()), around.end());
      around.erase(std::remove(around.begin(), around.end(), static_cast<uint32_t>(i)), around.end());
    }
    std::vector<Eigen::Vector3d> q;
    q.reserve(around.size());
    for (uint32_t j : around) q.push_back(mesh.vertices_m[j]);
    const internal::FittedPlane plane = internal::FitPlane(q);
    if (!plane.valid) return;
    const Eigen::Vector3d& p = mesh.vertices_m[i];
    const double h = (p - plane.centroid).dot(plane.normal);
    const Eigen::Vector3d foot = p - h * plane.normal;
    double radius = 0;  // mean distance, in the plane, from the foot to the ring
    for (const auto& x : q) {
      const Eigen::Vector3d d = x - foot;
      radius += (d - d.dot(plane.normal) * plane.normal).norm();
    }
    radius /= static_cast<double>(q.size());
    if (std::abs(h) > std::max(options.spike_min_m, options.spike_factor * radius)) {
      (*moved)[i] = foot;
      (*height)[i] = std::abs(h);
    }
  });
}

// Step 3: spikes flattened onto the plane of their ring, pass by pass until none is left.
void FlattenSpikes(TriangleMesh& mesh, const SurfaceTrimOptions& options, SurfaceTrimReport* report) {
  const size_t n = mesh.vertices_m.size();
  const std::vector<std::vector<uint32_t>> ring = VertexRings(mesh);
  for (int pass = 0; pass < options.spike_passes; ++pass) {
    std::vector<Eigen::Vector3d> moved = mesh.vertices_m;
    std::vector<double> height(n, 0.0);
    MeasureSpikes(mesh, ring, options, &moved, &height);
    int64_t flattened = 0;
    for (size_t i = 0; i < n; ++i) {
      if (height[i] > 0) {
        ++flattened;
        report->max_spike_height_m = std::max(report->max_spike_height_m, height[i]);
      }
    }
    if (flattened == 0) break;
    report->spike_vertices_flattened += flattened;
    mesh.vertices_m = std::move(moved);
  }
}

}  // namespace

Json SurfaceTrimReport::ToJson() const {
  Json j;
  j["faces_in"] = faces_in;
  j["faces_far_from_data"] = faces_far_from_data;
  j["border_faces_unsupported"] = border_faces_unsupported;
  j["border_faces_stretched"] = border_faces_stretched;
  j["border_passes"] = border_passes;
  j["border_ears_cut"] = border_ears_cut;
  j["ear_passes"] = ear_passes;
  j["border_vertices_pulled"] = border_vertices_pulled;
  j["border_pulls_refused"] = border_pulls_refused;
  j["border_moves_shortened"] = border_moves_shortened;
  j["max_border_pull_m"] = RoundToDecimals(max_border_pull_m, 4);
  j["border_vertices_extended"] = border_vertices_extended;
  j["max_border_extension_m"] = RoundToDecimals(max_border_extension_m, 4);
  j["spike_vertices_flattened"] = spike_vertices_flattened;
  j["max_spike_height_m"] = RoundToDecimals(max_spike_height_m, 4);
  if (options.settle_factor > 0) {  // (absent where step 4 does not run: the height field's report unchanged)
    j["settle_vertices_moved"] = settle_vertices_moved;
    j["settle_moves_refused"] = settle_moves_refused;
    if (options.settle_creases) j["settle_crease_vertices_moved"] = settle_crease_vertices_moved;
    j["max_settle_move_m"] = RoundToDecimals(max_settle_move_m, 4);
  }
  if (options.max_spacing_ratio > 0) j["spacings_capped"] = spacings_capped;
  j["faces_out"] = faces_out;
  j["median_spacing_m"] = RoundToDecimals(median_spacing_m, 4);
  j["median_point_spacing_m"] = RoundToDecimals(median_point_spacing_m, 4);
  Json criteria;
  criteria["spacing_neighbours"] = options.spacing_neighbours;
  criteria["min_spacing_m"] = RoundToDecimals(options.min_spacing_m, 4);
  criteria["far_factor"] = options.far_factor;
  criteria["border_factor"] = options.border_factor;
  criteria["border_edge_factor"] = options.border_edge_factor;
  criteria["ear_edge_factor"] = options.ear_edge_factor;
  criteria["max_ear_passes"] = options.max_ear_passes;
  criteria["border_pull_factor"] = options.border_pull_factor;
  criteria["border_extend_factor"] = options.border_extend_factor;
  criteria["spike_factor"] = options.spike_factor;
  criteria["spike_min_m"] = options.spike_min_m;
  criteria["spike_passes"] = options.spike_passes;
  if (options.settle_factor > 0) criteria["settle_factor"] = options.settle_factor;
  if (options.settle_factor > 0 && options.settle_creases) criteria["settle_creases"] = true;
  if (options.max_spacing_ratio > 0) criteria["max_spacing_ratio"] = options.max_spacing_ratio;
  j["criteria"] = std::move(criteria);
  return j;
}

TriangleMesh TrimSurfaceToData(const TriangleMesh& mesh, const PointCloud& points, const SurfaceTrimOptions& options,
                               SurfaceTrimReport* report_out) {
  SurfaceTrimReport report;
  report.options = options;
  report.faces_in = static_cast<int64_t>(mesh.num_faces());
  const internal::PointSearch search(points.positions_m);
  const DataSpacing spacing = MeasureDataSpacing(points, search, options, &report);
  const FaceSupport support = MeasureFaceSupport(mesh, search, spacing.spacing);

  std::vector<char> alive(mesh.num_faces(), 1);
  if (options.far_factor > 0) CutFarFaces(support, options.far_factor, &alive, &report);
  const bool peel = options.border_factor > 0 || options.border_edge_factor > 0;
  const bool cut_ears = options.ear_edge_factor > 0 && options.max_ear_passes > 0;
  if (peel || cut_ears) {
    KeptFaces kept(mesh.faces, &alive);
    if (peel) PeelBorder(kept, support, options, &report);
    if (cut_ears) CutStretchedEars(mesh, kept, support.edge_ratio, options, &report);
  }
  TriangleMesh out = KeptMesh(mesh, alive);

  // 2c. Border fit: the border's vertices onto the data's border.
  if (options.border_pull_factor > 0 && search.size() > 0 && !out.faces.empty()) {
    FitBorderToData(out, points, search, spacing.point_spacing, options, &report);
  }
  if (options.spike_factor > 0 && options.spike_passes > 0 && !out.faces.empty()) FlattenSpikes(out, options, &report);
  // 4. Onto the points.
  if (options.settle_factor > 0 && search.size() > 0 && !out.faces.empty()) {
    SettleOntoData(out, points, search, spacing.point_spacing, options, &report);
  }
  report.faces_out = static_cast<int64_t>(out.num_faces());
  if (report_out) *report_out = report;
  return out;
}

}  // namespace cinepath::photogrammetry
