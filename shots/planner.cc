#include "shots/planner.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "core/angles.h"
#include "core/easing.h"
#include "core/error.h"
#include "core/feasibility.h"
#include "core/local_level.h"
#include "core/rotation.h"
#include "shots/lens_track.h"
#include "shots/shot_pose.h"

namespace cinepath::shots {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Precomputed curves of a KEYFRAMES shot.
struct KeyframesShot {
  std::unique_ptr<PathSpline> path;
  std::vector<Eigen::Quaterniond> q, s;  // aligned keys and SQUAD controls
  std::vector<ScalarKey> focal, focus, f_number;
};

struct ShotState {
  double start_s = 0;
  Eigen::Vector3d position_offset = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity_offset = Eigen::Vector3d::Zero();  // m/s, matched at the join
  Eigen::Quaterniond rotation_offset = Eigen::Quaterniond::Identity();
  double log_focal_offset = 0;     // zoom continuity: log(previous end focal / this shot's start focal)
  double log_f_number_offset = 0;  // aperture continuity, the same in stops (a step was 30 stops/s)
  double blend_s = 0;              // 0 = no offset
  KeyframesShot keyframes;
};

struct Evaluated {
  TrajectorySample sample;
  LensRequest request;
};

class Planner {
 public:
  explicit Planner(const ShotList& list) : list_(list) {
    if (list.origin) frame_.emplace(*list.origin);
  }

  Trajectory Run(const PlanOptions& options);

 private:
  // The pose before the transition offset (position) and before the rotation offset.
  void Prepare();
  // The steps of Run.
  size_t SampleCount(const PlanOptions& options) const;
  void AddShotSpans(Trajectory& plan) const;
  void SampleShots(Trajectory& plan, std::vector<bool>& cut_before, std::vector<LensRequest>& requests);
  void AddSubjectTracks(Trajectory& plan) const;
  void AddKeyframes(Trajectory& plan);
  Evaluated Evaluate(size_t shot_index, double tau, double fallback_heading_deg,
                     bool apply_rotation_offset = true) const;
  // The steps of Evaluate.
  double RequestedFocalLengthMm(const ShotSpec& shot, const ShotState& st, const ShotPose& pose,
                                const Eigen::Vector3d& position, double lens_time) const;
  // local_from_enu: EnuFrame::LocalLevelFromEnu at the camera (the identity without an origin).
  Eigen::Quaterniond OrientationAt(const ShotSpec& shot, const ShotState& st, const ShotPose& pose,
                                   const Eigen::Vector3d& position, const Eigen::Matrix3d& local_from_enu,
                                   double focal_length_mm, double t, double fallback_heading_deg, double blend_w,
                                   bool apply_rotation_offset) const;
  double RequestedFocusM(const ShotSpec& shot, const ShotState& st, const Eigen::Vector3d& position,
                         const Eigen::Quaterniond& q, double t, double tau, double lens_time) const;
  double ShotFocusM(const ShotSpec& shot, const ShotState& st, const Eigen::Vector3d& position,
                    const Eigen::Quaterniond& q, double t, double tau, double lens_time) const;
  std::vector<std::string> SubjectsInFrame(const TrajectorySample& s, double t) const;
  ShotIntent IntentOf(const ShotSpec& shot) const;

