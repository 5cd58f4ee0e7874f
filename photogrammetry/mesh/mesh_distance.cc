#include "photogrammetry/mesh/mesh_distance.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_sort.h>
#include <Eigen/Geometry>

#include "core/error.h"
#include "photogrammetry/mesh/cgal_mesh_internal.h"
#include "photogrammetry/mesh/closest_on_triangle.h"

namespace cinepath::photogrammetry {
namespace {

using internal::Kernel;
using internal::Point3;

// Fixed work units: faces (or vertices) [k·kChunk, (k+1)·kChunk) form chunk k whatever the thread
// count, so the samples and their order depend only on the mesh, the count and the seed.
constexpr size_t kChunk = 16384;
// Greedy walk steps from the previous sample's triangle before a tree query (see measure below).
constexpr int kWalkSteps = 12;

Point3 ToPoint(const Eigen::Vector3d& v) { return Point3(v.x(), v.y(), v.z()); }

// One triangle of a TriangleMesh, by index; the positions stay in the mesh (no copy per face).
class FacePrimitive {
 public:
  using Id = uint32_t;
  using Point = Point3;
  using Datum = Kernel::Triangle_3;

  FacePrimitive() = default;
  FacePrimitive(std::vector<uint32_t>::const_iterator it, const TriangleMesh* mesh) : id_(*it), mesh_(mesh) {}
  Id id() const { return id_; }
  Datum datum() const { return TriangleOf(*mesh_, id_); }
  static Datum TriangleOf(const TriangleMesh& mesh, Id face) {
    const auto& f = mesh.faces[face];
    return Datum(ToPoint(mesh.vertices_m[f[0]]), ToPoint(mesh.vertices_m[f[1]]), ToPoint(mesh.vertices_m[f[2]]));
  }
  Point reference_point() const { return ToPoint(mesh_->vertices_m[mesh_->faces[id_][0]]); }

 private:
  Id id_ = 0;
  const TriangleMesh* mesh_ = nullptr;
};

using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, FacePrimitive>>;

// SplitMix64: a tiny, portable generator (std:: distributions differ between standard libraries).
struct SplitMix64 {
  uint64_t state;
  explicit SplitMix64(uint64_t seed) : state(seed) {}
  uint64_t Next() {
    uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double Uniform01() { return static_cast<double>(Next() >> 11) * 0x1.0p-53; }  // [0, 1)
};

double TriangleArea(const TriangleMesh& mesh, const std::array<uint32_t, 3>& f) {
  const Eigen::Vector3d& a = mesh.vertices_m[f[0]];
  return 0.5 * (mesh.vertices_m[f[1]] - a).cross(mesh.vertices_m[f[2]] - a).norm();
}

size_t NumChunks(size_t n) { return (n + kChunk - 1) / kChunk; }

// Morton (Z-order) code of a point in a box: 21 bits per axis, interleaved.
uint64_t SpreadBits(uint64_t x) {
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffull;
  x = (x | x << 16) & 0x1f0000ff0000ffull;
  x = (x | x << 8) & 0x100f00f00f00f00full;
  x = (x | x << 4) & 0x10c30c30c30c30c3ull;
  x = (x | x << 2) & 0x1249249249249249ull;
  return x;
}

uint64_t MortonCode(const Eigen::Vector3d& p, const Eigen::Vector3d& lo, const Eigen::Vector3d& scale) {
  uint64_t code = 0;
  for (int k = 0; k < 3; ++k) {
    const double t = std::clamp((p[k] - lo[k]) * scale[k], 0.0, 2097151.0);
    code |= SpreadBits(static_cast<uint64_t>(t)) << k;
  }
  return code;
}

// Sorts ids by the Morton code of their point (ties by id): neighbouring ids, neighbouring points.
void SortAlongZCurve(std::vector<uint32_t>& ids, const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& lo,
                     const Eigen::Vector3d& scale) {
  std::vector<std::pair<uint64_t, uint32_t>> keyed(ids.size());
  tbb::parallel_for(size_t{0}, ids.size(), [&](size_t i) { keyed[i] = {MortonCode(points[i], lo, scale), ids[i]}; });
  tbb::parallel_sort(keyed.begin(), keyed.end());  // keys are unique: the order is deterministic
  for (size_t i = 0; i < ids.size(); ++i) ids[i] = keyed[i].second;
}

}  // namespace

struct MeshDistanceIndex::Impl {
  const TriangleMesh* mesh = nullptr;
  std::vector<uint32_t> faces;            // valid faces (distinct, in-range corners), in Z-curve order
  std::vector<uint32_t> vertices;         // vertices the valid faces use, in Z-curve order
  std::vector<double> chunk_area;         // area of each chunk of `faces`
  std::vector<double> chunk_area_before;  // cumulative area before each chunk (fixed order)
  double total_area = 0;
  std::vector<uint32_t> incident_start;  // faces around vertex v: incident[incident_start[v]..]
  std::vector<uint32_t> incident;        // (valid faces only)
  Tree tree;

