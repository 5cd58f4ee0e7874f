#include "preview/preview_scene.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>

#include <tbb/parallel_invoke.h>
#include <tbb/parallel_sort.h>

#include "core/error.h"
#include "preview/image_files.h"

namespace cinepath::preview {
namespace {

constexpr double kDegToRad = M_PI / 180;
constexpr float kSkyIrradiance = 0.25f;
constexpr float kSunIrradiance = 1.0f;
// 1 / (sin 45 deg + sky): a level surface under the default sun keeps about its flat colour.
constexpr float kSunNormalisation = 1.0f / (0.70710678f + kSkyIrradiance);
const Eigen::Vector3f kDefaultSurface(0.5f, 0.5f, 0.5f);  // a mesh without colours

float SrgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

// Linear light of each 8-bit sRGB value, as OpenImageIO's 8-bit to float conversion gives it (v times
// 1/255 in float; measured: all 256 values equal) and then converted: the same texels as decoding to
// floats first.
const std::array<float, 256>& LinearFromSrgb8() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int v = 0; v < 256; ++v) t[size_t(v)] = SrgbToLinear(float(v) * (1.0f / 255.0f));
    return t;
  }();
  return table;
}

Texture DecodeTexture(const scene::SceneImage& image, size_t index) {
  Srgb8Image decoded = DecodeSrgb8(image.encoded, "images[" + std::to_string(index) + "] (" + image.mime_type + ")");
  Texture texture;
  texture.width = decoded.width;
  texture.height = decoded.height;
  texture.srgb = std::move(decoded.rgb);
  return texture;
}

}  // namespace

Eigen::Vector3f Texture::Sample(const Eigen::Vector2f& uv) const {
  if (srgb.empty()) return Eigen::Vector3f::Ones();
  const float x = uv.x() * width - 0.5f, y = uv.y() * height - 0.5f;
  const float fx = std::floor(x), fy = std::floor(y);
  const float wx = x - fx, wy = y - fy;
  const std::array<float, 256>& linear = LinearFromSrgb8();
  // Wrapped once per axis (a division each), not per texel: the neighbour is the next or the first.
  auto wrap = [](long i, long n) { return i >= 0 && i < n ? i : ((i % n) + n) % n; };
  const long i0 = wrap(long(fx), width), j0 = wrap(long(fy), height);
  const long i1 = i0 + 1 == width ? 0 : i0 + 1, j1 = j0 + 1 == height ? 0 : j0 + 1;
  auto at = [&](long i, long j) {
    const uint8_t* p = &srgb[(size_t(j) * width + size_t(i)) * 3];
    return Eigen::Vector3f(linear[p[0]], linear[p[1]], linear[p[2]]);
  };
  return (1 - wy) * ((1 - wx) * at(i0, j0) + wx * at(i1, j0)) + wy * ((1 - wx) * at(i0, j1) + wx * at(i1, j1));
}

namespace {

using Clock = std::chrono::steady_clock;
double SecondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

}  // namespace

std::vector<Texture> DecodeTextures(const scene::SceneMesh& mesh) {
  std::vector<Texture> textures;
  for (size_t i = 0; i < mesh.images.size(); ++i) textures.push_back(DecodeTexture(mesh.images[i], i));
  return textures;
}

PreviewScene::PreviewScene(scene::SceneMesh mesh, const Trajectory& plan, Shading shading, SunDirection sun,
                           Backdrop backdrop)
    : mesh_(std::move(mesh)), subjects_(plan), shading_(shading) {
  // The BVH and the textures at once (two cores: Embree's build and libjpeg's decode each take one).
  tbb::parallel_invoke(
      [&] {
        const auto start = Clock::now();
        caster_ = std::make_unique<scene::RayCaster>(mesh_);
        load_times_.bvh_s = SecondsSince(start);
      },
      [&] {
        const auto start = Clock::now();
        textures_ = DecodeTextures(mesh_);
        load_times_.textures_s = SecondsSince(start);
      });
  Finish(sun, backdrop);
}

PreviewScene::PreviewScene(scene::SceneMesh mesh, std::vector<Texture> textures, const Trajectory& plan,
                           Shading shading, SunDirection sun, Backdrop backdrop)
    : mesh_(std::move(mesh)), subjects_(plan), textures_(std::move(textures)), shading_(shading) {
  if (textures_.size() != mesh_.images.size()) throw InternalError("PreviewScene: one texture per mesh image");
  const auto start = Clock::now();
  caster_ = std::make_unique<scene::RayCaster>(mesh_);
  load_times_.bvh_s = SecondsSince(start);
  Finish(sun, backdrop);
}

