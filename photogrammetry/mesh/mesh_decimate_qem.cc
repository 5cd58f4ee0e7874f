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
#include <atomic>
#include <cmath>
#include <cstring>
#include <functional>
#include <memory>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <Eigen/Dense>

#include "photogrammetry/mesh/closest_on_triangle.h"
#include "photogrammetry/mesh/kth_smallest.h"
#include "photogrammetry/mesh/mesh_decimate.h"
#include "photogrammetry/mesh/qem_placement.h"
#include "photogrammetry/mesh/quaternary_heap.h"

namespace cinepath::photogrammetry::internal {
namespace {

// The squared distance from p to the triangle (a, b, c) (C. Ericson, "Real-Time Collision Detection",
// 5.1.5: the closest point by the Voronoi regions of the vertices, edges and face).
// With its edges ab = b − a and ac = c − a given (a fan's faces are measured many times).
__attribute__((always_inline)) inline double SquaredDistanceToTriangle(
    const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
    const Eigen::Vector3d& ab, const Eigen::Vector3d& ac) {
  const Eigen::Vector3d ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.squaredNorm();
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bp.squaredNorm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (ap - d1 / (d1 - d3) * ab).squaredNorm();
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return cp.squaredNorm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (ap - d2 / (d2 - d6) * ac).squaredNorm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    return (bp - (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b)).squaredNorm();
  }
  const double denom = 1 / (va + vb + vc);
  return (ap - vb * denom * ab - vc * denom * ac).squaredNorm();
}

double SquaredDistanceToTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                 const Eigen::Vector3d& c) {
  return SquaredDistanceToTriangle(p, a, b, c, b - a, c - a);
}

struct HeapEntry {
  float cost;
  uint32_t a, b;
  uint32_t stamps;       // stamp[a] + stamp[b] when pushed: stamps only grow, so any change shows
  uint32_t checked = 0;  // the cost already holds the removed vertices' distance to the new faces
};

// A HeapEntry packed into one 128-bit key whose order is the queue's: the cheapest first, ties by the
// edge's ends, then by the ends' stamps (a strict total order, so every exact priority queue pops the
// same sequence; the binary heap used before ordered by the first three alone, and the pops that
// differed were of the same edge, of which at most one is not stale: the same collapses either way).
// A cost is never negative (Pack maps −0 and NaN to 0), so its bits order as an unsigned integer; a
// stamp sum is below a piece's vertex count, which leaves the key's lowest bit to `checked`. Keys
// compare without branches, which is where the binary heap of structs lost its time (mispredicted
// comparisons while sifting down: 88 % of the pops are stale entries); four children fill a cache line.
using CollapseKey = unsigned __int128;

CollapseKey Pack(const HeapEntry& e) {
  const float cost = e.cost > 0 ? e.cost : 0.0f;
  uint32_t cost_bits;
  std::memcpy(&cost_bits, &cost, sizeof cost_bits);
  const uint64_t hi = (static_cast<uint64_t>(cost_bits) << 32) | e.a;
  const uint64_t lo = (static_cast<uint64_t>(e.b) << 32) | (static_cast<uint64_t>(e.stamps) << 1) | (e.checked & 1);
  return (static_cast<CollapseKey>(hi) << 64) | lo;
}

HeapEntry Unpack(CollapseKey key) {
  const auto hi = static_cast<uint64_t>(key >> 64), lo = static_cast<uint64_t>(key);
  HeapEntry e;
  const auto cost_bits = static_cast<uint32_t>(hi >> 32);
  std::memcpy(&e.cost, &cost_bits, sizeof e.cost);
  e.a = static_cast<uint32_t>(hi);
  e.b = static_cast<uint32_t>(lo >> 32);
  e.stamps = static_cast<uint32_t>(lo) >> 1;
  e.checked = static_cast<uint32_t>(lo) & 1;
  return e;
}

using CollapseQueue = QuaternaryHeap<CollapseKey, std::less<CollapseKey>>;

