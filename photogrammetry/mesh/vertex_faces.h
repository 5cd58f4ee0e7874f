// The faces around each vertex of a triangle list, in one flat array (compressed rows): the faces of
// vertex v are faces[offsets[v] .. offsets[v + 1]), in increasing face order.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace cinepath::photogrammetry {

struct VertexFaces {
  std::vector<uint32_t> offsets, faces;

  VertexFaces(size_t num_vertices, const std::vector<std::array<uint32_t, 3>>& mesh_faces)
      : offsets(num_vertices + 1, 0), faces(3 * mesh_faces.size()) {
    for (const auto& f : mesh_faces) {
      for (uint32_t v : f) ++offsets[v + 1];
    }
    for (size_t v = 0; v < num_vertices; ++v) offsets[v + 1] += offsets[v];
    std::vector<uint32_t> next(offsets.begin(), offsets.end() - 1);
    for (uint32_t k = 0; k < mesh_faces.size(); ++k) {
      for (uint32_t v : mesh_faces[k]) faces[next[v]++] = k;
    }
  }
  // Calls visit(face) for every face that uses vertex v.
  template <typename F>
  void ForEach(uint32_t v, F&& visit) const {
    for (uint32_t k = offsets[v]; k < offsets[v + 1]; ++k) visit(faces[k]);
  }
};

}  // namespace cinepath::photogrammetry
