#include "shots/planner.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "core/angles.h"
#include "core/error.h"
#include "core/rotation.h"
#include "shots/lens_track.h"

namespace cinepath::shots {
namespace {

using Eigen::Vector3d;

// A shot list around one actor; `shots` is the JSON array text.
Json ShotsDoc(const std::string& shots, const std::string& actors = "", double fps = 30,
              const std::string& camera_extra = "") {
  const std::string actor_list =
      actors.empty() ? R"([{"name": "hero", "height_m": 1.8, "position_enu_m": [5, -3, 2]}])" : actors;
  return Json::parse(R"({"schema": "cinepath.shots/1", "frame_rate_hz": )" + std::to_string(fps) +
                     R"(, "camera": {"filmback": "super35", "min_focal_length_mm": 12, "max_focal_length_mm": 1200)" +
                     camera_extra + R"(}, "drone": "px4_default_quad", "actors": )" + actor_list + R"(, "shots": )" +
                     shots + "}");
}

Trajectory Plan(const std::string& shots, const std::string& actors = "", double fps = 30) {
  return PlanShots(ParseShotList(ShotsDoc(shots, actors, fps), "shots.json"));
}

// Angle between the camera's ray through the subject's screen position and the subject.
double LookAtErrorRad(const TrajectorySample& s, const Vector3d& target) {
  const Vector3d forward = s.world_from_camera * Vector3d::UnitZ();
  const Vector3d to = (target - s.position_enu_m).normalized();
  return std::atan2(forward.cross(to).norm(), forward.dot(to));
}

TEST(PlanOrbit, RadiusAndHeightExactWithLinearEasing) {
  const Trajectory plan = Plan(
      R"([{"name": "o", "type": "ORBIT", "subject": "hero", "duration_s": 12, "radius_m": 37.5, "height_m": 14,
           "turns": 1.25, "direction": "cw", "start_bearing_deg": 30, "easing": "linear"}])");
  ASSERT_EQ(plan.samples.size(), 12u * 30u + 1u);
  const Vector3d subject(5, -3, 2);
  const Vector3d aim = subject + Vector3d(0, 0, 0.9);
  double angle_prev = 0;
  for (size_t i = 0; i < plan.samples.size(); ++i) {
    const auto& s = plan.samples[i];
    const Vector3d d = s.position_enu_m - subject;
    EXPECT_NEAR(std::hypot(d.x(), d.y()), 37.5, 1e-9) << i;
    EXPECT_NEAR(d.z(), 14.0, 1e-9) << i;
    EXPECT_NEAR(LookAtErrorRad(s, aim), 0.0, 1e-12) << i;
    // Constant angular speed, clockwise seen from above (compass bearing grows).
    const double bearing = NormalizeDeg360(DegFromRad(std::atan2(d.x(), d.y())));
    if (i > 0) EXPECT_NEAR(AngleDiffDeg(angle_prev, bearing), 450.0 / 360.0, 1e-9) << i;
    angle_prev = bearing;
    EXPECT_NEAR(s.world_from_camera.norm(), 1.0, 1e-12);
    EXPECT_EQ(s.subjects_in_frame, std::vector<std::string>{"hero"});
  }
  // Start bearing 30 deg from the subject.
  const Vector3d d0 = plan.samples.front().position_enu_m - subject;
  EXPECT_NEAR(d0.x(), 37.5 * std::sin(RadFromDeg(30)), 1e-9);
  EXPECT_NEAR(d0.y(), 37.5 * std::cos(RadFromDeg(30)), 1e-9);
}

TEST(PlanOrbit, RadiusZeroIsACleanError) {
  try {
    Plan(R"([{"type": "ORBIT", "subject": "hero", "duration_s": 5, "radius_m": 2, "height_m": 3, "turns": 1},
             {"type": "ORBIT", "subject": "hero", "duration_s": 5, "radius_m": 0, "height_m": 3, "turns": 1}])");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "shots.json: shots[1].radius_m: must be > 0");
  }
}