// One mesh (a tile, or the merged tiles) with local indices, simplified in place. With `goal2` (one
// squared error goal per vertex; empty: a face budget only) a collapse is made only while its error,
// the root of its quadric's weighted mean (its point's mean squared distance to the planes merged into
// the edge, by area), is within the smaller goal of its two vertices, and the vertex kept takes that
// goal. A vertex whose goal is 0 is never touched. `locked` must hold every vertex of an edge with
// one face or more than two (BorderVertices): such edges are never costed.
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
    merged_into_.resize(n);
    for (uint32_t v = 0; v < n; ++v) merged_into_[v] = v;
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

  // Costs every edge's collapse (done by Run when not called before).
  void BuildHeap() {
    heap_.clear();
    heap_.reserve(faces_.size() * 3 / 2 + 16);
    // Each interior edge is seen twice, once as a < b. An edge seen once (on the border) has both
    // ends locked, and PushAll skips it either way. Priced in batches, pushed in the faces' order.
    const auto push = [&](const HeapEntry& e) { heap_.PushUnordered(Pack(e)); };
    edges_.clear();
    for (const auto& f : faces_) {
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = f[k], b = f[(k + 1) % 3];
        if (a < b) edges_.push_back({a, b});
      }
      if (edges_.size() >= kPriceBatch) {
        PushAll(edges_, push);
        edges_.clear();
      }
    }
    PushAll(edges_, push);
    heap_.Heapify();
    heap_built_ = true;
  }

  // Calls visit(cost) for each collapse waiting in the heap (after BuildHeap: one per edge that may
  // collapse), in no particular order.
  template <typename F>
  void ForQueuedCosts(F&& visit) const {
    for (const CollapseKey key : heap_.items()) visit(Unpack(key).cost);
  }

  void Run(int64_t target_faces) {
    if (!heap_built_) BuildHeap();
    while (faces_alive_ > target_faces && !heap_.empty()) {
      const HeapEntry e = Unpack(heap_.Pop());
      if (Stale(e)) continue;
      double checked_cost = -1;
      const uint32_t kept = TryCollapse(e, &checked_cost);
      if (checked_cost >= 0) {  // costlier than it was queued at: back in the heap at its true cost
        heap_.Push(Pack({static_cast<float>(checked_cost), e.a, e.b, e.stamps, 1}));
        continue;
      }
      if (kept == kNone) continue;
      edges_.clear();
      ForNeighbours(kept, [&](uint32_t w) { edges_.push_back({std::min(kept, w), std::max(kept, w)}); });
      PushAll(edges_, [&](const HeapEntry& f) { heap_.Push(Pack(f)); });
    }
  }

  // An entry made stale by a later collapse at either end (stamps only grow: it stays stale).
  bool Stale(const HeapEntry& e) const {
    return !vertex_alive_[e.a] || !vertex_alive_[e.b] || stamp_[e.a] + stamp_[e.b] != e.stamps;
  }

  int64_t faces_alive() const { return faces_alive_; }
  // Faces with a locked corner (at the start: the faces along the piece's cuts and borders).
  int64_t FacesTouchingLocked() const {
    int64_t count = 0;
    for (const auto& t : faces_) count += (locked_[t[0]] || locked_[t[1]] || locked_[t[2]]) ? 1 : 0;
    return count;
  }

  const std::vector<Eigen::Vector3d>& positions() const { return pos_; }
  std::vector<Quadric> TakeQuadrics() { return std::move(quadric_); }
  const std::vector<double>& goals2() const { return goal2_; }
  const std::vector<char>& vertex_alive() const { return vertex_alive_; }
  // Each removed vertex's: the vertex it collapsed into (itself while alive).
  const std::vector<uint32_t>& merged_into() const { return merged_into_; }
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

  // Costs the collapses of `edges` (a < b) and hands them to `add` in their order (nothing for those that
  // may not collapse). The optimal placements go four at a time through PlaceFullRank4, what it leaves
  // four at a time through PlaceAny4, what that leaves (and the collapses onto a locked end) through
  // PlaceAndCost: the same costs, bit for bit (qem_placement.h).
  template <typename Add>
  void PushAll(const std::vector<std::array<uint32_t, 2>>& edges, Add&& add) {
    costs_.resize(edges.size());
    left_.clear();
    // Prices the edges at[0 .. filled) with `place`; the lanes it leaves go to `leave`.
    const auto place_lanes = [&](auto place, const std::array<size_t, 4>& at, int filled, auto leave) {
      Lanes4 lanes;
      for (int k = 0; k < 4; ++k) {  // a short batch repeats its first lane
        const auto [a, b] = edges[at[k < filled ? k : 0]];
        lanes.qa[k] = &quadric_[a], lanes.qb[k] = &quadric_[b], lanes.a[k] = &pos_[a], lanes.b[k] = &pos_[b];
      }
      std::array<double, 4> error;
      const int done = place(lanes, options_.placement_reach, options_.placement_rcond, error, wide_);
      for (int k = 0; k < filled; ++k) {
        if (done >> k & 1) {
          costs_[at[k]] = std::max(0.0, error[k]);
        } else {
          leave(at[k]);
        }
      }
    };
    const auto scalar = [&](size_t i) {
      Eigen::Vector3d p;
      costs_[i] = PlaceAndCost(edges[i][0], edges[i][1], &p);
    };
    std::array<size_t, 4> at{};
    int filled = 0;
    for (size_t i = 0; i < edges.size(); ++i) {
      const auto [a, b] = edges[i];
      if (locked_[a] && locked_[b]) continue;
      if (!options_.optimal_placement || locked_[a] || locked_[b]) {
        scalar(i);
        continue;
      }
      at[filled++] = i;
      if (filled == 4) {
        place_lanes(PlaceFullRank4, at, filled, [&](size_t j) { left_.push_back(j); });
        filled = 0;
      }
    }
    if (filled > 0) place_lanes(PlaceFullRank4, at, filled, [&](size_t j) { left_.push_back(j); });
    for (size_t k = 0; k < left_.size(); k += 4) {
      filled = static_cast<int>(std::min<size_t>(4, left_.size() - k));
      for (int j = 0; j < filled; ++j) at[j] = left_[k + j];
      place_lanes(PlaceAny4, at, filled, scalar);
    }
    for (size_t i = 0; i < edges.size(); ++i) {
      const auto [a, b] = edges[i];
      if (!(locked_[a] && locked_[b])) PushCosted(a, b, costs_[i], add);
    }
  }

  // Hands the collapse of (a, b) at `cost` (PlaceAndCost's) to `add`: as it is with a face budget, as a
  // share of the goal with error goals (nothing beyond the goal).
  template <typename Add>
  void PushCosted(uint32_t a, uint32_t b, double cost, Add&& add) {
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
    add(HeapEntry{static_cast<float>(cost), a, b, stamp_[a] + stamp_[b]});
  }

  double PlaceAndCost(uint32_t a, uint32_t b, Eigen::Vector3d* p) const {
    const Quadric q = Sum(quadric_[a], quadric_[b]);
    if (options_.optimal_placement && !locked_[a] && !locked_[b]) {
      const Placed placed = Placement(q, pos_[a], pos_[b], options_.placement_reach, options_.placement_rcond);
      *p = placed.point;
      return std::max(0.0, placed.error);
    }
    if (locked_[a]) {
      *p = pos_[a];
    } else if (locked_[b]) {
      *p = pos_[b];
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

  // The largest squared distance from the points the collapse of (keep, gone) to p takes off the surface
  // to the faces around keep and gone after it (the two faces of the edge gone): the two vertices, and
  // with `midpoints` the midpoints of their edges (an input face whose corners stay on the surface can
  // still leave it in between, where the new faces cut across its edges). With `new_edges` also the
  // other way: the midpoints of the new edges (from p to the two vertices' neighbours) to the faces
  // before the collapse (a new face whose corners lie on the surface can still stand off it in between,
  // as a sliver across a crease does). `opposite`: the two vertices both are joined to. A point's search
  // stops once it is nearer than the largest so far (which leaves the maximum exact), and starts with
  // the faces at the edge's far end, usually the nearest. With `floor2` > 0 only a largest above it is
  // exact (the result is floor2 when every point is within it): a point's search stops at the first face
  // within floor2, which is most of a collapse that passes the check.
  double FanSquaredDistance(uint32_t keep, uint32_t gone, const uint32_t (&opposite)[2], const Eigen::Vector3d& p,
                            bool midpoints, bool new_edges, double floor2) {
    fan_.clear();
    old_fan_.clear();
    const auto gather = [&](uint32_t f, bool around_gone) {
      const auto& t = faces_[f];
      const bool shared = Contains(t, keep) && Contains(t, gone);
      // The faces before: each once (a shared face is around both ends).
      if (new_edges && !(shared && around_gone)) old_fan_.push_back(MakeFanFace(pos_[t[0]], pos_[t[1]], pos_[t[2]], t));
      if (shared) return;
      const auto at = [&](uint32_t v) -> const Eigen::Vector3d& { return v == keep || v == gone ? p : pos_[v]; };
      fan_.push_back(MakeFanFace(at(t[0]), at(t[1]), at(t[2]), t));
    };
    ForFaces(keep, [&](uint32_t f) { gather(f, false); });
    ForFaces(gone, [&](uint32_t f) { gather(f, true); });
    double worst = floor2;
    // Measures x against `faces`, those with corner `first` (kNone: none) first.
    const auto measure = [&](const std::vector<FanFace>& faces, const Eigen::Vector3d& x, uint32_t first) {
      double best = INFINITY;
      for (int pass = 0; pass < 2; ++pass) {
        for (const FanFace& f : faces) {
          if (Contains(f.v, first) != (pass == 0)) continue;
          best = std::min(best, SquaredDistanceToTriangle(x, f.p[0], f.p[1], f.p[2], f.ab, f.ac));
          if (best <= worst) return;
        }
      }
      worst = best;
    };
    measure(fan_, pos_[gone], gone);  // first the faces that were gone's (their ids still name it)
    measure(fan_, pos_[keep], keep);
    if (!midpoints && !new_edges) return worst;
    for (const uint32_t v : {gone, keep}) {
      ForNeighbours(v, [&](uint32_t w) {
        if (v == keep && w == gone) return;  // the edge itself, measured from gone
        if (midpoints) measure(fan_, 0.5 * (pos_[v] + pos_[w]), w);
        // The new edges: to gone's neighbours, then to keep's others (the opposite two once).
        if (new_edges && w != keep && !(v == keep && (w == opposite[0] || w == opposite[1]))) {
          measure(old_fan_, 0.5 * (p + pos_[w]), w);
        }
      });
    }
    return worst;
  }

  // Collapses edge (a, b) if it is an interior, manifold edge whose collapse keeps the mesh a
  // manifold (the link condition) and folds no face. Returns the vertex kept, or kNone.
  uint32_t TryCollapse(const HeapEntry& e, double* checked_cost) {
    const uint32_t a = e.a, b = e.b;
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
    if (options_.distance_check > 0 && goal2_.empty() && !e.checked) {
      // Hausdorff is a maximum: the quadric's cost is a mean over its planes, and a collapse can leave
      // one of its own vertices farther from the new faces than that mean says.
      const double scale = options_.distance_check * (quadric_[a].Weight() + quadric_[b].Weight());
      // The distances that cannot fail the check need not be exact: those within `floor2`, a little
      // under the cost's share (and kept to where the comparison below still passes, to rounding).
      double floor2 = (1 - 1e-6) * static_cast<double>(e.cost) / scale;
      if (!(floor2 > 0) || !std::isfinite(floor2) || static_cast<float>(scale * floor2) > e.cost) floor2 = 0;
      const double d2 = FanSquaredDistance(keep, gone, opposite, p, options_.distance_check_midpoints,
                                           options_.distance_check_new_edges, floor2);
      const double fan_cost = scale * d2;
      if (static_cast<float>(fan_cost) > e.cost) {
        *checked_cost = fan_cost;
        return kNone;
      }
    }
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
    merged_into_[gone] = keep;
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
  std::vector<uint32_t> merged_into_;
  std::vector<uint32_t> stamp_, mark_;
  uint32_t epoch_ = 0;
  std::vector<uint32_t> head_, next_;
  int64_t faces_alive_ = 0;
  CollapseQueue heap_;
  bool heap_built_ = false;
  struct FanFace {
    std::array<Eigen::Vector3d, 3> p;
    Eigen::Vector3d ab, ac;  // p[1] − p[0], p[2] − p[0]
    std::array<uint32_t, 3> v;
  };
  static FanFace MakeFanFace(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                             const std::array<uint32_t, 3>& v) {
    return {{a, b, c}, b - a, c - a, v};
  }
  std::vector<FanFace> fan_, old_fan_;  // FanSquaredDistance's scratch: the faces after and before
  static constexpr size_t kPriceBatch = 256;
  std::vector<std::array<uint32_t, 2>> edges_;  // PushAll's edges, and their costs
  std::vector<double> costs_;
  std::vector<size_t> left_;  // the edges PlaceFullRank4 left
  bool wide_ = CpuHasAvx2();
};

// Plane quadric of each of the first face_count faces added to its three corners, weighted by the face's
// area plus `area_floor` × the median area of those faces (or one per face).
std::vector<Quadric> FaceQuadrics(const std::vector<Eigen::Vector3d>& pos,
                                  const std::vector<std::array<uint32_t, 3>>& faces, size_t face_count,
                                  bool area_weighted, double area_floor) {
  std::vector<Quadric> q(pos.size());
  // Each face's unit normal and offset, and the length of its cross product (twice its area).
  struct Plane {
    Eigen::Vector3d n;
    double d, len;
  };
  std::vector<Plane> planes(face_count);
  for (size_t f = 0; f < face_count; ++f) {
    const auto& t = faces[f];
    const Eigen::Vector3d n2 = (pos[t[1]] - pos[t[0]]).cross(pos[t[2]] - pos[t[0]]);
    const double len = n2.norm();
    planes[f].len = len;
    if (!(len > 0)) continue;  // no plane (area 0 or not a number)
    planes[f].n = n2 / len;
    planes[f].d = -planes[f].n.dot(pos[t[0]]);
  }
  double floor_m2 = 0;
  if (area_weighted && area_floor > 0 && face_count > 0) {
    std::vector<double> sorted(face_count);
    for (size_t f = 0; f < face_count; ++f) sorted[f] = 0.5 * planes[f].len;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(face_count / 2), sorted.end());
    floor_m2 = area_floor * sorted[face_count / 2];
  }
  for (size_t f = 0; f < face_count; ++f) {
    if (!(planes[f].len > 0)) continue;
    const double w = area_weighted ? 0.5 * planes[f].len + floor_m2 : 1.0;
    Quadric plane;
    plane.AddPlane(planes[f].n, planes[f].d, w);
    for (uint32_t v : faces[f]) q[v] += plane;
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
  // v is interior when each neighbour appears exactly twice in its list: counted in `count` (indexed
  // by neighbour), then checked and reset at its first appearance (at its second the count is 0).
  std::vector<char> locked(n, 0);
  std::vector<uint32_t> count(n, 0);
  for (size_t v = 0; v < n; ++v) {
    for (uint32_t k = start[v]; k < start[v + 1]; ++k) ++count[nb[k]];
    bool two_each = true;
    for (uint32_t k = start[v]; k < start[v + 1]; ++k) {
      const uint32_t w = nb[k];
      two_each = two_each && (count[w] == 2 || count[w] == 0);
      count[w] = 0;
    }
    locked[v] = two_each ? 0 : 1;
  }
  return locked;
}

constexpr uint32_t kUnmapped = 0xffffffffu;
// Blocks of this many items for the parallel passes over a mesh's vertices or faces.
constexpr size_t kBlock = size_t{1} << 16;

// Splits `items` into `bins` lists by bin_of(item) (kUnmapped: dropped), each list in the items'
// order, the same on any thread count: each block of items counts its share of every bin, the counts'
// running sums say where each block writes, and the blocks fill their places in parallel.
template <typename T, typename BinOf>
std::vector<std::vector<T>> ScatterInOrder(const std::vector<T>& items, size_t bins, BinOf bin_of) {
  const size_t blocks = (items.size() + kBlock - 1) / kBlock;
  std::vector<uint32_t> bin(items.size());
  std::vector<size_t> at(blocks * bins, 0);  // block b's count in bin i, then where it starts writing
  tbb::parallel_for(tbb::blocked_range<size_t>(0, blocks, 1), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t b = range.begin(); b != range.end(); ++b) {
      for (size_t k = b * kBlock; k < std::min(items.size(), (b + 1) * kBlock); ++k) {
        bin[k] = bin_of(items[k]);
        if (bin[k] != kUnmapped) ++at[b * bins + bin[k]];
      }
    }
  });
  std::vector<std::vector<T>> out(bins);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, bins, 1), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t i = range.begin(); i != range.end(); ++i) {
      size_t size = 0;
      for (size_t b = 0; b < blocks; ++b) {
        const size_t count = at[b * bins + i];
        at[b * bins + i] = size;
        size += count;
      }
      out[i].resize(size);
    }
  });
  tbb::parallel_for(tbb::blocked_range<size_t>(0, blocks, 1), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t b = range.begin(); b != range.end(); ++b) {
      for (size_t k = b * kBlock; k < std::min(items.size(), (b + 1) * kBlock); ++k) {
        if (bin[k] != kUnmapped) out[bin[k]][at[b * bins + bin[k]]++] = items[k];
      }
    }
  });
  return out;
}

// Result of one simplification, in global vertex ids.
struct Piece {
  std::vector<uint32_t> vertices;  // global ids of the surviving vertices used by faces
  std::vector<uint32_t> local;     // each one's id in `quadrics`
  std::vector<Eigen::Vector3d> positions;
  std::vector<Quadric> quadrics;               // the simplifier's own, by its vertex ids (moved, not copied)
  std::vector<double> goals2;                  // with error goals: each survivor's squared goal
  std::vector<std::array<uint32_t, 3>> faces;  // global ids
  const Quadric& quadric(size_t k) const { return quadrics[local[k]]; }
};

