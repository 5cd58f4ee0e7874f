// Quadric edge collapse with optimal vertex placement (Garland & Heckbert, "Surface Simplification
// Using Quadric Error Metrics", SIGGRAPH 1997), run on fixed tiles in parallel with the tiles' cut
// edges locked, then one pass over the band around the cuts (where the tiles kept every face) that
// carries every vertex's accumulated quadric: internal::DecimateQemTiled in mesh_decimate.h.
//
// Why hand-written: the installed meshoptimizer (0.18) only collapses a vertex onto a neighbour (no
// placement option: meshopt_SimplifyPrune, meshopt_SimplifyPermissive and position updates came in
// later releases), which keeps its error near 0.14 m however light the budget on the bench terrain;
// CGAL and OpenMesh place optimally or keep vertices but run at ~39 k faces/s on one core
// (bench/RESULTS.md). This file does what they do with flat arrays and a lazy heap.
#include <algorithm>
#include <array>
#include <cmath>
#include <queue>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <Eigen/Dense>

#include "photogrammetry/mesh_decimate.h"

namespace cinepath::photogrammetry::internal {
namespace {

// Symmetric 4×4 quadric: rows (a00 a01 a02 a03 | a11 a12 a13 | a22 a23 | a33).
struct Quadric {
  std::array<double, 10> q{};
  void AddPlane(const Eigen::Vector3d& n, double d, double w) {
    q[0] += w * n.x() * n.x();
    q[1] += w * n.x() * n.y();
    q[2] += w * n.x() * n.z();
    q[3] += w * n.x() * d;
    q[4] += w * n.y() * n.y();
    q[5] += w * n.y() * n.z();
    q[6] += w * n.y() * d;
    q[7] += w * n.z() * n.z();
    q[8] += w * n.z() * d;
    q[9] += w * d * d;
  }
  Quadric& operator+=(const Quadric& o) {
    for (int k = 0; k < 10; ++k) q[k] += o.q[k];
    return *this;
  }
  // The planes' total weight: each plane adds w·|n|² = w to the trace of the 3 × 3 part.
  double Weight() const { return q[0] + q[4] + q[7]; }
  double Error(const Eigen::Vector3d& p) const {
    const double x = p.x(), y = p.y(), z = p.z();
    return q[0] * x * x + 2 * q[1] * x * y + 2 * q[2] * x * z + 2 * q[3] * x + q[4] * y * y + 2 * q[5] * y * z +
           2 * q[6] * y + q[7] * z * z + 2 * q[8] * z + q[9];
  }
};

Quadric Sum(const Quadric& a, const Quadric& b) {
  Quadric s = a;
  s += b;
  return s;
}

// The point minimising q on the segment [a, b] (closed form of a quadratic in t).
Eigen::Vector3d BestOnSegment(const Quadric& q, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double ea = q.Error(a), eb = q.Error(b), em = q.Error(0.5 * (a + b));
  // e(t) = ea + t·(−3ea + 4em − eb) + t²·(2ea − 4em + 2eb)
  const double c2 = 2 * ea - 4 * em + 2 * eb, c1 = -3 * ea + 4 * em - eb;
  double t = ea <= eb ? 0.0 : 1.0;
  if (c2 > 0) {
    const double tm = std::clamp(-c1 / (2 * c2), 0.0, 1.0);
    if (ea + tm * c1 + tm * tm * c2 < std::min(ea, eb)) t = tm;
  }
  return a + t * (b - a);
}

// Where an edge (a, b) collapses to. The quadric's minimum is solved in the eigenbasis of its 3×3
// part, and the directions the quadric does not pin down (eigenvalue at most rcond × the largest) are
// held at the edge's midpoint, as in Lindstrom's out-of-core simplification (P. Lindstrom, "Out-of-Core
// Simplification of Large Polygonal Models", SIGGRAPH 2000). On a near-flat patch the quadric fixes
// only the height; a plain inverse slides the point far along the plane on rounding noise. The point
// is used when it lies within `reach` edge lengths of the midpoint and beats the best point on the
// edge; otherwise the best point on the edge.
Eigen::Vector3d Placement(const Quadric& q, const Eigen::Vector3d& a, const Eigen::Vector3d& b, double reach,
                          double rcond) {
  Eigen::Matrix3d m;
  m << q.q[0], q.q[1], q.q[2], q.q[1], q.q[4], q.q[5], q.q[2], q.q[5], q.q[7];
  const Eigen::Vector3d rhs(-q.q[3], -q.q[6], -q.q[8]);
  const Eigen::Vector3d mid = 0.5 * (a + b);
  const Eigen::Vector3d on_edge = BestOnSegment(q, a, b);
  const Eigen::Vector3d residual = rhs - m * mid;
  Eigen::Vector3d p = mid;
  // Every eigenvalue is above rcond × the largest when det / m2 > rcond × trace, since the smallest
  // is at least det / m2 (m2: the sum of the principal 2 × 2 minors, λ1λ2 + λ1λ3 + λ2λ3) and the
  // largest at most the trace. Then nothing is truncated and the plain inverse (the adjugate) gives
  // the same point without the eigen solve: most of a curved surface's edges.
  const Eigen::Matrix3d adjugate = (Eigen::Matrix3d() << m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1),
                                    m(0, 2) * m(2, 1) - m(0, 1) * m(2, 2), m(0, 1) * m(1, 2) - m(0, 2) * m(1, 1),
                                    m(1, 2) * m(2, 0) - m(1, 0) * m(2, 2), m(0, 0) * m(2, 2) - m(0, 2) * m(2, 0),
                                    m(0, 2) * m(1, 0) - m(0, 0) * m(1, 2), m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0),
                                    m(0, 1) * m(2, 0) - m(0, 0) * m(2, 1), m(0, 0) * m(1, 1) - m(0, 1) * m(1, 0))
                                       .finished();
  const double trace = m.trace();
  const double minors = adjugate(0, 0) + adjugate(1, 1) + adjugate(2, 2);
  const double det = m(0, 0) * adjugate(0, 0) + m(0, 1) * adjugate(1, 0) + m(0, 2) * adjugate(2, 0);
  // (The first test keeps rounding noise out: minors that small leave at most one direction pinned.)
  if (minors > 1e-9 * trace * trace && det > rcond * trace * minors) {
    p += adjugate * residual / det;
  } else {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
    eigen.computeDirect(m);
    const Eigen::Vector3d& lambda = eigen.eigenvalues();  // ascending
    if (!(lambda(2) > 0)) return on_edge;
    for (int k = 0; k < 3; ++k) {
      if (lambda(k) > rcond * lambda(2)) {
        const Eigen::Vector3d axis = eigen.eigenvectors().col(k);
        p += axis * (axis.dot(residual) / lambda(k));
      }
    }
  }
  if (p.allFinite() && (p - mid).squaredNorm() <= reach * reach * (b - a).squaredNorm() &&
      q.Error(p) < q.Error(on_edge)) {
    return p;
  }
  return on_edge;
}

