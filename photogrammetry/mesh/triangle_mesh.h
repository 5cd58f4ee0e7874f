// An indexed triangle mesh in double precision (ENU metres once georeferenced), with optional
// per-vertex colours. The exchange type between readers, surface reconstruction, cleaning,
// decimation and the glTF writer; CGAL/OpenMesh types stay inside the .cc files that use them.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace cinepath::photogrammetry {

struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices_m;
  std::vector<std::array<uint32_t, 3>> faces;      // counter-clockwise seen from outside / above
  std::vector<std::array<uint8_t, 3>> colors_rgb;  // empty, or one per vertex

  size_t num_vertices() const { return vertices_m.size(); }
  size_t num_faces() const { return faces.size(); }
  bool has_colors() const { return !colors_rgb.empty(); }
};

}  // namespace cinepath::photogrammetry