TEST(PlanLookAt, ZeroErrorForEveryAimedShotType) {
  const std::string car = R"([{"name": "hero", "height_m": 1.5, "interpolation": "catmull_rom", "keyframes": [
      {"time_s": 0, "position_enu_m": [0, 0, 0]}, {"time_s": 10, "position_enu_m": [80, 10, 0]},
      {"time_s": 20, "position_enu_m": [120, 70, 2]}, {"time_s": 60, "position_enu_m": [300, 100, 5]}]}])";
  const Trajectory plan = Plan(R"([
      {"name": "a", "type": "CHASE", "subject": "hero", "duration_s": 6, "distance_m": 15, "height_m": 5,
        "lateral_m": 2, "lag_s": 0.5, "transition": "cut"},
      {"name": "b", "type": "FLYBY", "subject": "hero", "duration_s": 6, "closest_distance_m": 12, "height_m": 4,
        "speed_m_s": 5, "transition": "cut"},
      {"name": "c", "type": "TRACK", "subject": "hero", "duration_s": 6, "distance_m": 10, "side": "left",
        "transition": "cut"},
      {"name": "d", "type": "CRANE", "subject": "hero", "duration_s": 6, "distance_m": 10, "height_m": 2,
        "height_end_m": 20, "transition": "cut"},
      {"name": "e", "type": "DRONIE", "subject": "hero", "duration_s": 6, "distance_m": 5, "distance_end_m": 60,
        "height_m": 3, "height_end_m": 40, "transition": "cut"},
      {"name": "f", "type": "HELIX", "subject": "hero", "duration_s": 6, "radius_m": 10, "radius_end_m": 20,
        "height_m": 3, "height_end_m": 30, "turns": 1, "transition": "cut"},
      {"name": "g", "type": "LOCKED-OFF", "subject": "hero", "duration_s": 6, "position_enu_m": [200, -40, 30],
        "pan": true, "transition": "cut"}
  ])",
                               car);
  for (const auto& s : plan.samples) {
    const Vector3d aim = plan.subjects[0].positions_enu_m[&s - &plan.samples[0]] + Vector3d(0, 0, 0.75);
    EXPECT_LT(LookAtErrorRad(s, aim), 1e-12) << s.shot << " t=" << s.time_s;
    EXPECT_LT(std::fabs(s.gimbal_roll_deg), 1e-9) << "level horizon";
  }
}

TEST(PlanLookAt, ScreenPositionPutsTheSubjectOnTheThird) {
  const Trajectory plan = Plan(
      R"([{"type": "ORBIT", "subject": "hero", "duration_s": 4, "radius_m": 20, "height_m": 8, "turns": 0.25,
           "lens": {"focal_length_mm": 35, "screen_position": "upper_left_third"}}])");
  // The 16:9 image covers 24.89 x 14.0006 mm of the 4:3 Super 35 filmback (sensor fit, core/optics.h).
  const double w = 24.89, h = 24.89 * 2160.0 / 3840.0;
  for (const auto& s : plan.samples) {
    const Vector3d c = s.world_from_camera.conjugate() * (Vector3d(5, -3, 2.9) - s.position_enu_m);
    const double x_mm = c.x() / c.z() * s.focal_length_mm, y_mm = c.y() / c.z() * s.focal_length_mm;
    EXPECT_NEAR(x_mm / w + 0.5, 1.0 / 3.0, 1e-9);
    EXPECT_NEAR(y_mm / h + 0.5, 1.0 / 3.0, 1e-9);
  }
}

// The sensor-fit rule: a subject planned at a frame-height fraction fills that fraction of the image's
// rows, measured by projecting its feet and head to pixels (a 16:9 image on a 4:3 filmback, where
// framing by the filmback's height would give 0.4 instead of 0.3).
TEST(PlanFraming, SubjectFillsThePlannedFractionOfTheImageRows) {
  const Trajectory plan = Plan(
      R"([{"type": "ORBIT", "subject": "hero", "duration_s": 2, "radius_m": 30, "height_m": 0,
           "turns": 0.1, "lens": {"frame_height_fraction": 0.3}}])");
  ASSERT_EQ(plan.camera.width_px, 3840);
  ASSERT_EQ(plan.camera.height_px, 2160);
  const Vector3d base(5, -3, 2), top = base + Vector3d(0, 0, 1.8);
  for (const auto& s : plan.samples) {
    // Pixels per unit of x/z: fx = f * W / sensor width; square pixels, so fy = fx.
    const double f_px = s.focal_length_mm * plan.camera.width_px / plan.camera.sensor_width_mm;
    const auto q = s.world_from_camera.conjugate();
    const Vector3d a = q * (base - s.position_enu_m), b = q * (top - s.position_enu_m);
    const double rows = std::fabs(a.y() / a.z() - b.y() / b.z()) * f_px;
    EXPECT_NEAR(rows / plan.camera.height_px, 0.3, 1e-3) << "t=" << s.time_s;
  }
}

