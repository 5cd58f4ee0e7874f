// optimizer/optimizer.h on plans whose answer is known: the unchanged plan, two actors held sharp, the
// background blurred by a dolly-zoom, a wall and a pillar in the way, limits made to hold, and the
// extremes. Every figure the tests hold it to is derived in docs/optimize.md.
#include "optimizer/optimizer.h"

#include <algorithm>
#include <cmath>

#include <ceres/problem.h>
#include <gtest/gtest.h>

#include "core/optics.h"
#include "core/rotation.h"
#include "scene/ray_caster.h"
#include "scene/surface_distance.h"
#include "shots/planner.h"
#include "shots/shot_list.h"
#include "tests/optimizer/test_scenes.h"

namespace cinepath::optimizer {
namespace {

using test_scenes::AddBox;
using test_scenes::PlanFromShots;

constexpr double kFps = 30;

CameraSpec TestCamera() {
  CameraSpec c;
  c.sensor_width_mm = 24.89;
  c.sensor_height_mm = 18.67;
  c.width_px = 3840;
  c.height_px = 2160;
  c.min_focal_length_mm = 10;
  c.max_focal_length_mm = 600;
  c.min_f_number = 1.0;
  c.max_f_number = 22;
  c.min_focus_distance_m = 0.5;
  c.max_focal_rate_mm_s = 1000;
  c.max_focus_rate_m_s = 1000;
  c.max_aperture_rate_stops_s = 100;
  return c;
}

// A still camera at `camera` looking at `look_at` for n samples, one shot "shot" framing actor "a".
Trajectory StillPlan(const Eigen::Vector3d& camera, const Eigen::Vector3d& look_at, int n, double focal_mm,
                     double f_number, double focus_m) {
  Trajectory p;
  p.frame_rate_hz = kFps;
  p.camera = TestCamera();
  p.drone.min_altitude_m = -1000;
  p.drone.min_subject_distance_m = 2;
  ShotSpan span;
  span.name = "shot";
  span.type = "LOCKED-OFF";
  span.subject = "a";
  span.end_time_s = (n - 1) / kFps;
  p.shots.push_back(span);
  for (int k = 0; k < n; ++k) {
    TrajectorySample s;
    s.time_s = k / kFps;
    s.position_enu_m = camera;
    s.world_from_camera = LookAt(look_at - camera);
    const GimbalAngles g = GimbalFromWorldFromCamera(s.world_from_camera);
    s.drone_heading_deg = g.drone_heading_deg;
    s.gimbal_pitch_deg = g.gimbal_pitch_deg;
    s.focal_length_mm = focal_mm;
    s.f_number = f_number;
    s.focus_distance_m = focus_m;
    s.shot = "shot";
    p.samples.push_back(s);
  }
  return p;
}

void AddStillActor(Trajectory* plan, const std::string& name, const Eigen::Vector3d& aim, double height_m) {
  SubjectTrack t;
  t.name = name;
  t.height_m = height_m;
  t.positions_enu_m.assign(plan->samples.size(), aim - Eigen::Vector3d(0, 0, height_m / 2));
  plan->subjects.push_back(t);
}

OptimizeResult Optimize(const Trajectory& plan, const scene::SceneMesh* mesh = nullptr,
                        Quality quality = Quality::kStandard) {
  OptimizeInput in;
  in.plan = plan;
  in.plan_source = "test_plan.json";
  in.mesh = mesh;
  in.scene_source = "test_scene.json";
  return OptimizePlan(in, OptimizeOptions::ForQuality(quality));
}

const char* kOrbitShots = R"({"schema": "cinepath.shots/1", "frame_rate_hz": 30,
  "camera": {"filmback": "super35", "width_px": 1920, "height_px": 1080, "min_focal_length_mm": 24,
             "max_focal_length_mm": 70, "min_f_number": 2.8, "max_f_number": 16},
  "drone": "px4-multirotor",
  "actors": [{"name": "keeper", "height_m": 1.8, "position_enu_m": [0, 0, 0]}],
  "shots": [{"name": "orbit", "type": "ORBIT", "subject": "keeper", "duration_s": 20, "radius_m": 25,
             "height_m": 10, "turns": 0.25, "direction": "ccw", "easing": "smootherstep",
             "lens": {"frame_height_fraction": 0.25, "f_number": 4}}]})";

