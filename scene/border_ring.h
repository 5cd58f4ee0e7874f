// The mesh's border ring: where a reconstruction ends, and what lies along that edge. `render` continues
// the ground past the edge from it (preview/preview_scene.h, GroundBackdrop) and `view` draws the same
// ground plane (viewer/previs.js); docs/render.md, "The horizon".
//
// Border edges are the edges only one face has; border faces the faces that hold one. Their centroids'
// mean (east, north) is the ring's centre, and each falls in one of kSectors sectors of azimuth about it
// (sector k covers [-180 + 5 k, -180 + 5 (k + 1)) degrees of atan2(north, east)). A reconstruction has
// holes as well as an edge, and a hole's border lies inside the mesh: the ring keeps, in each sector, the
// border faces within a band of the outermost one (kBandFraction of its distance, at least kMinBand_m).
// The ring's plane is at the median height of the kept faces' border edges' vertices (one entry per edge
// end), its radius the kept centroids' median distance from the centre. A closed mesh has no border:
// every face stands in (the outer band of them), and its lowest vertex gives the height.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "scene/scene_mesh.h"

namespace cinepath::scene {

struct BorderRing {
  static constexpr int kSectors = 72;  // 5 degrees each
  static constexpr double kBandFraction = 0.15;
  static constexpr double kMinBand_m = 5;
  static constexpr int kSmoothSectors = 4;             // SectorColors smooths over +-20 degrees
  double height_m = 0;                                 // up, ENU
  Eigen::Vector2d centre_m = Eigen::Vector2d::Zero();  // east, north
  double radius_m = 0;
  std::vector<uint32_t> faces;  // the border faces kept, ascending
  std::vector<int> sectors;     // each border face's sector, in [0, kSectors)
};

// InputError-free: an empty mesh gives an empty ring at height 0.
BorderRing FindBorderRing(const SceneMesh& mesh);

// The sector of an offset (east, north) from the ring's centre.
int SectorOf(const Eigen::Vector2d& offset_m);

// The mean colour of each sector's faces (`face_colors` one per ring face, in `faces`' order); a sector
// without faces takes the mean of the nearest filled sector on each side, weighted by nearness; then each
// sector is the weighted mean of its neighbours within kSmoothSectors (weights kSmoothSectors + 1 - |k|),
// so the ring changes colour gently around the horizon. No face at all leaves `fallback` everywhere. `mean` (optional)
// gets the mean over all faces.
std::vector<Eigen::Vector3f> SectorColors(const BorderRing& ring, const std::vector<Eigen::Vector3f>& face_colors,
                                          const Eigen::Vector3f& fallback, Eigen::Vector3f* mean = nullptr);

}  // namespace cinepath::scene
