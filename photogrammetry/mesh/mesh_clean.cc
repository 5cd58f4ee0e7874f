#include "photogrammetry/mesh/mesh_clean.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <numeric>
#include <tuple>
#include <vector>

#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/manifoldness.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair.h>
#include <CGAL/Polygon_mesh_processing/stitch_borders.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/boost/graph/iterator.h>

#include <tbb/parallel_for.h>
#include <Eigen/Geometry>

#include "core/error.h"
#include "photogrammetry/mesh/cgal_mesh_internal.h"
#include "photogrammetry/mesh/union_find.h"

namespace cinepath::photogrammetry {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using internal::Point3;
using internal::SurfaceMesh;
using Color = std::array<uint8_t, 3>;

// The rules both repair paths (the manifold soup's and CGAL's) apply, stated once.

// A component is small, and removed, when it has fewer faces than max(min_component_faces,
// ceil(min_component_fraction x the largest component)); the largest is always kept.
int64_t SmallComponentThreshold(const MeshCleanOptions& options, int64_t largest_faces) {
  return std::max<int64_t>(options.min_component_faces,
                           static_cast<int64_t>(std::ceil(options.min_component_fraction * largest_faces)));
}
bool IsSmallComponent(int64_t faces, int64_t threshold, int64_t largest_faces) {
  return faces < threshold && faces < largest_faces;
}
void CountComponent(bool small, int64_t faces, MeshCleanReport& report) {
  if (small) {
    ++report.small_components_removed;
    report.faces_in_small_components += faces;
  } else {
    ++report.components_kept;
  }
}

// The colour of a filled hole's new vertices: the mean over its border's vertices.
Color MeanColor(const std::array<double, 3>& sum, int64_t count) {
  Color mean{0, 0, 0};
  for (int k = 0; k < 3; ++k) mean[k] = static_cast<uint8_t>(std::lround(sum[k] / static_cast<double>(count)));
  return mean;
}

// The outer border of a component is its longest boundary cycle (the first of equals); it is never
// filled. `component` and `perimeter_m` are per cycle; the result marks the outer ones.
std::vector<char> OuterBorders(const std::vector<size_t>& component, const std::vector<double>& perimeter_m,
                               size_t num_components) {
  std::vector<double> longest(num_components, -1.0);
  for (size_t i = 0; i < component.size(); ++i) longest[component[i]] = std::max(longest[component[i]], perimeter_m[i]);
  std::vector<char> taken(num_components, 0), outer(component.size(), 0);
  for (size_t i = 0; i < component.size(); ++i) {
    if (!taken[component[i]] && perimeter_m[i] == longest[component[i]]) taken[component[i]] = outer[i] = 1;
  }
  return outer;
}

// Holes up to max_hole_edges edges and max_hole_perimeter_m are filled.
bool FillableHole(bool outer, int64_t edges, double perimeter_m, const MeshCleanOptions& options) {
  return !outer && edges <= options.max_hole_edges && perimeter_m <= options.max_hole_perimeter_m;
}
using VertexIndex = SurfaceMesh::Vertex_index;
using FaceIndex = SurfaceMesh::Face_index;
using HalfedgeIndex = SurfaceMesh::Halfedge_index;

bool SameCyclicOrder(const std::array<size_t, 3>& polygon, const std::array<uint32_t, 3>& face,
                     const std::vector<size_t>& original_of_point) {
  for (int shift = 0; shift < 3; ++shift) {
    bool same = true;
    for (int k = 0; k < 3 && same; ++k) {
      same = original_of_point[polygon[k]] == face[(k + shift) % 3];
    }
    if (same) return true;
  }
  return false;
}

constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();
// Fixed work units for the parallel loops: results never depend on the thread count.
constexpr size_t kChunk = 65536;

// Hash of a position's bits (+0.0 and −0.0 compare equal: both hash as +0.0).
uint64_t PositionHash(const Eigen::Vector3d& v) {
  uint64_t h = 0x9E3779B97F4A7C15ull;
  for (int k = 0; k < 3; ++k) {
    const double x = v[k] + 0.0;
    uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    h ^= bits + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
    h *= 0xff51afd7ed558ccdull;
  }
  return h ^ (h >> 33);
}

uint64_t FaceHash(const std::array<uint32_t, 3>& sorted) {
  uint64_t h = (static_cast<uint64_t>(sorted[0]) << 32 | sorted[1]) * 0x9E3779B97F4A7C15ull;
  h ^= (static_cast<uint64_t>(sorted[2]) + (h >> 29)) * 0xC2B2AE3D27D4EB4Full;
  return h ^ (h >> 32);
}

// Open-addressing table of uint32 ids (kNone = empty), sized to a power of two ≥ 2n.
struct IdTable {
  std::vector<uint32_t> slots;
  uint64_t mask = 0;
  explicit IdTable(size_t n) {
    size_t size = 16;
    while (size < 2 * n) size <<= 1;
    slots.assign(size, kNone);
    mask = size - 1;
  }
  // Returns the id already stored under an equal key, or stores `id` and returns it.
  template <typename Equal>
  uint32_t FindOrInsert(uint64_t hash, uint32_t id, Equal equal) {
    for (uint64_t s = hash & mask;; s = (s + 1) & mask) {
      if (slots[s] == kNone) {
        slots[s] = id;
        return id;
      }
      if (equal(slots[s])) return slots[s];
    }
  }
};

// The corners around each point of a triangle soup (CSR), and what they say about the surface.
struct Corner {
  uint32_t next, prev, face;  // face (v, next, prev), counter-clockwise
};
struct SoupTopology {
  bool oriented_manifold = false;
  std::vector<char> pinched;            // several fans meet at the point (a bowtie)
  std::vector<uint32_t> start;          // faces around point v: face_of[start[v] .. start[v + 1])
  std::vector<uint32_t> face_of;        // (4 bytes per corner: the table is 3 × faces long)
  std::vector<uint32_t> boundary_next;  // v → x when the directed edge v→x has no twin, else kNone
};

// The soup is an oriented 2-manifold (possibly with border) when no directed edge occurs twice
// and the corners around every point form a single fan: the link edges next → prev of its corners
// make one path or one cycle. A path starts at the point's only outgoing border edge.
SoupTopology AnalyzeSoup(const std::vector<std::array<uint32_t, 3>>& faces, size_t num_points) {
  SoupTopology t;
  t.start.assign(num_points + 1, 0);
  for (const auto& f : faces) {
    for (int k = 0; k < 3; ++k) ++t.start[f[k] + 1];
  }
  for (size_t i = 0; i < num_points; ++i) t.start[i + 1] += t.start[i];
  t.face_of.resize(t.start.back());
  {
    std::vector<uint32_t> fill(t.start.begin(), t.start.end() - 1);
    for (size_t i = 0; i < faces.size(); ++i) {
      for (uint32_t v : faces[i]) t.face_of[fill[v]++] = static_cast<uint32_t>(i);
    }
  }
  t.boundary_next.assign(num_points, kNone);
  t.pinched.assign(num_points, 0);
  const size_t chunks = (num_points + kChunk - 1) / kChunk;
  std::vector<char> chunk_ok(chunks, 1);
  tbb::parallel_for(size_t{0}, chunks, [&](size_t c) {
    std::vector<Corner> corners;  // the corners of one point, (next, prev) in its faces
    const size_t end = std::min(num_points, (c + 1) * kChunk);
    for (size_t v = c * kChunk; v < end; ++v) {
      corners.clear();
      for (uint32_t k = t.start[v]; k < t.start[v + 1]; ++k) {
        const auto& f = faces[t.face_of[k]];
        const int at = f[0] == v ? 0 : f[1] == v ? 1 : 2;
        corners.push_back({f[(at + 1) % 3], f[(at + 2) % 3], t.face_of[k]});
      }
      Corner* begin = corners.data();
      Corner* stop = corners.data() + corners.size();
      const size_t n = corners.size();
      if (n == 0) continue;
      std::sort(begin, stop, [](const Corner& a, const Corner& b) { return a.next < b.next; });
      for (Corner* e = begin; e + 1 < stop; ++e) {
        if (e->next == (e + 1)->next) {  // the directed edge v→next occurs twice
          chunk_ok[c] = 0;
          return;
        }
      }
      // A path starts at a `next` that is no corner's `prev`: the border edge v→next.
      uint32_t first = begin->next, path_starts = 0;
      for (Corner* e = begin; e != stop; ++e) {
        bool is_prev = false;
        for (Corner* g = begin; g != stop && !is_prev; ++g) is_prev = g->prev == e->next;
        if (!is_prev) {
          if (path_starts++ == 0) first = e->next;
        }
      }
      if (path_starts > 1) {  // several fans meet at v (its edges may still be manifold)
        t.pinched[v] = 1;
        continue;
      }
      auto find = [&](uint32_t x) -> const Corner* {
        const Corner* it =
            std::lower_bound(begin, stop, x, [](const Corner& a, uint32_t value) { return a.next < value; });
        return it != stop && it->next == x ? it : nullptr;
      };
      size_t walked = 0;
      uint32_t x = first;
      for (const Corner* e = find(x); e != nullptr && walked <= n; e = find(x)) {
        ++walked;
        x = e->prev;
        if (x == first) break;
      }
      if (walked != n) {
        t.pinched[v] = 1;
        continue;
      }
      if (path_starts == 1) t.boundary_next[v] = first;
    }
  });
  t.oriented_manifold = std::all_of(chunk_ok.begin(), chunk_ok.end(), [](char ok) { return ok; }) &&
                        std::none_of(t.pinched.begin(), t.pinched.end(), [](char p) { return p; });
  return t;
}

// Where only pinched points (bowties: several fans of faces meet at one point, every edge manifold)
// keep a soup from being an oriented 2-manifold, gives each fan but the first its own copy of the
// point, as CGAL's duplicate_non_manifold_vertices does, so the fast path can clean it. Fans are the
// corners linked by shared edges: corner e continues into corner g when e.prev == g.next. New points
// are appended in point order, copies of one point in the order of their fans' lowest face.
// Returns the number of copies made.
int64_t SplitPinchedPoints(const SoupTopology& topology, std::vector<std::array<uint32_t, 3>>& faces,
                           std::vector<size_t>& original_of_point) {
  const size_t num_points = original_of_point.size();
  int64_t copies = 0;
  std::vector<uint32_t> corner_faces, fan;
  std::vector<uint32_t> next_of, prev_of, by_next;
  for (size_t v = 0; v < num_points; ++v) {
    if (!topology.pinched[v]) continue;
    corner_faces.assign(topology.face_of.begin() + topology.start[v], topology.face_of.begin() + topology.start[v + 1]);
    std::sort(corner_faces.begin(), corner_faces.end());
    const size_t n = corner_faces.size();
    next_of.resize(n);
    prev_of.resize(n);
    for (size_t k = 0; k < n; ++k) {
      const auto& f = faces[corner_faces[k]];
      const int at = f[0] == v ? 0 : f[1] == v ? 1 : 2;
      next_of[k] = f[(at + 1) % 3];
      prev_of[k] = f[(at + 2) % 3];
    }
    // Corners sorted by `next` (unique at v: no directed edge repeats), to find each one's successor.
    by_next.resize(n);
    for (size_t k = 0; k < n; ++k) by_next[k] = static_cast<uint32_t>(k);
    std::sort(by_next.begin(), by_next.end(), [&](uint32_t a, uint32_t b) { return next_of[a] < next_of[b]; });
    UnionFind fans(n);
    for (size_t a = 0; a < n; ++a) {
      const auto it = std::lower_bound(by_next.begin(), by_next.end(), prev_of[a],
                                       [&](uint32_t k, uint32_t value) { return next_of[k] < value; });
      if (it != by_next.end() && next_of[*it] == prev_of[a]) fans.Unite(static_cast<uint32_t>(a), *it);
    }
    // The fan of the lowest face keeps v; the others, in order of their lowest face, get copies.
    fan.assign(n, kNone);
    for (size_t k = 0; k < n; ++k) {
      const uint32_t root = fans.Find(static_cast<uint32_t>(k));
      if (fan[root] == kNone) {
        if (k == 0) {
          fan[root] = static_cast<uint32_t>(v);
        } else {
          fan[root] = static_cast<uint32_t>(original_of_point.size());
          original_of_point.push_back(original_of_point[v]);
          ++copies;
        }
      }
      auto& f = faces[corner_faces[k]];
      for (uint32_t& i : f) {
        if (i == v) i = fan[root];
      }
    }
  }
  return copies;
}

struct BoundaryCycle {
  std::vector<uint32_t> points;  // p0 → p1 → ... → p0, each p_i → p_{i+1} a border edge
  double perimeter_m = 0;
  uint32_t component = 0;
};

// Fills one hole of an oriented-manifold soup with CGAL's triangulate_and_refine_hole, on a local
// Surface_mesh made of the faces around the hole's border (all the hole filler looks at: the border
// polyline, the faces on it and the edge lengths around its vertices). Appends the new points and
// faces; returns the number of faces added (0: left open).
int64_t FillHoleLocally(const BoundaryCycle& cycle, const SoupTopology& topology, size_t faces_before_filling,
                        std::vector<Eigen::Vector3d>& points, std::vector<std::array<uint32_t, 3>>& faces,
                        std::vector<Color>* colors, const Color& fill_color) {
  // 1. The star of the border: faces around its points (from the CSR, plus faces added by
  //    earlier hole fills, which the CSR does not know).
  std::vector<uint32_t> star;
  for (uint32_t v : cycle.points) {
    for (uint32_t k = topology.start[v]; k < topology.start[v + 1]; ++k) {
      star.push_back(topology.face_of[k]);
    }
  }
  if (faces.size() > faces_before_filling) {
    std::vector<uint32_t> on_border(cycle.points);
    std::sort(on_border.begin(), on_border.end());
    for (size_t i = faces_before_filling; i < faces.size(); ++i) {
      for (uint32_t v : faces[i]) {
        if (std::binary_search(on_border.begin(), on_border.end(), v)) {
          star.push_back(static_cast<uint32_t>(i));
          break;
        }
      }
    }
  }
  std::sort(star.begin(), star.end());
  star.erase(std::unique(star.begin(), star.end()), star.end());
  std::vector<uint32_t> local_to_global;
  for (uint32_t f : star) local_to_global.insert(local_to_global.end(), faces[f].begin(), faces[f].end());
  std::sort(local_to_global.begin(), local_to_global.end());
  local_to_global.erase(std::unique(local_to_global.begin(), local_to_global.end()), local_to_global.end());
  auto local = [&](uint32_t g) {
    return static_cast<size_t>(std::lower_bound(local_to_global.begin(), local_to_global.end(), g) -
                               local_to_global.begin());
  };
  std::vector<Point3> local_points;
  local_points.reserve(local_to_global.size());
  for (uint32_t g : local_to_global) {
    local_points.emplace_back(points[g].x(), points[g].y(), points[g].z());
  }
  std::vector<std::array<size_t, 3>> polygons;
  polygons.reserve(star.size());
  for (uint32_t f : star) {
    polygons.push_back({local(faces[f][0]), local(faces[f][1]), local(faces[f][2])});
  }
  // 2. A subset of a manifold's faces can pinch at a point away from the hole: orient (which
  //    duplicates such points) when needed. Copies map back to their original by position.
  const size_t num_local = local_points.size();
  if (!internal::IsOrientedManifoldTriangleSoup(polygons, num_local)) {
    PMP::orient_polygon_soup(local_points, polygons);
    std::map<std::tuple<double, double, double>, uint32_t> by_position;
    for (size_t p = 0; p < num_local; ++p) {
      by_position.emplace(std::make_tuple(local_points[p].x(), local_points[p].y(), local_points[p].z()),
                          local_to_global[p]);
    }
    for (size_t p = num_local; p < local_points.size(); ++p) {
      local_to_global.push_back(
          by_position.at(std::make_tuple(local_points[p].x(), local_points[p].y(), local_points[p].z())));
    }
  }
  SurfaceMesh sm;
  PMP::polygon_soup_to_polygon_mesh(local_points, polygons, sm);
  const size_t soup_points = local_points.size();
  // 3. The hole's border halfedge: the edge p0 → p1 lies in a face; its opposite has none. If
  //    orienting reversed the local soup, the new faces are reversed back.
  const VertexIndex v0(static_cast<SurfaceMesh::size_type>(local(cycle.points[0])));
  const VertexIndex v1(static_cast<SurfaceMesh::size_type>(local(cycle.points[1])));
  HalfedgeIndex h = sm.halfedge(v0, v1);
  if (h == SurfaceMesh::null_halfedge()) return 0;
  bool reversed = false;
  if (sm.is_border(h)) {
    reversed = true;
  } else {
    h = sm.opposite(h);
    if (!sm.is_border(h)) return 0;
  }
  std::vector<FaceIndex> new_faces;
  std::vector<VertexIndex> new_vertices;
  PMP::triangulate_and_refine_hole(sm, h, std::back_inserter(new_faces), std::back_inserter(new_vertices));
  if (new_faces.empty()) return 0;
  // 4. Back into the soup: new points get new indices, in the order CGAL created them.
  std::map<uint32_t, uint32_t> global_of_new;
  for (VertexIndex v : new_vertices) {
    global_of_new[v.idx()] = static_cast<uint32_t>(points.size());
    const Point3& p = sm.point(v);
    points.emplace_back(p.x(), p.y(), p.z());
    if (colors) colors->push_back(fill_color);
  }
  for (FaceIndex f : new_faces) {
    std::array<uint32_t, 3> tri{};
    int k = 0;
    for (VertexIndex v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
      if (k < 3) {
        tri[k] = v.idx() < soup_points ? local_to_global[v.idx()] : global_of_new.at(v.idx());
      }
      ++k;
    }
    if (k != 3) continue;
    if (reversed) std::swap(tri[1], tri[2]);
    faces.push_back(tri);
  }
  return static_cast<int64_t>(new_faces.size());
}

// The soup's components (vertex-connected = edge-connected on a manifold), with the lowest point
// as root, and which components and faces are kept.
struct SoupComponents {
  std::vector<uint32_t> root;        // per point
  std::vector<char> component_kept;  // per root point
  std::vector<char> face_kept;       // per face
};

// Small components are removed, as the general path does (SmallComponentThreshold).
SoupComponents KeepLargeSoupComponents(const std::vector<std::array<uint32_t, 3>>& faces, size_t n,
                                       const MeshCleanOptions& options, MeshCleanReport& report) {
  SoupComponents s;
  UnionFind components(n);
  for (const auto& f : faces) {
    components.Unite(f[0], f[1]);
    components.Unite(f[0], f[2]);
  }
  s.root.resize(n);
  for (size_t v = 0; v < n; ++v) s.root[v] = components.Find(static_cast<uint32_t>(v));
  std::vector<int64_t> faces_per_root(n, 0);
  for (const auto& f : faces) ++faces_per_root[s.root[f[0]]];
  int64_t largest = 0;
  for (size_t v = 0; v < n; ++v) {
    if (s.root[v] == v) largest = std::max(largest, faces_per_root[v]);
  }
  const int64_t threshold = SmallComponentThreshold(options, largest);
  s.component_kept.assign(n, 0);
  for (size_t v = 0; v < n; ++v) {
    if (s.root[v] != v || faces_per_root[v] == 0) continue;
    const bool small = IsSmallComponent(faces_per_root[v], threshold, largest);
    CountComponent(small, faces_per_root[v], report);
    s.component_kept[v] = small ? 0 : 1;
  }
  s.face_kept.assign(faces.size(), 1);
  if (report.small_components_removed > 0) {
    for (size_t i = 0; i < faces.size(); ++i) s.face_kept[i] = s.component_kept[s.root[faces[i][0]]];
  }
  return s;
}

// The closed border cycles of the kept components, each from its lowest point; a chain that does
// not close is counted as a hole left open.
std::vector<BoundaryCycle> SoupBorderCycles(const SoupTopology& topology, const std::vector<Eigen::Vector3d>& points,
                                            const SoupComponents& components, MeshCleanReport& report) {
  const size_t n = points.size();
  std::vector<BoundaryCycle> cycles;
  std::vector<char> visited(n, 0);
  for (size_t v = 0; v < n; ++v) {
    if (topology.boundary_next[v] == kNone || visited[v] || !components.component_kept[components.root[v]]) continue;
    BoundaryCycle c;
    c.component = components.root[v];
    bool closed = false;
    for (uint32_t p = static_cast<uint32_t>(v); c.points.size() <= n;) {
      visited[p] = 1;
      c.points.push_back(p);
      const uint32_t q = topology.boundary_next[p];
      if (q == kNone) break;
      c.perimeter_m += (points[q] - points[p]).norm();
      if (q == v) {
        closed = true;
        break;
      }
      p = q;
    }
    if (!closed) {  // cannot happen on an oriented manifold; never fill such a chain
      ++report.holes_left_open;
      continue;
    }
    cycles.push_back(std::move(c));
  }
  return cycles;
}

// Fills each fillable hole among `cycles` (the longest cycle of a component is its outer border)
// in the colour of its border's mean; the new points, faces and colours are appended, all kept.
void FillSoupHoles(const std::vector<BoundaryCycle>& cycles, const SoupTopology& topology, bool colored,
                   const MeshCleanOptions& options, std::vector<Eigen::Vector3d>& points,
                   std::vector<std::array<uint32_t, 3>>& faces, std::vector<Color>& colors,
                   std::vector<char>& face_kept, MeshCleanReport& report) {
  std::vector<size_t> cycle_component;
  std::vector<double> cycle_perimeter;
  for (const BoundaryCycle& c : cycles) {
    cycle_component.push_back(c.component);
    cycle_perimeter.push_back(c.perimeter_m);
  }
  const std::vector<char> outer = OuterBorders(cycle_component, cycle_perimeter, points.size());
  const size_t faces_before_filling = faces.size();
  for (size_t i = 0; i < cycles.size(); ++i) {
    const BoundaryCycle& c = cycles[i];
    const int64_t edges = static_cast<int64_t>(c.points.size());
    if (!FillableHole(outer[i], edges, c.perimeter_m, options)) {
      ++report.holes_left_open;
      continue;
    }
    std::array<double, 3> sum{0, 0, 0};
    if (colored) {
      for (uint32_t p : c.points) {
        for (int k = 0; k < 3; ++k) sum[k] += colors[p][k];
      }
    }
    const Color mean = MeanColor(sum, edges);
    const int64_t added =
        FillHoleLocally(c, topology, faces_before_filling, points, faces, colored ? &colors : nullptr, mean);
    if (added == 0) {
      ++report.holes_left_open;
      continue;
    }
    ++report.holes_filled;
    report.hole_faces_added += added;
    face_kept.resize(faces.size(), 1);
  }
}

// The kept faces and the points they use, numbered in point order (points of removed components
// go with them).
TriangleMesh KeptSoup(const std::vector<Eigen::Vector3d>& points, const std::vector<std::array<uint32_t, 3>>& faces,
                      const std::vector<char>& face_kept, bool colored, const std::vector<Color>& colors) {
  std::vector<int64_t> compact(points.size(), -1);
  TriangleMesh out;
  out.faces.reserve(faces.size());
  for (size_t i = 0; i < faces.size(); ++i) {
    if (!face_kept[i]) continue;
    std::array<uint32_t, 3> tri;
    for (int k = 0; k < 3; ++k) {
      int64_t& c = compact[faces[i][k]];
      if (c < 0) c = 0;  // mark; numbered below in point order
      tri[k] = faces[i][k];
    }
    out.faces.push_back(tri);
  }
  int64_t next = 0;
  for (size_t p = 0; p < points.size(); ++p) {
    if (compact[p] < 0) continue;
    compact[p] = next++;
    out.vertices_m.push_back(points[p]);
    if (colored) out.colors_rgb.push_back(colors[p]);
  }
  for (auto& f : out.faces) {
    for (uint32_t& i : f) i = static_cast<uint32_t>(compact[i]);
  }
  return out;
}

// The fast path, for a soup that is already an oriented 2-manifold (a terrain from the height
// field, Poisson's output, most given meshes): components, small-component removal and border
// cycles come from the soup itself, and CGAL is called only around holes to fill.
TriangleMesh CleanManifoldSoup(const TriangleMesh& mesh, bool colored, const MeshCleanOptions& options,
                               std::vector<Eigen::Vector3d> points, std::vector<std::array<uint32_t, 3>> faces,
                               const std::vector<size_t>& original_of_point, const SoupTopology& topology,
                               MeshCleanReport& report) {
  const size_t n = points.size();
  SoupComponents components = KeepLargeSoupComponents(faces, n, options, report);
  std::vector<Color> colors;
  if (colored) {
    colors.reserve(n);
    for (size_t p = 0; p < n; ++p) colors.push_back(mesh.colors_rgb[original_of_point[p]]);
  }
  if (options.max_hole_edges > 0 && options.max_hole_perimeter_m > 0) {
    const std::vector<BoundaryCycle> cycles = SoupBorderCycles(topology, points, components, report);
    FillSoupHoles(cycles, topology, colored, options, points, faces, colors, components.face_kept, report);
  }
  TriangleMesh out = KeptSoup(points, faces, components.face_kept, colored, colors);
  report.vertices_out = static_cast<int64_t>(out.num_vertices());
  report.faces_out = static_cast<int64_t>(out.num_faces());
  return out;
}

// CGAL orients the soup, duplicating the points where the surface is not a 2-manifold (copies map
// to their originals by position). Then each component keeps the orientation most of its input
// faces had (orienting may flip a whole component).
void OrientSoupByMajority(const std::vector<std::array<uint32_t, 3>>& faces, std::vector<Point3>& points,
                          std::vector<std::array<size_t, 3>>& polygons, std::vector<size_t>& original_of_point,
                          MeshCleanReport& report) {
  const size_t points_before = points.size();
  PMP::orient_polygon_soup(points, polygons);
  report.non_manifold_vertices_split = static_cast<int64_t>(points.size() - points_before);
  // Points added by CGAL are copies: find their originals by position.
  std::map<std::tuple<double, double, double>, size_t> original_by_position;
  for (size_t p = 0; p < points_before; ++p) {
    original_by_position.emplace(std::make_tuple(points[p].x(), points[p].y(), points[p].z()), original_of_point[p]);
  }
  for (size_t p = points_before; p < points.size(); ++p) {
    original_of_point.push_back(original_by_position.at(std::make_tuple(points[p].x(), points[p].y(), points[p].z())));
  }
  UnionFind components(points.size());
  for (const auto& polygon : polygons) {
    components.Unite(static_cast<uint32_t>(polygon[0]), static_cast<uint32_t>(polygon[1]));
    components.Unite(static_cast<uint32_t>(polygon[0]), static_cast<uint32_t>(polygon[2]));
  }
  std::map<uint32_t, std::pair<int64_t, int64_t>> flipped_and_total;
  std::vector<char> flipped(polygons.size());
  for (size_t i = 0; i < polygons.size(); ++i) {
    flipped[i] = !SameCyclicOrder(polygons[i], faces[i], original_of_point);
    auto& counts = flipped_and_total[components.Find(static_cast<uint32_t>(polygons[i][0]))];
    counts.first += flipped[i];
    counts.second += 1;
  }
  for (size_t i = 0; i < polygons.size(); ++i) {
    const auto& counts = flipped_and_total[components.Find(static_cast<uint32_t>(polygons[i][0]))];
    if (2 * counts.first > counts.second) {
      std::reverse(polygons[i].begin(), polygons[i].end());
      flipped[i] = !flipped[i];
    }
    report.faces_reoriented += flipped[i];
  }
}

using ColorMap = SurfaceMesh::Property_map<VertexIndex, Color>;

// The Surface_mesh of the oriented soup with its vertex colours ("v:color"); the non-manifold
// vertices left are split.
ColorMap BuildColoredSurfaceMesh(const TriangleMesh& mesh, bool colored, const std::vector<Point3>& points,
                                 const std::vector<std::array<size_t, 3>>& polygons,
                                 const std::vector<size_t>& original_of_point, SurfaceMesh& sm,
                                 MeshCleanReport& report) {
  PMP::polygon_soup_to_polygon_mesh(points, polygons, sm);
  auto color_map = sm.add_property_map<VertexIndex, Color>("v:color", Color{0, 0, 0}).first;
  {
    // polygon_soup_to_polygon_mesh creates the vertices in point order.
    size_t p = 0;
    for (VertexIndex v : sm.vertices()) {
      CINEPATH_CHECK(p < points.size() && sm.point(v) == points[p]);
      if (colored) color_map[v] = mesh.colors_rgb[original_of_point[p]];
      ++p;
    }
  }
  std::vector<HalfedgeIndex> non_manifold;
  PMP::non_manifold_vertices(sm, std::back_inserter(non_manifold));
  if (!non_manifold.empty()) {
    report.non_manifold_vertices_split += static_cast<int64_t>(PMP::duplicate_non_manifold_vertices(sm));
  }
  return color_map;
}

// Small components and floating blobs (SmallComponentThreshold) are removed.
void RemoveSmallMeshComponents(SurfaceMesh& sm, const MeshCleanOptions& options, MeshCleanReport& report) {
  auto cc_map = sm.add_property_map<FaceIndex, std::size_t>("f:cc", 0).first;
  const std::size_t num_components = PMP::connected_components(sm, cc_map);
  std::vector<int64_t> faces_per_component(num_components, 0);
  for (FaceIndex f : sm.faces()) ++faces_per_component[cc_map[f]];
  const int64_t largest = *std::max_element(faces_per_component.begin(), faces_per_component.end());
  const int64_t threshold = SmallComponentThreshold(options, largest);
  for (int64_t count : faces_per_component) CountComponent(IsSmallComponent(count, threshold, largest), count, report);
  if (report.small_components_removed > 0) {
    const int64_t keep_threshold = std::min(threshold, largest);
    PMP::keep_large_connected_components(sm, static_cast<std::size_t>(keep_threshold));
  }
  sm.remove_property_map(cc_map);
}

// A border cycle of a Surface_mesh: one of its halfedges, its size and its component.
struct MeshBorderCycle {
  HalfedgeIndex h;
  int64_t edges = 0;
  double perimeter_m = 0;
  std::size_t component = 0;
  bool outer = false;  // the longest cycle of its component
};

std::vector<MeshBorderCycle> MeshBorderCycles(SurfaceMesh& sm) {
  auto cc_map = sm.add_property_map<FaceIndex, std::size_t>("f:cc", 0).first;
  const std::size_t num_components = PMP::connected_components(sm, cc_map);
  std::vector<HalfedgeIndex> cycles;
  PMP::extract_boundary_cycles(sm, std::back_inserter(cycles));
  std::vector<MeshBorderCycle> info;
  std::vector<size_t> cycle_component;
  std::vector<double> cycle_perimeter;
  for (HalfedgeIndex h : cycles) {
    MeshBorderCycle c;
    c.h = h;
    for (HalfedgeIndex e : CGAL::halfedges_around_face(h, sm)) {
      ++c.edges;
      c.perimeter_m += std::sqrt(CGAL::squared_distance(sm.point(sm.source(e)), sm.point(sm.target(e))));
    }
    c.component = cc_map[sm.face(sm.opposite(h))];
    cycle_component.push_back(c.component);
    cycle_perimeter.push_back(c.perimeter_m);
    info.push_back(c);
  }
  const std::vector<char> outer = OuterBorders(cycle_component, cycle_perimeter, num_components);
  for (size_t i = 0; i < info.size(); ++i) info[i].outer = outer[i];
  sm.remove_property_map(cc_map);
  return info;
}

// Holes up to a size are filled, their new vertices in the mean colour of the hole's border.
void FillMeshHoles(SurfaceMesh& sm, ColorMap color_map, const MeshCleanOptions& options, MeshCleanReport& report) {
  for (const MeshBorderCycle& c : MeshBorderCycles(sm)) {
    if (!FillableHole(c.outer, c.edges, c.perimeter_m, options)) {
      ++report.holes_left_open;
      continue;
    }
    std::array<double, 3> sum{0, 0, 0};
    for (HalfedgeIndex e : CGAL::halfedges_around_face(c.h, sm)) {
      for (int k = 0; k < 3; ++k) sum[k] += color_map[sm.target(e)][k];
    }
    std::vector<FaceIndex> new_faces;
    std::vector<VertexIndex> new_vertices;
    PMP::triangulate_and_refine_hole(sm, c.h, std::back_inserter(new_faces), std::back_inserter(new_vertices));
    if (new_faces.empty()) {
      ++report.holes_left_open;
      continue;
    }
    ++report.holes_filled;
    report.hole_faces_added += static_cast<int64_t>(new_faces.size());
    const Color mean = MeanColor(sum, c.edges);
    for (VertexIndex v : new_vertices) color_map[v] = mean;
  }
}

// The general path, for soups that are not an oriented 2-manifold: CGAL orients the soup
// (duplicating points where the surface is not a manifold), then Polygon_mesh_processing does
// every repair on a Surface_mesh.
TriangleMesh CleanWithSurfaceMesh(const TriangleMesh& mesh, bool colored, const MeshCleanOptions& options,
                                  std::vector<Point3> points, std::vector<std::array<size_t, 3>> polygons,
                                  const std::vector<std::array<uint32_t, 3>>& faces,
                                  std::vector<size_t> original_of_point, MeshCleanReport& report) {
  // 4. Non-manifold edges and vertices.
  OrientSoupByMajority(faces, points, polygons, original_of_point, report);
  SurfaceMesh sm;
  ColorMap color_map = BuildColoredSurfaceMesh(mesh, colored, points, polygons, original_of_point, sm, report);
  // 5. Small components and floating blobs.
  RemoveSmallMeshComponents(sm, options, report);
  // Non-manifold edges were cut open by orienting; once the extra sheets are gone, zip the slits.
  report.borders_stitched = static_cast<int64_t>(PMP::stitch_borders(sm));
  // 6. Holes up to a size; the longest boundary of each component is its outer border.
  if (options.max_hole_edges > 0 && options.max_hole_perimeter_m > 0) FillMeshHoles(sm, color_map, options, report);
  // 7. Isolated vertices left by the steps above.
  report.isolated_vertices_removed += static_cast<int64_t>(PMP::remove_isolated_vertices(sm));
  sm.collect_garbage();

  TriangleMesh out = internal::TriangleMeshOf(sm);
  if (colored) {
    out.colors_rgb.reserve(out.vertices_m.size());
    for (VertexIndex v : sm.vertices()) out.colors_rgb.push_back(color_map[v]);
  }
  report.vertices_out = static_cast<int64_t>(out.num_vertices());
  report.faces_out = static_cast<int64_t>(out.num_faces());
  return out;
}

// 1. Merge vertices with exactly equal positions (the lowest index represents the group): one
//    pass in index order over a hash table of positions. Returns each vertex's representative.
std::vector<uint32_t> MergeEqualPositions(const TriangleMesh& mesh, MeshCleanReport& report) {
  const size_t n = mesh.num_vertices();
  std::vector<uint32_t> representative(n);
  IdTable table(n);
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d& v = mesh.vertices_m[i];
    if (!v.allFinite()) {  // NaN equals nothing; such vertices invalidate their faces below
      representative[i] = static_cast<uint32_t>(i);
      continue;
    }
    representative[i] = table.FindOrInsert(PositionHash(v), static_cast<uint32_t>(i),
                                           [&](uint32_t j) { return mesh.vertices_m[j] == v; });
    if (representative[i] != i) ++report.duplicate_vertices_merged;
  }
  return representative;
}