TEST(Optimizer, FeasiblePlanWithNothingToImproveComesBackUnchanged) {
  const Trajectory plan = PlanFromShots(kOrbitShots);
  ASSERT_TRUE(plan.feasibility.feasible());
  const OptimizeResult r = Optimize(plan);
  ASSERT_EQ(r.plan.samples.size(), plan.samples.size());
  for (size_t k = 0; k < plan.samples.size(); ++k) {
    const auto &a = plan.samples[k], &b = r.plan.samples[k];
    EXPECT_LT((a.position_enu_m - b.position_enu_m).norm(), 1e-3);
    EXPECT_LT(AngleBetweenRad(a.world_from_camera, b.world_from_camera) * 180 / M_PI, 0.01);
    EXPECT_NEAR(a.focal_length_mm, b.focal_length_mm, 1e-6);
    EXPECT_NEAR(a.focus_distance_m, b.focus_distance_m, 1e-6);
    EXPECT_NEAR(a.f_number, b.f_number, 1e-6);
  }
  EXPECT_TRUE(r.failure.empty());
  EXPECT_EQ(r.report["total"]["before"].get<double>(), 0.0);
  // Without a scene the report says what it did not model.
  EXPECT_EQ(r.report["skipped"].size(), 2u);
}

TEST(Optimizer, TwoActorsSharpOpenTheApertureAsFarAsBothAllow) {
  // Actors at 10 m and 14 m on the axis; position, orientation and focal length held; a background
  // goal beyond reach pushes the aperture open until the depth of field just holds both.
  const double d1 = 10, d2 = 14, f_mm = 50;
  Trajectory plan = StillPlan({0, 0, 10}, {0, 1, 10}, 31, f_mm, 8, 12);
  AddStillActor(&plan, "a", {0, d1, 10}, 1.8);
  AddStillActor(&plan, "b", {0, d2, 10}, 1.8);
  plan.shots[0].intent.sharp = {"a", "b"};
  plan.shots[0].intent.background_blur_px = 5000;
  plan.shots[0].intent.hold = {"position", "orientation", "focal_length"};
  const OptimizeResult r = Optimize(plan);
  const TrajectorySample& s = r.plan.samples[15];
  const double focus_expected = 2 * d1 * d2 / (d1 + d2);
  EXPECT_NEAR(s.focus_distance_m, focus_expected, 0.02 * focus_expected);
  const double coc = DefaultCocMm(plan.camera.sensor_width_mm, plan.camera.sensor_height_mm);
  const DepthOfField dof = DepthOfFieldLimits(s.focal_length_mm, s.f_number, s.focus_distance_m, coc);
  EXPECT_NEAR(dof.near_m, d1, 0.02 * d1);
  EXPECT_NEAR(dof.far_m, d2, 0.02 * d2);
  // The smallest f-number that holds both: K (1 - f/s) = (1/d1 - 1/d2) / 2 with K = N c / f^2.
  const double f_m = f_mm * 1e-3;
  const double n_expected = (1 / d1 - 1 / d2) / 2 * f_m * f_m / (coc * 1e-3) / (1 - f_m / focus_expected);
  EXPECT_NEAR(s.f_number, n_expected, 0.02 * n_expected);
  EXPECT_EQ(s.focal_length_mm, f_mm);  // held
}