  // Max squared distance from the samples of this mesh to `to`; `samples` receives their count.
  double MaxSquaredDistanceTo(const Impl& to, const HausdorffOptions& options, int64_t* samples) const;
};

MeshDistanceIndex::MeshDistanceIndex(const TriangleMesh& mesh, const char* name) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.mesh = &mesh;
  const size_t n = mesh.num_vertices();
  std::vector<char> used(n, 0);
  m.faces.reserve(mesh.num_faces());
  for (size_t i = 0; i < mesh.num_faces(); ++i) {
    const auto& f = mesh.faces[i];
    if (f[0] >= n || f[1] >= n || f[2] >= n || f[0] == f[1] || f[1] == f[2] || f[0] == f[2]) {
      continue;
    }
    m.faces.push_back(static_cast<uint32_t>(i));
    used[f[0]] = used[f[1]] = used[f[2]] = 1;
  }
  if (m.faces.empty()) throw InputError(std::string("hausdorff: mesh ") + name + " has no face");
  for (size_t v = 0; v < n; ++v) {
    if (used[v]) m.vertices.push_back(static_cast<uint32_t>(v));
  }
  // Samples in Z-curve order, then the incidence table while CGAL builds the AABB tree (on one
  // thread) over the faces in that order (neighbouring primitives, fewer cache misses).
  {
    // Faces and vertices in Z-curve order: each chunk is a compact patch of the surface and its
    // samples come one next to the other (the previous closest triangle is a good start).
    {
      Eigen::Vector3d lo = mesh.vertices_m[m.vertices.front()], hi = lo;
      for (uint32_t v : m.vertices) {
        lo = lo.cwiseMin(mesh.vertices_m[v]);
        hi = hi.cwiseMax(mesh.vertices_m[v]);
      }
      const Eigen::Vector3d scale = (2097151.0 / (hi - lo).cwiseMax(Eigen::Vector3d::Constant(1e-12)).array()).matrix();
      std::vector<Eigen::Vector3d> at(m.vertices.size());
      for (size_t i = 0; i < m.vertices.size(); ++i) at[i] = mesh.vertices_m[m.vertices[i]];
      SortAlongZCurve(m.vertices, at, lo, scale);
      at.resize(m.faces.size());
      for (size_t i = 0; i < m.faces.size(); ++i) {
        const auto& f = mesh.faces[m.faces[i]];
        at[i] = (mesh.vertices_m[f[0]] + mesh.vertices_m[f[1]] + mesh.vertices_m[f[2]]) / 3.0;
      }
      SortAlongZCurve(m.faces, at, lo, scale);
    }
    const size_t chunks = NumChunks(m.faces.size());
    m.chunk_area.assign(chunks, 0.0);
    tbb::parallel_for(size_t{0}, chunks, [&](size_t k) {
      double sum = 0;
      const size_t end = std::min(m.faces.size(), (k + 1) * kChunk);
      for (size_t i = k * kChunk; i < end; ++i) sum += TriangleArea(mesh, mesh.faces[m.faces[i]]);
      m.chunk_area[k] = sum;
    });
    m.chunk_area_before.resize(chunks);
    for (size_t k = 0; k < chunks; ++k) {
      m.chunk_area_before[k] = m.total_area;
      m.total_area += m.chunk_area[k];
    }
  }
  m.tree.insert(m.faces.cbegin(), m.faces.cend(), &mesh);
  tbb::parallel_invoke([&] { m.tree.build(); },
                       [&] {
                         m.incident_start.assign(n + 1, 0);
                         for (uint32_t f : m.faces) {
                           for (uint32_t v : mesh.faces[f]) ++m.incident_start[v + 1];
                         }
                         for (size_t v = 0; v < n; ++v) m.incident_start[v + 1] += m.incident_start[v];
                         m.incident.resize(m.incident_start.back());
                         {
                           std::vector<uint32_t> fill(m.incident_start.begin(), m.incident_start.end() - 1);
                           for (uint32_t f : m.faces) {
                             for (uint32_t v : mesh.faces[f]) m.incident[fill[v]++] = f;
                           }
                         }
                       });
  // Every query below passes a hint (or starts from any primitive): no k-d tree of reference
  // points is needed, and none is built lazily from several threads.
  m.tree.do_not_accelerate_distance_queries();
}

MeshDistanceIndex::~MeshDistanceIndex() = default;

double MeshDistanceIndex::Impl::MaxSquaredDistanceTo(const Impl& to, const HausdorffOptions& options,
                                                     int64_t* samples) const {
  const size_t vertex_chunks = options.sample_vertices ? NumChunks(vertices.size()) : 0;
  const size_t face_chunks = NumChunks(faces.size());
  const int64_t total_samples = std::max<int64_t>(0, options.samples_per_mesh);
  // Samples of face chunk k: round(N·A_before_next/A) − round(N·A_before/A), so they add up to N.
  auto samples_before = [&](size_t k) -> int64_t {
    if (k >= face_chunks || total_area <= 0) return k >= face_chunks ? total_samples : 0;
    return static_cast<int64_t>(
        std::floor(static_cast<double>(total_samples) * (chunk_area_before[k] / total_area) + 0.5));
  };
  std::vector<double> chunk_max(vertex_chunks + face_chunks, 0.0);
  tbb::parallel_for(size_t{0}, chunk_max.size(), [&](size_t c) {
    // Samples come in mesh order, so a sample's closest point is usually on or near the triangle
    // that held the previous one. A short greedy walk over neighbouring triangles (those sharing a
    // vertex) from there gives a triangle whose distance bounds the sample's distance to the mesh
    // from above. When the bound is not above this chunk's maximum so far, the sample cannot raise
    // the maximum and the tree query is skipped (the maximum is unchanged, exactly); otherwise
    // the walk's closest point is the query's hint, which keeps the tree traversal short.
    double max_sq = 0;
    bool have_hint = false;
    Tree::Point_and_primitive_id hint;
    const TriangleMesh& target = *to.mesh;
    auto closest_on_face = [&](uint32_t face, const Eigen::Vector3d& p) {
      const auto& f = target.faces[face];
      return ClosestOnTriangle(p, target.vertices_m[f[0]], target.vertices_m[f[1]], target.vertices_m[f[2]]);
    };
    auto measure = [&](const Eigen::Vector3d& point) {
      const Point3 p = ToPoint(point);
      if (have_hint) {
        uint32_t face = hint.second;
        Eigen::Vector3d q = closest_on_face(face, point);
        double best = (q - point).squaredNorm();
        for (int step = 0; step < kWalkSteps && best > max_sq; ++step) {
          const uint32_t from = face;
          for (uint32_t v : target.faces[from]) {
            for (uint32_t k = to.incident_start[v]; k < to.incident_start[v + 1]; ++k) {
              const uint32_t g = to.incident[k];
              if (g == from) continue;
              const Eigen::Vector3d r = closest_on_face(g, point);
              const double d = (r - point).squaredNorm();
              if (d < best) {
                best = d;
                face = g;
                q = r;
              }
            }
          }
          if (face == from) break;  // a local minimum
        }
        hint = Tree::Point_and_primitive_id(ToPoint(q), face);
        if (best <= max_sq) return;
        hint = to.tree.closest_point_and_primitive(p, hint);
      } else {
        hint = to.tree.closest_point_and_primitive(p);
        have_hint = true;
      }
      max_sq = std::max(max_sq, CGAL::squared_distance(hint.first, p));
    };
    if (c < vertex_chunks) {
      const size_t end = std::min(vertices.size(), (c + 1) * kChunk);
      for (size_t i = c * kChunk; i < end; ++i) measure(mesh->vertices_m[vertices[i]]);
    } else {
      const size_t k = c - vertex_chunks;
      const int64_t count = samples_before(k + 1) - samples_before(k);
      if (count <= 0) return;
      const size_t begin = k * kChunk, end = std::min(faces.size(), (k + 1) * kChunk);
      SplitMix64 rng((static_cast<uint64_t>(options.seed) << 32) ^ (0xA24BAED4963EE407ull * (k + 1)));
      // Area-weighted face choice: sorted uniform positions walked along the cumulative area, so
      // the samples come in face order (neighbouring queries, good hints).
      std::vector<double> positions(static_cast<size_t>(count));
      for (double& x : positions) x = rng.Uniform01() * chunk_area[k];
      std::sort(positions.begin(), positions.end());
      size_t i = begin;
      double area_end = TriangleArea(*mesh, mesh->faces[faces[i]]);
      for (double x : positions) {
        while (x >= area_end && i + 1 < end) {
          ++i;
          area_end += TriangleArea(*mesh, mesh->faces[faces[i]]);
        }
        const auto& f = mesh->faces[faces[i]];
        const Eigen::Vector3d& a = mesh->vertices_m[f[0]];
        const Eigen::Vector3d& b = mesh->vertices_m[f[1]];
        const Eigen::Vector3d& cc = mesh->vertices_m[f[2]];
        // Uniform in the triangle: s = √u1, weights (1 − s, s(1 − u2), s·u2).
        const double s = std::sqrt(rng.Uniform01());
        const double u2 = rng.Uniform01();
        measure(Eigen::Vector3d((1.0 - s) * a + s * (1.0 - u2) * b + s * u2 * cc));
      }
    }
    chunk_max[c] = max_sq;
  });
  if (samples) {
    *samples = total_samples + (options.sample_vertices ? static_cast<int64_t>(vertices.size()) : 0);
  }
  double max_sq = 0;
  for (double d : chunk_max) max_sq = std::max(max_sq, d);
  return max_sq;
}

double MeshDistanceIndex::MaxDistanceTo(const MeshDistanceIndex& other, const HausdorffOptions& options,
                                        int64_t* samples) const {
  return std::sqrt(impl_->MaxSquaredDistanceTo(*other.impl_, options, samples));
}

namespace {

// The largest distance from a point of triangle (a, b, c) to its nearest corner: the circumradius
// when no angle is obtuse; otherwise at most the longest edge / √2 (the triangle then lies in the
// disc on its longest edge, where one end of that edge is within that distance).
double CoverRadius(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  double e[3] = {(b - c).squaredNorm(), (c - a).squaredNorm(), (a - b).squaredNorm()};
  std::sort(e, e + 3);
  const double area2 = (b - a).cross(c - a).norm();  // twice the area
  if (e[2] <= e[0] + e[1] && area2 > 0) {
    return std::sqrt(e[0] * e[1] * e[2]) / (2.0 * area2);  // abc / (4 · area)
  }
  return std::sqrt(0.5 * e[2]);
}

// The exact nearest face of B (the mesh of `to`) and distance for every vertex of A (the mesh of
// `from`), warm-started along the Z curve. Returns the largest of those distances and `known_lower_m`.
double NearestFacesOfVertices(const MeshDistanceIndex::Impl& from, const MeshDistanceIndex::Impl& to,
                              double known_lower_m, std::vector<double>& vertex_d, std::vector<uint32_t>& vertex_face) {
  const TriangleMesh& a = *from.mesh;
  vertex_d.assign(a.num_vertices(), 0.0);
  vertex_face.assign(a.num_vertices(), 0);
  const size_t vertex_chunks = NumChunks(from.vertices.size());
  std::vector<double> vertex_chunk_max(vertex_chunks, 0.0);
  tbb::parallel_for(size_t{0}, vertex_chunks, [&](size_t c) {
    Tree::Point_and_primitive_id hint;
    bool have_hint = false;
    double max_d = 0;
    const size_t end = std::min(from.vertices.size(), (c + 1) * kChunk);
    for (size_t i = c * kChunk; i < end; ++i) {
      const uint32_t v = from.vertices[i];
      const Point3 p = ToPoint(a.vertices_m[v]);
      hint = have_hint ? to.tree.closest_point_and_primitive(p, hint) : to.tree.closest_point_and_primitive(p);
      have_hint = true;
      vertex_d[v] = std::sqrt(CGAL::squared_distance(hint.first, p));
      vertex_face[v] = hint.second;
      max_d = std::max(max_d, vertex_d[v]);
    }
    vertex_chunk_max[c] = max_d;
  });
  double lower0 = std::max(0.0, known_lower_m);
  for (double d : vertex_chunk_max) lower0 = std::max(lower0, d);
  return lower0;
}

// A piece of a triangle of A: its corners, their exact distances to B and their nearest faces of B.
struct BoundPiece {
  Eigen::Vector3d p[3];
  double d[3];
  uint32_t face[3];
  int depth;
};

// What the pieces of one chunk of A's faces showed.
struct ChunkBound {
  double lower = 0, upper = 0;
  int64_t points = 0, unresolved = 0;
};

// Bounds the distance from the triangles of A to B (the mesh of `to`), cutting them into pieces.
class TriangleBounder {
 public:
  TriangleBounder(const MeshDistanceIndex::Impl& to, const HausdorffBoundOptions& options)
      : to_(to), b_(*to.mesh), options_(options) {}

