// The scene as triangles in local ENU metres: what optimize, render, plan --scene and view get from
// scene.glb (scene/glb_reader.h). Positions stay double here; stages that build float structures
// (Embree) re-centre them first (docs/optics.md, "Precision").
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace cinepath::scene {

// An image as stored in the GLB (PNG or JPEG bytes); decoding is the user's business (render uses
// OpenImageIO), so the scene module carries no image codec.
struct SceneImage {
  std::string mime_type;  // "image/png", "image/jpeg"
  std::vector<uint8_t> encoded;
};

// The part of a glTF material a previs needs: the base colour (linear RGBA factor) and its texture.
struct SceneMaterial {
  Eigen::Vector4f base_color_factor{1, 1, 1, 1};
  int base_color_image = -1;  // index into SceneMesh::images, -1 = none
};

struct SceneMesh {
  std::vector<Eigen::Vector3d> positions_enu_m;
  std::vector<std::array<uint32_t, 3>> faces;  // counter-clockwise seen from the front
  std::vector<Eigen::Vector3f> colors_linear;  // COLOR_0 (linear RGB), empty or one per vertex
  std::vector<Eigen::Vector2f> texcoords;      // TEXCOORD_0, empty or one per vertex
  std::vector<int> face_material;              // index into materials per face, empty = none
  std::vector<SceneMaterial> materials;
  std::vector<SceneImage> images;

  size_t num_vertices() const { return positions_enu_m.size(); }
  size_t num_faces() const { return faces.size(); }
  bool has_colors() const { return !colors_linear.empty(); }
  bool has_texcoords() const { return !texcoords.empty(); }
  // The axis-aligned bounds of the vertices that faces use (empty box for an empty mesh).
  Eigen::AlignedBox3d Bounds() const;
};

// The faces whose bounding boxes meet `box`, with only the vertices they use (renumbered in order
// of first use, so the result is deterministic). Colours, texture coordinates and materials follow.
SceneMesh CropToBox(const SceneMesh& mesh, const Eigen::AlignedBox3d& box);

}  // namespace cinepath::scene