TEST(PlanDollyZoom, ImageHeightConstantWithinATenthOfAPercent) {
  const Trajectory plan = Plan(
      R"([{"type": "DOLLY-ZOOM", "subject": "hero", "duration_s": 8, "distance_m": 8, "distance_end_m": 40,
           "bearing_deg": 200, "easing": "smootherstep", "lens": {"focal_length_mm": 24}}])");
  const Vector3d base(5, -3, 2), top = base + Vector3d(0, 0, 1.8);
  const double sensor_h = 24.89 * 2160.0 / 3840.0;  // the image's height on the sensor
  double first = 0;
  double f_min = 1e9, f_max = 0;
  for (const auto& s : plan.samples) {
    // Project the subject's feet and head onto the sensor (pinhole at the sample's focal length).
    const auto q = s.world_from_camera.conjugate();
    const Vector3d a = q * (base - s.position_enu_m), b = q * (top - s.position_enu_m);
    const double image_fraction = std::fabs(a.y() / a.z() - b.y() / b.z()) * s.focal_length_mm / sensor_h;
    if (first == 0) first = image_fraction;
    EXPECT_NEAR(image_fraction / first, 1.0, 1e-3) << "t=" << s.time_s;
    f_min = std::min(f_min, s.focal_length_mm);
    f_max = std::max(f_max, s.focal_length_mm);
  }
  EXPECT_NEAR(plan.samples.front().focal_length_mm, 24.0, 1e-9);
  EXPECT_NEAR(f_max / f_min, 5.0, 1e-6);  // distance x5 -> focal x5
}

TEST(PlanExtremes, SubjectStraightBelowTheCamera) {
  const Trajectory plan = Plan(
      R"([{"type": "TOP-DOWN", "subject": "hero", "duration_s": 3, "height_m": 50, "up_bearing_deg": 90,
           "rotate_deg": 90},
          {"type": "LOCKED-OFF", "subject": "hero", "duration_s": 2, "position_enu_m": [5, -3, 60],
            "transition": "cut"}])");
  for (const auto& s : plan.samples) {
    EXPECT_NEAR(s.gimbal_pitch_deg, -90.0, 1e-9) << s.time_s;
    EXPECT_TRUE(s.world_from_camera.coeffs().allFinite());
    EXPECT_NEAR((s.world_from_camera * Vector3d::UnitZ() - Vector3d(0, 0, -1)).norm(), 0.0, 1e-12);
    EXPECT_EQ(s.subjects_in_frame, std::vector<std::string>{"hero"});
  }
  // TOP-DOWN: image top toward east at the start, turning clockwise to south at the end.
  EXPECT_NEAR(plan.samples.front().drone_heading_deg, 90.0, 1e-9);
  EXPECT_NEAR(plan.samples[89].drone_heading_deg, 90.0 + 90.0 * 89.0 / 90.0, 1e-9);
  EXPECT_NEAR(CameraHeadingDeg(plan.keyframes[1].world_from_camera), 180.0, 1e-9);
  // The locked-off nadir shot keeps the heading it inherited (the undefined-roll rule).
  EXPECT_NEAR(plan.samples[90].drone_heading_deg, plan.samples[89].drone_heading_deg, 1e-9);
}