TEST(Optimizer, BackgroundBlurGoalMovesTheCameraBackAndZoomsInAtEveryPreset) {
  // The dolly-zoom family: the subject keeps its size (frame_height_fraction) while the camera backs
  // off and zooms in until the background 50 m behind blurs by the goal. Aperture held at f/2.8.
  const double h = 1.8, fraction = 0.5, behind = 50, n_stop = 2.8;
  const CameraSpec cam = TestCamera();
  const double image_h_mm = cam.image_extent_mm().height_mm;
  const double d0 = 10;
  const double f0 = fraction * image_h_mm * d0 / h;  // mm, the planned framing at 10 m
  Trajectory plan = StillPlan({0, -d0, 0.9}, {0, 0, 0.9}, 31, f0, n_stop, d0);
  AddStillActor(&plan, "a", {0, 0, 0.9}, h);
  plan.shots[0].intent.frame_height_fraction = fraction;
  plan.shots[0].intent.background_distance_m = behind;
  plan.shots[0].intent.hold = {"aperture"};
  plan.shots[0].intent.max_deviation_m = 30;
  // With the subject at the far limit of the depth of field (the most background blur that keeps it
  // sharp): 1/far = D - K (1 - f D) = 1/d, so D = (1/d + K) / (1 + K f), K = N c / f^2.
  const double coc_m = DefaultCocMm(cam.sensor_width_mm, cam.sensor_height_mm) * 1e-3;
  const auto blur_px = [&](double d) {
    const double f = fraction * image_h_mm * d / h * 1e-3;
    const double k = n_stop * coc_m / (f * f);
    const double dioptre = (1 / d + k) / (1 + k * f);
    return f * f / n_stop * (dioptre - 1 / (d + behind)) / (1 - f * dioptre) * cam.width_px /
           (cam.sensor_width_mm * 1e-3);
  };
  const double goal_px = 1.6 * blur_px(d0);
  plan.shots[0].intent.background_blur_px = goal_px;
  double lo = d0, hi = 1000;  // the analytic minimal distance: blur_px(d) = goal
  for (int i = 0; i < 100; ++i) (blur_px((lo + hi) / 2) < goal_px ? lo : hi) = (lo + hi) / 2;
  for (Quality quality : {Quality::kDraft, Quality::kStandard, Quality::kFinal}) {
    SCOPED_TRACE(QualityName(quality));
    const OptimizeResult r = Optimize(plan, nullptr, quality);
    const TrajectorySample& s = r.plan.samples[15];
    const double d = (s.position_enu_m - Eigen::Vector3d(0, 0, 0.9)).norm();
    // It backs off and zooms in, to the analytic minimal distance.
    EXPECT_NEAR(d, lo, 0.05 * lo);
    EXPECT_GT(s.focal_length_mm, f0 * 1.2);
    const double fraction_now = h * s.focal_length_mm / (d * image_h_mm);
    EXPECT_NEAR(fraction_now, fraction, 0.05 * fraction);
    const double achieved = BlurCircleMm(s.focal_length_mm, s.f_number, s.focus_distance_m, d + behind) * cam.width_px /
                            cam.sensor_width_mm;
    EXPECT_GE(achieved, goal_px * 0.98);
    const DepthOfField dof = DepthOfFieldLimits(s.focal_length_mm, s.f_number, s.focus_distance_m, coc_m * 1e3);
    EXPECT_LE(dof.near_m, d * 1.005);  // the subject stays sharp
    EXPECT_GE(dof.far_m, d * 0.995);
    EXPECT_EQ(s.f_number, n_stop);
  }
}

// Rule 5: a goal the limits let it reach is reached; one they do not names the limit it gave way to. The
// dolly-zoom above with 30 m of deviation reaches its background blur with no deviation multiplier; with
// 1 m the camera cannot back off far enough, and the report says the deviation held it.
TEST(Optimizer, AGoalThatCannotBeReachedNamesTheLimitItGaveWayTo) {
  const double h = 1.8, fraction = 0.5, d0 = 10;
  const CameraSpec cam = TestCamera();
  const double f0 = fraction * cam.image_extent_mm().height_mm * d0 / h;
  for (const double max_deviation_m : {30.0, 1.0}) {
    SCOPED_TRACE(max_deviation_m);
    Trajectory plan = StillPlan({0, -d0, 0.9}, {0, 0, 0.9}, 31, f0, 2.8, d0);
    AddStillActor(&plan, "a", {0, 0, 0.9}, h);
    plan.shots[0].intent.frame_height_fraction = fraction;
    plan.shots[0].intent.background_distance_m = 50;
    plan.shots[0].intent.hold = {"aperture"};
    plan.shots[0].intent.max_deviation_m = max_deviation_m;
    const double planned_px = BlurCircleMm(f0, 2.8, d0, d0 + 50) * cam.width_px / cam.sensor_width_mm;
    plan.shots[0].intent.background_blur_px = 2.5 * planned_px;
    const Json shot = Optimize(plan, nullptr, Quality::kStandard).report["shots"][0];
    const double reached = shot["background_blur_px_min"].get<double>() / shot["background_blur_px_goal"].get<double>();
    bool deviation_bound = false;
    for (const auto& name : shot["binding_limits"]) deviation_bound = deviation_bound || name == "max_deviation";
    if (max_deviation_m > 10) {
      EXPECT_GE(reached, 0.98);
      EXPECT_FALSE(deviation_bound) << shot.dump();
    } else {
      EXPECT_LT(reached, 0.95);
      EXPECT_TRUE(deviation_bound) << shot.dump();
    }
  }
}

