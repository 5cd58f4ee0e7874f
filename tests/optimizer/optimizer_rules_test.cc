// optimizer/optimizer.h against the rules a crew relies on (docs/optimize.md): never worse than the input
// in any limit (rule 2), never under or through the mesh, a double-sided ground included (rule 3), and a
// quality ladder that climbs (rule 4). Each plan's standing is measured here with `plan`'s own check on
// the whole mesh and with ray casts of its own, not with the optimizer's guard.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <memory>
#include <random>

#include <gtest/gtest.h>

#include "core/drone_profiles.h"
#include "core/feasibility.h"
#include "optimizer/optimizer.h"
#include "scene/caster_ground.h"
#include "scene/ray_caster.h"
#include "tests/optimizer/test_scenes.h"

namespace cinepath::optimizer {
namespace {

using test_scenes::AddBox;
using test_scenes::AddGroundQuad;
using test_scenes::PlanFromShots;

// Where a plan stands: the worst excess of every broken limit, the frames whose subject is hidden, the
// steps that pass through a surface, and the lowest camera height over the ground (at z = 0).
struct Standing {
  std::map<std::string, double> worst_excess;
  int blocked = 0;
  int crossings = 0;
  double lowest_m = std::numeric_limits<double>::infinity();
};

Standing Measure(const Trajectory& plan, const scene::SceneMesh* mesh) {
  std::unique_ptr<scene::RayCaster> caster;
  std::unique_ptr<scene::CasterGround> ground;
  if (mesh) {
    caster = std::make_unique<scene::RayCaster>(*mesh);
    ground = std::make_unique<scene::CasterGround>(*caster, "test_scene.json");
  }
  Standing out;
  const std::vector<bool> cut(plan.samples.size(), false);  // one shot
  for (const auto& series : MeasureLimits(plan, cut, {}, ground.get())) {
    for (size_t k = 0; k < series.values.size(); ++k) {
      if (series.Excess(k) > 0)
        out.worst_excess[series.limit] = std::max(out.worst_excess[series.limit], series.Excess(k));
    }
  }
  for (size_t k = 0; k < plan.samples.size(); ++k) {
    const Eigen::Vector3d& p = plan.samples[k].position_enu_m;
    out.lowest_m = std::min(out.lowest_m, p.z());
    if (!caster) continue;
    const SubjectTrack& subject = plan.subjects[0];
    const Eigen::Vector3d aim = subject.positions_enu_m[k] + Eigen::Vector3d(0, 0, subject.height_m / 2);
    const Eigen::Vector3d d = aim - p;
    out.blocked += caster->Occluded(p, d.normalized(), 0.05, d.norm() - 0.3) ? 1 : 0;
    if (k > 0) {
      const Eigen::Vector3d step = p - plan.samples[k - 1].position_enu_m;
      if (step.norm() > 1e-12) {
        out.crossings += caster->Occluded(plan.samples[k - 1].position_enu_m, step.normalized(), 0, step.norm());
      }
    }
  }
  return out;
}

// `after` breaks no limit more than `before` does, hides the subject in no more frames, never passes
// through a surface and stays above the ground.
void ExpectNoWorse(const Standing& before, const Standing& after, const std::string& what) {
  for (const auto& [limit, excess] : after.worst_excess) {
    const double was = before.worst_excess.count(limit) ? before.worst_excess.at(limit) : 0.0;
    EXPECT_LE(excess, was + 1e-6) << what << ": " << limit;
  }
  EXPECT_LE(after.blocked, before.blocked) << what;
  EXPECT_LE(after.crossings, before.crossings) << what;
  EXPECT_GT(after.lowest_m, 0.0) << what;
}

OptimizeResult Optimize(const Trajectory& plan, const scene::SceneMesh& mesh, Quality quality) {
  OptimizeInput in;
  in.plan = plan;
  in.plan_source = "test_plan.json";
  in.mesh = &mesh;
  in.scene_source = "test_scene.json";
  return OptimizePlan(in, OptimizeOptions::ForQuality(quality));
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
  return text;
}

// The head of a shot list flown by `profile`, up to its actors: a zoom, or the aircraft's built-in lens.
std::string Head(const std::string& profile) {
  std::string lens =
      R"("min_focal_length_mm": 24, "max_focal_length_mm": 200, "min_f_number": 2.8, "max_f_number": 16)";
  const auto drone = FindDroneProfile(profile);  // held: a reference into the returned profile must outlive it
  if (const auto& fixed = drone->lens) {
    lens = "\"min_focal_length_mm\": " + std::to_string(fixed->min_focal_length_mm) +
           ", \"max_focal_length_mm\": " + std::to_string(fixed->max_focal_length_mm) +
           ", \"min_f_number\": " + std::to_string(fixed->min_f_number) +
           ", \"max_f_number\": " + std::to_string(fixed->max_f_number) +
           ", \"min_focus_distance_m\": " + std::to_string(fixed->min_focus_distance_m);
  }
  return R"({"schema": "cinepath.shots/1", "frame_rate_hz": 30, "camera": {"filmback": "super35", "width_px": 1920, )"
         R"("height_px": 1080, )" +
         lens + R"(}, "drone": ")" + profile + "\", ";
}

// An ORBIT behind a 6 m wall, a CHASE over a low pillar in its line of sight, a FLYBY behind a block at
// its closest approach: each with its obstacle between the camera and the subject for part of the shot,
// on a double-sided ground.
struct Case {
  std::string name;
  Trajectory plan;
  scene::SceneMesh mesh;
};

std::vector<Case> BlockedCases(const std::string& profile) {
  std::vector<Case> cases;
  const std::string head = Head(profile);
  {
    Case c{"orbit/" + profile,
           PlanFromShots(head + R"(
      "actors": [{"name": "keeper", "height_m": 1.8, "position_enu_m": [0, 0, 0]}],
      "shots": [{"name": "orbit", "type": "ORBIT", "subject": "keeper", "duration_s": 8, "radius_m": 20,
                 "height_m": 5, "turns": 0.17, "direction": "cw", "start_bearing_deg": 0,
                 "easing": "smootherstep", "lens": {"frame_height_fraction": 0.2}}]})"),
           {}};
    AddGroundQuad(&c.mesh, 200, true);
    AddBox(&c.mesh, {4, 8, 0}, {14, 9, 6});
    cases.push_back(std::move(c));
  }
  {
    Case c{"chase/" + profile,
           PlanFromShots(head + R"(
      "actors": [{"name": "runner", "height_m": 1.8,
                  "keyframes": [{"time_s": 0, "position_enu_m": [0, 0, 0]},
                                {"time_s": 10, "position_enu_m": [0, 40, 0]}]}],
      "shots": [{"name": "chase", "type": "CHASE", "subject": "runner", "duration_s": 10, "distance_m": 10,
                 "height_m": 4}]})"),
           {}};
    AddGroundQuad(&c.mesh, 200, true);
    // Half-way between the camera and the runner 5 s in, 2.5 m tall: it hides the runner's middle.
    const Eigen::Vector3d mid = 0.5 * (c.plan.samples[150].position_enu_m + c.plan.subjects[0].positions_enu_m[150]);
    AddBox(&c.mesh, {mid.x() - 0.5, mid.y() - 0.5, 0}, {mid.x() + 0.5, mid.y() + 0.5, 2.5});
    cases.push_back(std::move(c));
  }
  {
    Case c{"flyby/" + profile,
           PlanFromShots(head + R"(
      "actors": [{"name": "keeper", "height_m": 1.8, "position_enu_m": [0, 0, 0]}],
      "shots": [{"name": "flyby", "type": "FLYBY", "subject": "keeper", "duration_s": 10, "closest_distance_m": 15,
                 "height_m": 8, "speed_m_s": 4}]})"),
           {}};
    AddGroundQuad(&c.mesh, 200, true);
    const Eigen::Vector3d mid = 0.5 * c.plan.samples[150].position_enu_m;
    AddBox(&c.mesh, {mid.x() - 2, mid.y() - 2, 0}, {mid.x() + 2, mid.y() + 2, 6});
    cases.push_back(std::move(c));
  }
  return cases;
}