  const ShotList& list_;
  std::optional<EnuFrame> frame_;  // the scene frame about list_.origin, when it has one
  std::vector<FocusOverride> focus_overrides_;
  std::vector<ShotState> states_;
};

// The distance to an actor's aim point along the optical axis (its straight distance when it is not in
// front of the camera).
double AxialDistanceM(const Actor& actor, const Eigen::Vector3d& position, const Eigen::Quaterniond& q, double t) {
  const Eigen::Vector3d v = actor.AimPointAt(t) - position;
  const double along = v.dot(q * Eigen::Vector3d::UnitZ());
  return along > 1e-9 ? along : v.norm();
}

double Smootherstep(double x) { return Ease(Easing::kSmootherstep, x); }

void Planner::Prepare() {
  states_.resize(list_.shots.size());
  double start = 0;
  for (size_t i = 0; i < list_.shots.size(); ++i) {
    const ShotSpec& shot = list_.shots[i];
    ShotState& st = states_[i];
    st.start_s = start;
    start += shot.duration_s;
    if (shot.type == ShotType::kKeyframes) {
      std::vector<double> times;
      std::vector<Eigen::Vector3d> points;
      std::vector<Eigen::Quaterniond> rotations;
      for (const auto& k : shot.keys) {
        times.push_back(k.time_s);
        points.push_back(k.position_enu_m);
        if (k.world_from_camera) rotations.push_back(*k.world_from_camera);
        if (k.focal_length_mm) st.keyframes.focal.push_back({k.time_s, *k.focal_length_mm});
        if (k.focus_distance_m) st.keyframes.focus.push_back({k.time_s, *k.focus_distance_m});
        if (k.f_number) st.keyframes.f_number.push_back({k.time_s, *k.f_number});
      }
      st.keyframes.path = std::make_unique<PathSpline>(times, points, shot.interpolation);
      if (rotations.size() == shot.keys.size() && !rotations.empty()) {
        st.keyframes.q = AlignHemispheres(rotations);
        st.keyframes.s = SquadControlPoints(st.keyframes.q);
      }
    }
  }
  // Transition offsets, in order: each shot starts where the previous (final) pose ended.
  double heading = 0;
  for (size_t i = 1; i < list_.shots.size(); ++i) {
    const ShotSpec& shot = list_.shots[i];
    const ShotSpec& prev_shot = list_.shots[i - 1];
    ShotState& st = states_[i];
    st.blend_s = std::min(shot.blend_s, shot.duration_s);
    if (shot.cut || !(st.blend_s > 0)) {
      st.blend_s = 0;
      continue;
    }
    const Evaluated prev_end = Evaluate(i - 1, prev_shot.duration_s, heading);
    heading = prev_end.sample.drone_heading_deg;
    st.position_offset.setZero();
    st.rotation_offset.setIdentity();
    // Position first: the raw start evaluated without offsets.
    const double saved_blend = st.blend_s;
    st.blend_s = 0;
    const Evaluated raw_start = Evaluate(i, 0.0, heading);
    st.position_offset = prev_end.sample.position_enu_m - raw_start.sample.position_enu_m;
    // Velocities at the join by one-sided differences (a shot shorter than h joins at rest).
    constexpr double h = 1e-4;
    Eigen::Vector3d v_prev = Eigen::Vector3d::Zero(), v_raw = Eigen::Vector3d::Zero();
    if (prev_shot.duration_s >= h) {
      v_prev =
          (prev_end.sample.position_enu_m - Evaluate(i - 1, prev_shot.duration_s - h, heading).sample.position_enu_m) /
          h;
    }
    if (shot.duration_s >= h)
      v_raw = (Evaluate(i, h, heading).sample.position_enu_m - raw_start.sample.position_enu_m) / h;
    st.velocity_offset = v_prev - v_raw;
    st.log_focal_offset = std::log(prev_end.request.focal_length_mm / raw_start.request.focal_length_mm);
    st.log_f_number_offset = std::log(prev_end.request.f_number / raw_start.request.f_number);
    st.blend_s = saved_blend;
    // Then the rotation: the aim from the shifted start, without a rotation offset.
    const Evaluated aimed_start = Evaluate(i, 0.0, heading, /*apply_rotation_offset=*/false);
    st.rotation_offset =
        (prev_end.sample.world_from_camera * aimed_start.sample.world_from_camera.conjugate()).normalized();
  }
}

// A KEYFRAMES shot at local time tau: the spline at the segment-eased time, SLERP/SQUAD between
// key orientations (or an aim at the subject), and the eased time lens keys are read at.
ShotPose EvaluateKeyframes(const ShotSpec& shot, const ShotState& st, const Actor* actor, double t, double tau,
                           double* lens_time) {
  ShotPose pose;
  const auto& keys = shot.keys;
  const double tc = std::clamp(tau, keys.front().time_s, keys.back().time_s);
  size_t k = 0;
  while (k + 2 < keys.size() && tc >= keys[k + 1].time_s) ++k;
  double w = 0, teased = tc;
  if (keys.size() > 1) {
    const double h = keys[k + 1].time_s - keys[k].time_s;
    w = Ease(keys[k].easing, (tc - keys[k].time_s) / h);
    teased = keys[k].time_s + w * h;
  }
  *lens_time = teased;
  pose.position_enu_m = st.keyframes.path->Position(teased);
  if (!st.keyframes.q.empty()) {
    if (keys.size() == 1) {
      pose.world_from_camera = st.keyframes.q[0];
    } else if (shot.orientation == OrientationInterpolation::kSquad) {
      pose.world_from_camera =
          Squad(st.keyframes.q[k], st.keyframes.q[k + 1], st.keyframes.s[k], st.keyframes.s[k + 1], w);
    } else {
      pose.world_from_camera = Slerp(st.keyframes.q[k], st.keyframes.q[k + 1], w);
    }
  } else if (actor) {
    pose.aim_point_enu_m = actor->AimPointAt(t);
  }
  pose.eased = shot.duration_s > 0 ? teased / shot.duration_s : 0;
  return pose;
}

// The transition offset still applied at shot-local time tau (blend_w: position, orientation and
// focal length; velocity_w: the quintic velocity term h(u) = u - 6u^3 + 8u^4 - 3u^5 scaled by blend_s:
// h(0) = 0, h'(0) = 1, and h, h', h'' vanish at 1).
struct BlendWeights {
  double blend_w = 0;
  double velocity_w = 0;
};

BlendWeights BlendAt(const ShotState& st, double tau) {
  BlendWeights w;
  if (st.blend_s > 0) {
    const double u = std::clamp(tau / st.blend_s, 0.0, 1.0);
    w.blend_w = 1.0 - Smootherstep(u);
    w.velocity_w = st.blend_s * u * (1.0 + u * u * (-6.0 + u * (8.0 - 3.0 * u)));
  }
  return w;
}

// The focal length the shot asks for (before clamping to the camera): framing, dolly zoom, free keys,
// or a fixed/zoom lens; `eased` is the shot's eased progress, `lens_time` the time lens keys are read at.
double Planner::RequestedFocalLengthMm(const ShotSpec& shot, const ShotState& st, const ShotPose& pose,
                                       const Eigen::Vector3d& position, double lens_time) const {
  const CameraSpec& cam = list_.camera;
  const LensSpec& lens = shot.lens;
  const Actor* actor = shot.subject >= 0 ? &list_.actors[shot.subject] : nullptr;
  const double image_height_mm = cam.image_extent_mm().height_mm;
  const double subject_distance = pose.aim_point_enu_m ? (*pose.aim_point_enu_m - position).norm() : 0.0;
  if (shot.type == ShotType::kDollyZoom) {
    double fraction;
    if (lens.frame_height_fraction) {
      fraction = *lens.frame_height_fraction;
    } else {
      // Keep the image size the start focal length gives at the start distance.
      const ShotPose start = EvaluateShotPose(shot, list_, st.start_s, 0.0);
      const double d0 = (*start.aim_point_enu_m - start.position_enu_m).norm();
      fraction = ImageHeightFraction(image_height_mm, *lens.focal_length_mm, actor->height_m(), d0);
    }
    return FramingFocalLengthMm(image_height_mm, actor->height_m(), std::max(subject_distance, 1e-6), fraction);
  }
  if (lens.frame_height_fraction && actor) {
    const double k0 = *lens.frame_height_fraction;
    const double k1 = lens.frame_height_fraction_end.value_or(k0);
    const double fraction = std::exp((1 - pose.eased) * std::log(k0) + pose.eased * std::log(k1));
    return FramingFocalLengthMm(image_height_mm, actor->height_m(), std::max(subject_distance, 1e-6), fraction);
  }
  if (!st.keyframes.focal.empty())
    return InterpolateLensKeys(st.keyframes.focal, lens_time, LensQuantity::kFocalLength);
  if (lens.focal_length_mm) {
    return InterpolateFocalLengthMm(*lens.focal_length_mm, lens.focal_length_end_mm.value_or(*lens.focal_length_mm),
                                    pose.eased);
  }
  return cam.min_focal_length_mm;
}

// The camera orientation: given by the shot, aimed at the subject (at the lens's screen position, with a
// crane's tilt blend), straight down, or level along the previous heading; then the transition's
// rotation offset.
Eigen::Quaterniond Planner::OrientationAt(const ShotSpec& shot, const ShotState& st, const ShotPose& pose,
                                          const Eigen::Vector3d& position, const Eigen::Matrix3d& local_from_enu,
                                          double focal_length_mm, double t, double fallback_heading_deg, double blend_w,
                                          bool apply_rotation_offset) const {
  Eigen::Quaterniond q;
  if (pose.world_from_camera) {
    q = *pose.world_from_camera;
  } else {
    // Aimed and levelled where the camera is: the gimbal holds the horizon of the local vertical there,
    // and the fallback heading is a true one (core/local_level.h; the scene frame's axes without an origin).
    Eigen::Quaterniond local_from_camera;
    if (pose.down_up_bearing_deg) {  // straight down the local vertical
      local_from_camera = LookAt(-Eigen::Vector3d::UnitZ(), *pose.down_up_bearing_deg);
    } else if (pose.aim_point_enu_m) {
      const Eigen::Vector3d to_subject = *pose.aim_point_enu_m - position;
      if (to_subject.norm() < 1e-9) {
        throw InputError(list_.source + ": shot \"" + shot.name +
                         "\": the camera reaches the subject's aim point at t = " + std::to_string(t) +
                         " s; nothing to look at");
      }
      const Eigen::Vector3d to_subject_local = local_from_enu * to_subject;
      const Eigen::Vector2d sp = shot.lens.screen_position;
      if (sp.x() == 0.5 && sp.y() == 0.5) {
        local_from_camera = LookAt(to_subject_local, fallback_heading_deg);
      } else {
        const ImageExtentMm image = list_.camera.image_extent_mm();
        const Eigen::Vector3d ray((sp.x() - 0.5) * image.width_mm, (sp.y() - 0.5) * image.height_mm, focal_length_mm);
        local_from_camera = AimWithScreenOffset(to_subject_local, ray, fallback_heading_deg);
      }
      if (pose.tilt_start_deg) {
        GimbalAngles g;
        g.drone_heading_deg = CameraHeadingDeg(local_from_camera);
        g.gimbal_pitch_deg = *pose.tilt_start_deg;
        local_from_camera = Slerp(WorldFromCameraFromGimbal(g), local_from_camera, pose.tilt_weight);
      }
    } else {
      GimbalAngles g;
      g.drone_heading_deg = fallback_heading_deg;
      local_from_camera = WorldFromCameraFromGimbal(g);
    }
    q = Eigen::Quaterniond(local_from_enu.transpose()) * local_from_camera;
  }
  if (apply_rotation_offset && blend_w > 0) {
    q = Slerp(st.rotation_offset, Eigen::Quaterniond::Identity(), 1.0 - blend_w) * q;
  }
  return q.normalized();
}

// The focus the shot asks for: free keys, a fixed distance, or the subject's distance along the optical
// axis with racks between subjects in dioptres; +inf for infinity.
double Planner::RequestedFocusM(const ShotSpec& shot, const ShotState& st, const Eigen::Vector3d& position,
                                const Eigen::Quaterniond& q, double t, double tau, double lens_time) const {
  double focus = ShotFocusM(shot, st, position, q, t, tau, lens_time);
  for (const FocusOverride& o : focus_overrides_) {
    double w = 0;
    if (t >= o.start_s - 1e-9 && t <= o.end_s + 1e-9) {
      w = 1;
    } else if (t < o.start_s && t > o.start_s - o.ramp_s) {
      w = Ease(Easing::kSmoothstep, (t - (o.start_s - o.ramp_s)) / o.ramp_s);
    } else if (t > o.end_s && t < o.end_s + o.ramp_s) {
      w = Ease(Easing::kSmoothstep, (o.end_s + o.ramp_s - t) / o.ramp_s);
    }
    if (w > 0) focus = InterpolateFocusDistanceM(focus, AxialDistanceM(list_.actors[o.actor], position, q, t), w);
  }
  return focus;
}

double Planner::ShotFocusM(const ShotSpec& shot, const ShotState& st, const Eigen::Vector3d& position,
                           const Eigen::Quaterniond& q, double t, double tau, double lens_time) const {
  const LensSpec& lens = shot.lens;
  if (!st.keyframes.focus.empty())
    return InterpolateLensKeys(st.keyframes.focus, lens_time, LensQuantity::kFocusDistance);
  if (lens.focus == LensSpec::Focus::kFixed) return lens.focus_distance_m;
  if (lens.focus != LensSpec::Focus::kFollow || shot.subject < 0) return kInf;
  auto axial = [&](const Actor& a) { return AxialDistanceM(a, position, q, t); };
  const Actor* current = &list_.actors[shot.subject];
  double focus = axial(*current);
  for (const auto& r : lens.rack) {
    const Actor& next = list_.actors[r.actor];
    if (tau <= r.at_s) break;
    const double w = Ease(Easing::kSmoothstep, (tau - r.at_s) / r.duration_s);
    focus = InterpolateFocusDistanceM(axial(*current), axial(next), w);
    current = &next;
  }
  return focus;
}

// The actors whose aim points project inside the image (sensor-fit rule, core/optics.h).
std::vector<std::string> Planner::SubjectsInFrame(const TrajectorySample& s, double t) const {
  std::vector<std::string> names;
  const Eigen::Quaterniond camera_from_world = s.world_from_camera.conjugate();
  const ImageExtentMm image = list_.camera.image_extent_mm();
  const double half_w = image.width_mm / (2.0 * s.focal_length_mm);
  const double half_h = image.height_mm / (2.0 * s.focal_length_mm);
  for (const auto& a : list_.actors) {
    const Eigen::Vector3d c = camera_from_world * (a.AimPointAt(t) - s.position_enu_m);
    if (c.z() > 1e-9 && std::fabs(c.x() / c.z()) <= half_w && std::fabs(c.y() / c.z()) <= half_h) {
      names.push_back(a.name());
    }
  }
  return names;
}

// One sample of shot `index` at shot-local time tau: pose, transition offset, focal length,
// orientation, focus, aperture and shutter (each clamped to the camera, the request kept for the
// feasibility report), and the subjects in frame.
Evaluated Planner::Evaluate(size_t index, double tau, double fallback_heading_deg, bool apply_rotation_offset) const {
  const ShotSpec& shot = list_.shots[index];
  const ShotState& st = states_[index];
  const CameraSpec& cam = list_.camera;
  const double t = st.start_s + tau;
  const Actor* actor = shot.subject >= 0 ? &list_.actors[shot.subject] : nullptr;

  double lens_time = tau;  // local time that lens keys are read at (eased for free keyframes)
  const ShotPose pose = shot.type == ShotType::kKeyframes ? EvaluateKeyframes(shot, st, actor, t, tau, &lens_time)
                                                          : EvaluateShotPose(shot, list_, st.start_s, tau);
  const BlendWeights blend = BlendAt(st, tau);

  Evaluated out;
  TrajectorySample& s = out.sample;
  s.time_s = t;
  s.shot = shot.name;
  s.position_enu_m = pose.position_enu_m + blend.blend_w * st.position_offset + blend.velocity_w * st.velocity_offset;
  // The local level frame where the camera is (core/local_level.h) and, from the same step, its lat/lon/h.
  const Eigen::Matrix3d local_from_enu =
      frame_ ? frame_->LocalLevelFromEnu(s.position_enu_m, &s.geodetic) : Eigen::Matrix3d::Identity().eval();

  out.request.focal_length_mm = RequestedFocalLengthMm(shot, st, pose, s.position_enu_m, lens_time) *
                                std::exp(blend.blend_w * st.log_focal_offset);
  s.focal_length_mm = std::clamp(out.request.focal_length_mm, cam.min_focal_length_mm, cam.max_focal_length_mm);

  s.world_from_camera = OrientationAt(shot, st, pose, s.position_enu_m, local_from_enu, s.focal_length_mm, t,
                                      fallback_heading_deg, blend.blend_w, apply_rotation_offset);
  // Against true north and the vertical where the camera is.
  const GimbalAngles g = GimbalFromWorldFromCamera(Eigen::Quaterniond(local_from_enu) * s.world_from_camera);
  s.drone_heading_deg = g.drone_heading_deg;
  s.gimbal_pitch_deg = g.gimbal_pitch_deg;
  s.gimbal_roll_deg = g.gimbal_roll_deg;
  s.gimbal_yaw_deg = g.gimbal_yaw_deg;

  out.request.focus_distance_m = RequestedFocusM(shot, st, s.position_enu_m, s.world_from_camera, t, tau, lens_time);
  s.focus_distance_m = std::isinf(out.request.focus_distance_m)
                           ? out.request.focus_distance_m
                           : std::max(out.request.focus_distance_m, cam.min_focus_distance_m);

  out.request.f_number = std::clamp(4.0, cam.min_f_number, cam.max_f_number);
  if (!st.keyframes.f_number.empty()) {
    out.request.f_number = InterpolateLensKeys(st.keyframes.f_number, lens_time, LensQuantity::kFNumber);
  } else if (!shot.lens.f_number.empty()) {
    out.request.f_number = InterpolateLensKeys(shot.lens.f_number, tau, LensQuantity::kFNumber);
  }
  out.request.f_number *= std::exp(blend.blend_w * st.log_f_number_offset);
  s.f_number = std::clamp(out.request.f_number, cam.min_f_number, cam.max_f_number);
  s.shutter_s = shot.lens.shutter_s.empty() ? 1.0 / (2.0 * list_.frame_rate_hz)
                                            : InterpolateLensKeys(shot.lens.shutter_s, tau, LensQuantity::kShutter);

  s.subjects_in_frame = SubjectsInFrame(s, t);
  return out;
}

// What the shot asks of the picture, as plan.json carries it for `optimize`.
ShotIntent Planner::IntentOf(const ShotSpec& shot) const {
  ShotIntent intent;
  const bool focus_keys = std::any_of(shot.keys.begin(), shot.keys.end(),
                                      [](const CameraKey& k) { return k.focus_distance_m.has_value(); });
  if (focus_keys) {
    intent.focus = "keys";
  } else if (shot.lens.focus == LensSpec::Focus::kFixed) {
    intent.focus = "fixed";
  } else if (shot.lens.focus == LensSpec::Focus::kInfinity || shot.subject < 0) {
    intent.focus = "infinity";
  } else if (shot.lens.rack.empty()) {
    intent.focus = "follow";
  } else {
    intent.focus = "rack";
    for (const RackFocus& r : shot.lens.rack)
      intent.rack.push_back({r.at_s, r.duration_s, list_.actors[r.actor].name()});
  }
  if (shot.type != ShotType::kDollyZoom || shot.lens.frame_height_fraction) {
    intent.frame_height_fraction = shot.lens.frame_height_fraction;
    intent.frame_height_fraction_end = shot.lens.frame_height_fraction_end;
  }
  if (shot.subject >= 0) intent.screen_position = shot.lens.screen_position;
  for (int a : shot.lens.sharp) intent.sharp.push_back(list_.actors[a].name());
  intent.background_blur_px = shot.lens.background_blur_px;
  intent.background_distance_m = shot.lens.background_distance_m;
  intent.hold = shot.optimize.hold;
  intent.max_deviation_m = shot.optimize.max_deviation_m;
  intent.retime = shot.optimize.retime;
  return intent;
}

Trajectory Planner::Run(const PlanOptions& options) {
  focus_overrides_ = options.focus_overrides;
  for (const FocusOverride& o : focus_overrides_) CINEPATH_CHECK(o.actor >= 0 && o.ramp_s > 0);
  Prepare();
  Trajectory plan;
  plan.origin = list_.origin;
  plan.frame_rate_hz = list_.frame_rate_hz;
  plan.camera = list_.camera;
  plan.drone = list_.drone;
  const size_t n = SampleCount(options);
  AddShotSpans(plan);
  std::vector<bool> cut_before(n, false);
  std::vector<LensRequest> requests(n);
  plan.samples.resize(n);
  SampleShots(plan, cut_before, requests);
  AddSubjectTracks(plan);
  AddKeyframes(plan);
  plan.feasibility = CheckFeasibility(plan, cut_before, requests, list_.ground.get());
  return plan;
}

// Samples at the frame rate over every shot's duration; InputError beyond the limit.
size_t Planner::SampleCount(const PlanOptions& options) const {
  double total = 0;
  for (const auto& s : list_.shots) total += s.duration_s;
  const double frames = std::floor(total * list_.frame_rate_hz + 1e-9);
  if (frames + 1 > static_cast<double>(options.max_samples)) {
    throw InputError(list_.source + ": " + std::to_string(static_cast<long long>(frames + 1)) +
                     " samples (duration x frame_rate_hz) exceed the limit of " + std::to_string(options.max_samples) +
                     "; lower frame_rate_hz");
  }
  return static_cast<size_t>(frames) + 1;
}

void Planner::AddShotSpans(Trajectory& plan) const {
  for (size_t i = 0; i < list_.shots.size(); ++i) {
    const ShotSpec& shot = list_.shots[i];
    ShotSpan span;
    span.name = shot.name;
    span.type = std::string(ShotTypeName(shot.type));
    span.subject = shot.subject >= 0 ? list_.actors[shot.subject].name() : "";
    span.transition = shot.cut ? "cut" : "continuous";
    span.start_time_s = states_[i].start_s;
    span.end_time_s = states_[i].start_s + shot.duration_s;
    span.intent = IntentOf(shot);
    plan.shots.push_back(span);
  }
}

// Every sample: its shot, pose and lens; a cut before it where the shots say so; the lens asked for.
void Planner::SampleShots(Trajectory& plan, std::vector<bool>& cut_before, std::vector<LensRequest>& requests) {
  // Which shot owns sample k: the last shot with start <= t and (t < end or it is the last shot
  // with a positive duration).
  const size_t n = plan.samples.size();
  double heading = 0;
  size_t shot = 0;
  size_t last_positive = 0;
  for (size_t i = 0; i < list_.shots.size(); ++i) {
    if (list_.shots[i].duration_s > 0) last_positive = i;
  }
  size_t prev_shot = 0;
  for (size_t k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) / list_.frame_rate_hz;
    while (shot < last_positive && t >= states_[shot].start_s + list_.shots[shot].duration_s - 1e-12) ++shot;
    if (list_.shots[shot].duration_s == 0 && shot < last_positive) ++shot;
    const double tau = std::clamp(t - states_[shot].start_s, 0.0, list_.shots[shot].duration_s);
    Evaluated e = Evaluate(shot, tau, heading);
    e.sample.time_s = t;
    heading = e.sample.drone_heading_deg;
    if (k > 0 && shot != prev_shot) {
      for (size_t j = prev_shot + 1; j <= shot; ++j) cut_before[k] = cut_before[k] || list_.shots[j].cut;
    }
    prev_shot = shot;
    plan.samples[k] = std::move(e.sample);
    requests[k] = e.request;
  }
}