void PreviewScene::Finish(SunDirection sun, Backdrop backdrop) {
  const double az = sun.azimuth_deg * kDegToRad, el = sun.elevation_deg * kDegToRad;
  sun_direction_enu_ = Eigen::Vector3d(std::sin(az) * std::cos(el), std::cos(az) * std::cos(el), std::sin(el));
  const auto ground_start = Clock::now();
  if (backdrop == Backdrop::kGround) ground_ = BorderGround();
  load_times_.ground_s = SecondsSince(ground_start);
}

// The plane and colour of the ground past the edge: the median height of the border's vertices (edges
// of one face), and the mean colour of the faces that hold a border edge, at their centroids. A closed
// mesh has no border: its lowest vertex and its mean face colour stand in.
GroundBackdrop PreviewScene::BorderGround() const {
  std::vector<std::array<uint32_t, 3>> edges;  // (smaller vertex, larger vertex, face)
  edges.reserve(3 * mesh_.faces.size());
  for (uint32_t f = 0; f < mesh_.faces.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = mesh_.faces[f][size_t(k)], b = mesh_.faces[f][size_t((k + 1) % 3)];
      edges.push_back({std::min(a, b), std::max(a, b), f});
    }
  }
  tbb::parallel_sort(edges.begin(), edges.end());  // 3 per face: a tenth of a second at 1 M faces
  std::vector<double> heights;
  std::vector<uint32_t> border_faces;
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j][0] == edges[i][0] && edges[j][1] == edges[i][1]) ++j;
    if (j - i == 1) {
      heights.push_back(mesh_.positions_enu_m[edges[i][0]].z());
      heights.push_back(mesh_.positions_enu_m[edges[i][1]].z());
      border_faces.push_back(edges[i][2]);
    }
    i = j;
  }
  GroundBackdrop ground;
  if (heights.empty()) {
    ground.height_m = std::numeric_limits<double>::infinity();
    for (const auto& p : mesh_.positions_enu_m) ground.height_m = std::min(ground.height_m, p.z());
    border_faces.resize(mesh_.faces.size());
    std::iota(border_faces.begin(), border_faces.end(), 0u);
  } else {
    std::nth_element(heights.begin(), heights.begin() + heights.size() / 2, heights.end());
    ground.height_m = heights[heights.size() / 2];
  }
  std::sort(border_faces.begin(), border_faces.end());
  border_faces.erase(std::unique(border_faces.begin(), border_faces.end()), border_faces.end());
  std::vector<Eigen::Vector2d> centroid(border_faces.size());
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (size_t i = 0; i < border_faces.size(); ++i) {
    const auto& f = mesh_.faces[border_faces[i]];
    centroid[i] =
        ((mesh_.positions_enu_m[f[0]] + mesh_.positions_enu_m[f[1]] + mesh_.positions_enu_m[f[2]]) / 3.0).head<2>();
    centre += centroid[i];
  }
  if (!border_faces.empty()) centre /= double(border_faces.size());
  ground.centre_m = centre;
  const int n = GroundBackdrop::kSectors;
  std::vector<Eigen::Vector3d> sum(size_t(n), Eigen::Vector3d::Zero());
  std::vector<int> count(size_t(n), 0);
  for (size_t i = 0; i < border_faces.size(); ++i) {
    scene::RayHit at_centroid;
    at_centroid.face = border_faces[i];
    at_centroid.u = at_centroid.v = 1.0 / 3.0;
    const Eigen::Vector2d d = centroid[i] - centre;
    const int sector = int(std::floor((std::atan2(d.y(), d.x()) + M_PI) / (2 * M_PI) * n)) % n;
    sum[size_t(sector)] += SurfaceColor(at_centroid).cast<double>();
    ++count[size_t(sector)];
  }
  std::vector<double> radius;
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < border_faces.size(); ++i) radius.push_back((centroid[i] - centre).norm());
  for (int k = 0; k < n; ++k) total += sum[size_t(k)];
  if (!radius.empty()) {
    std::nth_element(radius.begin(), radius.begin() + radius.size() / 2, radius.end());
    ground.border_radius_m = radius[radius.size() / 2];
    ground.mean_color = (total / double(border_faces.size())).cast<float>();
  }
  // Empty sectors take the distance-weighted mean of the nearest filled one on each side.
  for (int k = 0; k < n; ++k) {
    if (count[size_t(k)] > 0) {
      ground.sector_color[size_t(k)] = (sum[size_t(k)] / count[size_t(k)]).cast<float>();
      continue;
    }
    int lo = 1, hi = 1;
    while (lo < n && count[size_t((k - lo + n) % n)] == 0) ++lo;
    while (hi < n && count[size_t((k + hi) % n)] == 0) ++hi;
    if (lo >= n) break;  // no border face at all: the default grey stays
    const Eigen::Vector3d a = sum[size_t((k - lo + n) % n)] / count[size_t((k - lo + n) % n)];
    const Eigen::Vector3d b = sum[size_t((k + hi) % n)] / count[size_t((k + hi) % n)];
    ground.sector_color[size_t(k)] = ((hi * a + lo * b) / double(lo + hi)).cast<float>();
  }
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