TEST(PlanExtremes, ZeroLengthShots) {
  // A zero-length plan has one sample; a zero-length shot inside a plan owns no sample.
  const Trajectory still =
      Plan(R"([{"type": "ORBIT", "subject": "hero", "duration_s": 0, "radius_m": 10, "height_m": 5, "turns": 1}])");
  ASSERT_EQ(still.samples.size(), 1u);
  EXPECT_NEAR(still.samples[0].time_s, 0.0, 0.0);
  const Trajectory mixed = Plan(R"([
      {"name": "a", "type": "ORBIT", "subject": "hero", "duration_s": 1, "radius_m": 10, "height_m": 5, "turns": 0.1},
      {"name": "z", "type": "ORBIT", "subject": "hero", "duration_s": 0, "radius_m": 12, "height_m": 5, "turns": 0.1},
      {"name": "b", "type": "ORBIT", "subject": "hero", "duration_s": 1, "radius_m": 10, "height_m": 5, "turns": 0.1,
        "transition": "cut"}])");
  ASSERT_EQ(mixed.samples.size(), 61u);
  for (const auto& s : mixed.samples) EXPECT_NE(s.shot, "z");
  EXPECT_EQ(mixed.samples[30].shot, "b");
  EXPECT_EQ(mixed.shots[1].start_time_s, 1.0);
  EXPECT_EQ(mixed.shots[1].end_time_s, 1.0);
}

TEST(PlanExtremes, HundredThousandSecondOrbit) {
  const Trajectory plan = Plan(
      R"([{"type": "ORBIT", "subject": "hero", "duration_s": 100000, "radius_m": 50, "height_m": 20,
           "angular_speed_deg_s": 3}])",
      "", 1.0);
  ASSERT_EQ(plan.samples.size(), 100001u);
  const Vector3d subject(5, -3, 2);
  for (size_t i = 0; i < plan.samples.size(); i += 997) {
    const Vector3d d = plan.samples[i].position_enu_m - subject;
    EXPECT_NEAR(std::hypot(d.x(), d.y()), 50.0, 1e-9);
    EXPECT_NEAR(d.z(), 20.0, 1e-9);
  }
  EXPECT_EQ(plan.samples.back().time_s, 100000.0);
  // Samples per frame rate x duration beyond the guard: a clean error, not an allocation failure.
  EXPECT_THROW(
      Plan(R"([{"type": "ORBIT", "subject": "hero", "duration_s": 1e7, "radius_m": 50, "height_m": 20, "turns": 1}])",
           "", 1000.0),
      InputError);
}

TEST(PlanExtremes, Framing1200mmAt2km) {
  // A 1.8 m subject 2 km away filling 7.7 % of a 16:9 frame on Super 35 (14.0 mm high) needs ~1200 mm.
  const double target_focal = 1200.0;
  const double fraction = ImageHeightFraction(24.89 * 2160.0 / 3840.0, target_focal, 1.8, 2000.0);
  const Trajectory plan = Plan(
      R"([{"type": "LOCKED-OFF", "subject": "hero", "duration_s": 1, "bearing_deg": 0, "distance_m": 2000,
        "height_m": 0.9,
           "lens": {"frame_height_fraction": )" +
      Json(fraction).dump() + R"(}}])");
  for (const auto& s : plan.samples) {
    EXPECT_NEAR(s.focal_length_mm, target_focal, 1e-3);
    EXPECT_NEAR(s.focus_distance_m, 2000.0, 1e-6);
    EXPECT_EQ(s.subjects_in_frame, std::vector<std::string>{"hero"});
  }
  EXPECT_TRUE(plan.feasibility.feasible()) << plan.feasibility.violations[0].limit;
  // Asking for 20 % more than the lens has is clamped and reported.
  const Trajectory over = Plan(
      R"([{"type": "LOCKED-OFF", "subject": "hero", "duration_s": 1, "bearing_deg": 0, "distance_m": 2000,
        "height_m": 0.9,
           "lens": {"frame_height_fraction": )" +
      Json(fraction * 1.2).dump() + R"(}}])");
  EXPECT_NEAR(over.samples[0].focal_length_mm, 1200.0, 1e-9);
  ASSERT_FALSE(over.feasibility.feasible());
  EXPECT_EQ(over.feasibility.violations[0].limit, "focal_length_max");
  EXPECT_NEAR(over.feasibility.violations[0].worst_value, 1440.0, 1e-2);
}