// At draft, to keep the test quick: each dearer preset is held never worse than the cheaper one's result
// (TheQualityLadderClimbs, and the orbit below at the default preset).
TEST(OptimizerRules, ObstaclesBetweenShotsAndSubjectsWithEveryProfile) {
  for (const std::string& profile : DroneProfileNames()) {
    for (const Case& c : BlockedCases(profile)) {
      const Standing before = Measure(c.plan, &c.mesh);
      ASSERT_GT(before.blocked, 0) << c.name;  // the obstacle is in the way
      const OptimizeResult r = Optimize(c.plan, c.mesh, Quality::kDraft);
      const Standing after = Measure(r.plan, &c.mesh);
      ExpectNoWorse(before, after, c.name);
      // The report counts what the test counts, and says what it kept.
      EXPECT_LE(r.report["occlusion"]["blocked_fraction_after"].get<double>(),
                r.report["occlusion"]["blocked_fraction_before"].get<double>())
          << c.name;
      EXPECT_GE(r.report["guard"]["alpha"].get<double>(), 0.0) << c.name;
      EXPECT_EQ(r.failure.empty(), r.report["guard"]["still_broken"].empty()) << c.name;
    }
  }
}

// Rule 1: the limits are constraints of the solve (the augmented Lagrangian's multipliers), not weights the
// goals may outbid. On the chase over a pillar (the camera must climb over it and brake behind the runner)
// the penalties alone leave the acceleration or the jerk over its limit at draft with some profiles, and the
// guard keeps only part of the change (alpha 0.98); with the multipliers the solve meets them itself and keeps all of
// it. The ardupilot-copter profile's chase and the orbit and flyby cases are still cut back by the guard
// (docs/optimize.md, "Known limits").
TEST(OptimizerRules, TheSolveItselfKeepsTheLimitsOnTheChaseOverAPillar) {
  int cut_without_multipliers = 0;
  for (const std::string profile : {"px4-multirotor", "dji-m30", "dji-mini4pro"}) {
    const Case c = std::move(BlockedCases(profile)[1]);
    ASSERT_EQ(c.name, "chase/" + profile);
    for (const int rounds : {0, OptimizeOptions::ForQuality(Quality::kDraft).multiplier_rounds}) {
      OptimizeInput in;
      in.plan = c.plan;
      in.plan_source = "test_plan.json";
      in.mesh = &c.mesh;
      in.scene_source = "test_scene.json";
      OptimizeOptions options = OptimizeOptions::ForQuality(Quality::kDraft);
      options.multiplier_rounds = rounds;
      const Json guard = OptimizePlan(in, options).report["guard"];
      if (rounds == 0) {  // the penalties alone: the guard cuts the change back
        if (guard["alpha"].get<double>() < 1.0 && !guard["raw_broke"].empty()) ++cut_without_multipliers;
      } else {
        EXPECT_EQ(guard["alpha"].get<double>(), 1.0) << c.name << ": " << guard["raw_broke"].dump();
        EXPECT_TRUE(guard["raw_broke"].empty()) << c.name;
      }
    }
  }
  // The penalties alone break a limit somewhere (the px4 chase, since the coarse grid's soft stages,
  // keeps its whole change even without them; docs/optimize.md, "Speed").
  EXPECT_GE(cut_without_multipliers, 1);
}