struct HeapEntry {
  float cost;
  uint32_t a, b;
  uint32_t stamps;                            // stamp[a] + stamp[b] when pushed: stamps only grow, so any change shows
  bool operator<(const HeapEntry& o) const {  // std::priority_queue is a max-heap: reversed
    if (cost != o.cost) return cost > o.cost;
    if (a != o.a) return a > o.a;
    return b > o.b;
  }
};

// One mesh (a tile, or the merged tiles) with local indices, simplified in place. With `goal2` (one
// squared error goal per vertex; empty: a face budget only) a collapse is made only while its error,
// the root of its quadric's weighted mean (its point's mean squared distance to the planes merged into
// the edge, by area), is within the smaller goal of its two vertices, and the vertex kept takes that
// goal. A vertex whose goal is 0 is never touched.
class QemSimplifier {
 public:
  QemSimplifier(std::vector<Eigen::Vector3d> positions, std::vector<std::array<uint32_t, 3>> faces,
                std::vector<Quadric> quadrics, std::vector<char> locked, std::vector<double> goal2,
                const QemOptions& options)
      : pos_(std::move(positions)),
        faces_(std::move(faces)),
        quadric_(std::move(quadrics)),
        locked_(std::move(locked)),
        goal2_(std::move(goal2)),
        options_(options) {
    const size_t n = pos_.size();
    face_alive_.assign(faces_.size(), 1);
    vertex_alive_.assign(n, 1);
    stamp_.assign(n, 0);
    mark_.assign(n, 0);
    // Each vertex's corners as a singly linked list (corner c: slot c % 3 of face c / 3); corners of
    // dead faces are unlinked lazily, a collapsed vertex's list is spliced onto the kept one's.
    head_.assign(n, kNone);
    next_.assign(3 * faces_.size(), kNone);
    for (uint32_t c = static_cast<uint32_t>(3 * faces_.size()); c-- > 0;) {
      const uint32_t v = faces_[c / 3][c % 3];
      next_[c] = head_[v];
      head_[v] = c;
    }
    faces_alive_ = static_cast<int64_t>(faces_.size());
  }

