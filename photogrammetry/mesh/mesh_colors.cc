#include "photogrammetry/mesh/mesh_colors.h"

#include <cmath>

#include <tbb/parallel_for.h>

#include "core/error.h"
#include "photogrammetry/surface/cgal_point_search_internal.h"

namespace cinepath::photogrammetry {

void ColorVerticesFromPoints(TriangleMesh& mesh, const PointCloud& cloud, int neighbours) {
  if (!cloud.has_colors() || cloud.colors_rgb.size() != cloud.size()) {
    throw InputError("colours: the point cloud has no colours");
  }
  const internal::PointSearch search(cloud.positions_m);
  if (search.size() == 0) throw InputError("colours: the point cloud has no finite point");
  mesh.colors_rgb.assign(mesh.num_vertices(), {0, 0, 0});
  tbb::parallel_for(size_t{0}, mesh.num_vertices(), [&](size_t v) {
    const auto nearest = search.Nearest(mesh.vertices_m[v], neighbours);
    double sum[3] = {0, 0, 0};
    double weight_sum = 0;
    for (const auto& [squared_distance, index] : nearest) {
      // Inverse distance; an exact hit dominates (1e-12 m² floor keeps the weight finite).
      const double w = 1.0 / std::max(std::sqrt(squared_distance), 1e-6);
      for (int c = 0; c < 3; ++c) sum[c] += w * cloud.colors_rgb[index][c];
      weight_sum += w;
    }
    for (int c = 0; c < 3; ++c) {
      mesh.colors_rgb[v][c] = static_cast<uint8_t>(std::clamp<long>(std::lround(sum[c] / weight_sum), 0, 255));
    }
  });
}

}  // namespace cinepath::photogrammetry