Eigen::Vector3f PreviewScene::SurfaceColor(const scene::RayHit& hit) const {
  const auto& f = mesh_.faces[hit.face];
  const float u = float(hit.u), v = float(hit.v), w = 1 - u - v;
  Eigen::Vector3f color = kDefaultSurface;
  if (mesh_.has_colors()) {
    color = w * mesh_.colors_linear[f[0]] + u * mesh_.colors_linear[f[1]] + v * mesh_.colors_linear[f[2]];
  }
  if (!mesh_.face_material.empty()) {
    const int m = mesh_.face_material[hit.face];
    if (m >= 0 && size_t(m) < mesh_.materials.size()) {
      const auto& material = mesh_.materials[m];
      color = color.cwiseProduct(material.base_color_factor.head<3>());
      if (material.base_color_image >= 0 && size_t(material.base_color_image) < textures_.size() &&
          mesh_.has_texcoords()) {
        const Eigen::Vector2f uv = w * mesh_.texcoords[f[0]] + u * mesh_.texcoords[f[1]] + v * mesh_.texcoords[f[2]];
        color = color.cwiseProduct(textures_[material.base_color_image].Sample(uv));
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
  const auto mesh_hit = caster_->Intersect(origin, direction);
  double mesh_distance = mesh_hit ? mesh_hit->distance_m : std::numeric_limits<double>::infinity();
  // The ground past the edge: only where the mesh is missed (under the mesh it is hidden anyway).
  double ground_distance = std::numeric_limits<double>::infinity();
  if (!mesh_hit && ground_ && direction.z() < 0 && origin.z() > ground_->height_m) {
    ground_distance = (ground_->height_m - origin.z()) / direction.z();
    mesh_distance = ground_distance;
  }
  std::optional<ProxyHit> proxy;
  if (!subjects_.empty()) proxy = subjects_.Intersect(origin, direction, at.subject_bases, mesh_distance);
  if (!mesh_hit && !proxy && std::isfinite(ground_distance)) {
    const Eigen::Vector3d position = origin + ground_distance * direction;
    if (hit_out) *hit_out = TraceHit{ground_distance, position, -1, kGroundFace};
    Eigen::Vector3f color = ground_->ColorAt(position);
    if (shading_ == Shading::kSun) color = color.cwiseProduct(Light(position, Eigen::Vector3d::UnitZ(), at));
    const float haze = 1.0f - float(std::exp(-3.0 * ground_distance / ground_->visibility_m));
    return color + haze * (Sky(Eigen::Vector3d(direction.x(), direction.y(), 0.0)) - color);
  }
  if (!mesh_hit && !proxy) {
    if (hit_out) *hit_out = TraceHit{std::numeric_limits<double>::infinity(), {}, -1, 0};
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
    color = SurfaceColor(*mesh_hit);
    if (hit_out) *hit_out = TraceHit{mesh_hit->distance_m, position, -1, mesh_hit->face};
  }
  if (shading_ == Shading::kFlat) return color;
  if (normal.dot(direction) > 0) normal = -normal;  // two-sided: light the side the ray sees
  return color.cwiseProduct(Light(position, normal, at));
}

}  // namespace cinepath::preview