// The quadrics of some of a mesh's vertices: vertex v's is values[slot[v]] (kUnmapped: not held).
struct QuadricStore {
  std::vector<uint32_t> slot;
  std::vector<Quadric> values;
};

// Dense ids, in increasing order, for the vertices `faces` use (kUnmapped for the others), and how many
// (`count`): each block of vertices counts its used ones in parallel, the counts' running sums say where
// each block's ids start. The same ids on any thread count.
std::vector<uint32_t> IdsOfUsedVertices(const std::vector<std::array<uint32_t, 3>>& faces, size_t n, size_t* count) {
  std::vector<char> used(n, 0);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, faces.size(), kBlock), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t f = range.begin(); f != range.end(); ++f) {
      // Threads may mark the same vertex: the same value, stored atomically.
      for (uint32_t v : faces[f]) std::atomic_ref<char>(used[v]).store(1, std::memory_order_relaxed);
    }
  });
  const size_t blocks = (n + kBlock - 1) / kBlock;
  std::vector<size_t> block_start(blocks + 1, 0);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, blocks, 1), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t b = range.begin(); b != range.end(); ++b) {
      block_start[b + 1] =
          static_cast<size_t>(std::count(used.begin() + b * kBlock, used.begin() + std::min(n, (b + 1) * kBlock), 1));
    }
  });
  for (size_t b = 0; b < blocks; ++b) block_start[b + 1] += block_start[b];
  std::vector<uint32_t> ids(n);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, blocks, 1), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t b = range.begin(); b != range.end(); ++b) {
      auto id = static_cast<uint32_t>(block_start[b]);
      for (size_t v = b * kBlock; v < std::min(n, (b + 1) * kBlock); ++v) ids[v] = used[v] ? id++ : kUnmapped;
    }
  });
  *count = block_start[blocks];
  return ids;
}

// The quadrics of the vertices of `faces`, each summed over the pieces it survived in (a cut vertex
// belongs to several; each piece's quadric holds its own faces and what collapsed into it there).
QuadricStore SumQuadrics(const std::vector<Piece>& pieces, const std::vector<std::array<uint32_t, 3>>& faces,
                         size_t n) {
  QuadricStore store;
  size_t held = 0;
  store.slot = IdsOfUsedVertices(faces, n, &held);
  store.values.assign(held, Quadric{});
  // A vertex in one piece takes that piece's quadric (in parallel); a cut vertex, in several, their sum
  // in the pieces' order (after: the same additions as one serial pass).
  std::vector<uint8_t> in_pieces(n, 0);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, pieces.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t p = range.begin(); p != range.end(); ++p) {
      for (uint32_t v : pieces[p].vertices) {
        std::atomic_ref<uint8_t> count(in_pieces[v]);  // 0, 1 or 2 (two or more)
        uint8_t seen = count.load(std::memory_order_relaxed);
        while (seen < 2 && !count.compare_exchange_weak(seen, seen + 1, std::memory_order_relaxed)) {}
      }
    }
  });
  tbb::parallel_for(tbb::blocked_range<size_t>(0, pieces.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t p = range.begin(); p != range.end(); ++p) {
      const Piece& piece = pieces[p];
      for (size_t k = 0; k < piece.vertices.size(); ++k) {
        const uint32_t slot = store.slot[piece.vertices[k]];
        if (slot != kUnmapped && in_pieces[piece.vertices[k]] == 1) store.values[slot] += piece.quadric(k);
      }
    }
  });
  for (const Piece& piece : pieces) {
    for (size_t k = 0; k < piece.vertices.size(); ++k) {
      const uint32_t slot = store.slot[piece.vertices[k]];
      if (slot != kUnmapped && in_pieces[piece.vertices[k]] > 1) store.values[slot] += piece.quadric(k);
    }
  }
  return store;
}

// The spike pass's state: the vertices pinned (locked as the cuts are), or the collapses recorded
// (each removed vertex's parent, by global id: the vertex it merged into).
struct SpikeContext {
  const std::vector<char>* pinned = nullptr;
  std::vector<uint32_t>* parent = nullptr;
};

// One piece of the mesh (a tile, or a cell of the band) in local vertex ids, ready to simplify.
struct PieceJob {
  std::vector<uint32_t> global;  // local → global vertex id
  // The simplifier's faces are the piece's own, then `halo_faces` of its neighbours' (never changed).
  std::unique_ptr<QemSimplifier> simplifier;
  int64_t halo_faces = 0;
  int64_t touching_cuts = 0;                // faces with a corner on the piece's cuts or borders (the halo's included)
  std::vector<uint32_t>* parent = nullptr;  // when set: each removed vertex's global parent is written there
  int64_t own_faces_alive() const { return simplifier->faces_alive() - halo_faces; }
};

// For each piece, the faces of the other pieces around its cut vertices (those in the faces of two
// or more pieces), in the pieces' order. A piece simplified with its halo as fixed context sees the
// whole neighbourhood of each cut vertex in its link and fold-over checks; without it, a collapse onto
// a cut vertex can join an edge the next piece already has, and make it non-manifold.
std::vector<std::vector<std::array<uint32_t, 3>>> Halos(const std::vector<std::vector<std::array<uint32_t, 3>>>& pieces,
                                                        size_t n) {
  constexpr uint32_t kNoPiece = 0xffffffffu, kCut = 0xfffffffeu;
  // Each vertex's piece, or kCut when two or more have it: the same in any order of the pieces.
  std::vector<uint32_t> piece_of(n, kNoPiece);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, pieces.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t p = range.begin(); p != range.end(); ++p) {
      for (const auto& t : pieces[p]) {
        for (uint32_t v : t) {
          std::atomic_ref<uint32_t> of(piece_of[v]);
          uint32_t seen = of.load(std::memory_order_relaxed);
          while (seen != kCut && seen != p &&
                 !of.compare_exchange_weak(seen, seen == kNoPiece ? static_cast<uint32_t>(p) : kCut,
                                           std::memory_order_relaxed)) {}
        }
      }
    }
  });
  // The faces around each cut vertex, as (piece, face) references in one array, in any order (each
  // piece's halo sorts its own).
  std::vector<uint32_t> start(n + 1, 0);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, pieces.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t p = range.begin(); p != range.end(); ++p) {
      for (const auto& t : pieces[p]) {
        for (uint32_t v : t) {
          if (piece_of[v] == kCut) std::atomic_ref<uint32_t>(start[v + 1]).fetch_add(1, std::memory_order_relaxed);
        }
      }
    }
  });
  for (size_t v = 0; v < n; ++v) start[v + 1] += start[v];
  std::vector<std::pair<uint32_t, uint32_t>> around(start[n]);
  std::vector<uint32_t> fill(start.begin(), start.end() - 1);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, pieces.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t p = range.begin(); p != range.end(); ++p) {
      for (uint32_t f = 0; f < pieces[p].size(); ++f) {
        for (uint32_t v : pieces[p][f]) {
          if (piece_of[v] != kCut) continue;
          const uint32_t at = std::atomic_ref<uint32_t>(fill[v]).fetch_add(1, std::memory_order_relaxed);
          around[at] = {static_cast<uint32_t>(p), f};
        }
      }
    }
  });
  std::vector<std::vector<std::array<uint32_t, 3>>> halos(pieces.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, pieces.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t p = range.begin(); p != range.end(); ++p) {
      std::vector<std::pair<uint32_t, uint32_t>> refs;
      for (const auto& t : pieces[p]) {
        for (uint32_t v : t) {
          if (piece_of[v] != kCut) continue;
          for (uint32_t k = start[v]; k < start[v + 1]; ++k) {
            if (around[k].first != p) refs.push_back(around[k]);
          }
        }
      }
      std::sort(refs.begin(), refs.end());
      refs.erase(std::unique(refs.begin(), refs.end()), refs.end());
      for (const auto& [q, f] : refs) halos[p].push_back(pieces[q][f]);
    }
  });
  return halos;
}

// The faces `faces` (global ids) of a mesh whose positions are `positions`, with per-vertex quadrics
// either computed from these faces (tiles) or given (`quadrics`, the band). goals2: the squared
// error goal of every global vertex, or empty (a face budget only). The piece's border and cut
// vertices are locked. scratch: n entries, kUnmapped outside a call.
PieceJob PreparePiece(const std::vector<Eigen::Vector3d>& positions, const QuadricStore* quadrics,
                      const std::vector<std::array<uint32_t, 3>>& own_faces,
                      const std::vector<std::array<uint32_t, 3>>& halo, const std::vector<double>& goals2,
                      const QemOptions& options, std::vector<uint32_t>& scratch, const SpikeContext* spikes) {
  PieceJob job;
  job.halo_faces = static_cast<int64_t>(halo.size());
  // The simplifier's faces: the piece's own, then the halo's.
  const std::array<const std::vector<std::array<uint32_t, 3>>*, 2> lists = {&own_faces, &halo};
  const size_t face_count = own_faces.size() + halo.size();
  // The piece's vertices in increasing global order: read off a bitmap of their id range when it is
  // dense enough (a tile's ids span a few of the mesh's rows), sorted otherwise.
  std::vector<uint32_t>& global = job.global;
  global.reserve(face_count / 2 + 16);
  uint32_t lowest = kUnmapped, highest = 0;
  for (const auto* list : lists) {
    for (const auto& t : *list) {
      for (uint32_t v : t) {
        if (scratch[v] == kUnmapped) {
          scratch[v] = 0;
          global.push_back(v);
          lowest = std::min(lowest, v);
          highest = std::max(highest, v);
        }
      }
    }
  }
  if (!global.empty() && highest - lowest < 64 * static_cast<uint64_t>(global.size())) {
    std::vector<uint64_t> bits((highest - lowest) / 64 + 1, 0);
    for (uint32_t v : global) bits[(v - lowest) / 64] |= uint64_t{1} << ((v - lowest) % 64);
    global.clear();
    for (size_t w = 0; w < bits.size(); ++w) {
      for (uint64_t word = bits[w]; word != 0; word &= word - 1) {
        global.push_back(lowest + static_cast<uint32_t>(64 * w + static_cast<uint32_t>(__builtin_ctzll(word))));
      }
    }
  } else {
    std::sort(global.begin(), global.end());
  }
  std::vector<Eigen::Vector3d> local_pos(global.size());
  for (size_t k = 0; k < global.size(); ++k) {
    scratch[global[k]] = static_cast<uint32_t>(k);
    local_pos[k] = positions[global[k]];
  }
  std::vector<std::array<uint32_t, 3>> local_faces;
  local_faces.reserve(face_count);
  for (const auto* list : lists) {
    for (const auto& t : *list) local_faces.push_back({scratch[t[0]], scratch[t[1]], scratch[t[2]]});
  }
  for (uint32_t g : global) scratch[g] = kUnmapped;
  std::vector<Quadric> local_q;
  if (quadrics) {
    local_q.resize(global.size());
    for (size_t k = 0; k < global.size(); ++k) local_q[k] = quadrics->values[quadrics->slot[global[k]]];
  } else {
    // From the piece's own faces (the halo's are its neighbours' to count).
    local_q = FaceQuadrics(local_pos, local_faces, own_faces.size(), options.area_weighted, options.area_floor);
  }
  std::vector<char> locked = BorderVertices(global.size(), local_faces);
  for (size_t f = own_faces.size(); f < local_faces.size(); ++f) {
    for (uint32_t v : local_faces[f]) locked[v] = 1;
  }
  // The faces at the piece's cuts and borders, before the pinned vertices (SimplifyTiles' target).
  for (const auto& t : local_faces) job.touching_cuts += (locked[t[0]] || locked[t[1]] || locked[t[2]]) ? 1 : 0;
  if (spikes && spikes->pinned) {
    for (size_t k = 0; k < global.size(); ++k) locked[k] = locked[k] || (*spikes->pinned)[global[k]];
  }
  if (spikes) job.parent = spikes->parent;
  std::vector<double> local_goal2;
  if (!goals2.empty()) {
    local_goal2.resize(global.size());
    for (size_t k = 0; k < global.size(); ++k) local_goal2[k] = goals2[global[k]];
  }
  job.simplifier = std::make_unique<QemSimplifier>(std::move(local_pos), std::move(local_faces), std::move(local_q),
                                                   std::move(locked), std::move(local_goal2), options);
  return job;
}

