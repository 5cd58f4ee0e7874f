#include "preview/frame_renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "preview/denoiser.h"
#include "preview/sample_sequence.h"
#include "preview/subject_proxies.h"
#include "preview/thin_lens_camera.h"
#include "preview/uninitialized_allocator.h"

namespace cinepath::preview {
namespace {

constexpr int kTile = 16;
constexpr double kSharpPx = 0.5;  // under half a pixel of blur and motion: one ray
// A frame in which no pixel's point moves this far across the shutter takes all its rays at the frame's
// instant (eight to a packet): a twentieth of a pixel of streak is not to be seen.
constexpr double kStillMotionPx = 0.05;
constexpr double kEdgeDepthRatio = 0.02;
constexpr int kMaxGatherRadiusPx = 48;  // draft: blur wider than 97 px is clipped

// Every element is written by the pass before it is read (so not zero-filled first).
struct PrePass {
  UninitializedVector<Eigen::Vector3f> rgb;
  UninitializedVector<double> depth_m;
  UninitializedVector<double> blur_px;    // the blur-circle diameter at the pixel centre's depth
  UninitializedVector<double> need_px;    // max(blur, motion) at the pixel
  UninitializedVector<double> motion_px;  // how far the point at the pixel centre moves in the image across the shutter
  UninitializedVector<int> kind;          // -2 sky, -1 mesh, >= 0 subject
  UninitializedVector<uint32_t> face;
};

// Depth along the optical axis (the camera's z axis in ENU, `axis`, worked out once per frame).
double AxisDepth(const CameraPose& pose, const Eigen::Vector3d& axis, const Eigen::Vector3d& point) {
  return (point - pose.position_enu_m).dot(axis);
}

// The camera and the subjects at the shutter's ends, for MotionPx (the same for every pixel).
struct ShutterEnds {
  CameraFrame frame0, frame1;
  std::vector<Eigen::Vector3d> move0, move1;  // each subject's base at t0 (t1) minus at t_mid
};

ShutterEnds ShutterEndsOf(const Trajectory& plan, const SubjectProxies& subjects, double t_mid, double t0, double t1) {
  ShutterEnds ends{CameraFrame(PoseAt(plan, t0)), CameraFrame(PoseAt(plan, t1)), {}, {}};
  for (size_t i = 0; i < plan.subjects.size(); ++i) {
    ends.move0.push_back(subjects.BaseAt(i, t0) - subjects.BaseAt(i, t_mid));
    ends.move1.push_back(subjects.BaseAt(i, t1) - subjects.BaseAt(i, t_mid));
  }
  return ends;
}

// Pixel motion of what the pixel centre sees, across the shutter: the point reprojected at its ends.
double MotionPx(const ThinLensCamera& camera, const ShutterEnds& ends, const TraceHit& hit,
                const Eigen::Vector3d& direction, const Eigen::Vector3d& origin) {
  Eigen::Vector3d point = std::isinf(hit.distance_m) ? origin + 1e7 * direction : hit.position_enu_m;
  auto at = [&](const CameraFrame& frame, const std::vector<Eigen::Vector3d>& move) {
    Eigen::Vector3d p = point;
    if (hit.subject >= 0) p += move[size_t(hit.subject)];
    double depth = 0;
    const Eigen::Vector2d xy = camera.Project(frame, p, &depth);
    return depth > 0 ? xy : Eigen::Vector2d(1e9, 1e9);
  };
  return std::min(1e6, (at(ends.frame1, ends.move1) - at(ends.frame0, ends.move0)).norm());
}

// `texture_lod`: each texture lookup at the level of its pyramid a pixel's footprint spans (draft).
PrePass PinholePrePass(const PreviewScene& scene, const Trajectory& plan, const ThinLensCamera& camera, double t_mid,
                       double t0, double t1, bool motion_blur, bool texture_lod) {
  const int w = camera.width_px(), h = camera.height_px();
  PrePass pass;
  const size_t n = size_t(w) * h;
  pass.rgb.resize(n);
  pass.depth_m.resize(n);
  pass.blur_px.resize(n);
  pass.need_px.resize(n);
  pass.motion_px.resize(n);
  pass.kind.resize(n);
  pass.face.resize(n);
  const CameraPose pose = PoseAt(plan, t_mid);
  const CameraFrame frame(pose);
  const Eigen::Vector3d axis = frame.world_from_camera.col(2);
  const SubjectProxies subjects(plan);
  const PreviewScene::Instant at_mid = scene.At(t_mid);
  const bool moving = motion_blur && t1 > t0;
  const ShutterEnds ends = moving ? ShutterEndsOf(plan, subjects, t_mid, t0, t1) : ShutterEnds{frame, frame, {}, {}};
  const SubjectsInImage seen = scene.SubjectsSeen(at_mid, camera, frame);
  const PinholeRays rays(camera, frame);
  // The angle one pixel spans at the image's centre (its slope step).
  const float pixel_angle_rad = texture_lod ? float(camera.SlopeX(1) - camera.SlopeX(0)) : 0.0f;
  // Eight pixels of a row at a time, traced as one packet.
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
    Eigen::Vector3d origins[8], directions[8];
    Eigen::Vector3f radiance[8];
    TraceHit hits[8];
    for (int y = rows.begin(); y < rows.end(); ++y) {
      for (int x0 = 0; x0 < w; x0 += 8) {
        const int count = std::min(8, w - x0);
        unsigned may_see_subject = 0;
        for (int j = 0; j < count; ++j) {
          const CameraRay ray = rays.At(x0 + j, y);
          origins[j] = ray.origin_enu_m;
          directions[j] = ray.direction_enu;
          if (seen.MaySee(x0 + j + 0.5, y + 0.5)) may_see_subject |= 1u << j;
        }
        scene.Radiance8(origins, directions, count, at_mid, radiance, hits, may_see_subject, pixel_angle_rad);
        for (int j = 0; j < count; ++j) {
          const int x = x0 + j;
          const size_t i = size_t(y) * w + x;
          const TraceHit& hit = hits[j];
          const CameraRay ray{origins[j], directions[j]};
          pass.rgb[i] = radiance[j];
          const bool sky = std::isinf(hit.distance_m);
          pass.depth_m[i] = sky ? std::numeric_limits<double>::infinity() : AxisDepth(pose, axis, hit.position_enu_m);
          pass.kind[i] = sky ? -2 : hit.subject;
          pass.face[i] = hit.face;
          const double blur = pass.blur_px[i] = camera.BlurPx(pass.depth_m[i]);
          const double motion = moving ? MotionPx(camera, ends, hit, ray.direction_enu, ray.origin_enu_m) : 0;
          pass.motion_px[i] = motion;
          pass.need_px[i] = std::max(blur, motion);
        }
      }
    }
  });
  return pass;
}