enum FaceVerdict : char { kKeep = 0, kInvalid = 1, kDegenerate = 2 };

// 2a. Invalid and degenerate faces, classified in parallel (fixed chunks).
std::vector<char> ClassifyFaces(const TriangleMesh& mesh, const std::vector<uint32_t>& representative,
                                const MeshCleanOptions& options) {
  const size_t n = mesh.num_vertices();
  std::vector<char> verdict(mesh.num_faces(), kKeep);
  tbb::parallel_for(size_t{0}, (mesh.num_faces() + kChunk - 1) / kChunk, [&](size_t c) {
    const size_t end = std::min(mesh.num_faces(), (c + 1) * kChunk);
    for (size_t i = c * kChunk; i < end; ++i) {
      const auto& f = mesh.faces[i];
      bool valid = true;
      for (uint32_t v : f) valid = valid && v < n && mesh.vertices_m[v].allFinite();
      if (!valid || f[0] == f[1] || f[1] == f[2] || f[0] == f[2]) {
        verdict[i] = kInvalid;
        continue;
      }
      const std::array<uint32_t, 3> r{representative[f[0]], representative[f[1]], representative[f[2]]};
      const Eigen::Vector3d& a = mesh.vertices_m[r[0]];
      const Eigen::Vector3d& b = mesh.vertices_m[r[1]];
      const Eigen::Vector3d& cc = mesh.vertices_m[r[2]];
      const double area = 0.5 * (b - a).cross(cc - a).norm();
      if (r[0] == r[1] || r[1] == r[2] || r[0] == r[2] || area < options.min_face_area_m2 ||
          CGAL::collinear(Point3(a.x(), a.y(), a.z()), Point3(b.x(), b.y(), b.z()), Point3(cc.x(), cc.y(), cc.z()))) {
        verdict[i] = kDegenerate;
      }
    }
  });
  return verdict;
}