TEST(PlanTransitions, ContinuousInPositionAndOrientation) {
  const Trajectory plan = Plan(R"([
      {"name": "a", "type": "ORBIT", "subject": "hero", "duration_s": 4, "radius_m": 20, "height_m": 5, "turns": 0.25},
      {"name": "b", "type": "DRONIE", "subject": "hero", "duration_s": 4, "distance_m": 30, "distance_end_m": 60,
       "height_m": 10, "height_end_m": 30, "bearing_deg": 45, "blend_s": 2}])");
  // Across the boundary (t = 4 s, sample 120) the step is no larger than a normal frame step.
  double max_step = 0, max_turn = 0;
  for (size_t i = 1; i < plan.samples.size(); ++i) {
    if (i == 120) continue;
    max_step = std::max(max_step, (plan.samples[i].position_enu_m - plan.samples[i - 1].position_enu_m).norm());
    max_turn =
        std::max(max_turn, AngleBetweenRad(plan.samples[i].world_from_camera, plan.samples[i - 1].world_from_camera));
  }
  EXPECT_LE((plan.samples[120].position_enu_m - plan.samples[119].position_enu_m).norm(), max_step * 1.5);
  EXPECT_LE(AngleBetweenRad(plan.samples[120].world_from_camera, plan.samples[119].world_from_camera), max_turn * 1.5);
  // After the blend the dronie is on its own geometry: 2 s in, back on the bearing-45 line.
  const Vector3d d = plan.samples[180].position_enu_m - Vector3d(5, -3, 2);
  EXPECT_NEAR(NormalizeDeg360(DegFromRad(std::atan2(d.x(), d.y()))), 45.0, 1e-9);
  // An explicit cut jumps.
  const Trajectory cut = Plan(R"([
      {"name": "a", "type": "ORBIT", "subject": "hero", "duration_s": 4, "radius_m": 20, "height_m": 5, "turns": 0.25},
      {"name": "b", "type": "DRONIE", "subject": "hero", "duration_s": 4, "distance_m": 30, "distance_end_m": 60,
       "height_m": 10, "height_end_m": 30, "bearing_deg": 45, "transition": "cut"}])");
  EXPECT_GT((cut.samples[120].position_enu_m - cut.samples[119].position_enu_m).norm(), 10.0);
}

// A continuous join whose previous shot ends at a moving actor's key (bug 2026-11-29): a FLYBY past a
// walker ends at t = 6 s, the walker's second key, and a CHASE blends in from it. The join matches the
// flyby's velocity: the first step of the chase is a normal frame step, not the 16 m/s dash the blend took
// when the actor's direction of travel jumped by a millimetre's worth at its key.
// A CHASE that runs on past its actor's last key, reached at 1.5 m/s: the actor stops dead there, and the
// camera eases into the stop (Actor::EaseCameraIntoTheStop) within the drone's acceleration and jerk. With the
// camera stopping with the actor the plan broke jerk by hundreds of m/s^3 at the key.
TEST(PlanChase, TheCameraEasesIntoTheStopOfAnActorFollowedPastItsLastKey) {
  const std::string walker = R"([{"name": "walker", "height_m": 1.8, "keyframes": [
    {"time_s": 0, "position_enu_m": [0, 0, 0]}, {"time_s": 10, "position_enu_m": [15, 0, 0]}]}])";
  const Trajectory plan =
      Plan(R"([{"type": "CHASE", "subject": "walker", "duration_s": 16, "distance_m": 12, "height_m": 5}])", walker);
  for (const auto& v : plan.feasibility.violations) {
    EXPECT_NE(v.limit, "jerk") << v.start_time_s << "-" << v.end_time_s << " s: " << v.worst_value;
    EXPECT_NE(v.limit, "horizontal_acceleration") << v.start_time_s << "-" << v.end_time_s << " s: " << v.worst_value;
  }
  // At rest a second after the key, 12 m behind where the walker stopped, 5 m up.
  const TrajectorySample& end = plan.samples.back();
  EXPECT_NEAR((end.position_enu_m - Vector3d(3, 0, 5)).norm(), 0.0, 1e-6);
  const TrajectorySample& before = plan.samples[plan.samples.size() - 31];
  EXPECT_NEAR((before.position_enu_m - end.position_enu_m).norm(), 0.0, 1e-6);
  // Well before the key the camera is where it would be without easing: 12 m behind the walker.
  const TrajectorySample& mid = plan.samples[5 * 30];
  EXPECT_NEAR((mid.position_enu_m - Vector3d(7.5 - 12, 0, 5)).norm(), 0.0, 1e-6);
}

