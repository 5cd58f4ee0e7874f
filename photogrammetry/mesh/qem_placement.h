// Where a quadric edge collapse puts its vertex, and at what cost: the quadric (Garland & Heckbert,
// "Surface Simplification Using Quadric Error Metrics", SIGGRAPH 1997), Placement (its minimum, with the
// directions it does not pin down held at the edge's midpoint) and PlaceFullRank4 (four edges at once
// where Placement takes the plain inverse). For the tiled decimation, photogrammetry/mesh/mesh_decimate_qem.cc.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/Dense>

namespace cinepath::photogrammetry::internal {

// Whether this CPU runs AVX2 (read once).
inline bool CpuHasAvx2() {
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
}

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
  Quadric& operator-=(const Quadric& o) {
    for (int k = 0; k < 10; ++k) q[k] -= o.q[k];
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

inline Quadric Sum(const Quadric& a, const Quadric& b) {
  Quadric s = a;
  s += b;
  return s;
}

// A collapse's point and its quadric error there.
struct Placed {
  Eigen::Vector3d point;
  double error;
};

// The point minimising q on the segment [a, b] (closed form of a quadratic in t).
inline Placed BestOnSegment(const Quadric& q, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double ea = q.Error(a), eb = q.Error(b), em = q.Error(0.5 * (a + b));
  // e(t) = ea + t·(−3ea + 4em − eb) + t²·(2ea − 4em + 2eb)
  const double c2 = 2 * ea - 4 * em + 2 * eb, c1 = -3 * ea + 4 * em - eb;
  double t = ea <= eb ? 0.0 : 1.0;
  if (c2 > 0) {
    const double tm = std::clamp(-c1 / (2 * c2), 0.0, 1.0);
    if (ea + tm * c1 + tm * tm * c2 < std::min(ea, eb)) t = tm;
  }
  if (t == 0) return {a, ea};
  const Eigen::Vector3d point = a + t * (b - a);  // at t = 1 not always b, to rounding
  return {point, q.Error(point)};
}

// The adjugate (transposed cofactor matrix) of m: m · adj(m) = det(m) · I.
inline Eigen::Matrix3d Adjugate(const Eigen::Matrix3d& m) {
  return (Eigen::Matrix3d() << m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1), m(0, 2) * m(2, 1) - m(0, 1) * m(2, 2),
          m(0, 1) * m(1, 2) - m(0, 2) * m(1, 1), m(1, 2) * m(2, 0) - m(1, 0) * m(2, 2),
          m(0, 0) * m(2, 2) - m(0, 2) * m(2, 0), m(0, 2) * m(1, 0) - m(0, 0) * m(1, 2),
          m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0), m(0, 1) * m(2, 0) - m(0, 0) * m(2, 1),
          m(0, 0) * m(1, 1) - m(0, 1) * m(1, 0))
      .finished();
}

// The eigenvalues of a symmetric 3 × 3 matrix, ascending.
struct Eigenvalues3 {
  double l1, l2, l3;
};

// The eigenvalues, ascending: the largest by Newton's method on the characteristic polynomial
// x³ − trace x² + minors x − det from x = trace, above it, where the cubic is convex and rising, so
// the steps fall monotonically onto it (two or three steps when it stands apart, as on a surface);
// the other two from the quadratic left. Eigen's closed form (acos, cos, sin) where Newton does not
// settle in 16 steps (a repeated largest eigenvalue, met slowly). On the bench terrain's truncated
// quadrics: 48 ns per solve against 61 ns with the closed form alone.
// `first_step`: Newton's first step when Placement took it already, else 0.
inline Eigenvalues3 EigenvaluesAscending(const Eigen::Matrix3d& m, double trace, double minors, double det,
                                         double first_step) {
  double l3 = trace;
  bool settled = false;
  int step = 0;
  if (first_step > 0) {  // the loop's first step, already taken above (the same numbers)
    l3 -= first_step;
    settled = !(first_step > 1e-13 * l3);
    step = 1;
  }
  for (; step < 16 && !settled; ++step) {
    const double value = ((l3 - trace) * l3 + minors) * l3 - det;
    const double slope = (3 * l3 - 2 * trace) * l3 + minors;
    if (!(value > 0 && slope > 0)) {
      settled = true;  // on the root, to rounding
    } else {
      const double dx = value / slope;
      l3 -= dx;
      settled = !(dx > 1e-13 * l3);
    }
  }
  const double sum12 = trace - l3, product12 = minors - l3 * sum12;  // λ1 + λ2, λ1 λ2
  double l2 = 0.5 * (sum12 + std::sqrt(std::max(0.0, sum12 * sum12 - 4 * product12)));
  double l1 = l2 > 0 ? product12 / l2 : 0.0;
  if (!settled || !(l2 <= l3)) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
    eigen.computeDirect(m, Eigen::EigenvaluesOnly);
    l1 = eigen.eigenvalues()(0), l2 = eigen.eigenvalues()(1), l3 = eigen.eigenvalues()(2);
  }
  return {l1, l2, l3};
}