  // Refines `root` until every piece's upper bound is within the threshold above the lower bound, or
  // at the maximum depth. `stack`: scratch.
  void Bound(const BoundPiece& root, ChunkBound& r, std::vector<BoundPiece>& stack) const {
    stack.push_back(root);
    while (!stack.empty()) {
      const BoundPiece s = stack.back();
      stack.pop_back();
      const double threshold = r.lower + std::max(options_.tolerance_m, options_.relative_tolerance * r.lower);
      const double best = UpperBound(s, threshold);
      if (best <= threshold || s.depth >= options_.max_depth) {
        r.upper = std::max(r.upper, best);
        if (best > threshold) ++r.unresolved;
        continue;
      }
      Split(s, r, stack);
    }
  }

 private:
  Eigen::Vector3d ClosestOn(uint32_t face, const Eigen::Vector3d& p) const {
    const auto& t = b_.faces[face];
    return ClosestOnTriangle(p, b_.vertices_m[t[0]], b_.vertices_m[t[1]], b_.vertices_m[t[2]]);
  }
  double FaceDistance(uint32_t face, const Eigen::Vector3d& p) const { return (ClosestOn(face, p) - p).norm(); }

  // The corners' largest distance plus the piece's cover radius, lowered while above `threshold` by
  // the max over the corners of the distance to one triangle of B (which bounds the whole piece): the
  // corners' nearest faces, then the faces around them.
  double UpperBound(const BoundPiece& s, double threshold) const {
    double best = std::max({s.d[0], s.d[1], s.d[2]}) + CoverRadius(s.p[0], s.p[1], s.p[2]);
    auto try_face = [&](uint32_t face) {
      double m = 0;
      for (int k = 0; k < 3 && m < best; ++k) m = std::max(m, FaceDistance(face, s.p[k]));
      best = std::min(best, m);
    };
    if (best > threshold) {
      for (int k = 0; k < 3; ++k) try_face(s.face[k]);
    }
    if (best > threshold) {  // the faces around the corners' nearest faces
      for (int k = 0; k < 3 && best > threshold; ++k) {
        for (uint32_t w : b_.faces[s.face[k]]) {
          for (uint32_t j = to_.incident_start[w]; j < to_.incident_start[w + 1] && best > threshold; ++j) {
            try_face(to_.incident[j]);
          }
        }
      }
    }
    return best;
  }

