#include "photogrammetry/texture/texture_view_selection.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "scene/ray_caster.h"

namespace cinepath::photogrammetry {
namespace {

// Whether anything lies between `point` and the camera centre (the face itself excluded by starting a
// little off it).
bool Hidden(const scene::RayCaster& caster, const Eigen::Vector3d& point, const Eigen::Vector3d& centre) {
  const Eigen::Vector3d d = centre - point;
  const double length = d.norm();
  if (length <= 0) return true;
  const double start = 1e-3 + 1e-5 * length;
  return caster.Occluded(point, d / length, start, length - start);
}

FaceView Evaluate(const TriangleMesh& mesh, uint32_t f, const TextureView& view, int index,
                  const scene::RayCaster& caster, const ViewSelectionOptions& options) {
  const auto& face = mesh.faces[f];
  const Eigen::Vector3d& a = mesh.vertices_m[face[0]];
  const Eigen::Vector3d& b = mesh.vertices_m[face[1]];
  const Eigen::Vector3d& c = mesh.vertices_m[face[2]];
  const Eigen::Vector3d cross = (b - a).cross(c - a);
  const double double_area = cross.norm();
  if (!(double_area > 0)) return {};
  const Eigen::Vector3d normal = cross / double_area;
  const Eigen::Vector3d centroid = (a + b + c) / 3;
  const Eigen::Vector3d to_camera = view.centre_m() - centroid;
  const double cosine = normal.dot(to_camera) / to_camera.norm();
  if (!(cosine > options.min_cosine)) return {};
  std::array<Eigen::Vector2d, 3> px;
  for (int k = 0; k < 3; ++k) {
    if (!view.Project(mesh.vertices_m[face[k]], &px[k]) || !view.Inside(px[k], options.margin_px)) return {};
  }
  const double area_px =
      0.5 * std::abs((px[1] - px[0]).x() * (px[2] - px[0]).y() - (px[1] - px[0]).y() * (px[2] - px[0]).x());
  if (!(area_px > 0)) return {};
  if (Hidden(caster, centroid, view.centre_m())) return {};
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d near_corner = 0.8 * mesh.vertices_m[face[k]] + 0.2 * centroid;
    if (Hidden(caster, near_corner, view.centre_m())) return {};
  }
  return {index, float(area_px * cosine)};
}

double DataCost(const std::vector<FaceView>& candidates, int view, float best) {
  for (const FaceView& c : candidates) {
    if (c.view == view) return 1.0 - double(c.quality) / double(best);
  }
  return 1e9;
}

}  // namespace

