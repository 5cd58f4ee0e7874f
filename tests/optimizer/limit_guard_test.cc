// optimizer/limit_guard.h: a candidate that breaks a limit more than the input anywhere is cut back along
// the straight line towards the input, to the largest fraction that is never worse; what still breaks is
// reported with where, by how much and a hint.
#include "optimizer/limit_guard.h"

#include <gtest/gtest.h>

#include "core/drone_profiles.h"

namespace cinepath::optimizer {
namespace {

constexpr double kFps = 30;

// A level flight east at `speed(t)` m/s (the position integrated sample by sample), 10 m up, 121 samples.
Trajectory Flight(const std::function<double(double)>& speed_m_s) {
  Trajectory p;
  p.frame_rate_hz = kFps;
  p.drone = DefaultDroneProfile();
  ShotSpan span;
  span.name = "shot";
  span.end_time_s = 4;
  p.shots.push_back(span);
  double x = 0;
  for (int k = 0; k <= 120; ++k) {
    TrajectorySample s;
    s.time_s = k / kFps;
    if (k > 0) x += speed_m_s(s.time_s) / kFps;
    s.position_enu_m = {x, 0, 10};
    s.focal_length_mm = 24;
    s.f_number = 4;
    s.focus_distance_m = 20;
    s.shot = "shot";
    p.samples.push_back(s);
  }
  return p;
}

GuardSetup SetupFor(const Trajectory& input, double max_deviation_m = 1e9) {
  GuardSetup g;
  g.cut_before.assign(input.samples.size(), false);
  g.shot_of_sample.assign(input.samples.size(), 0);
  for (const auto& s : input.samples) g.origin_enu_m.push_back(s.position_enu_m);
  g.max_deviation_m.assign(input.samples.size(), max_deviation_m);
  g.aim_enu_m.resize(input.samples.size());
  return g;
}

// input + alpha (output - input), position by position.
std::function<Trajectory(double)> Between(const Trajectory& input, const Trajectory& output) {
  return [=](double alpha) {
    Trajectory p = input;
    for (size_t k = 0; k < p.samples.size(); ++k) {
      p.samples[k].position_enu_m += alpha * (output.samples[k].position_enu_m - input.samples[k].position_enu_m);
    }
    return p;
  };
}

TEST(LimitGuard, AnOutputThatIsNeverWorseIsKeptWhole) {
  const Trajectory input = Flight([](double) { return 6.0; });
  const Trajectory output = Flight([](double) { return 7.0; });
  const LimitGuard guard(input, SetupFor(input));
  const GuardedPlan r = KeepNeverWorse(guard, Between(input, output));
  EXPECT_EQ(r.alpha, 1.0);
  EXPECT_TRUE(r.raw_broke.empty());
  EXPECT_EQ(r.plan.samples[60].position_enu_m, output.samples[60].position_enu_m);
}

TEST(LimitGuard, ALimitTheInputMetIsMetAtTheLargestFractionFound) {
  // 6 m/s, asked for 18 m/s: the 12 m/s limit holds up to alpha = 0.5.
  const Trajectory input = Flight([](double) { return 6.0; });
  const Trajectory output = Flight([](double) { return 18.0; });
  const LimitGuard guard(input, SetupFor(input));
  const GuardedPlan r = KeepNeverWorse(guard, Between(input, output));
  EXPECT_LE(r.alpha, 0.5);
  EXPECT_GT(r.alpha, 0.499);
  EXPECT_EQ(r.raw_broke, std::vector<std::string>{"horizontal_speed"});
  EXPECT_TRUE(guard.WorseThanInput(guard.Measure(r.plan)).empty());
  std::string message;
  EXPECT_TRUE(StillBroken(r.measure, r.plan, &message).empty());
  EXPECT_TRUE(message.empty());
}

TEST(LimitGuard, ALimitTheInputBreaksMayBeBrokenNowhereMore) {
  // 15 m/s against 12: the candidate slows the first half to 9 m/s but speeds the second up to 16 m/s.
  // Better in the worst case nowhere; worse where it speeds up: the input comes back, reported.
  const Trajectory input = Flight([](double) { return 15.0; });
  const Trajectory output = Flight([](double t) { return t < 2 ? 9.0 : 16.0; });
  const LimitGuard guard(input, SetupFor(input));
  const GuardedPlan r = KeepNeverWorse(guard, Between(input, output));
  EXPECT_EQ(r.alpha, 0.0);
  EXPECT_EQ(r.plan.samples[100].position_enu_m, input.samples[100].position_enu_m);
  std::string message;
  const Json still = StillBroken(r.measure, r.plan, &message);
  ASSERT_EQ(still.size(), 1u);
  EXPECT_EQ(still[0]["limit"], "horizontal_speed");
  EXPECT_NEAR(still[0]["by"].get<double>(), 3.0, 1e-6);
  EXPECT_EQ(still[0]["start_time_s"].get<double>(), 0.0);
  EXPECT_EQ(still[0]["end_time_s"].get<double>(), 4.0);
  EXPECT_NE(still[0]["hint"].get<std::string>().find("slower"), std::string::npos);
  EXPECT_NE(message.find("horizontal_speed in shot \"shot\" from 0 s to 4 s"), std::string::npos) << message;
}

TEST(LimitGuard, WithinAShotALimitTheInputBreaksMayMoveButNotGrowNorSpreadToAnotherShot) {
  // Two shots of 2 s. The input bursts to 14 m/s (the limit is 12) for half a second in the first; a
  // candidate flying 13 m/s for a second around it breaks the limit at frames the input met, in that
  // shot and by less: kept whole. The same in the second shot, where the input meets it: cut back.
  const auto burst = [](double from_s, double to_s, double speed) {
    return [=](double t) { return t >= from_s && t <= to_s ? speed : 6.0; };
  };
  const Trajectory input = Flight(burst(0.5, 1.0, 14.0));
  GuardSetup setup = SetupFor(input);
  for (size_t k = 61; k < input.samples.size(); ++k) setup.shot_of_sample[k] = 1;
  const LimitGuard guard(input, setup);
  const GuardedPlan spread = KeepNeverWorse(guard, Between(input, Flight(burst(0.3, 1.5, 13.0))));
  EXPECT_EQ(spread.alpha, 1.0);
  const GuardedPlan moved = KeepNeverWorse(guard, Between(input, Flight(burst(2.5, 3.5, 13.0))));
  EXPECT_LT(moved.alpha, 1.0);
  EXPECT_TRUE(guard.WorseThanInput(moved.measure).empty());
}

TEST(LimitGuard, EachGroupBetweenCutsKeepsTheLargestFractionOfItsOwnChange) {
  // A cut before sample 61 (2.03 s): two groups with their own variables. The candidate flies the first at 7 m/s (never
  // worse: kept whole) and the second at 18 m/s (the 12 m/s limit holds up to half of the change); with one
  // fraction for the whole plan, the first group would lose half of its change too.
  const Trajectory input = Flight([](double) { return 6.0; });
  const Trajectory output = Flight([](double t) { return t < 2.02 ? 7.0 : 18.0; });  // 18 from sample 61
  GuardSetup setup = SetupFor(input);
  setup.cut_before[61] = true;
  std::vector<int> group_of_sample(input.samples.size(), 0);
  for (size_t k = 61; k < input.samples.size(); ++k) setup.shot_of_sample[k] = group_of_sample[k] = 1;
  const LimitGuard guard(input, setup);
  const auto between = [&](const std::vector<double>& alpha) {
    Trajectory p = input;
    for (size_t k = 0; k < p.samples.size(); ++k) {
      p.samples[k].position_enu_m +=
          alpha[group_of_sample[k]] * (output.samples[k].position_enu_m - input.samples[k].position_enu_m);
    }
    return p;
  };
  const GuardedPlan r = KeepNeverWorseByGroup(guard, group_of_sample, between);
  ASSERT_EQ(r.group_alpha.size(), 2u);
  EXPECT_EQ(r.group_alpha[0], 1.0);
  EXPECT_LE(r.group_alpha[1], 0.5);
  EXPECT_GT(r.group_alpha[1], 0.499);
  EXPECT_EQ(r.alpha, r.group_alpha[1]);
  EXPECT_EQ(r.raw_broke, std::vector<std::string>{"horizontal_speed"});
  EXPECT_TRUE(guard.WorseThanInput(r.measure).empty());
  EXPECT_EQ(r.plan.samples[30].position_enu_m, output.samples[30].position_enu_m);
  // The measure returned is the plan's.
  EXPECT_EQ(guard.Measure(r.plan)[0].values, r.measure[0].values);
  // One group: the fraction of the plan as a whole.
  const GuardedPlan whole = KeepNeverWorse(guard, [&](double a) { return between({a, a}); });
  EXPECT_LE(whole.alpha, 0.5);
  EXPECT_GT(whole.alpha, 0.499);
}

TEST(LimitGuard, TheDeviationAllowedIsALimitAndSaysWhatItNeeds) {
  const Trajectory input = Flight([](double) { return 6.0; });
  Trajectory output = input;
  for (auto& s : output.samples) s.position_enu_m.y() += 8;
  const LimitGuard guard(input, SetupFor(input, 5.0));
  const GuardedPlan r = KeepNeverWorse(guard, Between(input, output));
  EXPECT_LE(r.alpha, 5.0 / 8.0);
  EXPECT_GT(r.alpha, 5.0 / 8.0 - 1e-3);
  EXPECT_EQ(r.raw_broke, std::vector<std::string>{"max_deviation"});
  std::string message;
  const Json raw = StillBroken(guard.Measure(output), output, &message);
  ASSERT_EQ(raw.size(), 1u);
  EXPECT_EQ(raw[0]["hint"], "needs 3 m more deviation (max_deviation_m)");
}

}  // namespace
}  // namespace cinepath::optimizer
