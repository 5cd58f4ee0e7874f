// Ray casts against the scene mesh (Embree 3): what `plan --scene` asks of the ground (the highest
// surface below a point), what `export --scene` asks of the take-off point, and the line-of-sight and
// visibility tests of the later stages.
//
// The BVH is built from the mesh re-centred about the centre of its bounds in float (float32 is 1 mm
// at 10 km: positions are re-centred so a scene far from its origin keeps millimetres; docs/optics.md,
// "Precision"); queries take and return double ENU metres. The scene is built with
// RTC_SCENE_FLAG_ROBUST (watertight triangle tests: a ray through an edge or vertex hits). Queries are
// thread-safe and deterministic: a ray gives the same hit whatever the thread count.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>

#include <Eigen/Core>

#include "scene/scene_mesh.h"

namespace cinepath::scene {

struct RayHit {
  double distance_m = 0;  // along the (normalized) direction
  uint32_t face = 0;      // index into SceneMesh::faces
  double u = 0, v = 0;    // barycentrics of vertices 1 and 2 of the face
  Eigen::Vector3d position_enu_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal_enu = Eigen::Vector3d::Zero();  // unit geometric normal, counter-clockwise front
};

class RayCaster {
 public:
  // How much the BVH build spends for faster queries: kHigh (Embree's SAH build with spatial splits, and each
  // face's normal kept, 48 bytes a face, so that a hit does not compute it again) for casters that trace many
  // rays (a render, the optimizer's corridor); kLow (its Morton build, several times cheaper to build, no
  // normals kept) for a large mesh that answers a few thousand rays (the optimizer's background distances
  // over the whole scene). The hits are the same: the triangle test is watertight either way, and a kept
  // normal is the number a hit would compute.
  enum class BuildQuality { kHigh, kLow };
  // InputError when the mesh has no faces or a non-finite vertex.
  explicit RayCaster(const SceneMesh& mesh, BuildQuality quality = BuildQuality::kHigh);
  ~RayCaster();
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  // The closest hit along origin + t * direction for t in [min_distance_m, max_distance_m]
  // (direction need not be normalized; distances are in metres along it once normalized).
  std::optional<RayHit> Intersect(const Eigen::Vector3d& origin_enu_m, const Eigen::Vector3d& direction,
                                  double min_distance_m = 0,
                                  double max_distance_m = std::numeric_limits<double>::infinity()) const;
  // The closest hits of `count` (1 to 8) rays from origins_enu_m[i] along directions[i] (unit length; they
  // are normalized again, as Intersect does), t in [0, inf), traced as one packet (Embree's rtcIntersect8,
  // coherent: the rays of neighbouring pixels share the BVH's traversal), into hits[i]. Embree runs the same
  // watertight triangle test per lane, so a ray gets the hit Intersect gives it (tests/scene/ray_caster_test.cc);
  // a ray through the very edge between two triangles may, rarely, get the other one (one pixel of 43 draft
  // frames of the bundled sample). Always the same hit for the same packet, on any thread.
  void Intersect8(const Eigen::Vector3d* origins_enu_m, const Eigen::Vector3d* unit_directions, int count,
                  std::optional<RayHit>* hits) const;
  // Whether anything lies on the segment (any hit; cheaper than Intersect).
  bool Occluded(const Eigen::Vector3d& origin_enu_m, const Eigen::Vector3d& direction, double min_distance_m,
                double max_distance_m) const;

  // The highest surface point below (e, n) at or under `from_up_m` (a ray cast straight down from
  // there); nullopt when the mesh has nothing below.
  std::optional<RayHit> SurfaceBelow(double east_m, double north_m,
                                     double from_up_m = std::numeric_limits<double>::infinity()) const;

  const Eigen::AlignedBox3d& bounds() const { return bounds_; }

 private:
  RayHit Refine(const Eigen::Vector3d& origin_enu_m, const Eigen::Vector3d& unit_direction, uint32_t face,
                float t_float, float u, float v) const;
  struct Embree;
  std::unique_ptr<Embree> embree_;
  Eigen::Vector3d centre_enu_m_;  // positions are stored minus this, in float
  Eigen::AlignedBox3d bounds_;
  std::vector<Eigen::Vector3d> vertices_enu_m_;
  std::vector<std::array<uint32_t, 3>> faces_;
  // kHigh: each face's (b - a) x (c - a) and its unit vector (UnitZ for a degenerate face), as Refine uses them.
  std::vector<Eigen::Vector3d> face_normals_, face_unit_normals_;
};

}  // namespace cinepath::scene