// Runs the piece down to target_faces (0 with error goals: as far as they allow) and returns what
// survives, in global ids.
Piece FinishPiece(PieceJob& job, int64_t target_faces) {
  const QemSimplifier& simplifier = *job.simplifier;
  // The halo's faces never die (each has only locked corners), and come last.
  job.simplifier->Run(target_faces + job.halo_faces);
  Piece piece;
  piece.faces = simplifier.AliveFaces();
  piece.faces.resize(piece.faces.size() - static_cast<size_t>(job.halo_faces));
  std::vector<char> used(job.global.size(), 0);
  for (auto& t : piece.faces) {
    for (uint32_t& v : t) {
      used[v] = 1;
      v = job.global[v];
    }
  }
  const bool goals = !simplifier.goals2().empty();
  if (job.parent) {  // the piece's vertices are its own (a cut vertex never dies): no two pieces write one
    for (size_t k = 0; k < job.global.size(); ++k) {
      if (!simplifier.vertex_alive()[k]) (*job.parent)[job.global[k]] = job.global[simplifier.merged_into()[k]];
    }
  }
  for (size_t k = 0; k < job.global.size(); ++k) {
    if (!used[k]) continue;
    piece.vertices.push_back(job.global[k]);
    piece.local.push_back(static_cast<uint32_t>(k));
    piece.positions.push_back(simplifier.positions()[k]);
    if (goals) piece.goals2.push_back(simplifier.goals2()[k]);
  }
  piece.quadrics = job.simplifier->TakeQuadrics();
  job.simplifier.reset();
  return piece;
}

// Splits `total` into whole shares proportional to `sizes` that add up to it: the floors of the exact
// shares, then one more for the largest remainders (ties to the lower index).
std::vector<int64_t> Apportion(const std::vector<int64_t>& sizes, int64_t total) {
  int64_t sum = 0;
  for (int64_t size : sizes) sum += size;
  std::vector<int64_t> shares(sizes.size(), 0);
  if (sum <= 0) return shares;
  std::vector<std::pair<int64_t, size_t>> remainders;  // (−remainder, index): the largest first
  int64_t given = 0;
  for (size_t i = 0; i < sizes.size(); ++i) {
    // total and sizes are face counts (< 2^32), so the product fits.
    const int64_t exact = sizes[i] * total;
    shares[i] = exact / sum;
    given += shares[i];
    remainders.push_back({-(exact % sum), i});
  }
  std::sort(remainders.begin(), remainders.end());
  for (size_t k = 0; given < total && k < remainders.size(); ++k, ++given) ++shares[remainders[k].second];
  return shares;
}

// Each band cell's face target, for a band budget of `target_faces`. The collapses are shared among
// the cells as the one serial pass over the band would share them: that pass makes the cheapest
// collapses first, anywhere, up to a cost τ, so a cell's share follows its number of edges whose
// collapse costs at most τ (by the costs before any collapse). A collapse removes two faces and
// three edges (the edge itself, and two that merge into others), so τ is the cost of the (3 ×
// collapses needed)-th cheapest edge. Shares in proportion to the faces instead (as the tiles take
// theirs) leave rough cells too coarse: on the bench terrain at 10 %, 0.188 m against 0.154 m for
// the serial pass; τ at 1 × the collapses gives 0.161 m, at 2× and 3× 0.154 m (bench/RESULTS.md).
std::vector<int64_t> CellTargets(const std::vector<PieceJob>& jobs, int64_t target_faces) {
  std::vector<int64_t> sizes(jobs.size(), 0);
  int64_t band_faces = 0;
  std::vector<std::vector<float>> costs(jobs.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, jobs.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t c = range.begin(); c != range.end(); ++c) {
      if (jobs[c].simplifier) jobs[c].simplifier->ForQueuedCosts([&](float cost) { costs[c].push_back(cost); });
    }
  });
  size_t queued = 0;
  for (size_t c = 0; c < jobs.size(); ++c) {
    if (!jobs[c].simplifier) continue;
    sizes[c] = jobs[c].own_faces_alive();
    band_faces += sizes[c];
    queued += costs[c].size();
  }
  const int64_t collapses = (band_faces - std::max<int64_t>(0, target_faces) + 1) / 2;
  if (collapses <= 0 || queued == 0) return sizes;
  const size_t edges = std::min(queued, static_cast<size_t>(3 * collapses));
  const float tau = KthSmallest(costs, edges - 1);
  std::vector<int64_t> cheap(jobs.size(), 0);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, jobs.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t c = range.begin(); c != range.end(); ++c) {
      for (float cost : costs[c]) cheap[c] += cost <= tau ? 1 : 0;
    }
  });
  const std::vector<int64_t> shares = Apportion(cheap, collapses);
  std::vector<int64_t> targets(jobs.size(), 0);
  for (size_t c = 0; c < jobs.size(); ++c) targets[c] = std::max<int64_t>(0, sizes[c] - 2 * shares[c]);
  return targets;
}

// Splits the tiles' merged faces into those within `rings` rings of a cut vertex (one in the faces of
// two or more tiles) and the rest, each in the tiles' order. The rings grow in each piece on its own
// (in parallel): they reach another piece's faces only through cut vertices, which are near from the
// start, and every other vertex a piece marks is its own.
void SplitCutBand(const std::vector<Piece>& pieces, size_t n, int rings, std::vector<std::array<uint32_t, 3>>* band,
                  std::vector<std::array<uint32_t, 3>>* rest) {
  constexpr uint32_t kNoTile = 0xffffffffu;
  std::vector<uint32_t> tile_of(n, kNoTile);
  std::vector<char> near(n, 0);  // a cut vertex, then a vertex of a band face
  // A vertex is a cut vertex when a second piece finds it taken: the same marks in any order.
  tbb::parallel_for(tbb::blocked_range<size_t>(0, pieces.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t p = range.begin(); p != range.end(); ++p) {
      for (const auto& t : pieces[p].faces) {
        for (uint32_t v : t) {
          std::atomic_ref<uint32_t> tile(tile_of[v]);
          uint32_t owner = tile.load(std::memory_order_relaxed);
          if (owner == kNoTile &&
              tile.compare_exchange_strong(owner, static_cast<uint32_t>(p), std::memory_order_relaxed)) {
            continue;
          }
          if (owner != p) std::atomic_ref<char>(near[v]).store(1, std::memory_order_relaxed);
        }
      }
    }
  });
  std::vector<std::vector<char>> in_band(pieces.size());  // per piece, per face
  std::vector<size_t> band_at(pieces.size() + 1, 0), rest_at(pieces.size() + 1, 0);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, pieces.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
    std::vector<size_t> added;
    for (size_t p = range.begin(); p != range.end(); ++p) {
      const auto& faces = pieces[p].faces;
      std::vector<char>& flags = in_band[p];
      flags.assign(faces.size(), 0);
      for (int ring = 0; ring < rings; ++ring) {
        added.clear();
        for (size_t f = 0; f < faces.size(); ++f) {
          const auto& t = faces[f];
          if (!flags[f] && (near[t[0]] || near[t[1]] || near[t[2]])) added.push_back(f);
        }
        for (size_t f : added) {
          flags[f] = 1;
          for (uint32_t v : faces[f]) {
            if (!near[v]) near[v] = 1;  // a cut vertex is only read: it is near already
          }
        }
      }
      band_at[p + 1] = static_cast<size_t>(std::count(flags.begin(), flags.end(), 1));
      rest_at[p + 1] = faces.size() - band_at[p + 1];
    }
  });
  for (size_t p = 0; p < pieces.size(); ++p) {
    band_at[p + 1] += band_at[p];
    rest_at[p + 1] += rest_at[p];
  }
  const size_t band_start = band->size(), rest_start = rest->size();
  band->resize(band_start + band_at.back());
  rest->resize(rest_start + rest_at.back());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, pieces.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t p = range.begin(); p != range.end(); ++p) {
      size_t to_band = band_start + band_at[p], to_rest = rest_start + rest_at[p];
      const auto& faces = pieces[p].faces;
      for (size_t f = 0; f < faces.size(); ++f) {
        if (in_band[p][f]) {
          (*band)[to_band++] = faces[f];
        } else {
          (*rest)[to_rest++] = faces[f];
        }
      }
    }
  });
}

using Scratches = tbb::enumerable_thread_specific<std::vector<uint32_t>>;

// One tile simplified on its own, its cut vertices locked.
Piece SimplifyTile(const std::vector<Eigen::Vector3d>& positions, const std::vector<std::array<uint32_t, 3>>& tile,
                   const std::vector<double>& goals2, const QemOptions& options, double keep_ratio,
                   std::vector<uint32_t>& scratch, const SpikeContext* spikes) {
  // No halo: the tiles cut the input mesh, whose faces around a cut vertex close no short loop
  // that a collapse could turn into a doubled edge (the band cells, cut from a thinned mesh, do).
  PieceJob job = PreparePiece(positions, nullptr, tile, {}, goals2, options, scratch, spikes);
  int64_t tile_target = 0;  // with error goals: as far as they allow
  if (goals2.empty()) {
    // The faces that touch a locked (cut) vertex stay for the band pass, which simplifies them
    // with the others near the cut; the rest are kept in proportion.
    const int64_t touching = job.touching_cuts - job.halo_faces;
    const int64_t rest = static_cast<int64_t>(tile.size()) - touching;
    tile_target = touching + static_cast<int64_t>(std::llround(keep_ratio * static_cast<double>(rest)));
  }
  return FinishPiece(job, tile_target);
}

