// optimizer/retime.h: a shot too fast for the drone flown slower along the same path, with every drone
// profile and several orbits; the plan after it moved later, never worse in any limit; shots that cannot
// be retimed say why; and optimize's report (optimizer/optimizer.h) carries it.
#include "optimizer/retime.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "core/drone_profiles.h"
#include "core/feasibility.h"
#include "core/json.h"
#include "optimizer/optimizer.h"
#include "optimizer/plan_samples.h"
#include "tests/optimizer/test_scenes.h"

namespace cinepath::optimizer {
namespace {

using test_scenes::PlanFromShots;

std::string Num(double v) { return std::to_string(v); }

// A fast orbit around a standing actor (opted in to retiming or not), then a slow one continuing from where it
// ends, joined continuously or by a cut.
std::string TwoOrbits(const std::string& profile, double radius_m, double turns, double duration_s, bool retime,
                      const std::string& transition) {
  Json camera = {{"filmback", "super35"},
                 {"width_px", 1920},
                 {"height_px", 1080},
                 {"min_focal_length_mm", 24},
                 {"max_focal_length_mm", 200}};
  const auto drone = FindDroneProfile(profile);  // held: the lens is a reference into it
  if (const auto& fixed = drone->lens) {         // the aircraft's built-in lens
    camera["min_focal_length_mm"] = fixed->min_focal_length_mm;
    camera["max_focal_length_mm"] = fixed->max_focal_length_mm;
    camera["min_f_number"] = fixed->min_f_number;
    camera["max_f_number"] = fixed->max_f_number;
    camera["min_focus_distance_m"] = fixed->min_focus_distance_m;
  }
  const auto orbit = [&](const std::string& name, double seconds, double orbit_turns, double bearing_deg) {
    return Json{{"name", name},
                {"type", "ORBIT"},
                {"subject", "keeper"},
                {"duration_s", seconds},
                {"radius_m", radius_m},
                {"height_m", 12},
                {"turns", orbit_turns},
                {"direction", "cw"},
                {"start_bearing_deg", bearing_deg},
                {"easing", "smootherstep"}};
  };
  Json fast = orbit("fast", duration_s, turns, 0);
  fast["optimize"] = {{"retime", retime}};
  Json slow = orbit("slow", 6, 0.02, 360 * turns);
  slow["transition"] = transition;
  const Json shots = {{"schema", "cinepath.shots/1"},
                      {"frame_rate_hz", 30},
                      {"camera", camera},
                      {"drone", profile},
                      {"actors", Json::array({{{"name", "keeper"}, {"height_m", 1.8}, {"position_enu_m", {0, 0, 0}}}})},
                      {"shots", Json::array({fast, slow})}};
  return shots.dump();
}

// The largest excess of every limit in every shot.
std::map<std::pair<std::string, std::string>, double> Worst(const Trajectory& plan) {
  std::map<std::pair<std::string, std::string>, double> worst;
  for (const auto& series : MeasureLimits(plan, SplitPlan(plan, 1.0, "plan", false).cut_before, {})) {
    for (size_t k = 0; k < series.values.size(); ++k) {
      double& w = worst[{plan.samples[k].shot, series.limit}];
      w = std::max(w, series.Excess(k));
    }
  }
  return worst;
}

size_t RateViolationsIn(const Trajectory& plan, const std::string& shot) {
  size_t n = 0;
  for (const auto& v : plan.feasibility.violations) n += v.shot == shot && TimeOrderOfLimit(v.limit) > 0;
  return n;
}

TEST(Retime, OrdersOfTheLimits) {
  EXPECT_EQ(TimeOrderOfLimit("horizontal_speed"), 1);
  EXPECT_EQ(TimeOrderOfLimit("yaw_rate"), 1);
  EXPECT_EQ(TimeOrderOfLimit("focus_rate"), 1);
  EXPECT_EQ(TimeOrderOfLimit("horizontal_acceleration"), 2);
  EXPECT_EQ(TimeOrderOfLimit("jerk"), 3);
  EXPECT_EQ(TimeOrderOfLimit("altitude_min"), 0);
  EXPECT_EQ(TimeOrderOfLimit("terrain_clearance"), 0);
  EXPECT_EQ(TimeOrderOfLimit("gimbal_pitch_min"), 0);
}

// Every profile, orbits of random radius and pace (fixed seed), joined on by a continuous shot or a cut:
// the fast shot's rates hold after, nothing is worse, the next shot is the same flight later.
TEST(Retime, TooFastOrbitsHoldTheirRatesAfterEveryProfile) {
  std::uniform_real_distribution<double> radius(15, 60), turns(0.3, 0.8);
  int refused_at_join = 0, cases = 0;
  for (const unsigned seed : {7u, 11u, 23u})
    for (const std::string& profile : DroneProfileNames()) {
      std::mt19937 rng(seed);
      for (const std::string transition : {"continuous", "cut"}) {
        const double r = radius(rng), t = turns(rng);
        SCOPED_TRACE(profile + " " + transition + " radius " + Num(r) + " turns " + Num(t));
        const Trajectory plan = PlanFromShots(TwoOrbits(profile, r, t, 6, true, transition));
        ASSERT_GT(RateViolationsIn(plan, "fast"), 0u) << "the case must be too fast to begin with";
        const RetimeResult out = RetimeShots(plan, nullptr);
        ++cases;
        if (transition == "continuous" && out.shots.empty()) {
          // The pace must meet the next shot's across the join: where the drone's jerk leaves no room to brake
          // there, it is said, and the plan stays as it was.
          ++refused_at_join;
          ASSERT_EQ(out.notes.size(), 1u);
          EXPECT_NE(out.notes[0].find("continuous join"), std::string::npos) << out.notes[0];
          EXPECT_EQ(out.plan.samples.size(), plan.samples.size());
          continue;
        }
        ASSERT_EQ(out.shots.size(), 1u) << (out.notes.empty() ? "" : out.notes[0]);
        const RetimedShot& shot = out.shots[0];
        EXPECT_EQ(shot.shot, "fast");
        if (transition == "cut") {
          EXPECT_EQ(shot.broken_samples_after, 0u);
          EXPECT_EQ(RateViolationsIn(out.plan, "fast"), 0u);
        } else {
          // Across a continuous join the pace may change only a little (the next shot keeps its own), so a
          // jerk the next shot's start adds may stay, within the last second; nowhere else.
          EXPECT_LT(shot.broken_samples_after, shot.broken_samples_before / 10);
          for (const auto& v : out.plan.feasibility.violations) {
            if (v.shot == "fast" && TimeOrderOfLimit(v.limit) > 0) {
              EXPECT_GE(v.start_time_s, out.plan.shots[0].end_time_s - 1.0) << v.limit;
            }
          }
        }
        EXPECT_GT(shot.duration_after_s, shot.duration_before_s);
        EXPECT_GT(shot.slowest_factor, 1.0);
        EXPECT_NEAR(out.added_s, shot.duration_after_s - shot.duration_before_s, 1e-9);
        // Never worse, shot by shot and limit by limit.
        const auto before = Worst(plan), after = Worst(out.plan);
        for (const auto& [key, excess] : after) {
          const double was = before.count(key) ? before.at(key) : 0.0;
          EXPECT_LE(excess, was * (1 + 1e-9) + 1e-12) << key.first << " " << key.second;
        }
        // The same path: every new sample of the fast shot lies on the planned polyline (within 2 cm).
        for (const auto& s : out.plan.samples) {
          if (s.shot != "fast") continue;
          double nearest = 1e9;
          for (size_t k = 0; k + 1 < plan.samples.size(); ++k) {
            const Eigen::Vector3d a = plan.samples[k].position_enu_m, b = plan.samples[k + 1].position_enu_m;
            const double w = (b - a).squaredNorm() > 0
                                 ? std::clamp((s.position_enu_m - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0)
                                 : 0.0;
            nearest = std::min(nearest, (s.position_enu_m - (a + w * (b - a))).norm());
          }
          EXPECT_LT(nearest, 0.02);
        }
        // The next shot is the same flight, later by the time added; its span and the actor follow.
        size_t first_slow = 0, first_slow_after = 0;
        while (plan.samples[first_slow].shot != "slow") ++first_slow;
        while (out.plan.samples[first_slow_after].shot != "slow") ++first_slow_after;
        ASSERT_EQ(plan.samples.size() - first_slow, out.plan.samples.size() - first_slow_after);
        for (size_t k = first_slow; k < plan.samples.size(); ++k) {
          const auto& a = plan.samples[k];
          const auto& b = out.plan.samples[first_slow_after + k - first_slow];
          EXPECT_EQ(a.position_enu_m, b.position_enu_m);
          EXPECT_NEAR(b.time_s - a.time_s, out.added_s, 1e-9);
        }
        EXPECT_NEAR(out.plan.shots[1].start_time_s - plan.shots[1].start_time_s, out.added_s, 1e-9);
        EXPECT_NEAR(out.plan.shots[0].end_time_s - plan.shots[0].end_time_s, out.added_s, 1e-9);
        ASSERT_EQ(out.plan.subjects.size(), 1u);
        EXPECT_EQ(out.plan.subjects[0].positions_enu_m.size(), out.plan.samples.size());
        // Samples stay one frame apart.
        for (size_t k = 1; k < out.plan.samples.size(); ++k) {
          EXPECT_NEAR(out.plan.samples[k].time_s - out.plan.samples[k - 1].time_s, 1 / 30.0, 1e-9);
        }
      }
    }
  std::printf("retime: %d of %d continuous cases refused at the join\n", refused_at_join, cases / 2);
  EXPECT_LE(refused_at_join, cases / 8);  // at most a quarter of the continuous ones
}

TEST(Retime, ShotsNotOptedInOrWithAMovingActorAreLeftAlone) {
  const Trajectory plan = PlanFromShots(TwoOrbits("px4-multirotor", 30, 0.6, 5, false, "continuous"));
  ASSERT_GT(RateViolationsIn(plan, "fast"), 0u);
  const RetimeResult none = RetimeShots(plan, nullptr);
  EXPECT_TRUE(none.shots.empty());
  EXPECT_TRUE(none.notes.empty());
  EXPECT_EQ(none.plan.samples.size(), plan.samples.size());

  const Trajectory chase = PlanFromShots(R"({"schema": "cinepath.shots/1", "frame_rate_hz": 30,
      "camera": {"filmback": "super35", "width_px": 1920, "height_px": 1080, "min_focal_length_mm": 24,
                 "max_focal_length_mm": 200}, "drone": "px4-multirotor",
      "actors": [{"name": "runner", "height_m": 1.8, "keyframes": [{"time_s": 0, "position_enu_m": [0, 0, 0]},
                 {"time_s": 4, "position_enu_m": [120, 0, 0]}]}],
      "shots": [{"name": "chase", "type": "CHASE", "subject": "runner", "duration_s": 4, "distance_m": 10,
                 "height_m": 5, "optimize": {"retime": true}}]})");
  const RetimeResult moving = RetimeShots(chase, nullptr);
  EXPECT_TRUE(moving.shots.empty());
  ASSERT_EQ(moving.notes.size(), 1u);
  EXPECT_NE(moving.notes[0].find("actor \"runner\" moves"), std::string::npos) << moving.notes[0];
}

// The opt-in is read from the shot list into the plan's intent; anything but a boolean is refused by name.
TEST(Retime, TheOptInIsReadFromTheShotList) {
  const std::string shots = TwoOrbits("px4-multirotor", 30, 0.6, 5, true, "cut");
  const Trajectory plan = PlanFromShots(shots);
  EXPECT_TRUE(plan.shots[0].intent.retime);
  EXPECT_FALSE(plan.shots[1].intent.retime);
  std::string bad = shots;
  bad.replace(bad.find("\"retime\":true"), 13, "\"retime\":1");
  try {
    PlanFromShots(bad);
    ADD_FAILURE() << "a number for retime was read";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("shots[0].optimize.retime"), std::string::npos) << e.what();
  }
}

// Through optimize: the retimed plan comes back feasible in its rates, the report says by how much the
// shot got longer; the same plan without the opt-in stays broken with a hint naming the opt-in.
TEST(Retime, OptimizeRetimesAndReports) {
  OptimizeOptions options = OptimizeOptions::ForQuality(Quality::kDraft);
  OptimizeInput input;
  input.plan = PlanFromShots(TwoOrbits("px4-multirotor", 30, 0.6, 5, true, "continuous"));
  const OptimizeResult r = OptimizePlan(input, options);
  ASSERT_TRUE(r.report.contains("retime")) << r.report.dump(1);
  const Json& shots = r.report["retime"]["shots"];
  ASSERT_EQ(shots.size(), 1u) << r.report["retime"].dump(1);
  EXPECT_EQ(shots[0]["shot"], "fast");
  EXPECT_GT(shots[0]["longer_s"].get<double>(), 0.5);
  EXPECT_GT(r.report["retime"]["added_s"].get<double>(), 0.5);
  EXPECT_EQ(RateViolationsIn(r.plan, "fast"), 0u) << r.failure;
  EXPECT_GT(r.plan.samples.size(), input.plan.samples.size());

  input.plan = PlanFromShots(TwoOrbits("px4-multirotor", 30, 0.6, 5, false, "continuous"));
  const OptimizeResult kept = OptimizePlan(input, options);
  EXPECT_FALSE(kept.report.contains("retime"));
  EXPECT_EQ(kept.plan.samples.size(), input.plan.samples.size());
  EXPECT_NE(kept.failure.find("\"retime\": true"), std::string::npos) << kept.failure;
}

}  // namespace
}  // namespace cinepath::optimizer
