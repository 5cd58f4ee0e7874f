// Screened-free (classic) Poisson surface reconstruction with CGAL (Kazhdan et al. 2006, CGAL's
// Poisson_reconstruction_function + Delaunay-refinement meshing). Normals come from the cloud, or
// are estimated by jet fitting (CGAL jet_estimate_normals) and oriented toward the cameras that
// observed each point (COLMAP tracks: PointCloud.observers / camera_centers_m); points without
// observations are oriented up. Poisson closes every surface: triangles far from any input point
// (more than trim_factor × the average spacing) are trimmed away.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/json.h"
#include "photogrammetry/io/point_cloud.h"
#include "photogrammetry/mesh/triangle_mesh.h"

namespace cinepath::photogrammetry {

struct PoissonOptions {
  int normal_neighbours = 18;  // k for jet normal estimation and for the average spacing
  // Meshing criteria (CGAL: facet angle in degrees, radius and distance relative to the spacing).
  double angle_deg = 20.0;
  double radius_factor = 1.0;  // CGAL example: 30, far too coarse for terrain detail
  double distance_factor = 0.375;
  // Spacing multiplier: > 1 gives a coarser (faster) surface.
  double spacing_factor = 1.0;
  double trim_factor = 3.0;  // 0 = no trimming
  // Seed of CGAL's default generator, from which the surface mesher draws its first points. Any value
  // gives a valid surface; a fixed one gives the same surface for the same input in a fresh process
  // (within one process CGAL's Poisson solver also follows the allocator's addresses: docs/mesh.md).
  unsigned int seed = 20240611;
  // Points closer than this fraction of the cloud's size (the larger of its bounding-box diagonal and its
  // largest coordinate) to an earlier point are merged into it before the solver runs (see
  // MergeCoincidentPoints). 0 turns the guard off (tests only: CGAL then divides by zero).
  double coincident_distance_ratio = 1e-6;
};

struct PoissonReport {
  int64_t points = 0;
  int64_t coincident_points_merged = 0;  // points within coincident_distance_m of an earlier point
  double coincident_distance_m = 0;
  bool normals_estimated = false;
  int64_t normals_flipped_toward_cameras = 0, normals_oriented_up = 0;
  double average_spacing_m = 0;
  int64_t faces_reconstructed = 0, faces_trimmed = 0, faces_out = 0;
  Json ToJson() const;
};

// Why CGAL's Poisson solver cannot take these points, or nothing when it can: fewer than 10 finite points,
// or points that span no volume (all on one plane, one line or one point). On such a cloud CGAL's Delaunay
// refinement runs on a triangulation of dimension < 3 and fails a precondition, reads its infinite cell
// out of bounds or divides by zero: a signal, not an error. Decided with exact predicates, as CGAL's
// triangulation decides its own dimension, so every cloud this accepts gives a 3D triangulation.
std::optional<std::string> PoissonInputProblem(const PointCloud& cloud);

// Coincident points. COLMAP's mapper leaves the same 3D point twice under two ids (two tracks of one
// feature, triangulated alike): the oblique house model has 191 such pairs at exactly the same
// position, and others 4e-16 m apart. CGAL's Poisson solver refines its Delaunay triangulation by
// inserting the circumcentre of each bad cell, rounded to doubles, as a point in conflict with that
// cell; around two points a few ulps apart the cells shrink until the rounded circumcentre lies outside
// the cell's own sphere (CGAL_MESHES_DEBUG_REFINEMENT_POINTS: "circumcenter out of sphere!"), the
// insertion corrupts the triangulation, and the exact circumcentre of a now flat cell divides by zero
// (GMP raises SIGFPE). No try/catch sees it. Such points carry no more surface than one of them, so each
// point within `tolerance_m` of an earlier one (in input order) is merged into it: returns, for each
// point, the index of the point it is merged into (itself when kept). Positions that are not finite are
// kept as they are (the caller skips them).
std::vector<uint32_t> MergeCoincidentPoints(const std::vector<Eigen::Vector3d>& positions_m, double tolerance_m);

// Throws InputError when PoissonInputProblem names a problem, RuntimeError if the Poisson solver fails.
// Colours: the vertices take the colour of their nearest input point.
TriangleMesh PoissonSurface(const PointCloud& cloud, const PoissonOptions& options, PoissonReport* report);

}  // namespace cinepath::photogrammetry