// The truncated solve Σ v_k (v_k · r) / λ_k over the kept eigenpairs, written as a polynomial in m
// that is 1/λ on the kept eigenvalues and 0 on the dropped ones (Lagrange interpolation), so that
// no eigenvector is needed: two products with m instead. The coefficients are symmetric in the
// eigenvalues kept together, so a repeated eigenvalue (λ2 = λ3 on a right-angled crease, λ1 = λ2
// on a plane) costs nothing in accuracy; they divide only by the gap between a kept and a dropped
// eigenvalue. One dropped (λ1): f(m) = (m − λ1)(β − α m) / (λ2 λ3 (λ2 − λ1)(λ3 − λ1)) with
// α = λ2 + λ3 − λ1 and β = (λ2 + λ3)² − λ2 λ3 − λ1 (λ2 + λ3). Two dropped: f(m) = (m − λ1)(m − λ2)
// / (λ3 (λ3 − λ1)(λ3 − λ2)).
// Returns mid plus that solve for the residual r = rhs − m · mid; `cut` = rcond × λ3, above λ1.
inline Eigen::Vector3d TruncatedSolve(const Eigen::Matrix3d& m, const Eigen::Vector3d& residual,
                                      const Eigen::Vector3d& mid, const Eigenvalues3& eigen, double cut) {
  const double l1 = eigen.l1, l2 = eigen.l2, l3 = eigen.l3;
  const Eigen::Vector3d u = m * residual - l1 * residual;
  Eigen::Vector3d p = mid;
  if (l2 > cut) {
    const double sum = l2 + l3, alpha = sum - l1, beta = sum * sum - l2 * l3 - l1 * sum;
    p += (beta * u - alpha * (m * u)) / (l2 * l3 * (l2 - l1) * (l3 - l1));
  } else {
    p += (m * u - l2 * u) / (l3 * (l3 - l1) * (l3 - l2));
  }
  return p;
}