// 2b. The kept faces, in representative (input) vertex indices: no invalid, degenerate or duplicate
//     faces (same three vertices in either orientation; the first one stays).
std::vector<std::array<uint32_t, 3>> DistinctValidFaces(const TriangleMesh& mesh,
                                                        const std::vector<uint32_t>& representative,
                                                        const std::vector<char>& verdict, MeshCleanReport& report) {
  std::vector<std::array<uint32_t, 3>> faces;
  faces.reserve(mesh.num_faces());
  IdTable seen(mesh.num_faces());
  auto sorted = [](std::array<uint32_t, 3> f) {
    std::sort(f.begin(), f.end());
    return f;
  };
  for (size_t i = 0; i < mesh.num_faces(); ++i) {
    if (verdict[i] == kInvalid) {
      ++report.invalid_faces_removed;
      continue;
    }
    if (verdict[i] == kDegenerate) {
      ++report.degenerate_faces_removed;
      continue;
    }
    const auto& f = mesh.faces[i];
    const std::array<uint32_t, 3> r{representative[f[0]], representative[f[1]], representative[f[2]]};
    const std::array<uint32_t, 3> key = sorted(r);
    const uint32_t id = static_cast<uint32_t>(faces.size());
    if (seen.FindOrInsert(FaceHash(key), id, [&](uint32_t j) { return sorted(faces[j]) == key; }) != id) {
      ++report.duplicate_faces_removed;
      continue;
    }
    faces.push_back(r);
  }
  return faces;
}