TEST(Optimizer, TheFocusFollowsWhatThePlanRecordsItFollows) {
  // The camera starts 1.5 m from actor "a", inside the drone's 2 m keep-out, so it must back off. The
  // focus racks from "a" to "b", 5 m behind "a", during [0.5, 1] s. Recorded as a rack, the focus follows
  // "b" wherever the camera goes after the rack (from 1.5 s on: the focus is a spline with knots every
  // 0.5 s); recorded as fixed, it stays exactly as planned.
  const Eigen::Vector3d a(0, 0, 0.9), b(0, 5, 0.9), camera(0, -1.5, 0.9);
  Trajectory plan = StillPlan(camera, a, 91, 35, 4, 1.5);
  for (auto& s : plan.samples) {
    const double w = std::clamp((s.time_s - 0.5) / 0.5, 0.0, 1.0);
    s.focus_distance_m = 1 / ((1 - w) / 1.5 + w / 6.5);  // the planner's blend in dioptres (linear here)
  }
  AddStillActor(&plan, "a", a, 1.8);
  AddStillActor(&plan, "b", b, 1.8);
  plan.shots[0].intent.focus = "rack";
  plan.shots[0].intent.rack = {{0.5, 0.5, "b"}};
  const OptimizeResult racked = Optimize(plan);
  bool moved = false;
  for (size_t k = 45; k < racked.plan.samples.size(); ++k) {
    const TrajectorySample& s = racked.plan.samples[k];
    const double depth_b = (s.world_from_camera.conjugate() * (b - s.position_enu_m)).z();
    EXPECT_NEAR(s.focus_distance_m, depth_b, 0.03 * depth_b) << "t=" << s.time_s;  // the plan's 6.5 m is 12 % off
    moved = moved || std::fabs(depth_b - 6.5) > 0.3;
  }
  EXPECT_TRUE(moved);  // the camera did back off, so following "b" is not the plan's focus
  plan.shots[0].intent.focus = "fixed";
  plan.shots[0].intent.rack.clear();
  const OptimizeResult fixed = Optimize(plan);
  for (size_t k = 0; k < fixed.plan.samples.size(); ++k) {
    EXPECT_EQ(fixed.plan.samples[k].focus_distance_m, plan.samples[k].focus_distance_m) << k;
  }
}

// The wall asks for a climb of about 4 m for a few seconds of a 12 s orbit. With the default profile's
// limits (jerk 4 m/s^3, descent 1.5 m/s) that barely fits in the shot (8 of 361 frames stay hidden, the
// limits held to 1 %); an agile profile lets the test see the occlusion term work rather than the limits.
// A minute's half orbit 40 m about a walker who turns at 30 s, framing and a background-blur goal the
// deviation allowed holds back (bench/optimize_bench.cc's shot), the walker's keys moved by `east_m`.
Trajectory WalkingOrbitPlan(double east_m) {
  const std::string keys = "[{\"time_s\": 0, \"position_enu_m\": [0, 0, 0]}, {\"time_s\": 30, \"position_enu_m\": [" +
                           std::to_string(40 + east_m) + ", 20, 0]}, {\"time_s\": 60, \"position_enu_m\": [" +
                           std::to_string(60 - east_m) + ", 70, 0]}]";
  return PlanFromShots(R"({"schema": "cinepath.shots/1", "frame_rate_hz": 30,
    "camera": {"filmback": "super35", "width_px": 3840, "height_px": 2160, "min_focal_length_mm": 24,
               "max_focal_length_mm": 120, "min_f_number": 1.4, "max_f_number": 16},
    "drone": "px4-multirotor",
    "actors": [{"name": "walker", "height_m": 1.8, "keyframes": )" +
                       keys + R"(}],
    "shots": [{"name": "orbit", "type": "ORBIT", "subject": "walker", "duration_s": 60, "radius_m": 40,
               "height_m": 15, "turns": 0.5, "easing": "smootherstep",
               "lens": {"frame_height_fraction": 0.15, "background_blur_px": 12, "f_number": 4}}]})");
}

