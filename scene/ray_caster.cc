#include "scene/ray_caster.h"

#include <cmath>
#include <limits>

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

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

// A face's (b - a) x (c - a), and its unit vector (UnitZ when it has none): what a hit on it reports.
Eigen::Vector3d FaceNormal(const std::vector<Eigen::Vector3d>& vertices, const std::array<uint32_t, 3>& f) {
  const Eigen::Vector3d a = vertices[f[0]], b = vertices[f[1]], c = vertices[f[2]];
  return (b - a).cross(c - a);
}
Eigen::Vector3d UnitNormal(const Eigen::Vector3d& n) {
  return n.norm() > 0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::UnitZ();
}

}  // namespace

RayCaster::RayCaster(const SceneMesh& mesh, BuildQuality quality) : embree_(std::make_unique<Embree>()) {
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
  // kLow: the Morton builder Embree uses for dynamic scenes (a low scene quality, a low geometry quality).
  rtcSetSceneFlags(embree_->scene, quality == BuildQuality::kHigh ? RTC_SCENE_FLAG_ROBUST
                                                                  : RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_DYNAMIC);
  rtcSetSceneBuildQuality(embree_->scene,
                          quality == BuildQuality::kHigh ? RTC_BUILD_QUALITY_HIGH : RTC_BUILD_QUALITY_LOW);
  RTCGeometry geometry = rtcNewGeometry(embree_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  if (quality == BuildQuality::kLow) rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_LOW);
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
  if (quality == BuildQuality::kHigh) {
    face_normals_.resize(faces_.size());
    face_unit_normals_.resize(faces_.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, faces_.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t f = r.begin(); f != r.end(); ++f) {
        face_normals_[f] = FaceNormal(vertices_enu_m_, faces_[f]);
        face_unit_normals_[f] = UnitNormal(face_normals_[f]);
      }
    });
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
  return Refine(origin_enu_m, d, rh.hit.primID, rh.ray.tfar, rh.hit.u, rh.hit.v);
}

void RayCaster::Intersect8(const Eigen::Vector3d* origins_enu_m, const Eigen::Vector3d* unit_directions, int count,
                           std::optional<RayHit>* hits) const {
  if (count < 1 || count > 8) throw InternalError("ray caster: Intersect8 takes 1 to 8 rays");
  alignas(32) int valid[8];
  Eigen::Vector3d d[8];
  RTCRayHit8 packet;
  for (int i = 0; i < 8; ++i) {
    // Normalized again, as Intersect does, so the packet's rays are its rays to the bit (the length taken
    // once: it was two square roots a ray).
    bool used = false;
    if (i < count && origins_enu_m[i].allFinite()) {
      const double length = unit_directions[i].norm();
      used = length > 0;
      // A unit direction (a camera's rays) is most often of length 1 exactly: dividing by it is a no-op.
      if (used) d[i] = length == 1.0 ? unit_directions[i] : Eigen::Vector3d(unit_directions[i] / length);
    }
    valid[i] = used ? -1 : 0;
    const RTCRay ray =
        used ? MakeRay(origins_enu_m[i] - centre_enu_m_, d[i], 0.0, std::numeric_limits<double>::infinity())
             : MakeRay(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), 0.0, 1.0);
    packet.ray.org_x[i] = ray.org_x;
    packet.ray.org_y[i] = ray.org_y;
    packet.ray.org_z[i] = ray.org_z;
    packet.ray.dir_x[i] = ray.dir_x;
    packet.ray.dir_y[i] = ray.dir_y;
    packet.ray.dir_z[i] = ray.dir_z;
    packet.ray.tnear[i] = ray.tnear;
    packet.ray.tfar[i] = ray.tfar;
    packet.ray.time[i] = 0;
    packet.ray.mask[i] = ray.mask;
    packet.ray.id[i] = 0;
    packet.ray.flags[i] = 0;
    packet.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    packet.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  rtcIntersect8(valid, embree_->scene, &context, &packet);
  for (int i = 0; i < count; ++i) {
    hits[i] = std::nullopt;
    if (valid[i] && packet.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID) {
      hits[i] =
          Refine(origins_enu_m[i], d[i], packet.hit.primID[i], packet.ray.tfar[i], packet.hit.u[i], packet.hit.v[i]);
    }
  }
}

// Refine in double on the hit triangle (float32 hits are good to ~1e-7 of the scene's extent).
RayHit RayCaster::Refine(const Eigen::Vector3d& origin_enu_m, const Eigen::Vector3d& d, uint32_t face, float t_float,
                         float u, float v) const {
  RayHit hit;
  hit.face = face;
  const Eigen::Vector3d& a = vertices_enu_m_[faces_[hit.face][0]];
  const bool kept = !face_normals_.empty();
  const Eigen::Vector3d n = kept ? face_normals_[face] : FaceNormal(vertices_enu_m_, faces_[face]);
  const double denom = n.dot(d);
  double t = t_float;
  if (std::fabs(denom) > 1e-300) {
    const double t_plane = n.dot(a - origin_enu_m) / denom;
    if (std::isfinite(t_plane) && std::fabs(t_plane - t) <= 1e-3 * (1.0 + std::fabs(t))) t = t_plane;
  }
  hit.distance_m = t;
  hit.position_enu_m = origin_enu_m + t * d;
  hit.u = u;
  hit.v = v;
  hit.normal_enu = kept ? face_unit_normals_[face] : UnitNormal(n);
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
