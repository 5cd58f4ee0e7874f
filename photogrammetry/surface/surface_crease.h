// Two planes meeting at a crease, fitted to the points around a surface vertex: where the foot of a
// cliff meets the ground, or its top edge the plateau, the points near the edge lie on two planes, and
// no single plane fits them. A smooth surface (Poisson's implicit function) rounds such an edge over a
// metre or two; the points themselves keep it sharp. FitCrease finds the two planes (RANSAC: one plane,
// then a second among the points the first leaves), checks that they describe an edge, and gives the
// nearest point to a query on the surface they bound: each plane is kept only on the side of the other
// plane where its own points lie (a half-plane), so the answer is correct at a convex edge (the top of a
// cliff: the rounded surface cuts inside the corner) and at a concave one (its foot: the rounded surface
// fills the corner), and never lies on a plane's extension past the edge.
//
// Deterministic: the random samples come from `seed` alone (the caller passes the vertex's index).
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace cinepath::photogrammetry {

struct CreaseFitOptions {
  double tolerance_m = 0;             // a point is on a plane when within this distance of it (> 0)
  int min_points_per_plane = 6;       // each plane must carry at least this many points
  double min_share_explained = 0.85;  // of all the points, the share on one of the two planes
  double min_share_one_plane = 0.75;  // one plane and strays: the share on the plane
  double min_angle_deg = 25;          // the planes must meet at least at this angle (else: one plane)
  double min_side_agreement = 0.8;    // the share of a plane's points (off the edge) on its own side of the other
  int trials = 48;                    // RANSAC samples for each plane
};

struct CreaseFit {
  // 2: the points lie on two planes meeting at an edge; 1: on one plane (a), but for fewer strays than
  // a second plane needs; 0: neither (`refused` says why).
  int planes = 0;
  const char* refused = "";
  Eigen::Vector3d normal_a = Eigen::Vector3d::UnitZ(), normal_b = Eigen::Vector3d::UnitZ();  // unit
  double offset_a = 0, offset_b = 0;  // plane k: normal_k · x = offset_k
  // Side of plane b where a's points lie (±1), and the side of plane a where b's points lie.
  double side_a_of_b = 1, side_b_of_a = 1;
  int points_a = 0, points_b = 0;  // points on each plane (a point on both counts for each)
  double angle_deg = 0;            // between the planes (0..90)
  CreaseFit& Refused(const char* why) {
    refused = why;
    planes = 0;
    return *this;
  }
};

// The surface `points` define around `query`: two planes, or one plane that carries most of them and the point
// nearest to the query (a robust plane: RANSAC keeps a few strays off it, a least-squares fit would tilt).
CreaseFit FitCrease(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& query,
                    const CreaseFitOptions& options, uint64_t seed);

// The nearest point to `query` on the two half-planes of a fit of two planes, or on the plane of a fit of one.
Eigen::Vector3d NearestOnCrease(const CreaseFit& fit, const Eigen::Vector3d& query);

}  // namespace cinepath::photogrammetry