// The first solve's continuation, a decade a stage (OptimizeOptions::ramp): with 1e-4, 1e-2, 1 the walking
// orbit's draft ended at the iteration cap outside the acceleration limit and the deviation, and the guard
// kept 83 % of the change (objective 208,098 against standard's 28,811); on walkers moved by half a metre it
// stopped at 35,000-40,000 in a quarter of the cases. Draft is held to 2 % of standard on three of them,
// without the guard's cut or a second solve (AChangeTheGuardCutIsSolvedAgainAtFullWeightAndTheBetterKept).
TEST(Optimizer, DraftReachesWithinTwoPerCentOfStandardOnAWalkingOrbit) {
  for (double east_m : {0.0, 0.37, -0.21}) {
    SCOPED_TRACE(east_m);
    const Trajectory plan = WalkingOrbitPlan(east_m);
    ASSERT_TRUE(plan.feasibility.feasible());
    const OptimizeResult draft = Optimize(plan, nullptr, Quality::kDraft);
    const OptimizeResult standard = Optimize(plan, nullptr, Quality::kStandard);
    EXPECT_EQ(draft.report["guard"]["alpha"].get<double>(), 1.0);
    EXPECT_FALSE(draft.report["guard"].contains("retry"));  // the ramp alone brought every limit back
    EXPECT_TRUE(draft.report["feasible_after"].get<bool>());
    const double d = draft.report["objective"].get<double>(), s = standard.report["objective"].get<double>();
    EXPECT_LE(d, 1.02 * s) << "draft " << d << ", standard " << s;
    EXPECT_LE(s, d);  // the ladder climbs
  }
}

// When the guard cuts the change (the soft stages led the path where the stiff one could not bring every
// limit back), the solve is tried again from the plan as given at full weight, and the guarded result with
// the smaller objective is kept. The ramp before the decades (1e-4, 1e-2, 1) leads there on this plan.
TEST(Optimizer, AChangeTheGuardCutIsSolvedAgainAtFullWeightAndTheBetterKept) {
  const Trajectory plan = WalkingOrbitPlan(0);
  OptimizeInput in;
  in.plan = plan;
  in.plan_source = "test_plan.json";
  OptimizeOptions options = OptimizeOptions::ForQuality(Quality::kDraft);
  options.ramp = {1e-4, 1e-2};
  const OptimizeResult r = OptimizePlan(in, options);
  const Json& guard = r.report["guard"];
  ASSERT_TRUE(guard.contains("retry")) << guard.dump();
  const Json& retry = guard["retry"];
  EXPECT_LT(retry["first_alpha"].get<double>(), 1.0);
  const bool kept_retry = retry["kept"] == "retry";
  EXPECT_EQ(kept_retry, retry["retry_objective"].get<double>() < retry["first_objective"].get<double>());
  EXPECT_EQ(guard["alpha"].get<double>(), retry[kept_retry ? "retry_alpha" : "first_alpha"].get<double>());
  EXPECT_NEAR(r.report["objective"].get<double>(),
              std::min(retry["retry_objective"].get<double>(), retry["first_objective"].get<double>()),
              1e-6 * r.report["objective"].get<double>());
  EXPECT_TRUE(r.report["feasible_after"].get<bool>());
}

TEST(Optimizer, WallBetweenOrbitAndSubjectIsSeenOver) {
  const Trajectory plan = PlanFromShots(R"({"schema": "cinepath.shots/1", "frame_rate_hz": 30,
    "camera": {"filmback": "super35", "width_px": 1920, "height_px": 1080, "min_focal_length_mm": 24,
               "max_focal_length_mm": 200, "min_f_number": 2.8, "max_f_number": 16},
    "drone": {"profile": "px4-multirotor", "max_jerk_m_s3": 40, "max_acceleration_m_s2": 10,
              "max_climb_rate_m_s": 6, "max_descent_rate_m_s": 6},
    "actors": [{"name": "keeper", "height_m": 1.8, "position_enu_m": [0, 0, 0]}],
    "shots": [{"name": "orbit", "type": "ORBIT", "subject": "keeper", "duration_s": 12, "radius_m": 20,
               "height_m": 2.5, "turns": 0.25, "direction": "cw", "start_bearing_deg": 0,
               "easing": "smootherstep", "lens": {"frame_height_fraction": 0.2}}]})");
  scene::SceneMesh mesh;
  AddBox(&mesh, {-40, -40, -1}, {40, 40, 0});  // the ground
  AddBox(&mesh, {4, 8, 0}, {14, 9, 3});        // a 3 m wall north-east of the subject
  const scene::RayCaster caster(mesh);
  const auto blocked = [&](const Trajectory& p) {
    int n = 0;
    for (size_t k = 0; k < p.samples.size(); ++k) {
      const Eigen::Vector3d aim = p.subjects[0].positions_enu_m[k] + Eigen::Vector3d(0, 0, 0.9);
      const Eigen::Vector3d d = aim - p.samples[k].position_enu_m;
      n += caster.Occluded(p.samples[k].position_enu_m, d.normalized(), 0.05, d.norm() - 0.3) ? 1 : 0;
    }
    return n;
  };
  ASSERT_GT(blocked(plan), 30);
  const OptimizeResult r = Optimize(plan, &mesh, Quality::kStandard);
  EXPECT_EQ(blocked(r.plan), 0);
  EXPECT_EQ(r.report["occlusion"]["blocked_fraction_after"].get<double>(), 0.0);
  EXPECT_GT(r.report["occlusion"]["blocked_fraction_before"].get<double>(), 0.0);
}