// The issue's orbit: feasible, a wall between it and its subject, flat ground with both windings, the
// default profile. Once it ended metres under the ground, every frame hidden.
TEST(OptimizerRules, DoubleSidedGroundAndAWallKeepTheOrbitAboveGroundAndFeasible) {
  for (const bool both_windings : {false, true}) {
    Case c = std::move(BlockedCases("px4-multirotor")[0]);
    c.mesh = {};
    AddGroundQuad(&c.mesh, 200, both_windings);
    AddBox(&c.mesh, {4, 8, 0}, {14, 9, 6});
    const Standing before = Measure(c.plan, &c.mesh);
    ASSERT_TRUE(before.worst_excess.empty());  // feasible
    {
      const OptimizeResult r = Optimize(c.plan, c.mesh, Quality::kStandard);
      const Standing after = Measure(r.plan, &c.mesh);
      const std::string what = both_windings ? "two windings" : "one winding";
      EXPECT_TRUE(after.worst_excess.empty()) << what << ": " << r.failure;
      EXPECT_LE(after.blocked, before.blocked) << what;
      EXPECT_EQ(after.crossings, 0) << what;
      EXPECT_GE(after.lowest_m, c.plan.drone.min_terrain_clearance_m - 1e-9) << what;
    }
  }
}