std::vector<std::pair<uint32_t, uint32_t>> FaceEdgeNeighbours(const TriangleMesh& mesh) {
  // (smaller vertex, larger vertex, face) for every face edge, sorted: faces of one edge end up together.
  std::vector<std::array<uint32_t, 3>> edges;
  edges.reserve(3 * mesh.num_faces());
  for (uint32_t f = 0; f < mesh.num_faces(); ++f) {
    const auto& t = mesh.faces[f];
    for (int k = 0; k < 3; ++k) {
      const uint32_t i = t[k], j = t[(k + 1) % 3];
      edges.push_back({std::min(i, j), std::max(i, j), f});
    }
  }
  std::sort(edges.begin(), edges.end());
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  for (size_t s = 0; s < edges.size();) {
    size_t e = s;
    while (e < edges.size() && edges[e][0] == edges[s][0] && edges[e][1] == edges[s][1]) ++e;
    for (size_t i = s; i < e; ++i) {
      for (size_t j = i + 1; j < e; ++j) {
        if (edges[i][2] != edges[j][2]) pairs.emplace_back(edges[i][2], edges[j][2]);
      }
    }
    s = e;
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

int RemoveInconsistentViews(uint32_t face, std::vector<FaceView>* candidates, const FaceColorFn& face_color,
                            const PhotoConsistencyOptions& options) {
  if (!options.enabled || static_cast<int>(candidates->size()) < std::max(options.min_views, 3)) return 0;
  std::vector<Eigen::Vector3f> color(candidates->size());
  std::vector<bool> sampled(candidates->size());
  std::array<std::vector<float>, 3> channel;
  for (size_t i = 0; i < candidates->size(); ++i) {
    Eigen::Vector3f linear;
    sampled[i] = face_color(face, (*candidates)[i].view, &linear);
    if (!sampled[i]) continue;
    color[i] = linear.cwiseMax(0.0f).cwiseSqrt();
    for (int c = 0; c < 3; ++c) channel[size_t(c)].push_back(color[i][c]);
  }
  const size_t n = channel[0].size();
  if (static_cast<int>(n) < std::max(options.min_views, 3)) return 0;
  auto median = [](std::vector<float> v) {
    const size_t mid = v.size() / 2;
    std::nth_element(v.begin(), v.begin() + mid, v.end());
    const float upper = v[mid];
    if (v.size() % 2) return upper;
    return 0.5f * (upper + *std::max_element(v.begin(), v.begin() + mid));
  };
  const Eigen::Vector3f consensus(median(channel[0]), median(channel[1]), median(channel[2]));
  std::vector<float> distance;
  for (size_t i = 0; i < candidates->size(); ++i) {
    if (sampled[i]) distance.push_back((color[i] - consensus).norm());
  }
  const double spread = 1.4826 * median(distance);
  const double limit = std::max(options.min_deviation, options.spread_factor * spread);
  int dropped = 0;
  std::vector<FaceView> kept;
  for (size_t i = 0; i < candidates->size(); ++i) {
    // A photo that cannot be sampled (its corner samples leave the image) keeps its place.
    if (sampled[i] && (color[i] - consensus).norm() > limit) {
      ++dropped;
    } else {
      kept.push_back((*candidates)[i]);
    }
  }
  *candidates = std::move(kept);
  return dropped;
}

ViewSelection SelectViews(const TriangleMesh& mesh, const std::vector<TextureView>& views,
                          const scene::RayCaster& caster, const ViewSelectionOptions& options,
                          const FaceColorFn* face_color) {
  const size_t n = mesh.num_faces();
  ViewSelection out;
  out.candidates.resize(n);
  out.label.assign(n, -1);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 64), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t f = range.begin(); f < range.end(); ++f) {
      for (size_t v = 0; v < views.size(); ++v) {
        const FaceView fv = Evaluate(mesh, uint32_t(f), views[v], int(v), caster, options);
        if (fv.view >= 0) out.candidates[f].push_back(fv);
      }
    }
  });
  if (face_color != nullptr && options.consistency.enabled) {
    std::vector<int> dropped(n, 0);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 64), [&](const tbb::blocked_range<size_t>& range) {
      for (size_t f = range.begin(); f < range.end(); ++f) {
        dropped[f] = RemoveInconsistentViews(uint32_t(f), &out.candidates[f], *face_color, options.consistency);
      }
    });
    for (int d : dropped) {
      out.views_inconsistent += d;
      out.faces_with_inconsistent_views += d > 0;
    }
  }

  std::vector<float> best(n, 0);
  for (size_t f = 0; f < n; ++f) {
    for (const FaceView& c : out.candidates[f]) {
      if (c.quality > best[f]) {  // strictly greater: the lowest view index wins a tie
        best[f] = c.quality;
        out.label[f] = c.view;
      }
    }
    if (!out.candidates[f].empty()) ++out.faces_seen;
  }

  const auto pairs = FaceEdgeNeighbours(mesh);
  std::vector<std::vector<uint32_t>> neighbours(n);
  for (const auto& [a, b] : pairs) {
    neighbours[a].push_back(b);
    neighbours[b].push_back(a);
  }
  auto seams = [&] {
    int64_t count = 0;
    for (const auto& [a, b] : pairs) count += out.label[a] != out.label[b];
    return count;
  };
  out.seam_edges_before = seams();
  for (int it = 0; it < options.smoothing_iterations; ++it) {
    bool changed = false;
    for (size_t f = 0; f < n; ++f) {
      if (out.candidates[f].size() < 2) continue;
      int best_label = out.label[f];
      double best_cost = std::numeric_limits<double>::infinity();
      for (const FaceView& c : out.candidates[f]) {
        double cost = DataCost(out.candidates[f], c.view, best[f]);
        for (uint32_t g : neighbours[f]) cost += options.seam_penalty * (out.label[g] != c.view);
        if (cost < best_cost - 1e-12) {
          best_cost = cost;
          best_label = c.view;
        }
      }
      if (best_label != out.label[f]) {
        out.label[f] = best_label;
        changed = true;
      }
    }
    out.iterations_run = it + 1;
    if (!changed) break;
  }
  out.seam_edges_after = seams();
  return out;
}

}  // namespace cinepath::photogrammetry