  void Run(int64_t target_faces) {
    std::vector<HeapEntry> entries;
    entries.reserve(faces_.size() * 3 / 2 + 16);
    for (const auto& f : faces_) {
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = f[k], b = f[(k + 1) % 3];
        if (a < b || IsBorderEdgeOnce(a, b)) Push(entries, a, b);
      }
    }
    std::priority_queue<HeapEntry> heap(std::less<HeapEntry>(), std::move(entries));
    std::vector<HeapEntry> fresh;
    while (faces_alive_ > target_faces && !heap.empty()) {
      const HeapEntry e = heap.top();
      heap.pop();
      if (!vertex_alive_[e.a] || !vertex_alive_[e.b] || stamp_[e.a] + stamp_[e.b] != e.stamps) continue;
      const uint32_t kept = TryCollapse(e.a, e.b);
      if (kept == kNone) continue;
      fresh.clear();
      ForNeighbours(kept, [&](uint32_t w) { Push(fresh, std::min(kept, w), std::max(kept, w)); });
      for (const HeapEntry& f : fresh) heap.push(f);
    }
  }

  const std::vector<Eigen::Vector3d>& positions() const { return pos_; }
  const std::vector<Quadric>& quadrics() const { return quadric_; }
  const std::vector<double>& goals2() const { return goal2_; }
  const std::vector<char>& vertex_alive() const { return vertex_alive_; }
  // Surviving faces, in their input order.
  std::vector<std::array<uint32_t, 3>> AliveFaces() const {
    std::vector<std::array<uint32_t, 3>> out;
    out.reserve(static_cast<size_t>(faces_alive_));
    for (size_t f = 0; f < faces_.size(); ++f) {
      if (face_alive_[f]) out.push_back(faces_[f]);
    }
    return out;
  }

 private:
  static constexpr uint32_t kNone = 0xffffffffu;

  // True when a → b is an edge seen in only one orientation (so the a < b rule would miss it when
  // a > b). Cheap enough: only consulted for a > b.
  bool IsBorderEdgeOnce(uint32_t a, uint32_t b) const {
    for (uint32_t c = head_[b]; c != kNone; c = next_[c]) {
      if (faces_[c / 3][(c % 3 + 1) % 3] == a) return false;
    }
    return true;
  }

  // Calls visit(face) for every live face around v, unlinking dead ones on the way.
  template <typename F>
  void ForFaces(uint32_t v, F&& visit) {
    uint32_t* link = &head_[v];
    while (*link != kNone) {
      const uint32_t c = *link;
      if (!face_alive_[c / 3]) {
        *link = next_[c];
        continue;
      }
      visit(c / 3);
      link = &next_[c];
    }
  }

  void Push(std::vector<HeapEntry>& out, uint32_t a, uint32_t b) {
    if (locked_[a] && locked_[b]) return;
    Eigen::Vector3d p;
    double cost = PlaceAndCost(a, b, &p);
    if (!goal2_.empty()) {
      // Error goals: the heap orders by the share of the goal, and holds only collapses within it
      // (an edge's cost changes only when one of its ends does, and it is pushed again then).
      const double goal2 = std::min(goal2_[a], goal2_[b]);
      const double weight = quadric_[a].Weight() + quadric_[b].Weight();
      if (!(goal2 > 0) || !(weight > 0)) return;
      cost = cost / weight / goal2;
      if (!(cost <= 1)) return;
      // Order ties by length, shortest first: on a plane every collapse costs ~0 (rounding noise), and
      // in noise order one vertex tends to swallow its neighbours one by one into a hub whose every
      // collapse re-pushes a hundred edges (56 pushes per collapse on the bench's building walls, 6.5
      // with this; 4× faster, the same face count). 1e-6 × (length / goal)² is below any real cost.
      cost += 1e-6 * (pos_[a] - pos_[b]).squaredNorm() / goal2;
    }
    out.push_back({static_cast<float>(cost), a, b, stamp_[a] + stamp_[b]});
  }

  double PlaceAndCost(uint32_t a, uint32_t b, Eigen::Vector3d* p) const {
    const Quadric q = Sum(quadric_[a], quadric_[b]);
    if (locked_[a]) {
      *p = pos_[a];
    } else if (locked_[b]) {
      *p = pos_[b];
    } else if (options_.optimal_placement) {
      *p = Placement(q, pos_[a], pos_[b], options_.placement_reach, options_.placement_rcond);
    } else {
      *p = q.Error(pos_[a]) <= q.Error(pos_[b]) ? pos_[a] : pos_[b];
    }
    return std::max(0.0, q.Error(*p));
  }

  template <typename F>
  void ForNeighbours(uint32_t v, F&& visit) {
    const uint32_t epoch = ++epoch_;
    ForFaces(v, [&](uint32_t f) {
      for (uint32_t w : faces_[f]) {
        if (w != v && mark_[w] != epoch) {
          mark_[w] = epoch;
          visit(w);
        }
      }
    });
  }

  static bool Contains(const std::array<uint32_t, 3>& t, uint32_t v) { return t[0] == v || t[1] == v || t[2] == v; }

  // Normal of face f with vertex `moved` at `p`, unnormalised.
  Eigen::Vector3d NormalWith(const std::array<uint32_t, 3>& t, uint32_t moved, const Eigen::Vector3d& p) const {
    const Eigen::Vector3d& a = t[0] == moved ? p : pos_[t[0]];
    const Eigen::Vector3d& b = t[1] == moved ? p : pos_[t[1]];
    const Eigen::Vector3d& c = t[2] == moved ? p : pos_[t[2]];
    return (b - a).cross(c - a);
  }

  // Faces around `v` other than those shared with `other` keep their orientation (no fold-over)
  // and do not become slivers when v moves to p.
  bool KeepsOrientation(uint32_t v, uint32_t other, const Eigen::Vector3d& p) {
    bool ok = true;
    ForFaces(v, [&](uint32_t f) {
      const auto& t = faces_[f];
      if (!ok || Contains(t, other)) return;
      const Eigen::Vector3d before = NormalWith(t, kNone, p);
      const Eigen::Vector3d after = NormalWith(t, v, p);
      const double nb = before.norm(), na = after.norm();
      if (!(na > 0) || after.dot(before) < options_.min_normal_cos * na * nb) ok = false;
    });
    return ok;
  }

  // Collapses edge (a, b) if it is an interior, manifold edge whose collapse keeps the mesh a
  // manifold (the link condition) and folds no face. Returns the vertex kept, or kNone.
  uint32_t TryCollapse(uint32_t a, uint32_t b) {
    // The kept vertex: the locked one, otherwise the lower index (deterministic).
    uint32_t keep = a, gone = b;
    if (locked_[b]) std::swap(keep, gone);
    if (locked_[gone]) return kNone;
    uint32_t shared = 0, opposite[2] = {kNone, kNone};
    bool manifold = true;
    ForFaces(gone, [&](uint32_t f) {
      const auto& t = faces_[f];
      if (!Contains(t, keep)) return;
      if (shared == 2) {
        manifold = false;
        return;
      }
      for (uint32_t w : t) {
        if (w != keep && w != gone) opposite[shared] = w;
      }
      ++shared;
    });
    if (!manifold || shared != 2 || opposite[0] == opposite[1]) return kNone;
    // Link condition: the only common neighbours are the two opposite vertices.
    const uint32_t around_gone = ++epoch_;
    ForFaces(gone, [&](uint32_t f) {
      for (uint32_t w : faces_[f]) mark_[w] = around_gone;
    });
    const uint32_t seen = ++epoch_;
    int common = 0;
    ForFaces(keep, [&](uint32_t f) {
      for (uint32_t w : faces_[f]) {
        if (w != keep && w != gone && mark_[w] == around_gone) {
          mark_[w] = seen;
          ++common;
        }
      }
    });
    if (common != 2) return kNone;
    Eigen::Vector3d p;
    PlaceAndCost(a, b, &p);
    if (!KeepsOrientation(gone, keep, p) || !KeepsOrientation(keep, gone, p)) return kNone;
    // Apply: the shared faces die, gone's other faces take keep, gone's corners join keep's list.
    uint32_t last = kNone;
    ForFaces(gone, [&](uint32_t f) {
      auto& t = faces_[f];
      int slot = 0;
      for (int k = 0; k < 3; ++k) {
        if (t[k] == gone) slot = k;
      }
      last = 3 * f + static_cast<uint32_t>(slot);
      if (Contains(t, keep)) {
        face_alive_[f] = 0;
        --faces_alive_;
        return;
      }
      t[slot] = keep;
    });
    if (last != kNone) {
      next_[last] = head_[keep];
      head_[keep] = head_[gone];
    }
    head_[gone] = kNone;
    vertex_alive_[gone] = 0;
    quadric_[keep] += quadric_[gone];
    if (!goal2_.empty()) goal2_[keep] = std::min(goal2_[keep], goal2_[gone]);
    pos_[keep] = p;
    ++stamp_[keep];
    return keep;
  }

  std::vector<Eigen::Vector3d> pos_;
  std::vector<std::array<uint32_t, 3>> faces_;
  std::vector<Quadric> quadric_;
  std::vector<char> locked_;
  std::vector<double> goal2_;
  QemOptions options_;
  std::vector<char> face_alive_, vertex_alive_;
  std::vector<uint32_t> stamp_, mark_;
  uint32_t epoch_ = 0;
  std::vector<uint32_t> head_, next_;
  int64_t faces_alive_ = 0;
};