// Pixels where the pre-pass sees an edge (another object, a depth step, a colour step): they get
// edge_samples jittered rays even when sharp, so in-focus edges are antialiased like the box filter.
std::vector<uint8_t> FindEdges(const PrePass& pass, int w, int h, float edge_color_step) {
  std::vector<uint8_t> edge(size_t(w) * h, 0);
  auto differ = [&](size_t a, size_t b) {  // symmetric in a and b
    if (pass.kind[a] != pass.kind[b]) return true;
    if (pass.kind[a] == -2) return false;
    const double da = pass.depth_m[a], db = pass.depth_m[b];
    if (std::abs(da - db) > kEdgeDepthRatio * std::min(da, db)) return true;
    return (pass.rgb[a] - pass.rgb[b]).cwiseAbs().maxCoeff() > edge_color_step;
  };
  // A pixel is an edge when it differs from one of its four neighbours. Each pair of neighbours is
  // compared once (differ is symmetric): with its right neighbour into `right`, with the one below into
  // `below`, rows in parallel; then each pixel looks at its four pairs.
  std::vector<uint8_t> right(edge.size(), 0), below(edge.size(), 0);
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y) {
      for (int x = 0; x < w; ++x) {
        const size_t i = size_t(y) * w + x;
        right[i] = x + 1 < w && differ(i, i + 1);
        below[i] = y + 1 < h && differ(i, i + w);
      }
    }
  });
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y) {
      // The pairs as bytes of 0 or 1, or'ed without a branch: the pixel's right and lower pairs, its left
      // one (none at x = 0) and its upper one (none in the first row).
      const size_t row = size_t(y) * w;
      const uint8_t* r = right.data() + row;
      const uint8_t* b = below.data() + row;
      const uint8_t* up = y > 0 ? below.data() + row - w : b;
      uint8_t* e = edge.data() + row;
      if (w > 0) e[0] = r[0] | b[0] | up[0];
      for (int x = 1; x < w; ++x) e[x] = r[x] | r[x - 1] | b[x] | up[x];
    }
  });
  return edge;
}

