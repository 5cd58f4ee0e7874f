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

// Four collapses priced at once, each lane bit for bit what Placement returns: its straight-line
// arithmetic runs four wide (AVX2 where the CPU has it, else two SSE2 halves; no FMA either way, so the
// same roundings: every sum in the order Placement's Eigen expressions take, which
// tests/photogrammetry/mesh/qem_placement_test.cc checks against Placement). PlaceFullRank4 takes the
// plain inverse's point (a full-rank quadric by either of Placement's two tests, its minimum in reach:
// most of a surface's edges); PlaceAny4 every path, for what the first leaves (the truncated solves
// of flat ground, and points out of reach). The edges' quadrics are summed in the lanes.
struct Lanes4 {
  std::array<const Quadric*, 4> qa, qb;
  std::array<const Eigen::Vector3d*, 4> a, b;
};

namespace placement_detail {
typedef double V4 __attribute__((vector_size(32)));
typedef long long M4 __attribute__((vector_size(32)));

__attribute__((always_inline)) inline V4 Select(M4 mask, V4 yes, V4 no) {
  return reinterpret_cast<V4>((reinterpret_cast<M4>(yes) & mask) | (reinterpret_cast<M4>(no) & ~mask));
}

__attribute__((always_inline)) inline bool Any(M4 mask) { return (mask[0] | mask[1] | mask[2] | mask[3]) != 0; }

// Quadric::Error, four wide.
__attribute__((always_inline)) inline V4 Error4(const V4* q, V4 x, V4 y, V4 z) {
  return q[0] * x * x + 2.0 * q[1] * x * y + 2.0 * q[2] * x * z + 2.0 * q[3] * x + q[4] * y * y + 2.0 * q[5] * y * z +
         2.0 * q[6] * y + q[7] * z * z + 2.0 * q[8] * z + q[9];
}

// A 3 × 3 symmetric matrix times a vector, summed as Eigen sums it: rows 0 and 1 from the left, row 2
// from the right.
struct Sym4 {
  V4 m00, m01, m02, m11, m12, m22;
  void Times(const V4* x, V4* out) const {
    out[0] = (m00 * x[0] + m01 * x[1]) + m02 * x[2];
    out[1] = (m01 * x[0] + m11 * x[1]) + m12 * x[2];
    out[2] = m02 * x[0] + (m12 * x[1] + m22 * x[2]);
  }
};

// What every path of Placement computes first.
struct Front4 {
  V4 q[10];
  V4 a[3], b[3], mid[3], residual[3];
  Sym4 m;
  V4 j00, j01, j02, j10, j11, j12, j20, j21, j22;  // the adjugate
  V4 trace, minors, det, reach2;
  M4 some_pinned, first_test;
  V4 p[3];      // the plain inverse's point
  M4 in_reach;  // and whether it is finite and in reach
};

__attribute__((always_inline)) inline void Prepare4(const Lanes4& in, double reach, double rcond, Front4& f) {
  for (int j = 0; j < 10; ++j) {
    f.q[j] = V4{in.qa[0]->q[j], in.qa[1]->q[j], in.qa[2]->q[j], in.qa[3]->q[j]} +
             V4{in.qb[0]->q[j], in.qb[1]->q[j], in.qb[2]->q[j], in.qb[3]->q[j]};
  }
  for (int i = 0; i < 3; ++i) {
    f.a[i] = V4{(*in.a[0])[i], (*in.a[1])[i], (*in.a[2])[i], (*in.a[3])[i]};
    f.b[i] = V4{(*in.b[0])[i], (*in.b[1])[i], (*in.b[2])[i], (*in.b[3])[i]};
    f.mid[i] = 0.5 * (f.a[i] + f.b[i]);
  }
  const V4* q = f.q;
  f.m = Sym4{q[0], q[1], q[2], q[4], q[5], q[7]};
  const V4 m00 = q[0], m01 = q[1], m02 = q[2], m11 = q[4], m12 = q[5], m22 = q[7];
  const V4 m10 = m01, m20 = m02, m21 = m12;
  V4 m_mid[3];
  f.m.Times(f.mid, m_mid);
  f.residual[0] = -q[3] - m_mid[0], f.residual[1] = -q[6] - m_mid[1], f.residual[2] = -q[8] - m_mid[2];
  f.j00 = m11 * m22 - m12 * m21, f.j01 = m02 * m21 - m01 * m22, f.j02 = m01 * m12 - m02 * m11;
  f.j10 = m12 * m20 - m10 * m22, f.j11 = m00 * m22 - m02 * m20, f.j12 = m02 * m10 - m00 * m12;
  f.j20 = m10 * m21 - m11 * m20, f.j21 = m01 * m20 - m00 * m21, f.j22 = m00 * m11 - m01 * m10;
  f.trace = m00 + (m11 + m22);  // Eigen's trace(): the last two first
  f.minors = (f.j00 + f.j11) + f.j22;
  f.det = (m00 * f.j00 + m01 * f.j10) + m02 * f.j20;
  const V4 e0 = f.b[0] - f.a[0], e1 = f.b[1] - f.a[1], e2 = f.b[2] - f.a[2];
  f.reach2 = reach * reach * ((e0 * e0 + e1 * e1) + e2 * e2);
  f.some_pinned = f.minors > 1e-9 * f.trace * f.trace;
  f.first_test = f.some_pinned & (f.det > rcond * f.trace * f.minors);
  const V4* r = f.residual;
  f.p[0] = f.mid[0] + ((f.j00 * r[0] + f.j01 * r[1]) + f.j02 * r[2]) / f.det;
  f.p[1] = f.mid[1] + ((f.j10 * r[0] + f.j11 * r[1]) + f.j12 * r[2]) / f.det;
  f.p[2] = f.mid[2] + (f.j20 * r[0] + (f.j21 * r[1] + f.j22 * r[2])) / f.det;
  const V4 d0 = f.p[0] - f.mid[0], d1 = f.p[1] - f.mid[1], d2 = f.p[2] - f.mid[2];
  const V4 moved2 = (d0 * d0 + d1 * d1) + d2 * d2;
  f.in_reach = moved2 <= f.reach2;
  for (int k = 0; k < 4; ++k) {
    if (!(std::isfinite(f.p[0][k]) && std::isfinite(f.p[1][k]) && std::isfinite(f.p[2][k]))) f.in_reach[k] = 0;
  }
}

// Placement's second test (Newton's bounds on the extreme eigenvalues) for the lanes the first leaves;
// `first_step`: the step it takes from the trace towards the largest, where Placement keeps it.
__attribute__((always_inline)) inline M4 SecondTest4(const Front4& f, double rcond, V4* first_step) {
  const V4 trace = f.trace, minors = f.minors, det = f.det;
  const V4 below = det / minors;
  const V4 p_below = ((below - trace) * below + minors) * below - det;
  const V4 slope_below = (3.0 * below - 2.0 * trace) * below + minors;
  const V4 smallest_at_least = below - p_below / slope_below;
  const V4 value = ((trace - trace) * trace + minors) * trace - det;
  const V4 rise = (3.0 * trace - 2.0 * trace) * trace + minors;
  const V4 largest_at_most = trace - value / rise;
  const M4 second = f.some_pinned & ~f.first_test & (smallest_at_least > rcond * largest_at_most);
  if (first_step) {
    const M4 taken = f.some_pinned & ~f.first_test & ~second & (value > 0.0) & (rise > 0.0);
    *first_step = Select(taken, value / rise, V4{0, 0, 0, 0});
  }
  return second;
}

__attribute__((always_inline)) inline int PlaceFullRank4Body(const Lanes4& in, double reach, double rcond,
                                                             std::array<double, 4>& error) {
  Front4 f;
  Prepare4(in, reach, rcond, f);
  M4 full = f.first_test;
  if (Any(f.some_pinned & ~full)) full = full | SecondTest4(f, rcond, nullptr);
  const M4 done = full & f.in_reach;
  if (!Any(done)) return 0;
  const V4 err = Error4(f.q, f.p[0], f.p[1], f.p[2]);
  int bits = 0;
  for (int k = 0; k < 4; ++k) {
    if (done[k]) {
      bits |= 1 << k;
      error[k] = err[k];
    }
  }
  return bits;
}

// BestOnSegment's error, four wide.
__attribute__((always_inline)) inline V4 BestOnSegment4(const Front4& f) {
  const V4* q = f.q;
  const V4 ea = Error4(q, f.a[0], f.a[1], f.a[2]), eb = Error4(q, f.b[0], f.b[1], f.b[2]);
  const V4 em = Error4(q, f.mid[0], f.mid[1], f.mid[2]);
  const V4 c2 = 2.0 * ea - 4.0 * em + 2.0 * eb, c1 = -3.0 * ea + 4.0 * em - eb;
  V4 t = Select(ea <= eb, V4{0, 0, 0, 0}, V4{1, 1, 1, 1});
  const V4 v = -c1 / (2.0 * c2);  // std::clamp(v, 0, 1): v when NaN
  const V4 tm = Select(v < 0.0, V4{0, 0, 0, 0}, Select(1.0 < v, V4{1, 1, 1, 1}, v));
  const V4 lower = Select(eb < ea, eb, ea);  // std::min(ea, eb)
  t = Select((c2 > 0.0) & (ea + tm * c1 + tm * tm * c2 < lower), tm, t);
  const V4 x = f.a[0] + t * (f.b[0] - f.a[0]), y = f.a[1] + t * (f.b[1] - f.a[1]);
  const V4 z = f.a[2] + t * (f.b[2] - f.a[2]);
  return Select(t == 0.0, ea, Error4(q, x, y, z));
}

// Every path of Placement; a lane whose largest eigenvalue Newton's method does not settle (Placement
// then asks Eigen's closed form) is left out of the result's bits.
__attribute__((always_inline)) inline int PlaceAny4Body(const Lanes4& in, double reach, double rcond,
                                                        std::array<double, 4>& error) {
  Front4 f;
  Prepare4(in, reach, rcond, f);
  V4 first_step{0, 0, 0, 0};
  const M4 full = f.first_test | SecondTest4(f, rcond, &first_step);
  const V4 on_edge = BestOnSegment4(f);
  const V4 full_rank = Select(f.in_reach, Error4(f.q, f.p[0], f.p[1], f.p[2]), on_edge);
  // EigenvaluesAscending, for the other lanes: the largest by Newton's method from the trace.
  const V4 trace = f.trace, minors = f.minors, det = f.det;
  V4 l3 = trace - first_step;
  const M4 stepped = first_step > 0.0;
  M4 settled = full | (stepped & ~(first_step > 1e-13 * l3));
  for (int step = 0; step < 16; ++step) {
    // A lane that took the first step above has 15 left.
    const M4 active = ~settled & ~(stepped & (step == 15 ? M4{-1, -1, -1, -1} : M4{0, 0, 0, 0}));
    if (!Any(active)) break;
    const V4 value = ((l3 - trace) * l3 + minors) * l3 - det;
    const V4 slope = (3.0 * l3 - 2.0 * trace) * l3 + minors;
    const M4 rising = (value > 0.0) & (slope > 0.0);
    const V4 dx = value / slope;
    const V4 next = l3 - dx;
    l3 = Select(active & rising, next, l3);
    settled = settled | (active & ~rising) | (active & rising & ~(dx > 1e-13 * next));
  }
  const V4 sum12 = trace - l3, product12 = minors - l3 * sum12;
  V4 disc = sum12 * sum12 - 4.0 * product12;
  disc = Select(0.0 < disc, disc, V4{0, 0, 0, 0});  // std::max(0.0, disc)
  V4 root;
  for (int k = 0; k < 4; ++k) root[k] = std::sqrt(disc[k]);
  const V4 l2 = 0.5 * (sum12 + root);
  const V4 l1 = Select(l2 > 0.0, product12 / l2, V4{0, 0, 0, 0});
  const M4 closed_form = ~full & (~settled | ~(l2 <= l3));
  const V4 cut = rcond * l3;
  // TruncatedSolve: mid + f(m) r, f the polynomial that is 1/λ on the kept eigenvalues, 0 on the others.
  V4 m_r[3], u[3], m_u[3];
  f.m.Times(f.residual, m_r);
  for (int i = 0; i < 3; ++i) u[i] = m_r[i] - l1 * f.residual[i];
  f.m.Times(u, m_u);
  const M4 two_kept = l2 > cut;
  const V4 sum = l2 + l3, alpha = sum - l1, beta = sum * sum - l2 * l3 - l1 * sum;
  const V4 denominator2 = l2 * l3 * (l2 - l1) * (l3 - l1), denominator1 = l3 * (l3 - l1) * (l3 - l2);
  // Eigen folds the scalar of alpha (m u) into the matrix: (alpha m) u.
  const Sym4 alpha_m{alpha * f.m.m00, alpha * f.m.m01, alpha * f.m.m02,
                     alpha * f.m.m11, alpha * f.m.m12, alpha * f.m.m22};
  V4 alpha_m_u[3];
  alpha_m.Times(u, alpha_m_u);
  V4 pt[3];
  for (int i = 0; i < 3; ++i) {
    pt[i] =
        f.mid[i] + Select(two_kept, (beta * u[i] - alpha_m_u[i]) / denominator2, (m_u[i] - l2 * u[i]) / denominator1);
  }
  const V4 d0 = pt[0] - f.mid[0], d1 = pt[1] - f.mid[1], d2 = pt[2] - f.mid[2];
  M4 truncated_in_reach = (d0 * d0 + d1 * d1) + d2 * d2 <= f.reach2;
  for (int k = 0; k < 4; ++k) {
    if (!(std::isfinite(pt[0][k]) && std::isfinite(pt[1][k]) && std::isfinite(pt[2][k]))) truncated_in_reach[k] = 0;
  }
  const V4 truncated_error = Error4(f.q, pt[0], pt[1], pt[2]);
  const V4 truncated = Select(truncated_in_reach & (truncated_error < on_edge), truncated_error, on_edge);
  // Placement's choice: the plain inverse by either test, else the edge when no eigenvalue is positive,
  // else the plain inverse when nothing is truncated, else the truncated solve.
  const V4 result = Select(full, full_rank, Select(~(l3 > 0.0), on_edge, Select(l1 > cut, full_rank, truncated)));
  int bits = 0;
  for (int k = 0; k < 4; ++k) {
    if (!closed_form[k]) {
      bits |= 1 << k;
      error[k] = result[k];
    }
  }
  return bits;
}

__attribute__((target("avx2"))) inline int PlaceFullRank4Avx2(const Lanes4& in, double reach, double rcond,
                                                              std::array<double, 4>& error) {
  return PlaceFullRank4Body(in, reach, rcond, error);
}

inline int PlaceFullRank4Generic(const Lanes4& in, double reach, double rcond, std::array<double, 4>& error) {
  return PlaceFullRank4Body(in, reach, rcond, error);
}

__attribute__((target("avx2"))) inline int PlaceAny4Avx2(const Lanes4& in, double reach, double rcond,
                                                         std::array<double, 4>& error) {
  return PlaceAny4Body(in, reach, rcond, error);
}

inline int PlaceAny4Generic(const Lanes4& in, double reach, double rcond, std::array<double, 4>& error) {
  return PlaceAny4Body(in, reach, rcond, error);
}
}  // namespace placement_detail

// Bit k set: lane k is done, error[k] its quadric error at Placement's point (the others untouched).
// `wide`: the AVX2 path (when the CPU has it), else the portable one; the same bits either way.
inline int PlaceFullRank4(const Lanes4& in, double reach, double rcond, std::array<double, 4>& error,
                          bool wide = CpuHasAvx2()) {
  return wide ? placement_detail::PlaceFullRank4Avx2(in, reach, rcond, error)
              : placement_detail::PlaceFullRank4Generic(in, reach, rcond, error);
}

// As PlaceFullRank4, on every path of Placement but Eigen's closed-form eigenvalues (rare).
inline int PlaceAny4(const Lanes4& in, double reach, double rcond, std::array<double, 4>& error,
                     bool wide = CpuHasAvx2()) {
  return wide ? placement_detail::PlaceAny4Avx2(in, reach, rcond, error)
              : placement_detail::PlaceAny4Generic(in, reach, rcond, error);
}

}  // namespace cinepath::photogrammetry::internal