  // Cuts the piece in four at the edge midpoints, each measured exactly (raising the lower bound).
  void Split(const BoundPiece& s, ChunkBound& r, std::vector<BoundPiece>& stack) const {
    Eigen::Vector3d mp[3];
    double md[3];
    uint32_t mf[3];
    for (int k = 0; k < 3; ++k) {
      const int k1 = (k + 1) % 3;
      mp[k] = 0.5 * (s.p[k] + s.p[k1]);
      const Point3 q = ToPoint(mp[k]);
      const Tree::Point_and_primitive_id hint(ToPoint(ClosestOn(s.face[k], mp[k])), s.face[k]);
      const Tree::Point_and_primitive_id near = to_.tree.closest_point_and_primitive(q, hint);
      md[k] = std::sqrt(CGAL::squared_distance(near.first, q));
      mf[k] = near.second;
      r.lower = std::max(r.lower, md[k]);
      ++r.points;
    }
    const int depth = s.depth + 1;
    // Corners 0,1,2 and midpoints m0 (of 0-1), m1 (of 1-2), m2 (of 2-0).
    stack.push_back({{s.p[0], mp[0], mp[2]}, {s.d[0], md[0], md[2]}, {s.face[0], mf[0], mf[2]}, depth});
    stack.push_back({{mp[0], s.p[1], mp[1]}, {md[0], s.d[1], md[1]}, {mf[0], s.face[1], mf[1]}, depth});
    stack.push_back({{mp[2], mp[1], s.p[2]}, {md[2], md[1], s.d[2]}, {mf[2], mf[1], s.face[2]}, depth});
    stack.push_back({{mp[0], mp[1], mp[2]}, {md[0], md[1], md[2]}, {mf[0], mf[1], mf[2]}, depth});
  }

