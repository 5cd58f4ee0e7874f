#include "scene/border_ring.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>

#include <tbb/parallel_sort.h>

namespace cinepath::scene {

int SectorOf(const Eigen::Vector2d& offset_m) {
  const int n = BorderRing::kSectors;
  return int(std::floor((std::atan2(offset_m.y(), offset_m.x()) + M_PI) / (2 * M_PI) * n)) % n;
}

namespace {

// The edges only one face has, as (smaller vertex, larger vertex, face), sorted.
void BorderEdges(const SceneMesh& mesh, std::vector<std::array<uint32_t, 3>>* border) {
  std::vector<std::array<uint32_t, 3>> edges;  // (smaller vertex, larger vertex, face)
  edges.reserve(3 * mesh.faces.size());
  for (uint32_t f = 0; f < mesh.faces.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = mesh.faces[f][size_t(k)], b = mesh.faces[f][size_t((k + 1) % 3)];
      edges.push_back({std::min(a, b), std::max(a, b), f});
    }
  }
  tbb::parallel_sort(edges.begin(), edges.end());  // 3 per face: a tenth of a second at 1 M faces
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j][0] == edges[i][0] && edges[j][1] == edges[i][1]) ++j;
    if (j - i == 1) border->push_back(edges[i]);
    i = j;
  }
}

Eigen::Vector2d Centroid(const SceneMesh& mesh, uint32_t face) {
  const auto& f = mesh.faces[face];
  return ((mesh.positions_enu_m[f[0]] + mesh.positions_enu_m[f[1]] + mesh.positions_enu_m[f[2]]) / 3.0).head<2>();
}

double Median(std::vector<double> values) {
  std::nth_element(values.begin(), values.begin() + long(values.size() / 2), values.end());
  return values[values.size() / 2];
}

}  // namespace

BorderRing FindBorderRing(const SceneMesh& mesh) {
  BorderRing ring;
  if (mesh.faces.empty()) return ring;
  std::vector<std::array<uint32_t, 3>> border;
  BorderEdges(mesh, &border);
  std::vector<uint32_t> candidates;
  for (const auto& e : border) candidates.push_back(e[2]);
  if (candidates.empty()) {  // closed: every face, at the lowest vertex
    candidates.resize(mesh.faces.size());
    std::iota(candidates.begin(), candidates.end(), 0u);
  }
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  for (uint32_t f : candidates) ring.centre_m += Centroid(mesh, f);
  ring.centre_m /= double(candidates.size());
  // The outer band of each sector: a hole's border inside the mesh is not where the mesh ends.
  std::vector<double> radius(candidates.size());
  std::vector<int> sector(candidates.size());
  std::vector<double> outermost(size_t(BorderRing::kSectors), 0.0);
  for (size_t i = 0; i < candidates.size(); ++i) {
    const Eigen::Vector2d offset = Centroid(mesh, candidates[i]) - ring.centre_m;
    radius[i] = offset.norm();
    sector[i] = SectorOf(offset);
    outermost[size_t(sector[i])] = std::max(outermost[size_t(sector[i])], radius[i]);
  }
  std::vector<double> kept_radius;
  for (size_t i = 0; i < candidates.size(); ++i) {
    const double far = outermost[size_t(sector[i])];
    if (radius[i] < far - std::max(BorderRing::kMinBand_m, BorderRing::kBandFraction * far)) continue;
    ring.faces.push_back(candidates[i]);
    ring.sectors.push_back(sector[i]);
    kept_radius.push_back(radius[i]);
  }
  ring.radius_m = Median(kept_radius);
  std::vector<double> heights;
  for (const auto& e : border) {
    if (!std::binary_search(ring.faces.begin(), ring.faces.end(), e[2])) continue;
    heights.push_back(mesh.positions_enu_m[e[0]].z());
    heights.push_back(mesh.positions_enu_m[e[1]].z());
  }
  if (heights.empty()) {
    ring.height_m = std::numeric_limits<double>::infinity();
    for (const auto& p : mesh.positions_enu_m) ring.height_m = std::min(ring.height_m, p.z());
  } else {
    ring.height_m = Median(heights);
  }
  return ring;
}

std::vector<Eigen::Vector3f> SectorColors(const BorderRing& ring, const std::vector<Eigen::Vector3f>& face_colors,
                                          const Eigen::Vector3f& fallback, Eigen::Vector3f* mean) {
  const int n = BorderRing::kSectors;
  std::vector<Eigen::Vector3d> sum(size_t(n), Eigen::Vector3d::Zero());
  std::vector<int> count(size_t(n), 0);
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < ring.sectors.size() && i < face_colors.size(); ++i) {
    sum[size_t(ring.sectors[i])] += face_colors[i].cast<double>();
    ++count[size_t(ring.sectors[i])];
  }
  for (int k = 0; k < n; ++k) total += sum[size_t(k)];
  if (mean)
    *mean = face_colors.empty() ? fallback : Eigen::Vector3f((total / double(face_colors.size())).cast<float>());
  std::vector<Eigen::Vector3f> colors(size_t(n), fallback);
  for (int k = 0; k < n; ++k) {
    if (count[size_t(k)] > 0) {
      colors[size_t(k)] = (sum[size_t(k)] / count[size_t(k)]).cast<float>();
      continue;
    }
    int lo = 1, hi = 1;
    while (lo < n && count[size_t((k - lo + n) % n)] == 0) ++lo;
    while (hi < n && count[size_t((k + hi) % n)] == 0) ++hi;
    if (lo >= n) break;  // no face at all: the fallback stays
    const Eigen::Vector3d a = sum[size_t((k - lo + n) % n)] / count[size_t((k - lo + n) % n)];
    const Eigen::Vector3d b = sum[size_t((k + hi) % n)] / count[size_t((k + hi) % n)];
    colors[size_t(k)] = ((hi * a + lo * b) / double(lo + hi)).cast<float>();
  }
  // Smoothed around the ring (a triangle of +-kSmoothSectors): one odd sector must not fan out as a streak.
  std::vector<Eigen::Vector3f> smooth(colors.size());
  const int r = BorderRing::kSmoothSectors;
  for (int k = 0; k < n; ++k) {
    Eigen::Vector3d sum_k = Eigen::Vector3d::Zero();
    double weight = 0;
    for (int d = -r; d <= r; ++d) {
      const double w = r + 1 - std::abs(d);
      sum_k += w * colors[size_t((k + d + n) % n)].cast<double>();
      weight += w;
    }
    smooth[size_t(k)] = (sum_k / weight).cast<float>();
  }
  return smooth;
}

}  // namespace cinepath::scene