TEST(PlanTransitions, ABlendFromAShotEndingAtAnActorsKeyKeepsItsVelocity) {
  const std::string walker = R"([{"name": "walker", "height_m": 1.75, "interpolation": "catmull_rom", "keyframes": [
      {"time_s": 0, "position_enu_m": [-20, -12, 0]}, {"time_s": 6, "position_enu_m": [-8, -12, 0]},
      {"time_s": 12, "position_enu_m": [4, -10, 0]}, {"time_s": 18, "position_enu_m": [12, -2, 0]}]}])";
  const Trajectory plan = Plan(R"([
      {"name": "a", "type": "FLYBY", "subject": "walker", "duration_s": 6, "closest_distance_m": 9, "side": "right",
       "height_m": 3, "speed_m_s": 3},
      {"name": "b", "type": "CHASE", "subject": "walker", "duration_s": 6, "distance_m": 8, "height_m": 3,
       "lateral_m": 2, "blend_s": 3}])",
                               walker);
  ASSERT_EQ(plan.samples[180].shot, "b");
  const double dt = 1.0 / 30;
  const Vector3d v_before = (plan.samples[179].position_enu_m - plan.samples[178].position_enu_m) / dt;
  for (size_t i = 180; i <= 182; ++i) {
    const Vector3d v = (plan.samples[i].position_enu_m - plan.samples[i - 1].position_enu_m) / dt;
    EXPECT_LT((v - v_before).norm(), 0.2)
        << "sample " << i << ": " << v.transpose() << " after " << v_before.transpose();
  }
}

// A continuous join between shots at f/2.8 and f/4 eases the aperture over the blend (in stops) and ends
// on the shot's own f-number; a cut steps. Before 2026-11-29 the continuous join stepped one stop in a frame
// (30 stops/s against a lens's 3).
TEST(PlanTransitions, AContinuousJoinEasesTheApertureInStops) {
  const std::string shots = R"([
      {"name": "a", "type": "ORBIT", "subject": "hero", "duration_s": 4, "radius_m": 20, "height_m": 5, "turns": 0.25,
       "lens": {"focal_length_mm": 35, "f_number": 2.8}},
      {"name": "b", "type": "ORBIT", "subject": "hero", "duration_s": 4, "radius_m": 20, "height_m": 5, "turns": 0.25,
       "start_bearing_deg": 90, "blend_s": 2, "TRANSITION" "lens": {"focal_length_mm": 35, "f_number": 4}}])";
  auto with = [&](const std::string& transition) {
    std::string s = shots;
    s.replace(s.find("\"TRANSITION\" "), 13, transition);
    return Plan(s);
  };
  const Trajectory plan = with("");
  double worst_stops_per_frame = 0;
  for (size_t i = 1; i < plan.samples.size(); ++i) {
    worst_stops_per_frame = std::max(worst_stops_per_frame,
                                     std::fabs(2 * std::log2(plan.samples[i].f_number / plan.samples[i - 1].f_number)));
  }
  EXPECT_NEAR(plan.samples[119].f_number, 2.8, 1e-9);
  EXPECT_LT(worst_stops_per_frame * 30, 1.0);  // 1.03 stops eased over 2 s: at most 0.97 stops/s
  EXPECT_NEAR(plan.samples[180].f_number, 4.0, 1e-9);
  const Trajectory cut = with(R"("transition": "cut", )");
  EXPECT_NEAR(cut.samples[119].f_number, 2.8, 1e-9);
  EXPECT_NEAR(cut.samples[120].f_number, 4.0, 1e-9);
}