// Rule 2 as a property: random feasible plans among random buildings, on ground of one or two windings,
// stay feasible in every limit after every preset, and hide their subject in no more frames. 20 plans in
// `make test`; CINEPATH_PROPERTY_PLANS=200 in `make bench` (scripts/bench.sh); CINEPATH_PROPERTY_SEED
// draws another set (the default seed's plans are the ones `make test` checks).
TEST(OptimizerRules, RandomFeasiblePlansStayFeasibleAtEveryPreset) {
  const char* seed_env = std::getenv("CINEPATH_PROPERTY_SEED");
  std::mt19937 rng(seed_env ? static_cast<std::mt19937::result_type>(std::strtoul(seed_env, nullptr, 10)) : 20261127);
  const auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
  const char* plans_env = std::getenv("CINEPATH_PROPERTY_PLANS");
  const int plans = plans_env ? std::max(1, std::atoi(plans_env)) : 20;
  int tried = 0, checked = 0;
  while (checked < plans && tried < 20 * plans) {
    ++tried;
    const int type = tried % 3;
    const std::string profile = DroneProfileNames()[tried % DroneProfileNames().size()];
    std::string shot;
    std::string actor = R"({"name": "a", "height_m": 1.8, "position_enu_m": [0, 0, 0]})";
    if (type == 0) {
      shot = R"({"name": "s", "type": "ORBIT", "subject": "a", "duration_s": %D, "radius_m": %R, "height_m": %H,
                 "turns": %T, "start_bearing_deg": %B, "easing": "smootherstep"})";
      shot = Replace(Replace(shot, "%T", std::to_string(uniform(0.05, 0.2))), "%B", std::to_string(uniform(0, 360)));
    } else if (type == 1) {
      shot = R"({"name": "s", "type": "FLYBY", "subject": "a", "duration_s": %D, "closest_distance_m": %R,
                 "height_m": %H, "speed_m_s": %V})";
      shot = Replace(shot, "%V", std::to_string(uniform(1, 4)));
    } else {
      const double heading = uniform(0, 2 * M_PI), run = uniform(5, 15);
      actor = R"({"name": "a", "height_m": 1.8, "keyframes": [{"time_s": 0, "position_enu_m": [0, 0, 0]},
                 {"time_s": %D, "position_enu_m": [%X, %Y, 0]}]})";
      actor = Replace(Replace(actor, "%X", std::to_string(run * std::cos(heading))), "%Y",
                      std::to_string(run * std::sin(heading)));
      shot = R"({"name": "s", "type": "CHASE", "subject": "a", "duration_s": %D, "distance_m": %R, "height_m": %H})";
    }
    const std::string duration = std::to_string(uniform(4, 7));
    shot = Replace(Replace(Replace(shot, "%D", duration), "%R", std::to_string(uniform(8, 25))), "%H",
                   std::to_string(uniform(4, 12)));
    actor = Replace(actor, "%D", duration);
    const Trajectory plan = PlanFromShots(Head(profile) + R"("actors": [)" + actor + R"(], "shots": [)" + shot + "]}");
    scene::SceneMesh mesh;
    AddGroundQuad(&mesh, 300, tried % 2 == 0);
    const int buildings = 1 + static_cast<int>(uniform(0, 3));
    for (int b = 0; b < buildings; ++b) {
      const Eigen::Vector3d at(uniform(-25, 25), uniform(-25, 25), 0);
      const double half = uniform(1, 4);
      AddBox(&mesh, at - Eigen::Vector3d(half, half, 0), at + Eigen::Vector3d(half, half, uniform(3, 12)));
    }
    const Standing before = Measure(plan, &mesh);
    if (!before.worst_excess.empty() || before.crossings > 0) continue;  // not a feasible plan: draw again
    ++checked;
    for (const Quality q : {Quality::kDraft, Quality::kStandard, Quality::kFinal}) {
      const OptimizeResult r = Optimize(plan, mesh, q);
      const Standing after = Measure(r.plan, &mesh);
      const std::string what = "draw " + std::to_string(tried) + " (" + profile + "), " + QualityName(q);
      EXPECT_TRUE(after.worst_excess.empty())
          << what << ": " << (after.worst_excess.empty() ? "" : after.worst_excess.begin()->first);
      EXPECT_LE(after.blocked, before.blocked) << what;
      EXPECT_EQ(after.crossings, 0) << what;
    }
  }
  EXPECT_EQ(checked, plans) << "only " << checked << " feasible plans in " << tried << " draws";
}