// Where an edge (a, b) collapses to. The quadric's minimum is solved in the eigenbasis of its 3×3
// part, and the directions the quadric does not pin down (eigenvalue at most rcond × the largest) are
// held at the edge's midpoint, as in Lindstrom's out-of-core simplification (P. Lindstrom, "Out-of-Core
// Simplification of Large Polygonal Models", SIGGRAPH 2000). On a near-flat patch the quadric fixes
// only the height; a plain inverse slides the point far along the plane on rounding noise. The point
// is used when it lies within `reach` edge lengths of the midpoint and beats the best point on the
// edge; otherwise the best point on the edge.
inline Placed Placement(const Quadric& q, const Eigen::Vector3d& a, const Eigen::Vector3d& b, double reach,
                        double rcond) {
  Eigen::Matrix3d m;
  m << q.q[0], q.q[1], q.q[2], q.q[1], q.q[4], q.q[5], q.q[2], q.q[5], q.q[7];
  const Eigen::Vector3d rhs(-q.q[3], -q.q[6], -q.q[8]);
  const Eigen::Vector3d mid = 0.5 * (a + b);
  const Eigen::Vector3d residual = rhs - m * mid;
  // Every eigenvalue is above rcond × the largest when det / m2 > rcond × trace, since the smallest
  // is at least det / m2 (m2: the sum of the principal 2 × 2 minors, λ1λ2 + λ1λ3 + λ2λ3) and the
  // largest at most the trace. Then nothing is truncated and the plain inverse (the adjugate) gives
  // the same point without the eigenvalues: most of a curved surface's edges.
  const Eigen::Matrix3d adjugate = Adjugate(m);
  const double trace = m.trace();
  const double minors = adjugate(0, 0) + adjugate(1, 1) + adjugate(2, 2);
  const double det = m(0, 0) * adjugate(0, 0) + m(0, 1) * adjugate(1, 0) + m(0, 2) * adjugate(2, 0);
  const double reach2 = reach * reach * (b - a).squaredNorm();
  const auto full_rank = [&] {
    // The quadric's minimum over all space, so no point of the edge does better when it is in reach.
    const Eigen::Vector3d p = mid + adjugate * residual / det;
    return p.allFinite() && (p - mid).squaredNorm() <= reach2 ? Placed{p, q.Error(p)} : BestOnSegment(q, a, b);
  };
  // Newton's first step down from the trace towards the largest eigenvalue (below), when it is taken.
  double first_step = 0;
  // (The first test keeps rounding noise out: minors that small leave at most one direction pinned.)
  if (minors > 1e-9 * trace * trace) {
    if (det > rcond * trace * minors) return full_rank();
    // Tighter bounds, from Newton's method on the characteristic polynomial p(x) = x³ − trace x² +
    // minors x − det: from 0, where p is concave and rising up to the smallest root, two steps stay
    // below it (the first is det / minors); from the trace, where p is convex and rising, one step
    // stays above the largest. On the bench terrain at 80 % this settles 0.95 M of the 1.08 M
    // quadrics that the first test leaves and that truncate nothing.
    const auto p = [&](double x) { return ((x - trace) * x + minors) * x - det; };
    const auto slope = [&](double x) { return (3 * x - 2 * trace) * x + minors; };
    const double below = det / minors, smallest_at_least = below - p(below) / slope(below);
    const double value = p(trace), rise = slope(trace);
    const double largest_at_most = trace - value / rise;
    if (smallest_at_least > rcond * largest_at_most) return full_rank();
    if (value > 0 && rise > 0) first_step = value / rise;
  }
  const Eigenvalues3 eigen = EigenvaluesAscending(m, trace, minors, det, first_step);
  const double l1 = eigen.l1, l3 = eigen.l3;
  if (!(l3 > 0)) return BestOnSegment(q, a, b);
  const double cut = rcond * l3;
  if (l1 > cut) return full_rank();
  const Eigen::Vector3d p = TruncatedSolve(m, residual, mid, eigen, cut);
  // Truncated: p holds some directions at the midpoint, so a point of the edge may do better.
  const Placed on_edge = BestOnSegment(q, a, b);
  if (p.allFinite() && (p - mid).squaredNorm() <= reach2) {
    const double error = q.Error(p);
    if (error < on_edge.error) return {p, error};
  }
  return on_edge;
}

// Four collapses priced at once, each lane bit for bit what Placement returns where it takes its plain
// inverse's point: a full-rank quadric (by either of Placement's two tests) whose minimum lies in reach.
// Those are most of a surface's edges, and Placement's straight-line arithmetic runs four wide here
// (AVX2 where the CPU has it, else two SSE2 halves; no FMA either way, so the same roundings: every sum
// in the order Placement's Eigen expressions take, which tests/photogrammetry/mesh/qem_placement_test.cc
// checks against Placement). The edges' quadrics are summed in the lanes.
struct Lanes4 {
  std::array<const Quadric*, 4> qa, qb;
  std::array<const Eigen::Vector3d*, 4> a, b;
};