// The pillar asks for a sideways move of 4 m within a few seconds: the agile profile again.
TEST(Optimizer, PillarOnAChasePathIsPassedWithTheMargin) {
  Trajectory plan = PlanFromShots(R"({"schema": "cinepath.shots/1", "frame_rate_hz": 30,
    "camera": {"filmback": "super35", "width_px": 1920, "height_px": 1080, "min_focal_length_mm": 24,
               "max_focal_length_mm": 70, "min_f_number": 2.8, "max_f_number": 16},
    "drone": {"profile": "px4-multirotor", "max_jerk_m_s3": 40, "max_acceleration_m_s2": 10,
              "max_climb_rate_m_s": 6, "max_descent_rate_m_s": 6},
    "actors": [{"name": "runner", "height_m": 1.8,
                "keyframes": [{"time_s": 0, "position_enu_m": [0, 0, 0]},
                              {"time_s": 10, "position_enu_m": [0, 40, 0]}]}],
    "shots": [{"name": "chase", "type": "CHASE", "subject": "runner", "duration_s": 10, "distance_m": 10,
               "height_m": 3}]})");
  // A pillar 1 m wide where the camera passes 5 s in.
  const Eigen::Vector3d at = plan.samples[150].position_enu_m;
  scene::SceneMesh mesh;
  AddBox(&mesh, {at.x() - 0.5, at.y() - 0.5, -1}, {at.x() + 0.5, at.y() + 0.5, 20});
  const OptimizeResult r = Optimize(plan, &mesh);
  const scene::SurfaceDistance surface(mesh);
  double closest = 1e9;
  for (const auto& s : r.plan.samples) closest = std::min(closest, surface.Closest(s.position_enu_m)->distance_m);
  EXPECT_GE(closest, 3.0 - 1e-3);
  EXPECT_GE(r.report["clearance"]["min_after_m"].get<double>(), 3.0 - 1e-3);
  EXPECT_LT(r.report["clearance"]["min_before_m"].get<double>(), 1.0);
}

TEST(Optimizer, OverJerkCornerBecomesFeasible) {
  // Linear keyframes with a corner: the acceleration jumps there, the jerk spikes in one frame.
  const Trajectory plan = PlanFromShots(R"({"schema": "cinepath.shots/1", "frame_rate_hz": 30,
    "camera": {"filmback": "super35", "width_px": 1920, "height_px": 1080, "min_focal_length_mm": 24,
               "max_focal_length_mm": 24, "min_f_number": 4, "max_f_number": 4},
    "drone": "px4-multirotor",
    "shots": [{"name": "corner", "type": "KEYFRAMES", "duration_s": 12, "interpolation": "linear",
               "keys": [{"time_s": 0, "position_enu_m": [0, 0, 20], "heading_deg": 0, "pitch_deg": -10},
                        {"time_s": 6, "position_enu_m": [0, 12, 20], "heading_deg": 0, "pitch_deg": -10},
                        {"time_s": 12, "position_enu_m": [12, 12, 20], "heading_deg": 0, "pitch_deg": -10}]}]})");
  ASSERT_FALSE(plan.feasibility.feasible());
  const OptimizeResult r = Optimize(plan);
  EXPECT_TRUE(r.plan.feasibility.feasible()) << r.failure;
  EXPECT_GT(r.report["max_deviation_m"].get<double>(), 0.01);
  EXPECT_LE(r.report["max_deviation_m"].get<double>(), 5.0 + 1e-6);
}