// The first pass: each tile simplified on its own (in parallel), its cut vertices locked.
std::vector<Piece> SimplifyTiles(const std::vector<Eigen::Vector3d>& positions,
                                 const std::vector<std::vector<std::array<uint32_t, 3>>>& tiles,
                                 const std::vector<double>& goals2, const QemOptions& options, double keep_ratio,
                                 Scratches& scratches, const SpikeContext* spikes) {
  std::vector<Piece> pieces(tiles.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
    std::vector<uint32_t>& scratch = scratches.local();
    for (size_t t = range.begin(); t != range.end(); ++t) {
      if (!tiles[t].empty())
        pieces[t] = SimplifyTile(positions, tiles[t], goals2, options, keep_ratio, scratch, spikes);
    }
  });
  return pieces;
}

// A cell walled in by its locked cuts could not take its share: one more pass, over the faces around the
// cells' cuts, takes the rest. Each cell started from the same quadrics, and a cut vertex's grew in each of
// its cells: add up what each cell added.
void PassAroundCellCuts(size_t n, int rings, int64_t target_faces, const std::vector<double>& goals2,
                        const QemOptions& options, std::vector<Eigen::Vector3d>& positions, QuadricStore& quadrics,
                        std::vector<uint32_t>& scratch, std::vector<Piece>& band_pieces, const SpikeContext* spikes) {
  const std::vector<Quadric> base = quadrics.values;
  for (const Piece& piece : band_pieces) {
    for (size_t k = 0; k < piece.vertices.size(); ++k) {
      const uint32_t slot = quadrics.slot[piece.vertices[k]];
      quadrics.values[slot] += piece.quadric(k);
      quadrics.values[slot] -= base[slot];
    }
  }
  std::vector<std::array<uint32_t, 3>> around_cuts, rest;
  SplitCutBand(band_pieces, n, rings, &around_cuts, &rest);
  const int64_t around_target = target_faces - static_cast<int64_t>(rest.size());
  if (around_target > 0) {
    PieceJob job = PreparePiece(positions, &quadrics, around_cuts, {}, goals2, options, scratch, spikes);
    Piece last = FinishPiece(job, around_target);
    for (size_t k = 0; k < last.vertices.size(); ++k) positions[last.vertices[k]] = last.positions[k];
    band_pieces.assign(1, Piece{});
    band_pieces[0].faces = std::move(rest);
    band_pieces[0].faces.insert(band_pieces[0].faces.end(), last.faces.begin(), last.faces.end());
  }
}

// The centre of the vertices' bounding box. Minima and maxima are the same in any order of reduction,
// so the parallel passes give the same numbers on any thread count.
Eigen::Vector3d BoundingBoxCenter(const std::vector<Eigen::Vector3d>& vertices) {
  const size_t n = vertices.size();
  using Box3 = std::pair<Eigen::Vector3d, Eigen::Vector3d>;
  const Box3 empty3(Eigen::Vector3d::Constant(INFINITY), Eigen::Vector3d::Constant(-INFINITY));
  const auto [lo, hi] = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, n, kBlock), empty3,
      [&](const tbb::blocked_range<size_t>& range, Box3 box) {
        for (size_t i = range.begin(); i != range.end(); ++i) {
          box.first = box.first.cwiseMin(vertices[i]);
          box.second = box.second.cwiseMax(vertices[i]);
        }
        return box;
      },
      [](const Box3& a, const Box3& b) { return Box3(a.first.cwiseMin(b.first), a.second.cwiseMax(b.second)); });
  return n > 0 ? Eigen::Vector3d(0.5 * (lo + hi)) : Eigen::Vector3d::Zero();
}

bool IsValidFace(const std::array<uint32_t, 3>& f) { return f[0] != f[1] && f[1] != f[2] && f[0] != f[2]; }

// The xy bounding box of the valid faces' centroids (fixed by the geometry), and how many faces are valid.
struct CentroidBox {
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(INFINITY), hi = Eigen::Vector2d::Constant(-INFINITY);
  size_t faces = 0;
};

Eigen::Vector2d CentroidXy(const std::vector<Eigen::Vector3d>& positions, const std::array<uint32_t, 3>& t) {
  return ((positions[t[0]] + positions[t[1]] + positions[t[2]]) / 3.0).head<2>();
}

CentroidBox FaceCentroidBox(const std::vector<Eigen::Vector3d>& positions,
                            const std::vector<std::array<uint32_t, 3>>& faces) {
  return tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, faces.size(), kBlock), CentroidBox{},
      [&](const tbb::blocked_range<size_t>& range, CentroidBox box) {
        for (size_t f = range.begin(); f != range.end(); ++f) {
          if (!IsValidFace(faces[f])) continue;
          ++box.faces;
          const Eigen::Vector2d c = CentroidXy(positions, faces[f]);
          box.lo = box.lo.cwiseMin(c);
          box.hi = box.hi.cwiseMax(c);
        }
        return box;
      },
      [](const CentroidBox& a, const CentroidBox& b) {
        return CentroidBox{a.lo.cwiseMin(b.lo), a.hi.cwiseMax(b.hi), a.faces + b.faces};
      });
}

// The surviving vertices (those `kept` uses) in their input order, then the faces. A vertex that never
// moved keeps its input coordinates exactly ((v − c) + c need not be v).
TriangleMesh CompactMesh(const TriangleMesh& mesh, const std::vector<std::array<uint32_t, 3>>& kept,
                         const std::vector<Eigen::Vector3d>& positions, const Eigen::Vector3d& center) {
  const size_t n = mesh.num_vertices();
  TriangleMesh out;
  size_t count = 0;
  const std::vector<uint32_t> remap = IdsOfUsedVertices(kept, n, &count);
  out.vertices_m.resize(count);
  if (mesh.has_colors()) out.colors_rgb.resize(count);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, kBlock), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t g = range.begin(); g != range.end(); ++g) {
      const uint32_t id = remap[g];
      if (id == kUnmapped) continue;
      const bool moved = positions[g] != Eigen::Vector3d(mesh.vertices_m[g] - center);
      out.vertices_m[id] = moved ? Eigen::Vector3d(positions[g] + center) : mesh.vertices_m[g];
      if (mesh.has_colors()) out.colors_rgb[id] = mesh.colors_rgb[g];
    }
  });
  out.faces.resize(kept.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, kept.size()), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t f = range.begin(); f != range.end(); ++f) {
      out.faces[f] = {remap[kept[f][0]], remap[kept[f][1]], remap[kept[f][2]]};
    }
  });
  return out;
}

// Each vertex's squared error goal (a goal at most 0 becomes 0: never touched).
std::vector<double> SquaredGoals(const std::vector<double>& goal_error_m, size_t n) {
  std::vector<double> goals2(n);
  for (size_t i = 0; i < n; ++i) goals2[i] = goal_error_m[i] > 0 ? goal_error_m[i] * goal_error_m[i] : 0.0;
  return goals2;
}

// The vertices relative to `center` (better conditioned quadrics).
std::vector<Eigen::Vector3d> CenteredPositions(const std::vector<Eigen::Vector3d>& vertices,
                                               const Eigen::Vector3d& center) {
  const size_t n = vertices.size();
  std::vector<Eigen::Vector3d> positions(n);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, kBlock), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t i = range.begin(); i != range.end(); ++i) positions[i] = vertices[i] - center;
  });
  return positions;
}

// The tiles: grid × grid cells over the xy bounding box of the valid faces' centroids (fixed by the
// geometry).
struct TileGrid {
  int grid = 1;
  Eigen::Vector2d lo, extent;
  size_t valid_faces = 0;
};

TileGrid MakeTileGrid(const std::vector<Eigen::Vector3d>& positions, const std::vector<std::array<uint32_t, 3>>& faces,
                      int partitions) {
  TileGrid tiles;
  tiles.grid = std::max(1, static_cast<int>(std::lround(std::sqrt(std::max(1, partitions)))));
  const CentroidBox centroids = FaceCentroidBox(positions, faces);
  tiles.lo = centroids.lo;
  tiles.valid_faces = centroids.faces;
  tiles.extent = (centroids.hi - tiles.lo).cwiseMax(Eigen::Vector2d(1e-9, 1e-9));
  return tiles;
}

// The tiles a side for a face budget keeping `keep_ratio` of the faces: at light budgets about
// light_budget_tile_faces faces a tile when the mesh holds at least 4 × 4 such tiles (QemOptions), at
// most the grid's own; else the grid's own.
int LightBudgetGrid(const TileGrid& grid, double keep_ratio, const QemOptions& options) {
  if (keep_ratio < options.light_budget_keep || !(options.light_budget_tile_faces > 0)) return grid.grid;
  const double tiles_at_most = static_cast<double>(grid.valid_faces) / options.light_budget_tile_faces;
  const int light_grid = static_cast<int>(std::lround(std::sqrt(tiles_at_most)));
  return light_grid >= 4 ? std::min(grid.grid, light_grid) : grid.grid;
}

// The faces of each tile, in the faces' order; faces with a repeated corner are dropped.
std::vector<std::vector<std::array<uint32_t, 3>>> FacesByTile(const TileGrid& tiles,
                                                              const std::vector<Eigen::Vector3d>& positions,
                                                              const std::vector<std::array<uint32_t, 3>>& faces) {
  const int grid = tiles.grid;
  const Eigen::Vector2d& clo = tiles.lo;
  const Eigen::Vector2d& extent = tiles.extent;
  return ScatterInOrder(faces, static_cast<size_t>(grid) * grid, [&](const std::array<uint32_t, 3>& f) {
    if (!IsValidFace(f)) return kUnmapped;
    const Eigen::Vector2d c = CentroidXy(positions, f);
    const int ix = std::min(grid - 1, static_cast<int>((c.x() - clo.x()) / extent.x() * grid));
    const int iy = std::min(grid - 1, static_cast<int>((c.y() - clo.y()) / extent.y() * grid));
    return static_cast<uint32_t>(iy * grid + ix);
  });
}

// Merge: the survivors' positions (and goals) back into the mesh's. Returns the faces the tiles kept.
size_t MergeTilePieces(const std::vector<Piece>& pieces, std::vector<Eigen::Vector3d>& positions,
                       std::vector<double>& goals2) {
  size_t tile_faces = 0;
  for (const Piece& piece : pieces) {
    for (size_t k = 0; k < piece.vertices.size(); ++k) {
      positions[piece.vertices[k]] = piece.positions[k];
      // A cut vertex is in several tiles: the smallest goal of what merged into it in any of them.
      if (!goals2.empty()) goals2[piece.vertices[k]] = std::min(goals2[piece.vertices[k]], piece.goals2[k]);
    }
    tile_faces += piece.faces.size();
  }
  return tile_faces;
}