  const MeshDistanceIndex::Impl& to_;
  const TriangleMesh& b_;
  const HausdorffBoundOptions& options_;
};

}  // namespace

HausdorffInterval MeshDistanceIndex::BoundDistanceTo(const MeshDistanceIndex& other, double known_lower_m,
                                                     const HausdorffBoundOptions& options) const {
  const Impl& from = *impl_;
  const Impl& to = *other.impl_;
  const TriangleMesh& a = *from.mesh;
  std::vector<double> vertex_d;
  std::vector<uint32_t> vertex_face;
  const double lower0 = NearestFacesOfVertices(from, to, known_lower_m, vertex_d, vertex_face);

  const TriangleBounder bounder(to, options);
  const size_t face_chunks = NumChunks(from.faces.size());
  std::vector<ChunkBound> results(face_chunks);
  tbb::parallel_for(size_t{0}, face_chunks, [&](size_t c) {
    ChunkBound r;
    r.lower = lower0;
    std::vector<BoundPiece> stack;
    const size_t end = std::min(from.faces.size(), (c + 1) * kChunk);
    for (size_t i = c * kChunk; i < end; ++i) {
      const auto& t = a.faces[from.faces[i]];
      BoundPiece root;
      for (int k = 0; k < 3; ++k) {
        root.p[k] = a.vertices_m[t[k]];
        root.d[k] = vertex_d[t[k]];
        root.face[k] = vertex_face[t[k]];
      }
      root.depth = 0;
      bounder.Bound(root, r, stack);
    }
    results[c] = r;
  });
  HausdorffInterval out;
  out.lower_m = lower0;
  out.points_measured = static_cast<int64_t>(from.vertices.size());
  for (const ChunkBound& r : results) {
    out.lower_m = std::max(out.lower_m, r.lower);
    out.upper_m = std::max(out.upper_m, r.upper);
    out.points_measured += r.points;
    out.unresolved_triangles += r.unresolved;
  }
  out.upper_m = std::max(out.upper_m, out.lower_m);
  return out;
}

double MeshDistanceIndex::AreaM2() const { return impl_->total_area; }

double MeshDistanceIndex::DistanceM(const Eigen::Vector3d& point) const {
  const Point3 p = ToPoint(point);
  return std::sqrt(CGAL::squared_distance(impl_->tree.closest_point(p), p));
}

HausdorffDistance ApproximateHausdorff(const MeshDistanceIndex& a, const MeshDistanceIndex& b,
                                       const HausdorffOptions& options) {
  HausdorffDistance d;
  d.a_to_b_m = a.MaxDistanceTo(b, options, &d.samples_a);
  d.b_to_a_m = b.MaxDistanceTo(a, options, &d.samples_b);
  d.symmetric_m = std::max(d.a_to_b_m, d.b_to_a_m);
  return d;
}

HausdorffDistance ApproximateHausdorff(const TriangleMesh& a, const TriangleMesh& b, const HausdorffOptions& options) {
  std::unique_ptr<MeshDistanceIndex> index_a, index_b;
  tbb::parallel_invoke([&] { index_a = std::make_unique<MeshDistanceIndex>(a, "A"); },
                       [&] { index_b = std::make_unique<MeshDistanceIndex>(b, "B"); });
  return ApproximateHausdorff(*index_a, *index_b, options);
}

}  // namespace cinepath::photogrammetry