// Plane quadric of each face added to its three corners (area-weighted, or one per face).
std::vector<Quadric> FaceQuadrics(const std::vector<Eigen::Vector3d>& pos,
                                  const std::vector<std::array<uint32_t, 3>>& faces, bool area_weighted) {
  std::vector<Quadric> q(pos.size());
  for (const auto& t : faces) {
    const Eigen::Vector3d n2 = (pos[t[1]] - pos[t[0]]).cross(pos[t[2]] - pos[t[0]]);
    const double len = n2.norm();
    if (!(len > 0)) continue;
    const Eigen::Vector3d n = n2 / len;
    const double d = -n.dot(pos[t[0]]);
    const double w = area_weighted ? 0.5 * len : 1.0;
    for (uint32_t v : t) q[v].AddPlane(n, d, w);
  }
  return q;
}

// Vertices on an edge used by exactly one face (a border or a tile cut) or by more than two.
std::vector<char> BorderVertices(size_t n, const std::vector<std::array<uint32_t, 3>>& faces) {
  // Neighbour lists (with repeats: once per face) in one array.
  std::vector<uint32_t> start(n + 1, 0);
  for (const auto& t : faces) {
    for (uint32_t v : t) start[v + 1] += 2;
  }
  for (size_t v = 0; v < n; ++v) start[v + 1] += start[v];
  std::vector<uint32_t> nb(start.back());
  {
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (const auto& t : faces) {
      for (int k = 0; k < 3; ++k) {
        nb[fill[t[k]]++] = t[(k + 1) % 3];
        nb[fill[t[k]]++] = t[(k + 2) % 3];
      }
    }
  }
  std::vector<char> locked(n, 0);
  for (size_t v = 0; v < n; ++v) {
    const auto begin = nb.begin() + start[v], end = nb.begin() + start[v + 1];
    std::sort(begin, end);
    for (auto i = begin; i != end;) {
      auto j = i;
      while (j != end && *j == *i) ++j;
      if (j - i != 2) {
        locked[v] = 1;
        break;
      }
      i = j;
    }
  }
  return locked;
}

