#include "preview/preview_scene.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include <tbb/parallel_invoke.h>

#include "core/error.h"
#include "scene/border_ring.h"

namespace cinepath::preview {
namespace {

constexpr double kDegToRad = M_PI / 180;
constexpr float kSkyIrradiance = 0.25f;
constexpr float kSunIrradiance = 1.0f;
// 1 / (sin 45 deg + sky): a level surface under the default sun keeps about its flat colour.
constexpr float kSunNormalisation = 1.0f / (0.70710678f + kSkyIrradiance);
const Eigen::Vector3f kDefaultSurface(0.5f, 0.5f, 0.5f);  // a mesh without colours

using Clock = std::chrono::steady_clock;
double SecondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

}  // namespace

PreviewScene::PreviewScene(scene::SceneMesh mesh, const Trajectory& plan, Shading shading, SunDirection sun,
                           Backdrop backdrop)
    : mesh_(std::move(mesh)), subjects_(plan), shading_(shading) {
  // The BVH and the textures at once (two cores: Embree's build and libjpeg's decode each take one).
  tbb::parallel_invoke(
      [&] {
        const auto start = Clock::now();
        caster_ = std::make_shared<const scene::RayCaster>(mesh_);
        load_times_.bvh_s = SecondsSince(start);
      },
      [&] {
        const auto start = Clock::now();
        textures_ = DecodeTextures(mesh_);
        load_times_.textures_s = SecondsSince(start);
      });
  Finish(sun, backdrop);
}

PreviewScene::PreviewScene(scene::SceneMesh mesh, std::vector<Texture> textures, const Prepared& prepared,
                           const Trajectory& plan, Shading shading, SunDirection sun, Backdrop backdrop)
    : mesh_(std::move(mesh)),
      caster_(prepared.caster),
      subjects_(plan),
      textures_(std::move(textures)),
      shading_(shading) {
  if (textures_.size() != mesh_.images.size()) throw InternalError("PreviewScene: one texture per mesh image");
  if (!caster_) throw InternalError("PreviewScene: no ray caster given");
  Finish(sun, backdrop, prepared.ring.get());
}

void PreviewScene::Finish(SunDirection sun, Backdrop backdrop, const scene::BorderRing* ring) {
  if (std::any_of(textures_.begin(), textures_.end(), [](const Texture& t) { return t.levels() > 1; }))
    face_texels_per_m_ = FaceTexelsPerMetre(mesh_, textures_);
  const double az = sun.azimuth_deg * kDegToRad, el = sun.elevation_deg * kDegToRad;
  sun_direction_enu_ = Eigen::Vector3d(std::sin(az) * std::cos(el), std::cos(az) * std::cos(el), std::sin(el));
  const auto ground_start = Clock::now();
  if (backdrop == Backdrop::kGround) ground_ = BorderGround(ring ? *ring : scene::FindBorderRing(mesh_));
  load_times_.ground_s = SecondsSince(ground_start);
}

// The plane and colour of the ground past the edge: the border ring (scene/border_ring.h), each ring
// face's colour at its centroid (texture included), averaged per sector of azimuth.
GroundBackdrop PreviewScene::BorderGround(const scene::BorderRing& ring) const {
  std::vector<Eigen::Vector3f> face_colors(ring.faces.size());
  for (size_t i = 0; i < ring.faces.size(); ++i) {
    scene::RayHit at_centroid;
    at_centroid.face = ring.faces[i];
    at_centroid.u = at_centroid.v = 1.0 / 3.0;
    face_colors[i] = SurfaceColor(at_centroid);
  }
  GroundBackdrop ground;
  ground.height_m = ring.height_m;
  ground.centre_m = ring.centre_m;
  ground.border_radius_m = ring.radius_m;
  const Eigen::Vector3f grey = ground.mean_color;  // no face at all: mid-grey
  ground.sector_color = scene::SectorColors(ring, face_colors, grey, &ground.mean_color);
  return ground;
}

Eigen::Vector3f GroundBackdrop::ColorAt(const Eigen::Vector3d& position) const {
  const Eigen::Vector2d d = position.head<2>() - centre_m;
  const double s = (std::atan2(d.y(), d.x()) + M_PI) / (2 * M_PI) * kSectors - 0.5;  // between sector centres
  const double k0 = std::floor(s);
  const float w = float(s - k0);
  const int a = (int(k0) % kSectors + kSectors) % kSectors, b = (a + 1) % kSectors;
  const Eigen::Vector3f ring = (1 - w) * sector_color[size_t(a)] + w * sector_color[size_t(b)];
  const float fade = float(1.0 - std::exp(-std::max(0.0, d.norm() - border_radius_m) / blend_m));
  return ring + fade * (mean_color - ring);
}

PreviewScene::~PreviewScene() = default;

Eigen::Vector3f PreviewScene::Sky(const Eigen::Vector3d& direction) const {
  const float up = float(std::clamp(direction.z(), -1.0, 1.0));
  if (up < 0) return Eigen::Vector3f(0.18f, 0.18f, 0.18f);  // below the horizon, off the mesh
  const Eigen::Vector3f horizon(0.75f, 0.80f, 0.88f), zenith(0.25f, 0.40f, 0.75f);
  return horizon + std::sqrt(up) * (zenith - horizon);
}

int PreviewScene::TextureLevelAt(const scene::RayHit& hit, const Eigen::Vector3d& direction,
                                 float pixel_angle_rad) const {
  if (!(pixel_angle_rad > 0) || face_texels_per_m_.empty()) return 0;
  // The pixel's footprint on the surface in texels of level 0: its width across the ray at the hit, over
  // the square root of the cosine to the surface (the geometric mean of the footprint's two axes, so a
  // slanted view reads neither the sharp axis's level nor the blurred one's), at the face's texel density.
  const double cosine = std::max(std::fabs(hit.normal_enu.dot(direction)), 1.0 / 64);
  const double across = hit.distance_m * pixel_angle_rad * face_texels_per_m_[hit.face];
  const double texels2 = across * across / cosine;  // the footprint's side in texels, squared
  return LevelOfFootprint(texels2);
}

Eigen::Vector3f PreviewScene::SurfaceColor(const scene::RayHit& hit, const Eigen::Vector3d& direction,
                                           float pixel_angle_rad) const {
  const auto& f = mesh_.faces[hit.face];
  const float u = float(hit.u), v = float(hit.v), w = 1 - u - v;
  // Written out per coordinate in the order the vector expressions w c0 + u c1 + v c2 sum (the same floats,
  // fewer instructions than Eigen's 3-float packets).
  auto blend3 = [w, u, v](const Eigen::Vector3f& a, const Eigen::Vector3f& b, const Eigen::Vector3f& c) {
    return Eigen::Vector3f(w * a.x() + u * b.x() + v * c.x(), w * a.y() + u * b.y() + v * c.y(),
                           w * a.z() + u * b.z() + v * c.z());
  };
  Eigen::Vector3f color = kDefaultSurface;
  if (mesh_.has_colors())
    color = blend3(mesh_.colors_linear[f[0]], mesh_.colors_linear[f[1]], mesh_.colors_linear[f[2]]);
  if (!mesh_.face_material.empty()) {
    const int m = mesh_.face_material[hit.face];
    if (m >= 0 && size_t(m) < mesh_.materials.size()) {
      const auto& material = mesh_.materials[m];
      color = color.cwiseProduct(material.base_color_factor.head<3>());
      if (material.base_color_image >= 0 && size_t(material.base_color_image) < textures_.size() &&
          mesh_.has_texcoords()) {
        const Eigen::Vector2f& t0 = mesh_.texcoords[f[0]];
        const Eigen::Vector2f& t1 = mesh_.texcoords[f[1]];
        const Eigen::Vector2f& t2 = mesh_.texcoords[f[2]];
        const Eigen::Vector2f uv(w * t0.x() + u * t1.x() + v * t2.x(), w * t0.y() + u * t1.y() + v * t2.y());
        const Texture& texture = textures_[size_t(material.base_color_image)];
        color = color.cwiseProduct(pixel_angle_rad > 0
                                       ? texture.SampleLevel(uv, TextureLevelAt(hit, direction, pixel_angle_rad))
                                       : texture.Sample(uv));
      }
    }
  }
  return color;
}

void PreviewScene::SetInstant(double time_s, Instant* instant, size_t sample_hint) const {
  instant->time_s = time_s;
  subjects_.BasesAt(time_s, &instant->subject_bases, sample_hint);
}

Eigen::Vector3f PreviewScene::Light(const Eigen::Vector3d& position, const Eigen::Vector3d& normal,
                                    const Instant& at) const {
  const float sky = kSkyIrradiance * float(0.5 * (1 + normal.z()));
  const double cosine = normal.dot(sun_direction_enu_);
  float sun = 0;
  if (cosine > 0) {
    const Eigen::Vector3d origin = position + 1e-3 * normal;
    const bool blocked = caster_->Occluded(origin, sun_direction_enu_, 1e-4, 1e6) ||
                         (!subjects_.empty() && subjects_.Intersect(origin, sun_direction_enu_, at.subject_bases, 1e6));
    if (!blocked) sun = kSunIrradiance * float(cosine);
  }
  return Eigen::Vector3f::Constant((sun + sky) * kSunNormalisation);
}

Eigen::Vector3f PreviewScene::Radiance(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                                       const Instant& at, TraceHit* hit_out) const {
  return Shade(origin, direction, at, caster_->Intersect(origin, direction), hit_out);
}

void PreviewScene::Radiance8(const Eigen::Vector3d* origins, const Eigen::Vector3d* directions, int count,
                             const Instant& at, Eigen::Vector3f* radiance, TraceHit* hits_out, unsigned may_see_subject,
                             float pixel_angle_rad) const {
  std::optional<scene::RayHit> mesh_hits[8];
  caster_->Intersect8(origins, directions, count, mesh_hits);
  for (int i = 0; i < count; ++i) {
    radiance[i] = Shade(origins[i], directions[i], at, mesh_hits[i], hits_out ? &hits_out[i] : nullptr,
                        (may_see_subject >> i) & 1u, pixel_angle_rad);
  }
}

Eigen::Vector3f PreviewScene::Shade(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, const Instant& at,
                                    const std::optional<scene::RayHit>& mesh_hit, TraceHit* hit_out,
                                    bool may_see_subject, float pixel_angle_rad) const {
  const double mesh_distance = mesh_hit ? mesh_hit->distance_m : std::numeric_limits<double>::infinity();
  // The ground past the edge: only where the mesh is missed (under the mesh it is hidden anyway). It
  // stands in for ground nobody measured, so it hides no subject: a plane at the border's height also
  // passes over the lower parts of the mesh, and would cut a subject standing there in two (as the
  // previs page draws it: behind everything).
  double ground_distance = std::numeric_limits<double>::infinity();
  if (!mesh_hit && ground_ && direction.z() < 0 && origin.z() > ground_->height_m) {
    ground_distance = (ground_->height_m - origin.z()) / direction.z();
  }
  std::optional<ProxyHit> proxy;
  if (may_see_subject && !subjects_.empty())
    proxy = subjects_.Intersect(origin, direction, at.subject_bases, mesh_distance);
  if (!mesh_hit && !proxy && std::isfinite(ground_distance)) {
    const Eigen::Vector3d position = origin + ground_distance * direction;
    if (hit_out) *hit_out = TraceHit{ground_distance, position, -1, kGroundFace};
    Eigen::Vector3f color = ground_->ColorAt(position);
    if (shading_ == Shading::kSun) color = color.cwiseProduct(Light(position, Eigen::Vector3d::UnitZ(), at));
    const float haze = 1.0f - float(std::exp(-3.0 * ground_distance / ground_->visibility_m));
    return color + haze * (Sky(Eigen::Vector3d(direction.x(), direction.y(), 0.0)) - color);
  }
  if (!mesh_hit && !proxy) {
    if (hit_out) *hit_out = TraceHit{std::numeric_limits<double>::infinity(), Eigen::Vector3d::Zero(), -1, 0};
    return Sky(direction);
  }
  Eigen::Vector3f color;
  Eigen::Vector3d normal, position;
  if (proxy) {
    position = origin + proxy->distance_m * direction;
    normal = proxy->normal_enu;
    color = SubjectColor(proxy->subject);
    if (hit_out) *hit_out = TraceHit{proxy->distance_m, position, proxy->subject, 0};
  } else {
    position = mesh_hit->position_enu_m;
    normal = mesh_hit->normal_enu;
    color = SurfaceColor(*mesh_hit, direction, pixel_angle_rad);
    if (hit_out) *hit_out = TraceHit{mesh_hit->distance_m, position, -1, mesh_hit->face};
  }
  if (shading_ == Shading::kFlat) return color;
  if (normal.dot(direction) > 0) normal = -normal;  // two-sided: light the side the ray sees
  return color.cwiseProduct(Light(position, normal, at));
}

}  // namespace cinepath::preview
