#include "photogrammetry/mesh_distance.h"

#include <algorithm>
#include <vector>

#include <CGAL/Polygon_mesh_processing/distance.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>

#include "core/error.h"
#include "photogrammetry/cgal_mesh_internal.h"

namespace cinepath::photogrammetry {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using internal::SurfaceMesh;

SurfaceMesh SurfaceMeshOf(const TriangleMesh& mesh, const char* name) {
  std::vector<internal::Point3> points = internal::PointsOf(mesh);
  std::vector<std::array<std::size_t, 3>> polygons;
  polygons.reserve(mesh.num_faces());
  for (const auto& f : internal::FacesWithDistinctCorners(mesh)) {
    if (f[0] >= points.size() || f[1] >= points.size() || f[2] >= points.size()) continue;
    polygons.push_back({f[0], f[1], f[2]});
  }
  if (polygons.empty()) throw InputError(std::string("hausdorff: mesh ") + name + " has no face");
  if (!internal::IsOrientedManifoldTriangleSoup(polygons, points.size())) PMP::orient_polygon_soup(points, polygons);
  SurfaceMesh sm;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, sm);
  return sm;
}

double OneSided(const SurfaceMesh& from, const SurfaceMesh& to, const HausdorffOptions& options) {
  // Samples: the vertices plus `samples_per_mesh` uniform random points on the faces (seeded).
  // CGAL 5.5 seeds only the choice of the face with random_seed: the point inside the face comes
  // from CGAL::get_default_random() (Generic_random_point_generator constructs
  // Random_points_in_triangle_3 without the seeded generator). Seed that one too, for this call,
  // so the same meshes always give the same distance. Sampling runs on this thread (the default
  // generator is thread-local); only the distance queries are parallel.
  struct DefaultRandomSeed {
    CGAL::Random saved = CGAL::get_default_random();
    explicit DefaultRandomSeed(uint32_t seed) { CGAL::get_default_random() = CGAL::Random(seed); }
    ~DefaultRandomSeed() { CGAL::get_default_random() = saved; }
  } default_random_seed(options.seed);
  return PMP::approximate_Hausdorff_distance<CGAL::Parallel_if_available_tag>(
      from, to,
      CGAL::parameters::number_of_points_on_faces(static_cast<std::size_t>(
                                                      std::max<int64_t>(1, options.samples_per_mesh)))
          .random_seed(options.seed)
          .do_sample_edges(false),
      CGAL::parameters::default_values());
}

}  // namespace

HausdorffDistance ApproximateHausdorff(const TriangleMesh& a, const TriangleMesh& b,
                                       const HausdorffOptions& options) {
  const SurfaceMesh sa = SurfaceMeshOf(a, "A");
  const SurfaceMesh sb = SurfaceMeshOf(b, "B");
  HausdorffDistance d;
  d.a_to_b_m = OneSided(sa, sb, options);
  d.b_to_a_m = OneSided(sb, sa, options);
  d.symmetric_m = std::max(d.a_to_b_m, d.b_to_a_m);
  return d;
}

}  // namespace cinepath::photogrammetry