// Result of one simplification, in global vertex ids.
struct Piece {
  std::vector<uint32_t> vertices;  // global ids of the surviving vertices used by faces
  std::vector<Eigen::Vector3d> positions;
  std::vector<Quadric> quadrics;
  std::vector<double> goals2;                  // with error goals: each survivor's squared goal
  std::vector<std::array<uint32_t, 3>> faces;  // global ids
};

// Simplifies the faces `faces` (global ids) of a mesh whose positions are `positions`, with
// per-vertex quadrics either computed from these faces (tiles) or given (`quadrics`, the merge).
// keep_ratio >= 0 (tiles): the target comes from the ratio instead of target_faces. goals2: the
// squared error goal of every global vertex, or empty (a face budget only).
Piece Simplify(const std::vector<Eigen::Vector3d>& positions, const std::vector<Quadric>* quadrics,
               const std::vector<std::array<uint32_t, 3>>& faces, int64_t target_faces, double keep_ratio,
               const std::vector<double>& goals2, const QemOptions& options, std::vector<uint32_t>& scratch) {
  std::vector<uint32_t> global;
  global.reserve(faces.size() / 2 + 16);
  for (const auto& t : faces) global.insert(global.end(), t.begin(), t.end());
  std::sort(global.begin(), global.end());
  global.erase(std::unique(global.begin(), global.end()), global.end());
  std::vector<Eigen::Vector3d> local_pos(global.size());
  for (size_t k = 0; k < global.size(); ++k) {
    scratch[global[k]] = static_cast<uint32_t>(k);
    local_pos[k] = positions[global[k]];
  }
  std::vector<std::array<uint32_t, 3>> local_faces(faces.size());
  for (size_t f = 0; f < faces.size(); ++f) {
    for (int k = 0; k < 3; ++k) local_faces[f][k] = scratch[faces[f][k]];
  }
  std::vector<Quadric> local_q;
  if (quadrics) {
    local_q.resize(global.size());
    for (size_t k = 0; k < global.size(); ++k) local_q[k] = (*quadrics)[global[k]];
  } else {
    local_q = FaceQuadrics(local_pos, local_faces, options.area_weighted);
  }
  std::vector<char> locked = BorderVertices(global.size(), local_faces);
  std::vector<double> local_goal2;
  if (!goals2.empty()) {
    local_goal2.resize(global.size());
    for (size_t k = 0; k < global.size(); ++k) local_goal2[k] = goals2[global[k]];
  }
  if (keep_ratio >= 0 && !goals2.empty()) {
    target_faces = 0;  // error goals only
  } else if (keep_ratio >= 0) {
    // A tile: its faces that touch a locked (cut) vertex stay for the pass over the whole, which
    // simplifies them with the cheapest collapses anywhere; the others are kept in proportion.
    int64_t touching = 0;
    for (const auto& t : local_faces) touching += (locked[t[0]] || locked[t[1]] || locked[t[2]]) ? 1 : 0;
    target_faces =
        touching + static_cast<int64_t>(std::llround(
                       keep_ratio * static_cast<double>(static_cast<int64_t>(local_faces.size()) - touching)));
  }
  QemSimplifier simplifier(std::move(local_pos), std::move(local_faces), std::move(local_q), std::move(locked),
                           std::move(local_goal2), options);
  simplifier.Run(target_faces);
  Piece piece;
  piece.faces = simplifier.AliveFaces();
  std::vector<char> used(global.size(), 0);
  for (auto& t : piece.faces) {
    for (uint32_t& v : t) {
      used[v] = 1;
      v = global[v];
    }
  }
  for (size_t k = 0; k < global.size(); ++k) {
    if (!used[k]) continue;
    piece.vertices.push_back(global[k]);
    piece.positions.push_back(simplifier.positions()[k]);
    piece.quadrics.push_back(simplifier.quadrics()[k]);
    if (!goals2.empty()) piece.goals2.push_back(simplifier.goals2()[k]);
  }
  return piece;
}

