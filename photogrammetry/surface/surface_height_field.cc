#include "photogrammetry/surface/surface_height_field.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>
#include <utility>
#include <vector>

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include "core/error.h"

namespace cinepath::photogrammetry {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<uint32_t, Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase>;
using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, Tds>;
using Point2 = Kernel::Point_2;

double Median(std::vector<double> values) {
  if (values.empty()) return 0;
  const size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + mid, values.end());
  return values[mid];
}

void Triangulate(const PointCloud& cloud, const std::vector<uint32_t>& indices, Delaunay& dt) {
  std::vector<std::pair<Point2, uint32_t>> input;
  input.reserve(indices.size());
  for (uint32_t i : indices) {
    input.emplace_back(Point2(cloud.positions_m[i].x(), cloud.positions_m[i].y()), i);
  }
  dt.clear();
  dt.insert(input.begin(), input.end());
}

// The indices of the points with finite coordinates; throws when fewer than 3.
std::vector<uint32_t> UsableIndices(const PointCloud& cloud) {
  const auto& p = cloud.positions_m;
  std::vector<uint32_t> indices;
  for (uint32_t i = 0; i < cloud.size(); ++i) {
    if (p[i].allFinite()) indices.push_back(i);
  }
  if (indices.size() < 3) {
    throw InputError("height field: fewer than 3 usable points (" + std::to_string(indices.size()) + ")");
  }
  return indices;
}

// The thinning grid's cell size: 0 (no thinning) unless there are more than `options.max_points` points.
double ThinningCellM(const std::vector<Eigen::Vector3d>& p, const std::vector<uint32_t>& indices,
                     const HeightFieldOptions& options) {
  double cell_m = 0;
  if (options.max_points > 0 && static_cast<int64_t>(indices.size()) > options.max_points) {
    Eigen::Vector2d lo = p[indices[0]].head<2>(), hi = lo;
    for (uint32_t i : indices) {
      lo = lo.cwiseMin(p[i].head<2>());
      hi = hi.cwiseMax(p[i].head<2>());
    }
    const double area = std::max((hi - lo).prod(), 1e-12);
    cell_m = std::sqrt(area / static_cast<double>(options.max_points));
  }
  return cell_m;
}

// One point per (e, n) position: equal positions keep the median height (lowest index on ties).
// With thinning (cell_m > 0), the positions are grid cells instead of exact coordinates.
void KeepOnePerPosition(const std::vector<Eigen::Vector3d>& p, double cell_m, std::vector<uint32_t>& indices,
                        HeightFieldReport& report) {
  using Key = std::tuple<double, double>;
  auto key_of = [&](uint32_t i) -> Key {
    if (cell_m > 0) return {std::floor(p[i].x() / cell_m), std::floor(p[i].y() / cell_m)};
    return {p[i].x(), p[i].y()};
  };
  std::vector<std::pair<Key, uint32_t>> keyed;
  keyed.reserve(indices.size());
  for (uint32_t i : indices) keyed.emplace_back(key_of(i), i);
  std::sort(keyed.begin(), keyed.end(), [&](const auto& a, const auto& b) {
    if (a.first != b.first) return a.first < b.first;
    if (p[a.second].z() != p[b.second].z()) return p[a.second].z() < p[b.second].z();
    return a.second < b.second;
  });
  std::vector<uint32_t> kept;
  for (size_t begin = 0; begin < keyed.size();) {
    size_t end = begin + 1;
    while (end < keyed.size() && keyed[end].first == keyed[begin].first) ++end;
    kept.push_back(keyed[begin + (end - begin - 1) / 2].second);
    (cell_m > 0 ? report.points_thinned : report.duplicate_xy_points) += static_cast<int64_t>(end - begin - 1);
    begin = end;
  }
  std::sort(kept.begin(), kept.end());
  indices.swap(kept);
}

// Each interior vertex's height deviation from the median height of its Delaunay neighbours.
std::vector<std::pair<uint32_t, double>> NeighbourDeviations(const std::vector<Eigen::Vector3d>& p, const Delaunay& dt,
                                                             size_t num_points) {
  std::vector<std::pair<uint32_t, double>> deviation;
  deviation.reserve(num_points);
  for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) {
    // Hull vertices are skipped: their neighbours all lie to one side, so on a slope the
    // median of their heights is biased.
    std::vector<double> neighbours;
    bool on_hull = false;
    auto c = dt.incident_vertices(v), done = c;
    do {
      if (dt.is_infinite(c))
        on_hull = true;
      else
        neighbours.push_back(p[c->info()].z());
    } while (++c != done);
    if (on_hull || neighbours.size() < 3) continue;
    deviation.emplace_back(v->info(), std::abs(p[v->info()].z() - Median(neighbours)));
  }
  return deviation;
}

// Spikes: height far from the median of the Delaunay neighbours. Removes them and triangulates again.
void RemoveSpikes(const PointCloud& cloud, const HeightFieldOptions& options, std::vector<uint32_t>& indices,
                  Delaunay& dt, HeightFieldReport& report) {
  const std::vector<std::pair<uint32_t, double>> deviation = NeighbourDeviations(cloud.positions_m, dt, indices.size());
  std::vector<double> all;
  all.reserve(deviation.size());
  for (const auto& d : deviation) all.push_back(d.second);
  const double threshold = std::max(options.spike_min_m, options.spike_factor * Median(all));
  std::vector<uint32_t> spikes;
  for (const auto& d : deviation) {
    if (d.second > threshold) spikes.push_back(d.first);
  }
  if (spikes.empty()) return;
  std::sort(spikes.begin(), spikes.end());
  std::vector<uint32_t> kept;
  std::set_difference(indices.begin(), indices.end(), spikes.begin(), spikes.end(), std::back_inserter(kept));
  report.spikes_removed = static_cast<int64_t>(spikes.size());
  indices.swap(kept);
  Triangulate(cloud, indices, dt);
  if (dt.dimension() < 2) throw InputError("height field: the points are collinear in (e, n)");
}