// 3. Compact: the faces in the numbering of the points they use (`original_of_point` maps back);
//    vertices no face uses are isolated (merged duplicates are counted above).
std::vector<std::array<uint32_t, 3>> CompactSoup(const std::vector<std::array<uint32_t, 3>>& faces,
                                                 const std::vector<uint32_t>& representative,
                                                 std::vector<size_t>& original_of_point, MeshCleanReport& report) {
  const size_t n = representative.size();
  std::vector<int64_t> compact(n, -1);
  for (const auto& f : faces) {
    for (uint32_t i : f) compact[i] = 0;
  }
  for (size_t i = 0; i < n; ++i) {
    if (compact[i] == 0) {
      compact[i] = static_cast<int64_t>(original_of_point.size());
      original_of_point.push_back(i);
    } else if (representative[i] == i) {
      ++report.isolated_vertices_removed;
    }
  }
  std::vector<std::array<uint32_t, 3>> soup(faces.size());
  for (size_t i = 0; i < faces.size(); ++i) {
    soup[i] = {static_cast<uint32_t>(compact[faces[i][0]]), static_cast<uint32_t>(compact[faces[i][1]]),
               static_cast<uint32_t>(compact[faces[i][2]])};
  }
  return soup;
}

// When bowties alone may keep the soup from being an oriented 2-manifold, splits them and looks
// again; keeps the split soup only if it is one. (The analysis stops early on a repeated directed
// edge, leaving `pinched` unset for the rest.)
void SplitBowtiesWhenAlone(std::vector<std::array<uint32_t, 3>>& soup, std::vector<size_t>& original_of_point,
                           SoupTopology& topology, MeshCleanReport& report) {
  if (topology.oriented_manifold ||
      std::none_of(topology.pinched.begin(), topology.pinched.end(), [](char p) { return p; })) {
    return;
  }
  std::vector<std::array<uint32_t, 3>> split = soup;
  std::vector<size_t> split_original = original_of_point;
  const int64_t copies = SplitPinchedPoints(topology, split, split_original);
  SoupTopology again = AnalyzeSoup(split, split_original.size());
  if (again.oriented_manifold) {
    report.non_manifold_vertices_split += copies;
    soup = std::move(split);
    original_of_point = std::move(split_original);
    topology = std::move(again);
  }
}