void Planner::AddSubjectTracks(Trajectory& plan) const {
  for (const auto& a : list_.actors) {
    SubjectTrack track;
    track.name = a.name();
    track.height_m = a.height_m();
    track.positions_enu_m.reserve(plan.samples.size());
    for (const auto& s : plan.samples) track.positions_enu_m.push_back(a.PositionAt(s.time_s));
    plan.subjects.push_back(std::move(track));
  }
}

// Keyframes: each shot's start and end (and every free key), final poses.
void Planner::AddKeyframes(Trajectory& plan) {
  double heading = 0;
  for (size_t i = 0; i < list_.shots.size(); ++i) {
    const ShotSpec& shot_spec = list_.shots[i];
    std::vector<double> taus = {0.0};
    if (shot_spec.type == ShotType::kKeyframes) {
      for (const auto& k : shot_spec.keys) {
        if (k.time_s > 0) taus.push_back(k.time_s);
      }
    }
    if (shot_spec.duration_s > taus.back()) taus.push_back(shot_spec.duration_s);
    for (double tau : taus) {
      const Evaluated e = Evaluate(i, tau, heading);
      heading = e.sample.drone_heading_deg;
      Keyframe key;
      key.shot = shot_spec.name;
      key.time_s = states_[i].start_s + tau;
      key.position_enu_m = e.sample.position_enu_m;
      key.world_from_camera = e.sample.world_from_camera;
      key.focal_length_mm = e.sample.focal_length_mm;
      key.focus_distance_m = e.sample.focus_distance_m;
      key.f_number = e.sample.f_number;
      plan.keyframes.push_back(key);
    }
  }
}

}  // namespace

Trajectory PlanShots(const ShotList& list, const PlanOptions& options) {
  // The actors a shot follows past a last key they reach moving (the shots run back to back): their cameras
  // ease into the stop (Actor::EaseCameraIntoTheStop).
  std::vector<size_t> stopping;
  double start_s = 0;
  for (const ShotSpec& shot : list.shots) {
    const double end_s = start_s + shot.duration_s;
    if (shot.subject >= 0) {
      const Actor& actor = list.actors[shot.subject];
      const double last_s = actor.path().times().back();
      if (last_s >= start_s && last_s < end_s - 1.0 / list.frame_rate_hz &&
          actor.SpeedAtLastKeyMS() > Actor::kMovingMS &&
          std::find(stopping.begin(), stopping.end(), size_t(shot.subject)) == stopping.end()) {
        stopping.push_back(shot.subject);
      }
    }
    start_s = end_s;
  }
  if (stopping.empty()) return Planner(list).Run(options);
  ShotList eased = list;
  for (size_t a : stopping) eased.actors[a].EaseCameraIntoTheStop();
  return Planner(eased).Run(options);
}

}  // namespace cinepath::shots