TEST(PlanLens, RackFocusInDioptresAndApertureInStops) {
  const std::string actors = R"([{"name": "near", "height_m": 1.8, "position_enu_m": [0, 10, 0]},
                                 {"name": "far", "height_m": 1.8, "position_enu_m": [0, 40, 0]}])";
  const Trajectory plan = Plan(
      R"([{"type": "LOCKED-OFF", "subject": "near", "duration_s": 4, "position_enu_m": [0, 0, 0.9],
           "lens": {"focal_length_mm": 50, "rack": [{"at_s": 1, "duration_s": 2, "subject": "far"}],
                    "f_number": [{"time_s": 0, "f_number": 2.8}, {"time_s": 4, "f_number": 11.2}]}}])",
      actors);
  EXPECT_NEAR(plan.samples[0].focus_distance_m, 10.0, 1e-9);
  EXPECT_NEAR(plan.samples[120].focus_distance_m, 40.0, 1e-9);
  // Halfway through the rack (t = 2 s): smoothstep 0.5 -> mean dioptre (1/10 + 1/40)/2 = 0.0625 -> 16 m.
  EXPECT_NEAR(plan.samples[60].focus_distance_m, 16.0, 1e-9);
  // Aperture 2.8 -> 11.2 (4 stops) linearly in stops: t = 2 s is f/5.6.
  EXPECT_NEAR(plan.samples[60].f_number, 5.6, 1e-9);
  EXPECT_EQ(plan.samples[60].subjects_in_frame, (std::vector<std::string>{"near", "far"}));
}

TEST(PlanKeyframes, SquadThroughKeysAndLensInLogSpace) {
  const Trajectory plan =
      Plan(R"([{"type": "KEYFRAMES", "interpolation": "cubic_bspline", "orientation": "squad", "keys": [
      {"time_s": 0, "position_enu_m": [0, 0, 10], "heading_deg": 0, "pitch_deg": -10, "focal_length_mm": 20},
      {"time_s": 2, "position_enu_m": [10, 5, 12], "heading_deg": 60, "pitch_deg": -30},
      {"time_s": 4, "position_enu_m": [20, 0, 15], "heading_deg": 120, "pitch_deg": -20, "focal_length_mm": 80}]}])");
  ASSERT_EQ(plan.samples.size(), 121u);
  EXPECT_NEAR(plan.samples[60].drone_heading_deg, 60.0, 1e-6);
  EXPECT_NEAR(plan.samples[60].gimbal_pitch_deg, -30.0, 1e-6);
  EXPECT_LT((plan.samples[60].position_enu_m - Vector3d(10, 5, 12)).norm(), 1e-9);
  // Focal keys at 0 and 4 s: halfway in log space is the geometric mean, 40 mm.
  EXPECT_NEAR(plan.samples[60].focal_length_mm, 40.0, 1e-9);
  EXPECT_EQ(plan.keyframes.size(), 3u);
}

TEST(PlanFeasibility, SpeedViolationsAreTimeRanges) {
  // 30 m radius, one turn in 10 s: 18.85 m/s around, over PX4's 12 m/s for the whole shot.
  const Trajectory plan = Plan(
      R"([{"name": "fast", "type": "ORBIT", "subject": "hero", "duration_s": 10, "radius_m": 30, "height_m": 10,
        "turns": 1}])");
  bool found = false;
  for (const auto& v : plan.feasibility.violations) {
    if (v.limit != "horizontal_speed") continue;
    found = true;
    EXPECT_EQ(v.shot, "fast");
    EXPECT_NEAR(v.start_time_s, 0.0, 1e-12);
    EXPECT_NEAR(v.end_time_s, 10.0, 1e-12);
    EXPECT_NEAR(v.worst_value, 2 * kPi * 30 / 10, 1e-3);
    EXPECT_EQ(v.limit_value, 12.0);
  }
  EXPECT_TRUE(found);
  // A slow orbit with smootherstep easing breaks nothing.
  const Trajectory slow = Plan(
      R"([{"type": "ORBIT", "subject": "hero", "duration_s": 40, "radius_m": 30, "height_m": 10, "turns": 0.5,
        "easing": "smootherstep"}])");
  EXPECT_TRUE(slow.feasibility.feasible())
      << slow.feasibility.violations.size() << " "
      << (slow.feasibility.violations.empty() ? "" : slow.feasibility.violations[0].limit);
}

TEST(PlanGeodesy, OriginFillsLatLonHeight) {
  Json doc = ShotsDoc(
      R"([{"type": "ORBIT", "subject": "hero", "duration_s": 1, "radius_m": 10, "height_m": 5, "turns": 0.1}])");
  doc["origin"] = Json::parse(R"({"lat_deg": 46.84265, "lon_deg": -91.99445, "height_m": 153.0})");
  const Trajectory plan = PlanShots(ParseShotList(doc, "shots.json"));
  ASSERT_TRUE(plan.origin.has_value());
  const EnuFrame frame(*plan.origin);
  for (const auto& s : plan.samples) {
    EXPECT_LT((frame.EnuFromGeodetic(s.geodetic) - s.position_enu_m).norm(), 1e-6);
  }
  EXPECT_NEAR(plan.samples[0].geodetic.lat_deg, 46.84265, 1e-3);
}