// The general path's input: the soup's points and polygons in CGAL's types.
TriangleMesh CleanGeneralSoup(const TriangleMesh& mesh, bool colored, const MeshCleanOptions& options,
                              const std::vector<std::array<uint32_t, 3>>& soup,
                              const std::vector<std::array<uint32_t, 3>>& faces, std::vector<size_t> original_of_point,
                              MeshCleanReport& report) {
  std::vector<Point3> points;
  points.reserve(original_of_point.size());
  for (size_t p : original_of_point) {
    const auto& v = mesh.vertices_m[p];
    points.emplace_back(v.x(), v.y(), v.z());
  }
  report.general_path = true;
  std::vector<std::array<size_t, 3>> polygons(soup.size());
  for (size_t i = 0; i < soup.size(); ++i) polygons[i] = {soup[i][0], soup[i][1], soup[i][2]};
  return CleanWithSurfaceMesh(mesh, colored, options, std::move(points), std::move(polygons), faces,
                              std::move(original_of_point), report);
}

}  // namespace

Json MeshCleanReport::ToJson() const {
  Json j;
  j["vertices_in"] = vertices_in;
  j["faces_in"] = faces_in;
  j["invalid_faces_removed"] = invalid_faces_removed;
  j["degenerate_faces_removed"] = degenerate_faces_removed;
  j["duplicate_vertices_merged"] = duplicate_vertices_merged;
  j["duplicate_faces_removed"] = duplicate_faces_removed;
  j["non_manifold_vertices_split"] = non_manifold_vertices_split;
  j["faces_reoriented"] = faces_reoriented;
  j["small_components_removed"] = small_components_removed;
  j["faces_in_small_components"] = faces_in_small_components;
  j["components_kept"] = components_kept;
  j["borders_stitched"] = borders_stitched;
  j["holes_filled"] = holes_filled;
  j["hole_faces_added"] = hole_faces_added;
  j["holes_left_open"] = holes_left_open;
  j["isolated_vertices_removed"] = isolated_vertices_removed;
  j["vertices_out"] = vertices_out;
  j["faces_out"] = faces_out;
  j["repair_path"] = general_path ? "cgal_surface_mesh" : "manifold_soup";
  return j;
}