// The last pass's faces: the band around the cuts, where the tiles kept every face, when it can meet
// the target (`target_faces` then loses the faces outside it, which are already at the tiles' ratio and
// stay as they are: `outside`); else every face the tiles kept.
std::vector<std::array<uint32_t, 3>> LastPassFaces(const std::vector<Piece>& pieces, size_t n, int rings,
                                                   const QemOptions& options, bool with_goals, int64_t& target_faces,
                                                   std::vector<std::array<uint32_t, 3>>& outside) {
  if (options.final_band_rings > 0) {
    std::vector<std::array<uint32_t, 3>> band;
    // Room for the last pass's faces too (fewer than the band's), which are appended to these.
    size_t tile_faces = 0;
    for (const Piece& piece : pieces) tile_faces += piece.faces.size();
    outside.reserve(tile_faces);
    SplitCutBand(pieces, n, rings, &band, &outside);
    if (with_goals) return band;  // the faces outside met their goals in the tiles
    if (target_faces > static_cast<int64_t>(outside.size())) {
      target_faces -= static_cast<int64_t>(outside.size());
      return band;
    }
    outside.clear();  // the band alone cannot meet the target
  }
  std::vector<std::array<uint32_t, 3>> merged;
  for (const Piece& piece : pieces) merged.insert(merged.end(), piece.faces.begin(), piece.faces.end());
  return merged;
}

// The last pass runs in parallel on the cells of a grid shifted by half a tile, k tiles wide: each
// cell holds crossings of the tiles' cuts, and its own cuts (locked, as the tiles' were) cross the
// band where the tiles had already thinned it. Cells are made large enough to keep about
// band_cell_faces faces each (of `band_out` in all), since a small cell, walled in by its locked cuts,
// is forced into costly collapses to meet its share; a band too small for four such cells is one
// piece. Returns the faces of each cell, in the faces' order.
std::vector<std::vector<std::array<uint32_t, 3>>> BandCells(const TileGrid& tiles,
                                                            const std::vector<Eigen::Vector3d>& positions,
                                                            const std::vector<std::array<uint32_t, 3>>& merged,
                                                            double band_out, const QemOptions& options) {
  const int grid = tiles.grid;
  const double wanted_cells = options.band_cell_faces > 0 ? band_out / options.band_cell_faces : 0.0;
  const int k = wanted_cells < 4 ? 2 * grid : std::max(1, static_cast<int>(std::ceil(grid / std::sqrt(wanted_cells))));
  // Cell boundaries at 0.5 + j·k tiles along each axis.
  const int per_axis = k >= 2 * grid ? 1 : static_cast<int>(std::floor((grid - 0.5) / k)) + 2;
  return ScatterInOrder(merged, static_cast<size_t>(per_axis) * per_axis, [&](const std::array<uint32_t, 3>& t) {
    const Eigen::Vector2d c = CentroidXy(positions, t);
    const auto cell = [&](int axis) {
      const double u = (c[axis] - tiles.lo[axis]) / tiles.extent[axis] * grid;  // in tiles
      return std::clamp(static_cast<int>(std::floor((u - 0.5) / k)) + 1, 0, per_axis - 1);
    };
    return static_cast<uint32_t>(cell(1) * per_axis + cell(0));
  });
}

// Each cell simplified in parallel, its cuts locked and with its halo, to its share of `target_faces`
// (with error goals: as far as they allow).
std::vector<Piece> SimplifyCells(const std::vector<std::vector<std::array<uint32_t, 3>>>& cells, size_t n,
                                 const std::vector<Eigen::Vector3d>& positions, const QuadricStore& quadrics,
                                 const std::vector<double>& goals2, const QemOptions& options, int64_t target_faces,
                                 Scratches& scratches, const SpikeContext* spikes) {
  const std::vector<std::vector<std::array<uint32_t, 3>>> halos = Halos(cells, n);
  std::vector<PieceJob> jobs(cells.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, cells.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
    std::vector<uint32_t>& cell_scratch = scratches.local();
    for (size_t c = range.begin(); c != range.end(); ++c) {
      if (cells[c].empty()) continue;
      jobs[c] = PreparePiece(positions, &quadrics, cells[c], halos[c], goals2, options, cell_scratch, spikes);
      if (goals2.empty()) jobs[c].simplifier->BuildHeap();
    }
  });
  std::vector<int64_t> cell_targets(cells.size(), 0);  // with error goals: as far as they allow
  if (goals2.empty())
    cell_targets = cells.size() == 1 ? std::vector<int64_t>{target_faces} : CellTargets(jobs, target_faces);
  std::vector<Piece> band_pieces(cells.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, cells.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t c = range.begin(); c != range.end(); ++c) {
      if (jobs[c].simplifier) band_pieces[c] = FinishPiece(jobs[c], cell_targets[c]);
    }
  });
  return band_pieces;
}

// The last pass over the band's cells (and, when the cells' cuts kept too many faces, around those
// cuts); appends the faces kept to `kept`.
void SimplifyBand(const TileGrid& tiles, const std::vector<std::array<uint32_t, 3>>& merged, size_t n, int rings,
                  double keep_ratio, int64_t target_faces, const std::vector<double>& goals2, const QemOptions& options,
                  std::vector<Eigen::Vector3d>& positions, QuadricStore& quadrics, Scratches& scratches,
                  std::vector<uint32_t>& scratch, std::vector<std::array<uint32_t, 3>>& kept,
                  const SpikeContext* spikes) {
  const double band_out =
      goals2.empty() ? static_cast<double>(target_faces) : keep_ratio * static_cast<double>(merged.size());
  const std::vector<std::vector<std::array<uint32_t, 3>>> cells =
      BandCells(tiles, positions, merged, band_out, options);
  std::vector<Piece> band_pieces =
      SimplifyCells(cells, n, positions, quadrics, goals2, options, target_faces, scratches, spikes);
  int64_t band_kept = 0;
  for (const Piece& piece : band_pieces) {
    for (size_t k = 0; k < piece.vertices.size(); ++k) positions[piece.vertices[k]] = piece.positions[k];
    band_kept += static_cast<int64_t>(piece.faces.size());
  }
  if (goals2.empty() && band_kept > target_faces && band_pieces.size() > 1) {
    PassAroundCellCuts(n, rings, target_faces, goals2, options, positions, quadrics, scratch, band_pieces, spikes);
  }
  size_t kept_faces = kept.size();
  for (const Piece& piece : band_pieces) kept_faces += piece.faces.size();
  kept.reserve(kept_faces);  // one allocation, not a doubling and a copy
  for (const Piece& piece : band_pieces) kept.insert(kept.end(), piece.faces.begin(), piece.faces.end());
}

// Each removed vertex's root, in place: the output vertex it ended in (chains point to later collapses).
void ToRoots(std::vector<uint32_t>& parent) {
  for (size_t v = 0; v < parent.size(); ++v) {
    uint32_t r = parent[v];
    while (parent[r] != r) r = parent[r];
    for (uint32_t w = static_cast<uint32_t>(v); parent[w] != r;) {
      const uint32_t next = parent[w];
      parent[w] = r;
      w = next;
    }
  }
}

// The spike pass's and the re-fit's largest distances start from a lower bound: every kSampleStep-th
// vertex measured in full.
constexpr size_t kSampleStep = 64;

// The output's faces around each output vertex, to measure input vertices against the output: each
// input vertex v against the faces around the output vertex it merged into (`roots`, after ToRoots),
// or around that vertex and its neighbours. Distances to some of the output's faces, so never below
// the true distance.
class OutputFans {
 public:
  OutputFans(const std::vector<Eigen::Vector3d>& input, const std::vector<Eigen::Vector3d>& output,
             const std::vector<std::array<uint32_t, 3>>& kept, const std::vector<uint32_t>& roots)
      : input_(input), output_(output), kept_(kept), roots_(roots), start_(input.size() + 1, 0) {
    const size_t n = input.size();
    for (const auto& t : kept) {
      for (uint32_t v : t) ++start_[v + 1];
    }
    for (size_t v = 0; v < n; ++v) start_[v + 1] += start_[v];
    around_.resize(start_[n]);
    std::vector<uint32_t> fill(start_.begin(), start_.end() - 1);
    for (uint32_t f = 0; f < kept.size(); ++f) {
      for (uint32_t v : kept[f]) around_[fill[v]++] = f;
    }
  }

  // Whether near(squared distance) holds for some face around v's root (or there is none).
  template <typename Near>
  bool SomeFaceAtRoot(size_t v, Near&& near) const {
    const uint32_t r = roots_[v];
    if (start_[r] == start_[r + 1]) return true;
    for (uint32_t k = start_[r]; k < start_[r + 1]; ++k) {
      if (near(ToFace(input_[v], around_[k]))) return true;
    }
    return false;
  }

  // Squared, against the faces around v's root and around its neighbours (`ring`: scratch), each face
  // once: at the first vertex of the ring it is around.
  double TwoRings(size_t v, std::vector<uint32_t>& ring) const {
    const uint32_t r = roots_[v];
    ring.assign(1, r);
    for (uint32_t k = start_[r]; k < start_[r + 1]; ++k) {
      for (uint32_t w : kept_[around_[k]]) {
        if (std::find(ring.begin(), ring.end(), w) == ring.end()) ring.push_back(w);
      }
    }
    double best = INFINITY;
    for (size_t i = 0; i < ring.size(); ++i) {
      const uint32_t w = ring[i];
      for (uint32_t j = start_[w]; j < start_[w + 1]; ++j) {
        const auto& t = kept_[around_[j]];
        bool earlier = false;
        for (size_t q = 0; q < i && !earlier; ++q) earlier = t[0] == ring[q] || t[1] == ring[q] || t[2] == ring[q];
        if (!earlier) best = std::min(best, ToFace(input_[v], around_[j]));
      }
    }
    return std::isfinite(best) ? best : 0.0;
  }

 private:
  double ToFace(const Eigen::Vector3d& x, uint32_t f) const {
    const auto& t = kept_[f];
    return SquaredDistanceToTriangle(x, output_[t[0]], output_[t[1]], output_[t[2]]);
  }

  const std::vector<Eigen::Vector3d>& input_;
  const std::vector<Eigen::Vector3d>& output_;
  const std::vector<std::array<uint32_t, 3>>& kept_;
  const std::vector<uint32_t>& roots_;
  std::vector<uint32_t> start_, around_;  // the output faces around vertex v: around_[start_[v] ..]
};

