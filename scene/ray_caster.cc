#include "scene/ray_caster.h"

#include <cmath>
#include <limits>

#include <embree3/rtcore.h>

#include "core/error.h"

namespace cinepath::scene {

struct RayCaster::Embree {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  ~Embree() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

namespace {

[[noreturn]] void ThrowEmbreeError(RTCDevice device, const char* what) {
  const RTCError e = rtcGetDeviceError(device);
  throw RuntimeError(std::string("ray caster: ") + what + " (Embree error " + std::to_string(static_cast<int>(e)) +
                     ")");
}

}  // namespace

RayCaster::RayCaster(const SceneMesh& mesh) : embree_(std::make_unique<Embree>()) {
  if (mesh.num_faces() == 0) throw InputError("ray caster: the mesh has no faces");
  bounds_ = mesh.Bounds();
  centre_enu_m_ = bounds_.center();
  vertices_enu_m_ = mesh.positions_enu_m;
  faces_ = mesh.faces;
  for (const auto& p : vertices_enu_m_) {
    if (!p.allFinite()) throw InputError("ray caster: a vertex position is not finite");
  }

  embree_->device = rtcNewDevice(nullptr);
  if (!embree_->device) throw RuntimeError("ray caster: cannot create an Embree device");
  embree_->scene = rtcNewScene(embree_->device);
  rtcSetSceneFlags(embree_->scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(embree_->scene, RTC_BUILD_QUALITY_HIGH);
  RTCGeometry geometry = rtcNewGeometry(embree_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                               3 * sizeof(float), vertices_enu_m_.size()));
  auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                 3 * sizeof(uint32_t), faces_.size()));
  if (!vertices || !indices) ThrowEmbreeError(embree_->device, "cannot allocate the mesh buffers");
  for (size_t i = 0; i < vertices_enu_m_.size(); ++i) {
    const Eigen::Vector3f p = (vertices_enu_m_[i] - centre_enu_m_).cast<float>();
    vertices[3 * i] = p.x();
    vertices[3 * i + 1] = p.y();
    vertices[3 * i + 2] = p.z();
  }
  for (size_t f = 0; f < faces_.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      if (faces_[f][k] >= vertices_enu_m_.size()) throw InputError("ray caster: a face refers to a missing vertex");
      indices[3 * f + k] = faces_[f][k];
    }
  }
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(embree_->scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(embree_->scene);
  if (rtcGetDeviceError(embree_->device) != RTC_ERROR_NONE) ThrowEmbreeError(embree_->device, "cannot build the BVH");
}

RayCaster::~RayCaster() = default;

namespace {

RTCRay MakeRay(const Eigen::Vector3d& origin_local, const Eigen::Vector3d& unit_direction, double tnear, double tfar) {
  RTCRay ray;
  ray.org_x = static_cast<float>(origin_local.x());
  ray.org_y = static_cast<float>(origin_local.y());
  ray.org_z = static_cast<float>(origin_local.z());
  ray.dir_x = static_cast<float>(unit_direction.x());
  ray.dir_y = static_cast<float>(unit_direction.y());
  ray.dir_z = static_cast<float>(unit_direction.z());
  ray.tnear = static_cast<float>(tnear);
  ray.tfar = std::isinf(tfar) ? std::numeric_limits<float>::infinity() : static_cast<float>(tfar);
  ray.time = 0;
  ray.mask = 0xFFFFFFFFu;
  ray.id = 0;
  ray.flags = 0;
  return ray;
}

}  // namespace

std::optional<RayHit> RayCaster::Intersect(const Eigen::Vector3d& origin_enu_m, const Eigen::Vector3d& direction,
                                           double min_distance_m, double max_distance_m) const {
  const double length = direction.norm();
  if (!(length > 0) || !origin_enu_m.allFinite() || !(max_distance_m > min_distance_m)) return std::nullopt;
  const Eigen::Vector3d d = direction / length;
  RTCRayHit rh;
  rh.ray = MakeRay(origin_enu_m - centre_enu_m_, d, std::max(0.0, min_distance_m), max_distance_m);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcIntersect1(embree_->scene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;

  // Refine in double on the hit triangle (float32 hits are good to ~1e-7 of the scene's extent).
  RayHit hit;
  hit.face = rh.hit.primID;
  const auto& f = faces_[hit.face];
  const Eigen::Vector3d a = vertices_enu_m_[f[0]], b = vertices_enu_m_[f[1]], c = vertices_enu_m_[f[2]];
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double denom = n.dot(d);
  double t = rh.ray.tfar;
  if (std::fabs(denom) > 1e-300) {
    const double t_plane = n.dot(a - origin_enu_m) / denom;
    if (std::isfinite(t_plane) && std::fabs(t_plane - t) <= 1e-3 * (1.0 + std::fabs(t))) t = t_plane;
  }
  hit.distance_m = t;
  hit.position_enu_m = origin_enu_m + t * d;
  hit.u = rh.hit.u;
  hit.v = rh.hit.v;
  hit.normal_enu = n.norm() > 0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::UnitZ();
  return hit;
}

bool RayCaster::Occluded(const Eigen::Vector3d& origin_enu_m, const Eigen::Vector3d& direction, double min_distance_m,
                         double max_distance_m) const {
  const double length = direction.norm();
  if (!(length > 0) || !origin_enu_m.allFinite() || !(max_distance_m > min_distance_m)) return false;
  RTCRay ray = MakeRay(origin_enu_m - centre_enu_m_, direction / length, std::max(0.0, min_distance_m), max_distance_m);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcOccluded1(embree_->scene, &context, &ray);
  return ray.tfar == -std::numeric_limits<float>::infinity();
}

std::optional<RayHit> RayCaster::SurfaceBelow(double east_m, double north_m, double from_up_m) const {
  const double top = std::isinf(from_up_m) ? bounds_.max().z() + 1.0 : from_up_m;
  return Intersect(Eigen::Vector3d(east_m, north_m, top), -Eigen::Vector3d::UnitZ());
}

}  // namespace cinepath::scene