TEST(Optimizer, OverSpeedFlybyBecomesFeasible) {
  // A FLYBY eased with smootherstep peaks at 1.875x its mean speed: 12.75 m/s against the profile's 12
  // (and its jerk, 60 D / T^3 = 4.08 m/s^3, is just over the 4 m/s^3 limit too).
  const Trajectory plan = PlanFromShots(R"({"schema": "cinepath.shots/1", "frame_rate_hz": 30,
    "camera": {"filmback": "super35", "width_px": 1920, "height_px": 1080, "min_focal_length_mm": 24,
               "max_focal_length_mm": 70, "min_f_number": 2.8, "max_f_number": 16},
    "drone": "px4-multirotor",
    "actors": [{"name": "keeper", "height_m": 1.8, "position_enu_m": [0, 0, 0]}],
    "shots": [{"name": "flyby", "type": "FLYBY", "subject": "keeper", "duration_s": 10, "closest_distance_m": 15,
               "height_m": 8, "speed_m_s": 6.8, "easing": "smootherstep"}]})");
  bool over_speed = false;
  for (const auto& v : plan.feasibility.violations) over_speed = over_speed || v.limit == "horizontal_speed";
  ASSERT_TRUE(over_speed);
  const OptimizeResult r = Optimize(plan);
  EXPECT_TRUE(r.plan.feasibility.feasible()) << r.failure;
  EXPECT_GT(r.report["max_deviation_m"].get<double>(), 0.1);  // reported
  EXPECT_LE(r.report["max_deviation_m"].get<double>(), 5.0 + 1e-6);
  EXPECT_FALSE(r.report["limits"]["horizontal_speed"]["before"].is_null());
  EXPECT_TRUE(r.report["limits"]["horizontal_speed"]["after"].is_null());
}

TEST(Optimizer, Extremes) {
  // One frame.
  {
    Trajectory plan = StillPlan({0, 0, 10}, {0, 1, 10}, 1, 35, 4, 10);
    AddStillActor(&plan, "a", {0, 10, 10}, 1.8);
    const OptimizeResult r = Optimize(plan);
    EXPECT_EQ(r.plan.samples.size(), 1u);
    EXPECT_TRUE(r.failure.empty());
  }
  // A subject 1 km away on a 1200 mm lens, focus and aperture asked to hold it and a background.
  {
    Trajectory plan = StillPlan({0, 0, 50}, {0, 1000, 50}, 31, 1200, 8, 1000);
    plan.camera.max_focal_length_mm = 1200;
    AddStillActor(&plan, "a", {0, 1000, 50}, 1.8);
    plan.shots[0].intent.sharp = {"a"};
    plan.shots[0].intent.background_blur_px = 3;
    const OptimizeResult r = Optimize(plan);
    for (const auto& s : r.plan.samples) {
      EXPECT_TRUE(std::isfinite(s.focal_length_mm) && std::isfinite(s.f_number));
      const double coc = DefaultCocMm(plan.camera.sensor_width_mm, plan.camera.sensor_height_mm);
      const DepthOfField dof = DepthOfFieldLimits(s.focal_length_mm, s.f_number, s.focus_distance_m, coc);
      EXPECT_LE(dof.near_m, 1000 * 1.01);
      EXPECT_GE(dof.far_m, 1000 * 0.99);
    }
  }
  // A mesh with no face in the corridor: clearance is modelled on nothing, the plan is unchanged.
  {
    Trajectory plan = StillPlan({0, 0, 10}, {0, 1, 10}, 31, 35, 4, 10);
    AddStillActor(&plan, "a", {0, 10, 10}, 1.8);
    scene::SceneMesh far;
    AddBox(&far, {5000, 5000, 0}, {5001, 5001, 1});
    const OptimizeResult r = Optimize(plan, &far);
    EXPECT_EQ(r.report["clearance"]["faces_indexed"].get<int>(), 0);
    EXPECT_EQ(r.plan.samples[10].position_enu_m, plan.samples[10].position_enu_m);
  }
  // A subject inside the mesh: reported, and what --strict refuses.
  {
    Trajectory plan = StillPlan({0, -20, 2}, {0, 0, 1}, 31, 35, 4, 20);
    AddStillActor(&plan, "a", {0, 0, 1}, 1.8);
    scene::SceneMesh mesh;
    AddBox(&mesh, {-3, -3, -1}, {3, 3, 4});
    const OptimizeResult r = Optimize(plan, &mesh);
    EXPECT_FALSE(r.failure.empty());
    EXPECT_GT(r.report["occlusion"]["frames_without_clear_view"].get<int>(), 0);
  }
  // A camera exactly at the keep-out radius is moved out past it.
  {
    Trajectory plan = StillPlan({0, -2, 1}, {0, 0, 1}, 31, 24, 4, 2);
    AddStillActor(&plan, "a", {0, 0, 1}, 1.8);
    plan.drone.min_subject_distance_m = 2.5;
    const OptimizeResult r = Optimize(plan);
    for (const auto& s : r.plan.samples) EXPECT_GE(std::hypot(s.position_enu_m.x(), s.position_enu_m.y()), 2.5 - 1e-3);
  }
}