// The angles a plan writes (and a mission flies) are taken where the drone is: 1.5 km off an origin at
// 89.95 deg the scene frame's north is 1.3 deg off true north there, and a 1,200 mm lens sees 1.7 deg
// across. Every sample's heading and pitch are the aim point's bearing and elevation in the local
// level frame at the drone (core/local_level_test.cc checks that frame against CartConvert), the horizon
// is level there, and angles given on a key come back as given.
TEST(PlanGeodesy, AnglesAreTakenWhereTheDroneIsNearThePole) {
  Json doc = ShotsDoc(
      R"([{"name": "tele", "type": "FLYBY", "subject": "sled", "duration_s": 30, "closest_distance_m": 1500,
           "side": "right", "height_m": 60, "speed_m_s": 1, "lens": {"focal_length_mm": 1200, "focus": "infinity"}},
          {"name": "keys", "type": "KEYFRAMES", "duration_s": 2, "transition": "cut", "keys": [
            {"time_s": 0, "position_enu_m": [1400, 900, 50], "heading_deg": 30, "pitch_deg": -10},
            {"time_s": 2, "position_enu_m": [1400, 910, 50], "heading_deg": 30, "pitch_deg": -10}]}])",
      R"([{"name": "sled", "height_m": 2, "keyframes": [{"time_s": 0, "position_enu_m": [-150, 0, 0]},
                                                         {"time_s": 30, "position_enu_m": [150, 0, 0]}]}])",
      10);
  doc["origin"] = Json::parse(R"({"lat_deg": 89.95, "lon_deg": 135.0, "height_m": 2800.0})");
  const Trajectory plan = PlanShots(ParseShotList(doc, "shots.json"));
  const EnuFrame frame(*plan.origin);
  double largest_convergence_deg = 0;
  for (size_t k = 0; k < plan.samples.size(); ++k) {
    const TrajectorySample& s = plan.samples[k];
    if (s.shot != "tele") {  // on the keys (between them the orientation is SLERPed in the scene frame)
      if (std::abs(s.time_s - 30) > 1e-9 && std::abs(s.time_s - 32) > 1e-9) continue;
      EXPECT_NEAR(AngleDiffDeg(s.drone_heading_deg, 30.0), 0.0, 1e-6) << s.time_s;
      EXPECT_NEAR(s.gimbal_pitch_deg, -10.0, 1e-6) << s.time_s;
      continue;
    }
    const Vector3d aim = plan.subjects[0].positions_enu_m[k] + Vector3d(0, 0, 1.0);
    const Vector3d local = frame.LocalLevelFromEnu(s.position_enu_m) * (aim - s.position_enu_m);
    const double bearing_deg = NormalizeDeg360(DegFromRad(std::atan2(local.x(), local.y())));
    EXPECT_NEAR(AngleDiffDeg(s.drone_heading_deg, bearing_deg), 0.0, 1e-6) << s.time_s;
    EXPECT_NEAR(s.gimbal_pitch_deg, DegFromRad(std::atan2(local.z(), local.head<2>().norm())), 1e-6) << s.time_s;
    EXPECT_NEAR(s.gimbal_roll_deg, 0.0, 1e-6) << s.time_s;
    EXPECT_LT(LookAtErrorRad(s, aim), 1e-9) << s.time_s;  // and still aimed at the subject in the scene
    const Vector3d to = aim - s.position_enu_m;
    const double frame_bearing_deg = NormalizeDeg360(DegFromRad(std::atan2(to.x(), to.y())));
    largest_convergence_deg = std::max(largest_convergence_deg, std::abs(AngleDiffDeg(frame_bearing_deg, bearing_deg)));
  }
  EXPECT_GT(largest_convergence_deg, 1.0);  // the case tells the two norths apart
}

}  // namespace
}  // namespace cinepath::shots