// Splits the tiles' merged faces into those within `rings` rings of a cut vertex (one in the faces of
// two or more tiles) and the rest, each in the tiles' order.
void SplitCutBand(const std::vector<Piece>& pieces, size_t n, int rings, std::vector<std::array<uint32_t, 3>>* band,
                  std::vector<std::array<uint32_t, 3>>* rest) {
  constexpr uint32_t kNoTile = 0xffffffffu;
  std::vector<uint32_t> tile_of(n, kNoTile);
  std::vector<char> near(n, 0);  // a cut vertex, then a vertex of a band face
  for (uint32_t p = 0; p < pieces.size(); ++p) {
    for (const auto& t : pieces[p].faces) {
      for (uint32_t v : t) {
        if (tile_of[v] == kNoTile) {
          tile_of[v] = p;
        } else if (tile_of[v] != p) {
          near[v] = 1;
        }
      }
    }
  }
  std::vector<const std::array<uint32_t, 3>*> faces;
  for (const Piece& piece : pieces) {
    for (const auto& t : piece.faces) faces.push_back(&t);
  }
  std::vector<char> in_band(faces.size(), 0);
  for (int ring = 0; ring < rings; ++ring) {
    std::vector<size_t> added;
    for (size_t f = 0; f < faces.size(); ++f) {
      const auto& t = *faces[f];
      if (!in_band[f] && (near[t[0]] || near[t[1]] || near[t[2]])) added.push_back(f);
    }
    for (size_t f : added) {
      in_band[f] = 1;
      for (uint32_t v : *faces[f]) near[v] = 1;
    }
  }
  for (size_t f = 0; f < faces.size(); ++f) (in_band[f] ? band : rest)->push_back(*faces[f]);
}

}  // namespace