// A blurred pixel spreads over its neighbours: a sharp pixel beside a blurred foreground must be
// sampled as if blurred too. Per tile of 16 x 16 px, the largest need of every tile whose blur disk
// (need / 2 from its border) reaches it.
std::vector<double> DilatedTileNeed(const PrePass& pass, int w, int h) {
  const int tw = (w + kTile - 1) / kTile, th = (h + kTile - 1) / kTile;
  std::vector<double> tile_max(size_t(tw) * th, 0.0);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      double& m = tile_max[size_t(y / kTile) * tw + x / kTile];
      m = std::max(m, pass.need_px[size_t(y) * w + x]);
    }
  }
  std::vector<double> dilated = tile_max;
  for (int ty = 0; ty < th; ++ty) {
    for (int tx = 0; tx < tw; ++tx) {
      const double need = tile_max[size_t(ty) * tw + tx];
      if (need < kSharpPx) continue;
      const int reach = int(std::ceil(std::min(need, 1e4) / 2 / kTile));
      for (int dy = std::max(0, ty - reach); dy <= std::min(th - 1, ty + reach); ++dy) {
        for (int dx = std::max(0, tx - reach); dx <= std::min(tw - 1, tx + reach); ++dx) {
          double& d = dilated[size_t(dy) * tw + dx];
          d = std::max(d, need);
        }
      }
    }
  }
  return dilated;
}

// One row's rays of the frame's instant, eight at a time as one packet, from one pixel or from several
// of the row (a pixel of one or two lens rays would otherwise send a packet of one or two); each pixel's
// rays are summed in their order. A row's packets depend on the row alone.
class RowPackets {
 public:
  RowPackets(const PreviewScene& scene, const PreviewScene::Instant& at, int width)
      : scene_(scene), at_(at), sum_(static_cast<size_t>(width)), rays_(static_cast<size_t>(width)) {}
  // Pixel x starts over with `rays` rays to come (0: not traced here).
  void Start(int x, int rays) {
    sum_[size_t(x)] = Eigen::Vector3d::Zero();
    rays_[size_t(x)] = rays;
  }
  // `may_see_subject` false: the ray is known to miss every subject (SubjectsInImage).
  void Queue(const CameraRay& ray, int x, bool may_see_subject = true) {
    origins_[queued_] = ray.origin_enu_m;
    directions_[queued_] = ray.direction_enu;
    owner_[queued_] = x;
    if (may_see_subject) may_see_subject_ |= 1u << queued_;
    if (++queued_ == 8) Trace();
  }
  // A ray traced elsewhere (at its own instant), added to pixel x.
  void Add(int x, const Eigen::Vector3f& radiance) { sum_[size_t(x)] += radiance.cast<double>(); }
  // Traces what is queued and writes the mean of each started pixel into `row` (the image's row).
  void Finish(Eigen::Vector3f* row) {
    Trace();
    for (size_t x = 0; x < sum_.size(); ++x) {
      if (rays_[x] > 0) row[x] = (sum_[x] / rays_[x]).cast<float>();
    }
  }

 private:
  void Trace() {
    if (queued_ == 0) return;
    scene_.Radiance8(origins_, directions_, queued_, at_, radiance_, nullptr, may_see_subject_);
    for (int j = 0; j < queued_; ++j) Add(owner_[j], radiance_[j]);
    queued_ = 0;
    may_see_subject_ = 0;
  }

  const PreviewScene& scene_;
  const PreviewScene::Instant& at_;
  std::vector<Eigen::Vector3d> sum_;
  std::vector<int> rays_;
  Eigen::Vector3d origins_[8], directions_[8];
  Eigen::Vector3f radiance_[8];
  int owner_[8] = {};
  int queued_ = 0;
  unsigned may_see_subject_ = 0;
};

int SamplesFor(double need_px, bool edge, const SamplingPreset& preset, int max_samples) {
  const int floor = std::min(preset.min_samples, max_samples);
  if (need_px < kSharpPx) return std::max(floor, std::min(edge ? preset.edge_samples : 1, max_samples));
  const double area_px2 = M_PI / 4 * need_px * need_px;
  const double wanted = std::ceil(preset.samples_per_blur_px2 * std::min(area_px2, 1e7));
  return std::max(floor,
                  int(std::clamp<double>(wanted, std::min(preset.min_blurred_samples, max_samples), max_samples)));
}

