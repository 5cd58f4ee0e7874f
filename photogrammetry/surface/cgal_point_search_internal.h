// INTERNAL to the CGAL translation units (mesh_colors.cc, surface_poisson.cc): a kd-tree over the
// points of a cloud that answers "which k input points are nearest" with their indices.
#pragma once

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/property_map.h>

#include "photogrammetry/io/point_cloud.h"

namespace cinepath::photogrammetry::internal {

class PointSearch {
 public:
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Point = Kernel::Point_3;
  using Entry = std::pair<Point, uint32_t>;
  using Traits =
      CGAL::Search_traits_adapter<Entry, CGAL::First_of_pair_property_map<Entry>, CGAL::Search_traits_3<Kernel>>;
  using Search = CGAL::Orthogonal_k_neighbor_search<Traits>;
  using Tree = Search::Tree;

  // Indexes the finite points of `positions`.
  explicit PointSearch(const std::vector<Eigen::Vector3d>& positions) {
    std::vector<Entry> entries;
    entries.reserve(positions.size());
    for (uint32_t i = 0; i < positions.size(); ++i) {
      const auto& p = positions[i];
      if (p.allFinite()) entries.emplace_back(Point(p.x(), p.y(), p.z()), i);
    }
    size_ = entries.size();
    tree_.insert(entries.begin(), entries.end());
    tree_.build();  // built before any (possibly concurrent) query
  }

  size_t size() const { return size_; }

  // (squared distance, index) of the k nearest points, nearest first, ties by index.
  std::vector<std::pair<double, uint32_t>> Nearest(const Eigen::Vector3d& q, int k) const {
    Search search(tree_, Point(q.x(), q.y(), q.z()), static_cast<unsigned>(std::max(1, k)));
    std::vector<std::pair<double, uint32_t>> out;
    for (const auto& hit : search) out.emplace_back(hit.second, hit.first.second);
    std::sort(out.begin(), out.end());
    return out;
  }

 private:
  Tree tree_;
  size_t size_ = 0;
};

}  // namespace cinepath::photogrammetry::internal