TEST(Optimizer, ZeroLengthShotAndCutsAreKept) {
  const Trajectory plan = PlanFromShots(R"({"schema": "cinepath.shots/1", "frame_rate_hz": 30,
    "camera": {"filmback": "super35", "width_px": 1920, "height_px": 1080, "min_focal_length_mm": 24,
               "max_focal_length_mm": 70, "min_f_number": 2.8, "max_f_number": 16},
    "actors": [{"name": "keeper", "height_m": 1.8, "position_enu_m": [0, 0, 0]}],
    "shots": [{"name": "hold", "type": "ORBIT", "subject": "keeper", "duration_s": 0, "radius_m": 25, "height_m": 10,
               "turns": 0.1},
              {"name": "orbit", "type": "ORBIT", "subject": "keeper", "duration_s": 4, "radius_m": 25,
               "height_m": 10, "turns": 0.05, "transition": "cut"}]})");
  const OptimizeResult r = Optimize(plan);
  EXPECT_EQ(r.plan.samples.size(), plan.samples.size());
  EXPECT_EQ(r.plan.shots.size(), 2u);
}

TEST(Optimizer, SameResultOnEveryRun) {
  Trajectory plan = StillPlan({0, 0, 10}, {0, 1, 10}, 61, 50, 8, 12);
  AddStillActor(&plan, "a", {0, 10, 10}, 1.8);
  AddStillActor(&plan, "b", {0, 14, 10}, 1.8);
  plan.shots[0].intent.sharp = {"a", "b"};
  const OptimizeResult a = Optimize(plan), b = Optimize(plan);
  for (size_t k = 0; k < a.plan.samples.size(); ++k) {
    EXPECT_EQ(a.plan.samples[k].f_number, b.plan.samples[k].f_number);
    EXPECT_EQ(a.plan.samples[k].focus_distance_m, b.plan.samples[k].focus_distance_m);
  }
}

}  // namespace
}  // namespace cinepath::optimizer

namespace cinepath::optimizer {
namespace {

// The bench's constrained peer (OptimizeOptions::constrained_solver) gets the same variables as Ceres, a
// finite objective and one finite signed margin per hard limit; a solver that moves nothing leaves the plan
// as given.
TEST(Optimizer, TheConstrainedPeerGetsFiniteGoalsAndMarginsOverTheSameVariables) {
  const Trajectory plan = PlanFromShots(kOrbitShots);
  OptimizeOptions options = OptimizeOptions::ForQuality(Quality::kDraft);
  int calls = 0;
  options.constrained_solver = [&calls, &plan](const ConstrainedProblem& p) {
    ++calls;
    EXPECT_FALSE(p.blocks.empty());
    EXPECT_EQ(p.blocks.size(), p.fixed_channels.size());
    ceres::Problem::EvaluateOptions eo;
    eo.parameter_blocks = p.blocks;
    double goals = 0, limits = 0;
    std::vector<double> margins, gradient;
    EXPECT_TRUE(p.goals->Evaluate(eo, &goals, nullptr, &gradient, nullptr));
    EXPECT_TRUE(p.limits->Evaluate(eo, &limits, &margins, nullptr, nullptr));
    EXPECT_TRUE(std::isfinite(goals));
    EXPECT_GT(margins.size(), plan.samples.size());  // every sample has at least its altitude limits
    for (double g : margins) EXPECT_TRUE(std::isfinite(g));
    return 0;
  };
  OptimizeInput in;
  in.plan = plan;
  const OptimizeResult r = OptimizePlan(in, options);
  EXPECT_EQ(calls, 1);
  for (size_t k = 0; k < plan.samples.size(); ++k)
    EXPECT_LT((plan.samples[k].position_enu_m - r.plan.samples[k].position_enu_m).norm(), 1e-9);
}

}  // namespace
}  // namespace cinepath::optimizer