// Draft: scatter-as-gather of the pre-pass. A neighbour q adds its colour to p when p lies in q's
// blur disk (weight 1 / disk area); a neighbour behind p only where p is itself blurred that far, so
// a sharp foreground does not take in the background.
std::vector<Eigen::Vector3f> GatherBlur(const std::vector<Eigen::Vector3f>& rgb, const PrePass& pass,
                                        const UninitializedVector<double>& blur_px,
                                        const std::vector<double>& tile_need, int w, int h) {
  std::vector<Eigen::Vector3f> out(rgb.size());
  const int tw = (w + kTile - 1) / kTile;
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y) {
      for (int x = 0; x < w; ++x) {
        const size_t i = size_t(y) * w + x;
        const double need = tile_need[size_t(y / kTile) * tw + x / kTile];
        const int radius = std::min(kMaxGatherRadiusPx, int(std::ceil(need / 2)));
        if (need < kSharpPx || radius == 0) {
          out[i] = rgb[i];
          continue;
        }
        const double rp = std::max(0.5, blur_px[i] / 2);
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
        double weight = 0;
        for (int qy = std::max(0, y - radius); qy <= std::min(h - 1, y + radius); ++qy) {
          for (int qx = std::max(0, x - radius); qx <= std::min(w - 1, x + radius); ++qx) {
            const size_t q = size_t(qy) * w + qx;
            const double rq = std::clamp(blur_px[q] / 2, 0.5, double(kMaxGatherRadiusPx));
            const double d2 = double(qx - x) * (qx - x) + double(qy - y) * (qy - y);
            if (d2 > rq * rq) continue;
            if (pass.depth_m[q] > pass.depth_m[i] && d2 > rp * rp) continue;
            const double wq = 1 / (rq * rq);
            sum += wq * rgb[q].cast<double>();
            weight += wq;
          }
        }
        out[i] = weight > 0 ? Eigen::Vector3f((sum / weight).cast<float>()) : rgb[i];
      }
    }
  });
  return out;
}

}  // namespace

std::pair<double, double> ShutterInterval(const Trajectory& plan, size_t k) {
  const auto& s = plan.samples;
  const double t = s[k].time_s;
  const double half = std::max(0.0, s[k].shutter_s) / 2;
  const double lo = k > 0 && s[k - 1].shot == s[k].shot ? s[k - 1].time_s : t;
  const double hi = k + 1 < s.size() && s[k + 1].shot == s[k].shot ? s[k + 1].time_s : t;
  return {std::max(lo, t - half), std::min(hi, t + half)};
}

double RelativeExposure(double shutter_s, double iso, double f_number) {
  const double reference = (1.0 / 50) * 100 / (4.0 * 4.0);
  return shutter_s * iso / (f_number * f_number) / reference;
}

std::pair<int, int> OutputSize(const CameraSpec& camera, std::optional<int> width_px) {
  if (!width_px) return {camera.width_px, camera.height_px};
  const int height = std::max(1, int(std::lround(double(*width_px) * camera.height_px / camera.width_px)));
  return {*width_px, height};
}