// The input vertices farther from the output than `share` × the largest such distance (the in→out
// side of the Hausdorff distance), and that largest distance (`largest_m`), each measured by
// OutputFans::TwoRings (`parent`: the vertex each removed one collapsed into; made roots here).
// Deterministic: no order of threads enters.
std::vector<char> SpikesToPin(const std::vector<Eigen::Vector3d>& input, const std::vector<Eigen::Vector3d>& output,
                              const std::vector<std::array<uint32_t, 3>>& kept, std::vector<uint32_t>& parent,
                              const std::vector<char>& used, double share, double* largest_m) {
  const size_t n = input.size();
  ToRoots(parent);
  const OutputFans fans(input, output, kept, parent);
  const double share2 = share * share;
  // A lower bound of the largest distance: every 64th vertex measured in full. A vertex with a face
  // nearer than share × that bound is then neither pinned nor the largest, which most vertices show
  // at their root's first face; the others are measured in full.
  std::vector<double> sample2((n + kSampleStep - 1) / kSampleStep, 0.0);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, sample2.size(), 256), [&](const tbb::blocked_range<size_t>& range) {
    std::vector<uint32_t> ring;
    for (size_t k = range.begin(); k != range.end(); ++k) {
      if (used[k * kSampleStep]) sample2[k] = fans.TwoRings(k * kSampleStep, ring);
    }
  });
  const double floor2 = share2 * *std::max_element(sample2.begin(), sample2.end());
  // (vertex, squared distance) of those measured in full, by blocks of vertices, in the vertices' order.
  const size_t blocks = (n + kBlock - 1) / kBlock;
  std::vector<std::vector<std::pair<uint32_t, double>>> measured(blocks);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, blocks, 1), [&](const tbb::blocked_range<size_t>& range) {
    std::vector<uint32_t> ring;
    for (size_t b = range.begin(); b != range.end(); ++b) {
      for (size_t v = b * kBlock; v < std::min(n, (b + 1) * kBlock); ++v) {
        if (used[v] && !fans.SomeFaceAtRoot(v, [&](double d2) { return d2 < floor2; }))
          measured[b].push_back({static_cast<uint32_t>(v), fans.TwoRings(v, ring)});
      }
    }
  });
  double largest2 = 0;
  for (const auto& block : measured) {
    for (const auto& [v, d2] : block) largest2 = std::max(largest2, d2);
  }
  std::vector<char> pinned(n, 0);
  for (const auto& block : measured) {
    for (const auto& [v, d2] : block) pinned[v] = d2 > share2 * largest2 ? 1 : 0;
  }
  *largest_m = std::sqrt(largest2);
  return pinned;
}

// Whether every input vertex lies nearer than limit_m to the output, as SpikesToPin measures it (its
// largest_m < limit_m, the same answer), without measuring each vertex in full: most are nearer than the
// limit to the first face around their root already. `parent` is made roots, as SpikesToPin does.
bool AllNearerThan(const std::vector<Eigen::Vector3d>& input, const std::vector<Eigen::Vector3d>& output,
                   const std::vector<std::array<uint32_t, 3>>& kept, std::vector<uint32_t>& parent,
                   const std::vector<char>& used, double limit_m) {
  const size_t n = input.size();
  ToRoots(parent);
  const OutputFans fans(input, output, kept, parent);
  std::atomic<bool> far{false};
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, kBlock), [&](const tbb::blocked_range<size_t>& range) {
    std::vector<uint32_t> ring;
    for (size_t v = range.begin(); v != range.end() && !far.load(std::memory_order_relaxed); ++v) {
      if (!used[v] || fans.SomeFaceAtRoot(v, [&](double d2) { return std::sqrt(d2) < limit_m; })) continue;
      if (!(std::sqrt(fans.TwoRings(v, ring)) < limit_m)) far.store(true, std::memory_order_relaxed);
    }
  });
  return !far.load();
}

// The spike pass's second run of the tiles: each tile holding a pinned vertex is simplified again (its
// vertices' collapse records reset first; a cut vertex never dies in a tile, so it is its own already),
// the others keep their first result.
void ResimplifyPinnedTiles(const std::vector<Eigen::Vector3d>& input,
                           const std::vector<std::vector<std::array<uint32_t, 3>>>& tiles,
                           const std::vector<double>& goals2, const QemOptions& options, double keep_ratio,
                           const std::vector<char>& pinned, Scratches& scratches, SpikeContext* spikes,
                           std::vector<uint32_t>& parent, std::vector<Piece>& pieces) {
  std::vector<char> rerun(tiles.size(), 0);
  for (size_t t = 0; t < tiles.size(); ++t) {
    for (const auto& f : tiles[t]) rerun[t] = rerun[t] || pinned[f[0]] || pinned[f[1]] || pinned[f[2]];
    if (!rerun[t]) continue;
    for (const auto& f : tiles[t]) {
      for (uint32_t v : f) parent[v] = v;
    }
  }
  tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
    std::vector<uint32_t>& tile_scratch = scratches.local();
    for (size_t t = range.begin(); t != range.end(); ++t) {
      if (rerun[t]) pieces[t] = SimplifyTile(input, tiles[t], goals2, options, keep_ratio, tile_scratch, spikes);
    }
  });
}

// Compressed sparse rows: the items of key k are items[start[k] .. start[k + 1]).
struct Csr {
  std::vector<uint32_t> start, items;
  uint32_t begin(uint32_t k) const { return start[k]; }
  uint32_t end(uint32_t k) const { return start[k + 1]; }
};

// Each vertex's faces (of `faces`, by index), in the faces' order.
Csr FacesAround(size_t n, const std::vector<std::array<uint32_t, 3>>& faces) {
  Csr csr;
  csr.start.assign(n + 1, 0);
  for (const auto& t : faces) {
    if (IsValidFace(t)) {
      for (uint32_t v : t) ++csr.start[v + 1];
    }
  }
  for (size_t v = 0; v < n; ++v) csr.start[v + 1] += csr.start[v];
  csr.items.resize(csr.start[n]);
  std::vector<uint32_t> fill(csr.start.begin(), csr.start.end() - 1);
  for (uint32_t f = 0; f < faces.size(); ++f) {
    if (!IsValidFace(faces[f])) continue;
    for (uint32_t v : faces[f]) csr.items[fill[v]++] = f;
  }
  return csr;
}

// The re-fit after the budget is met: each output vertex is measured against the input faces around
// the input vertices merged into it (`root`: the output vertex each input vertex ended in, from the
// collapse records), an upper bound of the out→in distance there. Those farther than a share of the
// largest are moved, one at a time in order of that distance (deterministic), towards the nearest
// point of those input faces (the whole way, half or a quarter); a move is kept only when it lowers
// the largest of the distances it can change, measured the same way (LocalMax), and flips no face.
class Refit {
 public:
  Refit(const std::vector<Eigen::Vector3d>& input, const std::vector<std::array<uint32_t, 3>>& faces,
        const std::vector<std::array<uint32_t, 3>>& kept, const std::vector<uint32_t>& root,
        std::vector<Eigen::Vector3d>& positions)
      : input_(input),
        faces_(faces),
        kept_(kept),
        positions_(positions),
        root_(root),
        input_around_(FacesAround(input.size(), faces)),
        output_around_(FacesAround(input.size(), kept)) {
    const size_t n = input.size();
    cluster_.start.assign(n + 1, 0);
    for (size_t v = 0; v < n; ++v) ++cluster_.start[root[v] + 1];
    for (size_t v = 0; v < n; ++v) cluster_.start[v + 1] += cluster_.start[v];
    cluster_.items.resize(n);
    std::vector<uint32_t> fill(cluster_.start.begin(), cluster_.start.end() - 1);
    for (uint32_t v = 0; v < n; ++v) cluster_.items[fill[root[v]]++] = v;
  }