TriangleMesh CleanMesh(const TriangleMesh& mesh, const MeshCleanOptions& options, MeshCleanReport* report_out) {
  MeshCleanReport report;
  report.vertices_in = static_cast<int64_t>(mesh.num_vertices());
  report.faces_in = static_cast<int64_t>(mesh.num_faces());
  const bool colored = mesh.has_colors() && mesh.colors_rgb.size() == mesh.num_vertices();

  const std::vector<uint32_t> representative = MergeEqualPositions(mesh, report);
  const std::vector<char> verdict = ClassifyFaces(mesh, representative, options);
  const std::vector<std::array<uint32_t, 3>> faces = DistinctValidFaces(mesh, representative, verdict, report);
  std::vector<size_t> original_of_point;
  std::vector<std::array<uint32_t, 3>> soup = CompactSoup(faces, representative, original_of_point, report);
  if (faces.empty()) {
    if (report_out) *report_out = report;
    return TriangleMesh{};
  }

  // 4. An oriented 2-manifold soup (the common case) is cleaned without building a Surface_mesh;
  //    anything else goes through CGAL's soup orientation and Surface_mesh repairs.
  SoupTopology topology = AnalyzeSoup(soup, original_of_point.size());
  SplitBowtiesWhenAlone(soup, original_of_point, topology, report);
  TriangleMesh out;
  if (topology.oriented_manifold) {
    std::vector<Eigen::Vector3d> points;
    points.reserve(original_of_point.size());
    for (size_t p : original_of_point) points.push_back(mesh.vertices_m[p]);
    out = CleanManifoldSoup(mesh, colored, options, std::move(points), std::move(soup), original_of_point, topology,
                            report);
  } else {
    out = CleanGeneralSoup(mesh, colored, options, soup, faces, std::move(original_of_point), report);
  }
  if (report_out) *report_out = report;
  return out;
}

}  // namespace cinepath::photogrammetry