FrameImage RenderFrame(const PreviewScene& scene, const Trajectory& plan, size_t k, const FrameSettings& settings) {
  const TrajectorySample& sample = plan.samples[k];
  const ThinLensCamera camera(plan.camera, settings.width_px, settings.height_px, sample.focal_length_mm,
                              sample.f_number, sample.focus_distance_m);
  const SamplingPreset& preset = settings.preset;
  // Not a structured binding: the per-pixel lambda below uses both, and clang before 16 (the fuzz
  // build's) cannot capture a structured binding.
  const std::pair<double, double> shutter = ShutterInterval(plan, k);
  const double t0 = shutter.first, t1 = shutter.second;
  const bool motion = preset.motion_blur && t1 > t0;
  const int w = settings.width_px, h = settings.height_px;

  const PrePass pass = PinholePrePass(scene, plan, camera, sample.time_s, t0, t1, motion, preset.texture_lod);
  const std::vector<uint8_t> edge = FindEdges(pass, w, h, preset.edge_color_step);
  const std::vector<double> tile_need = DilatedTileNeed(pass, w, h);
  const int tw = (w + kTile - 1) / kTile;

  FrameImage image;
  image.width = w;
  image.height = h;
  image.rgb_linear.resize(size_t(w) * h);
  image.depth_m.resize(image.rgb_linear.size());
  image.blur_px.resize(image.rgb_linear.size());
  image.subject_id.resize(image.rgb_linear.size());
  image.samples.resize(image.rgb_linear.size());
  for (size_t i = 0; i < image.rgb_linear.size(); ++i) {
    image.depth_m[i] = float(pass.depth_m[i]);
    image.blur_px[i] = float(pass.blur_px[i]);
    image.subject_id[i] = pass.kind[i] >= 0 ? float(pass.kind[i] + 1) : 0.0f;
  }

  const bool denoise = preset.denoise && !preset.gather_blur;
  DenoiseGuide guide;
  if (denoise) {
    guide.width = w;
    guide.height = h;
    guide.blur_px = image.blur_px;
    guide.noisy.assign(image.rgb_linear.size(), 0);
  }
  // Motion across the shutter, judged over the whole frame: a pixel that sees a still wall at the frame's
  // instant may see a subject pass through it within the shutter.
  const bool moving = motion && *std::max_element(pass.motion_px.begin(), pass.motion_px.end()) >= kStillMotionPx;
  const int max_samples = std::max(1, preset.max_samples);
  const CameraFrame frame_mid(PoseAt(plan, sample.time_s));
  const PreviewScene::Instant at_mid = scene.At(sample.time_s);
  const SubjectsInImage seen = scene.SubjectsSeen(at_mid, camera, frame_mid);  // for the pinhole rays
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
    PreviewScene::Instant at_ray;  // a ray's own instant across the shutter (storage kept between rays)
    RowPackets packets(scene, at_mid, w);
    for (int y = rows.begin(); y < rows.end(); ++y) {
      for (int x = 0; x < w; ++x) {
        const size_t i = size_t(y) * w + x;
        const double need = std::max(pass.need_px[i], tile_need[size_t(y / kTile) * tw + x / kTile]);
        const int n = preset.gather_blur ? std::min(edge[i] ? preset.edge_samples : 1, max_samples)
                                         : SamplesFor(need, edge[i] != 0, preset, max_samples);
        image.samples[i] = uint16_t(std::min(n, 65535));
        const bool lens = !preset.gather_blur && need >= kSharpPx;
        // One ray for a sharp pixel is the pinhole pass's; a blurred one still takes its ray through
        // the lens and the shutter (so `--spp 1` shows depth of field and motion, noisily).
        if (n == 1 && !lens) {
          image.rgb_linear[i] = pass.rgb[i];
          packets.Start(x, 0);
          continue;
        }
        packets.Start(x, n);
        if (denoise && lens) guide.noisy[i] = 1;
        const SampleSequence sequence(k, uint32_t(x), uint32_t(y));
        if (moving && lens) {  // each ray at its own instant
          for (int s = 0; s < n; ++s) {
            const PixelSample ps = sequence.Get(uint32_t(s));
            const double t = t0 + ps.time * (t1 - t0);
            const Eigen::Vector2d disk = ConcentricDisk(ps.lens_u, ps.lens_v);
            scene.SetInstant(t, &at_ray, k);
            const CameraRay ray = camera.Ray(PoseAt(plan, t, k), x + ps.pixel_x, y + ps.pixel_y, disk.x(), disk.y());
            packets.Add(x, scene.Radiance(ray.origin_enu_m, ray.direction_enu, at_ray));
          }
          continue;
        }
        for (int s = 0; s < n; ++s) {  // every ray at the frame's instant
          const PixelSample ps = lens ? sequence.Get(uint32_t(s)) : sequence.GetPixel(uint32_t(s));
          const Eigen::Vector2d disk = lens ? ConcentricDisk(ps.lens_u, ps.lens_v) : Eigen::Vector2d::Zero();
          const CameraRay ray = camera.Ray(frame_mid, x + ps.pixel_x, y + ps.pixel_y, disk.x(), disk.y());
          packets.Queue(ray, x, lens || seen.MaySee(x + ps.pixel_x, y + ps.pixel_y));
        }
      }
      packets.Finish(image.rgb_linear.data() + size_t(y) * w);
    }
  });
  if (denoise) {
    guide.rays = image.samples;
    image.rgb_linear = DenoiseBlurred(image.rgb_linear, guide);
  }
  if (preset.gather_blur) image.rgb_linear = GatherBlur(image.rgb_linear, pass, pass.blur_px, tile_need, w, h);
  for (uint16_t n : image.samples) image.total_samples += n;
  if (settings.exposure == Exposure::kPhysical) {
    const float scale = float(RelativeExposure(sample.shutter_s, settings.iso, sample.f_number));
    for (auto& c : image.rgb_linear) c *= scale;
  }
  return image;
}

}  // namespace cinepath::preview