  // The output vertices farther from the input than share × the largest such distance, farthest first.
  std::vector<uint32_t> Farthest(double share) const {
    const size_t n = input_.size();
    // The output vertices against the input faces around their clusters, in the vertices' order (which
    // follows the surface, so the faces of neighbouring clusters stay in cache). Refining from the
    // largest bound down (by r's own faces), as before, met 92 k of 116 k vertices at 10 % on the 2.5 M
    // bench terrain and 61 k of 408 k at 40 %, in no spatial order: 2.2-5x slower.
    // An output vertex at its input position is on the input.
    const auto measured = [&](size_t r) {
      return output_around_.begin(r) != output_around_.end(r) && positions_[r] != input_[r];
    };
    const auto far_from_input2 = [&](size_t r) {
      const double d2 = OutToIn(static_cast<uint32_t>(r), positions_[r], nullptr);
      return std::isfinite(d2) ? d2 : 0.0;
    };
    // A lower bound of the largest distance from every 64th vertex. A vertex with an input face nearer
    // than share × that bound is then neither listed nor the largest (share ≤ 1), which most show at
    // their first faces; only the others (1 % at 10 % and 40 % on the 500 k bench terrain) are measured
    // in full. The same list as measuring every vertex.
    std::vector<double> sample2((n + kSampleStep - 1) / kSampleStep, 0.0);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, sample2.size(), 256), [&](const tbb::blocked_range<size_t>& range) {
      for (size_t k = range.begin(); k != range.end(); ++k) {
        if (measured(k * kSampleStep)) sample2[k] = far_from_input2(k * kSampleStep);
      }
    });
    const double floor2 =
        std::min(1.0, share * share) * (sample2.empty() ? 0.0 : *std::max_element(sample2.begin(), sample2.end()));
    std::vector<double> far2(n, 0.0);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, kBlock), [&](const tbb::blocked_range<size_t>& range) {
      for (size_t r = range.begin(); r != range.end(); ++r) {
        if (measured(r) && !SomeInputFaceNearer(static_cast<uint32_t>(r), floor2)) far2[r] = far_from_input2(r);
      }
    });
    const double largest2 = n == 0 ? 0.0 : *std::max_element(far2.begin(), far2.end());
    std::vector<std::pair<double, uint32_t>> order;
    for (size_t r = 0; r < n && largest2 > 0; ++r) {
      if (far2[r] > share * share * largest2) order.push_back({-far2[r], static_cast<uint32_t>(r)});
    }
    std::sort(order.begin(), order.end());
    std::vector<uint32_t> farthest;
    for (const auto& entry : order) farthest.push_back(entry.second);
    return farthest;
  }

  // Moves r towards the nearest point of its input faces (the whole way, half or a quarter) when that
  // lowers LocalMax and flips none of its faces.
  void Move(uint32_t r) {
    ring_.assign(1, r);  // the vertex and its neighbours in the output
    for (uint32_t k = output_around_.begin(r); k < output_around_.end(r); ++k) {
      for (uint32_t w : kept_[output_around_.items[k]]) {
        if (std::find(ring_.begin(), ring_.end(), w) == ring_.end()) ring_.push_back(w);
      }
    }
    const Eigen::Vector3d start = positions_[r];
    Eigen::Vector3d nearest;
    if (!std::isfinite(OutToIn(r, start, &nearest))) return;
    std::vector<Eigen::Vector3d> normals;
    for (uint32_t k = output_around_.begin(r); k < output_around_.end(r); ++k)
      normals.push_back(Normal(kept_[output_around_.items[k]]));
    double best = LocalMax(r);
    Eigen::Vector3d best_at = start;
    for (double step : {1.0, 0.5, 0.25}) {
      positions_[r] = start + step * (nearest - start);
      bool flips = false;
      for (uint32_t k = output_around_.begin(r); k < output_around_.end(r) && !flips; ++k)
        flips = Normal(kept_[output_around_.items[k]]).dot(normals[k - output_around_.begin(r)]) <= 0;
      if (flips) continue;
      const double worst = LocalMax(r);
      if (worst < best) best = worst, best_at = positions_[r];
    }
    positions_[r] = best_at;
  }

 private:
  // Whether face t, met around cluster member m of r's cluster, has a corner earlier in that cluster.
  bool SeenEarlier(const std::array<uint32_t, 3>& t, uint32_t m, uint32_t r) const {
    return (t[0] < m && root_[t[0]] == r) || (t[1] < m && root_[t[1]] == r) || (t[2] < m && root_[t[2]] == r);
  }

  // Whether some input face around the vertices merged into r lies nearer than sqrt(limit2) to r's
  // position, or there is none (Farthest then counts r's distance as 0).
  bool SomeInputFaceNearer(uint32_t r, double limit2) const {
    bool none = true;
    for (uint32_t k = cluster_.begin(r); k < cluster_.end(r); ++k) {
      const uint32_t m = cluster_.items[k];
      for (uint32_t j = input_around_.begin(m); j < input_around_.end(m); ++j) {
        const auto& t = faces_[input_around_.items[j]];
        none = false;
        if (SquaredDistanceToTriangle(positions_[r], input_[t[0]], input_[t[1]], input_[t[2]]) < limit2) return true;
      }
    }
    return none && limit2 > 0;
  }

  // Squared distance from x to the input faces around the vertices merged into r; `nearest`: where.
  double OutToIn(uint32_t r, const Eigen::Vector3d& x, Eigen::Vector3d* nearest) const {
    double best = INFINITY;
    uint32_t best_face = 0;
    for (uint32_t k = cluster_.begin(r); k < cluster_.end(r); ++k) {
      const uint32_t m = cluster_.items[k];
      for (uint32_t j = input_around_.begin(m); j < input_around_.end(m); ++j) {
        const auto& t = faces_[input_around_.items[j]];
        // A face with two or three corners in the cluster is measured once, at its first corner in the
        // cluster's (increasing) order: the same faces in the same order as without the test.
        if (SeenEarlier(t, m, r)) continue;
        const double d2 = SquaredDistanceToTriangle(x, input_[t[0]], input_[t[1]], input_[t[2]]);
        if (d2 < best) best = d2, best_face = input_around_.items[j];
      }
    }
    if (nearest && std::isfinite(best)) {
      const auto& t = faces_[best_face];
      *nearest = ClosestOnTriangle(x, input_[t[0]], input_[t[1]], input_[t[2]]);
    }
    return best;
  }

  // The largest (squared) of the distances a move of r can change, each measured as above: r's own,
  // out→in at the centres and edge midpoints of its faces, and in→out of the input vertices merged
  // into r or its neighbours (`ring_`), against the output faces around the vertex each merged into.
  double LocalMax(uint32_t r) const {
    double worst = OutToIn(r, positions_[r], nullptr);
    for (uint32_t k = output_around_.begin(r); k < output_around_.end(r); ++k) {
      const auto& t = kept_[output_around_.items[k]];
      const Eigen::Vector3d centre = (positions_[t[0]] + positions_[t[1]] + positions_[t[2]]) / 3;
      double at_centre = INFINITY;
      for (uint32_t w : t) {
        at_centre = std::min(at_centre, OutToIn(w, centre, nullptr));
        if (w == r) continue;
        const Eigen::Vector3d mid = (positions_[r] + positions_[w]) / 2;
        worst = std::max(worst, std::min(OutToIn(r, mid, nullptr), OutToIn(w, mid, nullptr)));
      }
      worst = std::max(worst, at_centre);
    }
    for (uint32_t w : ring_) {
      for (uint32_t k = cluster_.begin(w); k < cluster_.end(w); ++k) {
        const Eigen::Vector3d& x = input_[cluster_.items[k]];
        double best = INFINITY;
        for (uint32_t j = output_around_.begin(w); j < output_around_.end(w); ++j) {
          const auto& t = kept_[output_around_.items[j]];
          best = std::min(best, SquaredDistanceToTriangle(x, positions_[t[0]], positions_[t[1]], positions_[t[2]]));
        }
        if (std::isfinite(best)) worst = std::max(worst, best);
      }
    }
    return worst;
  }

  Eigen::Vector3d Normal(const std::array<uint32_t, 3>& t) const {
    return (positions_[t[1]] - positions_[t[0]]).cross(positions_[t[2]] - positions_[t[0]]);
  }

  const std::vector<Eigen::Vector3d>& input_;
  const std::vector<std::array<uint32_t, 3>>& faces_;
  const std::vector<std::array<uint32_t, 3>>& kept_;
  std::vector<Eigen::Vector3d>& positions_;
  const std::vector<uint32_t>& root_;  // the output vertex each input vertex ended in
  const Csr input_around_, output_around_;
  Csr cluster_;                 // the input vertices merged into each output vertex (itself included)
  std::vector<uint32_t> ring_;  // Move's vertex and its neighbours
};

}  // namespace

TriangleMesh DecimateQemTiled(const TriangleMesh& mesh, int64_t target_faces, int partitions,
                              const QemOptions& requested, const std::vector<double>* goal_error_m) {
  const size_t n = mesh.num_vertices();
  std::vector<double> goals2;  // squared, per vertex (empty: a face budget only)
  if (goal_error_m) {
    goals2 = SquaredGoals(*goal_error_m, n);
    target_faces = 0;
  }
  // Work relative to the bounding-box centre (better conditioned quadrics).
  const Eigen::Vector3d center = BoundingBoxCenter(mesh.vertices_m);
  const std::vector<Eigen::Vector3d> input = CenteredPositions(mesh.vertices_m, center);
  std::vector<Eigen::Vector3d> positions = input;
  TileGrid grid = MakeTileGrid(positions, mesh.faces, partitions);
  double keep_ratio = static_cast<double>(target_faces) / std::max<size_t>(1, grid.valid_faces);
  if (!goal_error_m) grid.grid = LightBudgetGrid(grid, keep_ratio, requested);
  std::vector<std::vector<std::array<uint32_t, 3>>> tiles = FacesByTile(grid, positions, mesh.faces);
  QemOptions options = requested;
  if (goal_error_m || keep_ratio < options.light_budget_keep) {
    options.area_floor = 0;
    options.distance_check = 0;
  } else if (options.area_floor < 0) {
    options.area_floor = std::clamp(keep_ratio, 0.0, 1.0);
  }
  // Not at light budgets: there it made 80 % worse (bench/RESULTS.md, run M).
  const bool spike_pass = goals2.empty() && options.spike_pass > 0 && keep_ratio < options.light_budget_keep;
  // Nor the re-fit: at 80 % it changed no error on any mesh measured (bench/RESULTS.md, run N) and cost CPU.
  const bool refit = goals2.empty() && options.refit > 0 && target_faces > 0 && keep_ratio < options.light_budget_keep;
  SpikeContext spikes;
  std::vector<uint32_t> parent;
  if (spike_pass || refit) {
    parent.resize(n);
    for (size_t v = 0; v < n; ++v) parent[v] = static_cast<uint32_t>(v);
    spikes.parent = &parent;
  }
  // PreparePiece's scratch, one per thread (kUnmapped between calls).
  Scratches scratches(n, kUnmapped);
  std::vector<uint32_t> scratch(n, kUnmapped);
  std::vector<Piece> pieces(tiles.size());
  if (tiles.size() > 1) pieces = SimplifyTiles(input, tiles, goals2, options, keep_ratio, scratches, &spikes);
  const std::vector<uint32_t> tile_parent = parent;  // the collapses of the tiles alone
  const int64_t budget = target_faces;
  // The pass after the tiles (or the one pass over a single tile): `positions` from the input's, the
  // faces kept in `kept`.
  const auto last_pass = [&](std::vector<std::array<uint32_t, 3>>& kept) {
    int64_t target = budget;
    std::vector<std::array<uint32_t, 3>> merged;  // the faces of the last pass
    if (tiles.size() > 1) {
      const size_t tile_faces = MergeTilePieces(pieces, positions, goals2);
      // With error goals the band's width follows the share of the faces the tiles kept.
      if (!goals2.empty()) keep_ratio = static_cast<double>(tile_faces) / std::max<size_t>(1, grid.valid_faces);
    } else {
      merged = tiles[0];
    }
    std::vector<std::array<uint32_t, 3>> outside;
    const int rings =
        static_cast<int>(std::ceil(std::max(1.0, options.final_band_rings) / std::sqrt(std::max(keep_ratio, 1e-4))));
    QuadricStore quadrics;  // those of the last pass's vertices
    if (tiles.size() > 1) {
      merged = LastPassFaces(pieces, n, rings, options, !goals2.empty(), target, outside);
      quadrics = SumQuadrics(pieces, merged, n);
    }
    kept = std::move(outside);
    if (tiles.size() == 1) {
      PieceJob job = PreparePiece(positions, nullptr, merged, {}, goals2, options, scratch, &spikes);
      Piece whole = FinishPiece(job, target);
      for (size_t k = 0; k < whole.vertices.size(); ++k) positions[whole.vertices[k]] = whole.positions[k];
      kept = std::move(whole.faces);
    } else {
      SimplifyBand(grid, merged, n, rings, keep_ratio, target, goals2, options, positions, quadrics, scratches, scratch,
                   kept, &spikes);
    }
  };
  std::vector<std::array<uint32_t, 3>> kept;
  last_pass(kept);
  if (spike_pass && !kept.empty()) {
    // The spike pass: the input vertices the output left farthest (single noisy points, which the
    // quadrics' mean lets go) are pinned, and the tiles that hold one run again with the band: the
    // budget is met by other collapses, the cheapest left.
    std::vector<char> used(n, 0);
    for (const auto& t : mesh.faces) {
      if (IsValidFace(t)) used[t[0]] = used[t[1]] = used[t[2]] = 1;
    }
    double first_m = 0;
    const std::vector<char> pinned = SpikesToPin(input, positions, kept, parent, used, options.spike_pass, &first_m);
    std::vector<std::array<uint32_t, 3>> first_kept = std::move(kept);
    std::vector<Eigen::Vector3d> first_positions = positions;
    std::vector<uint32_t> first_parent = parent;
    // The second run records its collapses as the first did: the tiles it reuses keep theirs.
    parent = tile_parent;
    spikes.pinned = &pinned;
    positions = input;
    if (tiles.size() > 1) {
      ResimplifyPinnedTiles(input, tiles, goals2, options, keep_ratio, pinned, scratches, &spikes, parent, pieces);
    }
    last_pass(kept);
    // The second run is kept only when its farthest input vertex is nearer than the first's (measured
    // the same way): the collapses it makes instead can leave other points farther.
    if (!AllNearerThan(input, positions, kept, parent, used, first_m)) {
      kept = std::move(first_kept);
      positions = std::move(first_positions);
      parent = std::move(first_parent);
    }
  }
  if (refit && !kept.empty()) {
    ToRoots(parent);
    Refit refitter(input, mesh.faces, kept, parent, positions);
    for (uint32_t r : refitter.Farthest(options.refit)) refitter.Move(r);
  }

  // The surviving vertices in their input order, then the faces.
  return CompactMesh(mesh, kept, positions, center);
}

}  // namespace cinepath::photogrammetry::internal