namespace placement_detail {
typedef double V4 __attribute__((vector_size(32)));
typedef long long M4 __attribute__((vector_size(32)));

__attribute__((always_inline)) inline int PlaceFullRank4Body(const Lanes4& in, double reach, double rcond,
                                                             std::array<double, 4>& error) {
  V4 q[10];
  for (int j = 0; j < 10; ++j) {
    q[j] = V4{in.qa[0]->q[j], in.qa[1]->q[j], in.qa[2]->q[j], in.qa[3]->q[j]} +
           V4{in.qb[0]->q[j], in.qb[1]->q[j], in.qb[2]->q[j], in.qb[3]->q[j]};
  }
  V4 a[3], b[3];
  for (int i = 0; i < 3; ++i) {
    a[i] = V4{(*in.a[0])[i], (*in.a[1])[i], (*in.a[2])[i], (*in.a[3])[i]};
    b[i] = V4{(*in.b[0])[i], (*in.b[1])[i], (*in.b[2])[i], (*in.b[3])[i]};
  }
  const V4 m00 = q[0], m01 = q[1], m02 = q[2], m11 = q[4], m12 = q[5], m22 = q[7];
  const V4 m10 = m01, m20 = m02, m21 = m12;
  const V4 mid0 = 0.5 * (a[0] + b[0]), mid1 = 0.5 * (a[1] + b[1]), mid2 = 0.5 * (a[2] + b[2]);
  // A 3 × 3 product with a vector as Eigen sums it: rows 0 and 1 from the left, row 2 from the right.
  const V4 r0 = -q[3] - ((m00 * mid0 + m01 * mid1) + m02 * mid2);
  const V4 r1 = -q[6] - ((m10 * mid0 + m11 * mid1) + m12 * mid2);
  const V4 r2 = -q[8] - (m20 * mid0 + (m21 * mid1 + m22 * mid2));
  const V4 j00 = m11 * m22 - m12 * m21, j01 = m02 * m21 - m01 * m22, j02 = m01 * m12 - m02 * m11;
  const V4 j10 = m12 * m20 - m10 * m22, j11 = m00 * m22 - m02 * m20, j12 = m02 * m10 - m00 * m12;
  const V4 j20 = m10 * m21 - m11 * m20, j21 = m01 * m20 - m00 * m21, j22 = m00 * m11 - m01 * m10;
  const V4 trace = m00 + (m11 + m22);  // Eigen's trace() and the minors' sum: the last two first
  const V4 minors = j00 + (j11 + j22);
  const V4 det = (m00 * j00 + m01 * j10) + m02 * j20;
  const V4 e0 = b[0] - a[0], e1 = b[1] - a[1], e2 = b[2] - a[2];
  const V4 reach2 = reach * reach * ((e0 * e0 + e1 * e1) + e2 * e2);
  const M4 some_pinned = minors > 1e-9 * trace * trace;
  M4 full = some_pinned & (det > rcond * trace * minors);
  const M4 second = some_pinned & ~full;
  if (second[0] | second[1] | second[2] | second[3]) {  // Newton's bounds, as Placement takes them
    const V4 below = det / minors;
    const V4 p_below = ((below - trace) * below + minors) * below - det;
    const V4 slope_below = (3.0 * below - 2.0 * trace) * below + minors;
    const V4 smallest_at_least = below - p_below / slope_below;
    const V4 value = ((trace - trace) * trace + minors) * trace - det;
    const V4 rise = (3.0 * trace - 2.0 * trace) * trace + minors;
    const V4 largest_at_most = trace - value / rise;
    full = full | (second & (smallest_at_least > rcond * largest_at_most));
  }
  const V4 p0 = mid0 + ((j00 * r0 + j01 * r1) + j02 * r2) / det;
  const V4 p1 = mid1 + ((j10 * r0 + j11 * r1) + j12 * r2) / det;
  const V4 p2 = mid2 + (j20 * r0 + (j21 * r1 + j22 * r2)) / det;
  const V4 d0 = p0 - mid0, d1 = p1 - mid1, d2 = p2 - mid2;
  const V4 moved2 = (d0 * d0 + d1 * d1) + d2 * d2;
  const V4 err = q[0] * p0 * p0 + 2.0 * q[1] * p0 * p1 + 2.0 * q[2] * p0 * p2 + 2.0 * q[3] * p0 + q[4] * p1 * p1 +
                 2.0 * q[5] * p1 * p2 + 2.0 * q[6] * p1 + q[7] * p2 * p2 + 2.0 * q[8] * p2 + q[9];
  int done = 0;
  for (int k = 0; k < 4; ++k) {
    if (full[k] && std::isfinite(p0[k]) && std::isfinite(p1[k]) && std::isfinite(p2[k]) && moved2[k] <= reach2[k]) {
      done |= 1 << k;
      error[k] = err[k];
    }
  }
  return done;
}

__attribute__((target("avx2"))) inline int PlaceFullRank4Avx2(const Lanes4& in, double reach, double rcond,
                                                              std::array<double, 4>& error) {
  return PlaceFullRank4Body(in, reach, rcond, error);
}

inline int PlaceFullRank4Generic(const Lanes4& in, double reach, double rcond, std::array<double, 4>& error) {
  return PlaceFullRank4Body(in, reach, rcond, error);
}
}  // namespace placement_detail

// Bit k set: lane k is done, error[k] its quadric error at Placement's point (the others untouched).
// `wide`: the AVX2 path (when the CPU has it), else the portable one; the same bits either way.
inline int PlaceFullRank4(const Lanes4& in, double reach, double rcond, std::array<double, 4>& error,
                          bool wide = CpuHasAvx2()) {
  return wide ? placement_detail::PlaceFullRank4Avx2(in, reach, rcond, error)
              : placement_detail::PlaceFullRank4Generic(in, reach, rcond, error);
}

}  // namespace cinepath::photogrammetry::internal
