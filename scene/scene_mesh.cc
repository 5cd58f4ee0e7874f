#include "scene/scene_mesh.h"

#include <limits>

namespace cinepath::scene {

Eigen::AlignedBox3d SceneMesh::Bounds() const {
  Eigen::AlignedBox3d box;  // empty
  for (const auto& f : faces) {
    for (uint32_t v : f) box.extend(positions_enu_m[v]);
  }
  return box;
}

SceneMesh CropToBox(const SceneMesh& mesh, const Eigen::AlignedBox3d& box) {
  constexpr uint32_t kUnused = std::numeric_limits<uint32_t>::max();
  SceneMesh out;
  out.materials = mesh.materials;
  out.images = mesh.images;
  std::vector<uint32_t> remap(mesh.num_vertices(), kUnused);
  for (size_t i = 0; i < mesh.faces.size(); ++i) {
    const auto& f = mesh.faces[i];
    Eigen::AlignedBox3d face_box(mesh.positions_enu_m[f[0]]);
    face_box.extend(mesh.positions_enu_m[f[1]]);
    face_box.extend(mesh.positions_enu_m[f[2]]);
    if (!face_box.intersects(box)) continue;
    std::array<uint32_t, 3> g;
    for (int k = 0; k < 3; ++k) {
      uint32_t& r = remap[f[k]];
      if (r == kUnused) {
        r = static_cast<uint32_t>(out.positions_enu_m.size());
        out.positions_enu_m.push_back(mesh.positions_enu_m[f[k]]);
        if (mesh.has_colors()) out.colors_linear.push_back(mesh.colors_linear[f[k]]);
        if (mesh.has_texcoords()) out.texcoords.push_back(mesh.texcoords[f[k]]);
      }
      g[k] = r;
    }
    out.faces.push_back(g);
    if (!mesh.face_material.empty()) out.face_material.push_back(mesh.face_material[i]);
  }
  return out;
}

}  // namespace cinepath::scene