// Rule 4 on a corner flown too hard (no mesh, so that the dear presets stay quick): final <= standard <=
// draft in objective, and no preset breaks a limit more than a cheaper one.
TEST(OptimizerRules, TheQualityLadderClimbs) {
  const Trajectory plan = PlanFromShots(Head("px4-multirotor") + R"("shots": [
    {"name": "corner", "type": "KEYFRAMES", "duration_s": 12, "interpolation": "linear",
     "keys": [{"time_s": 0, "position_enu_m": [0, 0, 20], "heading_deg": 0, "pitch_deg": -10},
              {"time_s": 6, "position_enu_m": [0, 12, 20], "heading_deg": 0, "pitch_deg": -10},
              {"time_s": 12, "position_enu_m": [12, 12, 20], "heading_deg": 0, "pitch_deg": -10}]}]})");
  ASSERT_FALSE(Measure(plan, nullptr).worst_excess.empty());
  std::vector<OptimizeResult> results;
  for (const Quality q : {Quality::kDraft, Quality::kStandard, Quality::kFinal}) {
    OptimizeInput in;
    in.plan = plan;
    results.push_back(OptimizePlan(in, OptimizeOptions::ForQuality(q)));
  }
  ExpectNoWorse(Measure(plan, nullptr), Measure(results[0].plan, nullptr), "draft");
  for (size_t i = 1; i < results.size(); ++i) {
    EXPECT_LE(results[i].report["objective"].get<double>(), results[i - 1].report["objective"].get<double>()) << i;
    ExpectNoWorse(Measure(results[i - 1].plan, nullptr), Measure(results[i].plan, nullptr),
                  "preset " + std::to_string(i));
  }
  // The final preset's ladder runs the cheaper presets first: the same numbers.
  const Json& ladder = results[2].report["ladder"];
  ASSERT_EQ(ladder.size(), 3u);
  EXPECT_EQ(ladder[0]["quality"], "draft");
  EXPECT_EQ(ladder[0]["objective"], results[0].report["objective"]);
  EXPECT_EQ(ladder[1]["objective"], results[1].report["ladder"][1]["objective"]);
  EXPECT_EQ(ladder[2]["quality"], "final");
}

}  // namespace
}  // namespace cinepath::optimizer