// The median and percentile horizontal edge lengths into `report`; returns the long-edge limit.
double MaxEdgeM(const Delaunay& dt, const HeightFieldOptions& options, HeightFieldReport& report) {
  std::vector<double> edge_lengths;
  for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e) {
    edge_lengths.push_back(std::sqrt(dt.segment(*e).squared_length()));
  }
  report.median_edge_m = Median(edge_lengths);
  if (!edge_lengths.empty()) {
    const double q = std::clamp(options.max_edge_percentile, 0.0, 100.0) / 100.0;
    const size_t k =
        std::min(edge_lengths.size() - 1, static_cast<size_t>(q * static_cast<double>(edge_lengths.size() - 1)));
    std::nth_element(edge_lengths.begin(), edge_lengths.begin() + k, edge_lengths.end());
    report.percentile_edge_m = edge_lengths[k];
  }
  const double max_edge_m = options.max_edge_factor * report.percentile_edge_m;
  report.max_edge_m = max_edge_m;
  return max_edge_m;
}

// The Delaunay faces without an edge over `max_edge_m` (as point indices, lowest first), sorted.
std::vector<std::array<uint32_t, 3>> TrimmedFaces(const Delaunay& dt, const HeightFieldOptions& options,
                                                  double max_edge_m, HeightFieldReport& report) {
  std::vector<std::array<uint32_t, 3>> faces;
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) {
    ++report.triangles;
    double longest = 0;
    for (int k = 0; k < 3; ++k) {
      longest =
          std::max(longest, std::sqrt(CGAL::squared_distance(f->vertex(k)->point(), f->vertex((k + 1) % 3)->point())));
    }
    if (options.max_edge_factor > 0 && longest > max_edge_m) {
      ++report.long_edge_triangles_trimmed;
      continue;
    }
    // CGAL's 2D faces are counter-clockwise in (e, n): seen from above, the normal points up.
    std::array<uint32_t, 3> tri{f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()};
    std::rotate(tri.begin(), std::min_element(tri.begin(), tri.end()), tri.end());
    faces.push_back(tri);
  }
  std::sort(faces.begin(), faces.end());
  return faces;
}

// The mesh of `faces`: the used points, in input order.
TriangleMesh MeshOfFaces(const PointCloud& cloud, const std::vector<std::array<uint32_t, 3>>& faces) {
  const auto& p = cloud.positions_m;
  TriangleMesh mesh;
  std::vector<int64_t> remap(cloud.size(), -1);
  for (const auto& f : faces) {
    for (uint32_t i : f) remap[i] = 0;
  }
  for (uint32_t i = 0; i < cloud.size(); ++i) {
    if (remap[i] < 0) continue;
    remap[i] = static_cast<int64_t>(mesh.vertices_m.size());
    mesh.vertices_m.push_back(p[i]);
    if (cloud.has_colors()) mesh.colors_rgb.push_back(cloud.colors_rgb[i]);
  }
  mesh.faces.reserve(faces.size());
  for (const auto& f : faces) {
    mesh.faces.push_back(
        {static_cast<uint32_t>(remap[f[0]]), static_cast<uint32_t>(remap[f[1]]), static_cast<uint32_t>(remap[f[2]])});
  }
  return mesh;
}

}  // namespace

Json HeightFieldReport::ToJson() const {
  Json j;
  j["points_in"] = points_in;
  j["points_thinned"] = points_thinned;
  j["duplicate_xy_points"] = duplicate_xy_points;
  j["spikes_removed"] = spikes_removed;
  j["triangles"] = triangles;
  j["long_edge_triangles_trimmed"] = long_edge_triangles_trimmed;
  j["median_edge_m"] = median_edge_m;
  j["percentile_edge_m"] = percentile_edge_m;
  j["max_edge_m"] = max_edge_m;
  j["faces_out"] = faces_out;
  return j;
}

TriangleMesh HeightFieldSurface(const PointCloud& cloud, const HeightFieldOptions& options,
                                HeightFieldReport* report_out) {
  HeightFieldReport report;
  report.points_in = static_cast<int64_t>(cloud.size());
  std::vector<uint32_t> indices = UsableIndices(cloud);
  const double cell_m = ThinningCellM(cloud.positions_m, indices, options);
  KeepOnePerPosition(cloud.positions_m, cell_m, indices, report);

  Delaunay dt;
  Triangulate(cloud, indices, dt);
  if (dt.dimension() < 2) throw InputError("height field: the points are collinear in (e, n)");
  RemoveSpikes(cloud, options, indices, dt, report);

  // Long-edge trimming relative to the median horizontal edge length.
  const double max_edge_m = MaxEdgeM(dt, options, report);
  const std::vector<std::array<uint32_t, 3>> faces = TrimmedFaces(dt, options, max_edge_m, report);

  TriangleMesh mesh = MeshOfFaces(cloud, faces);
  report.faces_out = static_cast<int64_t>(mesh.num_faces());
  if (report_out) *report_out = report;
  return mesh;
}

}  // namespace cinepath::photogrammetry