TriangleMesh DecimateQemTiled(const TriangleMesh& mesh, int64_t target_faces, int partitions, const QemOptions& options,
                              const std::vector<double>* goal_error_m) {
  const size_t n = mesh.num_vertices();
  std::vector<double> goals2;  // squared, per vertex (empty: a face budget only)
  if (goal_error_m) {
    goals2.resize(n);
    for (size_t i = 0; i < n; ++i) goals2[i] = (*goal_error_m)[i] > 0 ? (*goal_error_m)[i] * (*goal_error_m)[i] : 0.0;
    target_faces = 0;
  }
  // Work relative to the bounding-box centre (better conditioned quadrics).
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  for (const auto& v : mesh.vertices_m) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const Eigen::Vector3d center = n > 0 ? Eigen::Vector3d(0.5 * (lo + hi)) : Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> positions(n);
  for (size_t i = 0; i < n; ++i) positions[i] = mesh.vertices_m[i] - center;
  std::vector<std::array<uint32_t, 3>> valid;
  valid.reserve(mesh.num_faces());
  for (const auto& f : mesh.faces) {
    if (f[0] != f[1] && f[1] != f[2] && f[0] != f[2]) valid.push_back(f);
  }

  // Tiles on a grid over the xy bounding box of the face centroids (fixed by the geometry).
  const int grid = std::max(1, static_cast<int>(std::lround(std::sqrt(std::max(1, partitions)))));
  Eigen::Vector2d clo(INFINITY, INFINITY), chi(-INFINITY, -INFINITY);
  std::vector<Eigen::Vector2d> centroids(valid.size());
  for (size_t f = 0; f < valid.size(); ++f) {
    const auto& t = valid[f];
    centroids[f] = ((positions[t[0]] + positions[t[1]] + positions[t[2]]) / 3.0).head<2>();
    clo = clo.cwiseMin(centroids[f]);
    chi = chi.cwiseMax(centroids[f]);
  }
  const Eigen::Vector2d extent = (chi - clo).cwiseMax(Eigen::Vector2d(1e-9, 1e-9));
  std::vector<std::vector<std::array<uint32_t, 3>>> tiles(static_cast<size_t>(grid) * grid);
  for (size_t f = 0; f < valid.size(); ++f) {
    const int ix = std::min(grid - 1, static_cast<int>((centroids[f].x() - clo.x()) / extent.x() * grid));
    const int iy = std::min(grid - 1, static_cast<int>((centroids[f].y() - clo.y()) / extent.y() * grid));
    tiles[static_cast<size_t>(iy) * grid + ix].push_back(valid[f]);
  }
  double keep_ratio = static_cast<double>(target_faces) / std::max<size_t>(1, valid.size());
  std::vector<Piece> pieces(tiles.size());
  if (tiles.size() > 1) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
      std::vector<uint32_t> scratch(n);
      for (size_t t = range.begin(); t != range.end(); ++t) {
        if (tiles[t].empty()) continue;
        pieces[t] = Simplify(positions, nullptr, tiles[t], 0, keep_ratio, goals2, options, scratch);
      }
    });
  }
  // Merge: positions of the survivors, quadrics summed over the tiles (a cut vertex belongs to
  // several; each tile's quadric holds its own faces and what collapsed into it there).
  std::vector<std::array<uint32_t, 3>> merged;
  std::vector<Quadric> quadrics;
  if (tiles.size() > 1) {
    quadrics.assign(n, Quadric{});
    for (const Piece& piece : pieces) {
      for (size_t k = 0; k < piece.vertices.size(); ++k) {
        positions[piece.vertices[k]] = piece.positions[k];
        quadrics[piece.vertices[k]] += piece.quadrics[k];
        // A cut vertex is in several tiles: the smallest goal of what merged into it in any of them.
        if (!goals2.empty()) goals2[piece.vertices[k]] = std::min(goals2[piece.vertices[k]], piece.goals2[k]);
      }
      merged.insert(merged.end(), piece.faces.begin(), piece.faces.end());
    }
    // With error goals the band's width follows the share of the faces the tiles kept.
    if (!goals2.empty()) keep_ratio = static_cast<double>(merged.size()) / std::max<size_t>(1, valid.size());
  } else {
    merged = std::move(valid);
  }
  // The last pass: over the band around the cuts, where the tiles kept every face; the faces outside it
  // are already at the tiles' ratio and stay as they are.
  std::vector<std::array<uint32_t, 3>> outside;
  if (tiles.size() > 1 && options.final_band_rings > 0) {
    std::vector<std::array<uint32_t, 3>> band;
    const int rings = static_cast<int>(std::ceil(options.final_band_rings / std::sqrt(std::max(keep_ratio, 1e-4))));
    SplitCutBand(pieces, n, rings, &band, &outside);
    if (!goals2.empty()) {
      merged = std::move(band);  // the faces outside met their goals in the tiles
    } else if (target_faces > static_cast<int64_t>(outside.size())) {
      merged = std::move(band);
      target_faces -= static_cast<int64_t>(outside.size());
    } else {
      outside.clear();  // the band alone cannot meet the target: every face takes part
    }
  }
  std::vector<uint32_t> scratch(n);
  Piece final_piece =
      Simplify(positions, tiles.size() > 1 ? &quadrics : nullptr, merged, target_faces, -1.0, goals2, options, scratch);
  for (size_t k = 0; k < final_piece.vertices.size(); ++k)
    positions[final_piece.vertices[k]] = final_piece.positions[k];
  final_piece.faces.insert(final_piece.faces.begin(), outside.begin(), outside.end());

  // The surviving vertices in their input order, then the faces.
  TriangleMesh out;
  std::vector<uint32_t>& remap = scratch;
  std::vector<char> used(n, 0);
  for (const auto& t : final_piece.faces) {
    for (uint32_t v : t) used[v] = 1;
  }
  for (uint32_t g = 0; g < n; ++g) {
    if (!used[g]) continue;
    remap[g] = static_cast<uint32_t>(out.vertices_m.size());
    // A vertex that never moved keeps its input coordinates exactly ((v − c) + c need not be v).
    const bool moved = positions[g] != Eigen::Vector3d(mesh.vertices_m[g] - center);
    out.vertices_m.push_back(moved ? Eigen::Vector3d(positions[g] + center) : mesh.vertices_m[g]);
    if (mesh.has_colors()) out.colors_rgb.push_back(mesh.colors_rgb[g]);
  }
  out.faces.reserve(final_piece.faces.size());
  for (const auto& t : final_piece.faces) out.faces.push_back({remap[t[0]], remap[t[1]], remap[t[2]]});
  return out;
}

}  // namespace cinepath::photogrammetry::internal
