// Every cost functor of optimizer/cost_terms.h and optimizer/clearance_cost.h: its
// Jacobians (analytic or automatic) against central finite differences, at points where each
// hinge is active, so that the checked derivative is not zero by construction.
#include "optimizer/cost_terms.h"

#include <algorithm>
#include <random>

#include <ceres/autodiff_cost_function.h>
#include <ceres/jet.h>
#include <gtest/gtest.h>

#include "optimizer/clearance_cost.h"
#include "optimizer/linear_cost_function.h"
#include "scene/surface_distance.h"
#include "tests/optimizer/test_samples.h"

namespace cinepath::optimizer {
namespace {

using test_samples::Knot;

using test_samples::MakeBase;
using test_samples::RandomKnots;

// The cost's Jacobians against central finite differences (step 1e-6 in every variable), entry by entry
// within 1e-4 relative (1e-7 absolute). Ceres' GradientChecker (2.1, Debian 12) was tried first: on
// SharpCost it reported numeric derivatives that disagree with a hand-written central difference of the
// same residual at every step size, so the check is done here directly.
void ExpectGradientsMatch(const ceres::CostFunction* cost, std::vector<Knot> knots, bool expect_nonzero = true) {
  const int blocks = static_cast<int>(knots.size());
  const int m = cost->num_residuals();
  std::vector<const double*> params;
  for (auto& k : knots) params.push_back(k.data());
  std::vector<double> r(m), rp(m), rm(m);
  std::vector<std::vector<double>> jac(blocks, std::vector<double>(m * kNumChannels));
  std::vector<double*> jp;
  for (auto& j : jac) jp.push_back(j.data());
  ASSERT_TRUE(cost->Evaluate(params.data(), r.data(), jp.data()));
  double norm = 0;
  const double h = 1e-6;
  for (int b = 0; b < blocks; ++b) {
    for (int c = 0; c < kNumChannels; ++c) {
      const double x = knots[b][c];
      knots[b][c] = x + h;
      ASSERT_TRUE(cost->Evaluate(params.data(), rp.data(), nullptr));
      knots[b][c] = x - h;
      ASSERT_TRUE(cost->Evaluate(params.data(), rm.data(), nullptr));
      knots[b][c] = x;
      for (int i = 0; i < m; ++i) {
        const double numeric = (rp[i] - rm[i]) / (2 * h);
        const double analytic = jac[b][i * kNumChannels + c];
        norm += std::fabs(analytic);
        EXPECT_NEAR(analytic, numeric, 1e-7 + 1e-4 * std::fabs(numeric))
            << "block " << b << " channel " << c << " residual " << i;
      }
    }
  }
  if (expect_nonzero) EXPECT_GT(norm, 1e-6) << "the Jacobian is zero: the test point does not exercise the term";
}

template <typename F, int R>
ceres::CostFunction* Auto(F* f) {
  return new ceres::AutoDiffCostFunction<F, R, kNumChannels, kNumChannels, kNumChannels, kNumChannels>(f);
}

TEST(CostTerms, FramingGradient) {
  const SampleBase b = MakeBase();
  auto* f = new FramingCost{b, Eigen::Vector3d(5, 30, 2), 1.8, 24.89, 14.0, 0.4, 0.6, 0.2, 20.0};
  std::unique_ptr<ceres::CostFunction> cost(Auto<FramingCost, 3>(f));
  ExpectGradientsMatch(cost.get(), RandomKnots(1, 0.5));
}

TEST(CostTerms, SharpGradientBothModes) {
  const SampleBase b = MakeBase();
  // An actor far outside the depth of field (the hinge is active), and the focus-follow residual.
  std::unique_ptr<ceres::CostFunction> sharp(
      Auto<SharpCost, 1>(new SharpCost{b, Eigen::Vector3d(3, 40, 0), 3e-5, false, 10}));
  ExpectGradientsMatch(sharp.get(), RandomKnots(2, 0.5));
  std::unique_ptr<ceres::CostFunction> follow(
      Auto<SharpCost, 1>(new SharpCost{b, Eigen::Vector3d(3, 40, 0), 3e-5, true, 10}));
  ExpectGradientsMatch(follow.get(), RandomKnots(3, 0.5));
}

TEST(CostTerms, BackgroundBlurGradient) {
  const SampleBase b = MakeBase();
  std::unique_ptr<ceres::CostFunction> cost(
      Auto<BackgroundBlurCost, 1>(new BackgroundBlurCost{b, Eigen::Vector3d(3, 14, 6), 50.0, 500.0, 154000, 5}));
  ExpectGradientsMatch(cost.get(), RandomKnots(4, 0.5));
  std::unique_ptr<ceres::CostFunction> at_infinity(Auto<BackgroundBlurCost, 1>(
      new BackgroundBlurCost{b, Eigen::Vector3d(3, 14, 6), std::numeric_limits<double>::infinity(), 500.0, 154000, 5}));
  ExpectGradientsMatch(at_infinity.get(), RandomKnots(5, 0.5));
}

TEST(CostTerms, LimitsGradient) {
  SampleBase b = MakeBase();
  DroneProfile drone;
  drone.max_horizontal_speed_m_s = 10;  // the base's 12.3 m/s breaks it, and the others sit near theirs
  CameraSpec camera;
  camera.min_focal_length_mm = 24;
  camera.max_focal_length_mm = 48;  // 50 mm breaks it
  auto* f = new LimitsCost{b, drone, camera, 0.0, 0.02, 100};
  std::unique_ptr<ceres::CostFunction> cost(
      new ceres::AutoDiffCostFunction<LimitsCost, LimitsCost::kNumResiduals, kNumChannels, kNumChannels, kNumChannels,
                                      kNumChannels>(f));
  ExpectGradientsMatch(cost.get(), RandomKnots(6, 0.3));
}

// The augmented Lagrangian's update: a broken limit's shift grows by how far past its aimed value the
// limit is, a limit held with room keeps a zero shift, and the shifted hinge's gradients are still exact.
TEST(CostTerms, LimitsMultipliersGrowWhereALimitIsBrokenAndKeepExactGradients) {
  const SampleBase b = MakeBase();
  DroneProfile drone;
  drone.max_horizontal_speed_m_s = 10;  // the base's 12.3 m/s breaks it
  CameraSpec camera;
  camera.min_focal_length_mm = 24;
  camera.max_focal_length_mm = 200;  // 50 mm holds it with room
  LimitsCost limits{b, drone, camera, 0.0, 0.02, 100};
  static const Knot kZero{};
  const double* zero[4] = {kZero.data(), kZero.data(), kZero.data(), kZero.data()};
  const double speed_past = std::hypot(b.velocity_m_s.x(), b.velocity_m_s.y()) / 10.0 - 0.98;
  ASSERT_GT(speed_past, 0.2);
  EXPECT_NEAR(limits.UpdateShifts(zero), speed_past, 1e-9);  // the worst argument
  EXPECT_NEAR(limits.shift[0], speed_past, 1e-9);
  EXPECT_EQ(limits.shift[14], 0.0);  // focal length max: held
  limits.UpdateShifts(zero);
  EXPECT_NEAR(limits.shift[0], 2 * speed_past, 1e-9);  // the same excess again: twice the shift
  double r[LimitsCost::kNumResiduals];
  limits(kZero.data(), kZero.data(), kZero.data(), kZero.data(), r);
  EXPECT_NEAR(r[0], 100 * 3 * speed_past, 1e-6);  // weight max(0, argument + shift)
  // A channel that does not move gets no multiplier.
  limits.free[kEast] = false;
  limits.shift = {};
  limits.UpdateShifts(zero);
  EXPECT_EQ(limits.shift[0], 0.0);
  limits.free[kEast] = true;
  limits.shift[0] = 0.3;
  std::unique_ptr<ceres::CostFunction> cost(
      new ceres::AutoDiffCostFunction<LimitsCost, LimitsCost::kNumResiduals, kNumChannels, kNumChannels, kNumChannels,
                                      kNumChannels>(new LimitsCost(limits)));
  ExpectGradientsMatch(cost.get(), RandomKnots(6, 0.3));
  // Keep-out and the deviation: the same update.
  KeepOutCost keep_out{b, b.position_enu_m + Eigen::Vector3d(1, 0, -1), 1.8, 3.0, 0.02, 100};
  EXPECT_NEAR(keep_out.UpdateShifts(zero), (3.06 - 1.0) / 3.0, 1e-6);
  EXPECT_NEAR(keep_out.shift, 2.06, 1e-6);
  AdherenceCost adherence{1.0, 0.5, 200, 1e-3};
  Knot far{};
  far[kEast] = 3;
  EXPECT_NEAR(adherence.UpdateShifts(far.data()), 2.0, 1e-12);
  EXPECT_NEAR(adherence.UpdateShifts(kZero.data()), -1.0, 1e-12);
  EXPECT_NEAR(adherence.shift, 1.0, 1e-12);
}

TEST(CostTerms, KeepOutGradient) {
  const SampleBase b = MakeBase();
  std::unique_ptr<ceres::CostFunction> cost(
      Auto<KeepOutCost, 1>(new KeepOutCost{b, Eigen::Vector3d(1.5, 2.5, 9), 1.8, 3.0, 0.02, 100}));
  ExpectGradientsMatch(cost.get(), RandomKnots(7, 0.2));
}

TEST(CostTerms, OutOfShotGradient) {
  const SampleBase b = MakeBase();
  // A viewer 40 m north-east of the sample looking back at it: the body sits inside its frame, near the
  // centre, so the hinge is active.
  const Eigen::Vector3d viewer = b.position_enu_m + Eigen::Vector3d(28, 28, 1);
  const Eigen::Quaterniond look = LookAt(b.position_enu_m + Eigen::Vector3d(-1.5, 0.5, 0) - viewer);
  const Eigen::Matrix3d camera_from_world = look.conjugate().toRotationMatrix();
  const Eigen::Vector3d c = camera_from_world * (b.position_enu_m - viewer);
  ASSERT_GT(c.z(), 30);
  // 25 x 14 mm at 50 mm: tan of the half angles 0.25 and 0.14.
  std::unique_ptr<ceres::CostFunction> cost(
      Auto<OutOfShotCost, 1>(new OutOfShotCost{b, false, viewer, camera_from_world, 50, 25, 14, 0.4, 0.02, 100}));
  ExpectGradientsMatch(cost.get(), RandomKnots(11, 0.2));
  // Outside a narrow frame (1250 mm): no cost.
  std::unique_ptr<ceres::CostFunction> away(
      Auto<OutOfShotCost, 1>(new OutOfShotCost{b, false, viewer, camera_from_world, 1250, 25, 14, 0.4, 0.02, 100}));
  ExpectGradientsMatch(away.get(), RandomKnots(12, 0.01), false);
  // This drone's camera (50 mm, its yaw, tilt and zoom free) sees a body held 30 m ahead.
  const Eigen::Vector3d ahead = b.position_enu_m + 30 * (b.world_from_camera * Eigen::Vector3d(0.1, 0.05, 1));
  std::unique_ptr<ceres::CostFunction> own(Auto<OutOfShotCost, 1>(
      new OutOfShotCost{b, true, ahead, Eigen::Matrix3d::Identity(), 0, 25, 14, 0.4, 0.02, 100}));
  ExpectGradientsMatch(own.get(), RandomKnots(13, 0.2));
}

TEST(CostTerms, SmoothnessAndClearViewGradient) {
  std::unique_ptr<ceres::CostFunction> smooth(
      new ceres::AutoDiffCostFunction<SmoothnessCost, SmoothnessCost::kNumResiduals, kNumChannels, kNumChannels,
                                      kNumChannels, kNumChannels>(new SmoothnessCost{0.5, 1}));
  ExpectGradientsMatch(smooth.get(), RandomKnots(8, 1));
  // With its Jacobian taken once (optimizer/linear_cost_function.h): against finite differences, and the same
  // numbers as automatic differentiation at a point away from the one it was taken at.
  LinearCostFunction<SmoothnessCost, SmoothnessCost::kNumResiduals> linear(new SmoothnessCost{0.5, 1});
  ExpectGradientsMatch(&linear, RandomKnots(8, 1));
  std::vector<Knot> knots = RandomKnots(14, 2);
  const double* at[4] = {knots[0].data(), knots[1].data(), knots[2].data(), knots[3].data()};
  constexpr int kRows = SmoothnessCost::kNumResiduals;
  std::array<std::array<double, kRows * kNumChannels>, 4> ja, jl;
  double* pa[4] = {ja[0].data(), ja[1].data(), ja[2].data(), ja[3].data()};
  double* pl[4] = {jl[0].data(), jl[1].data(), jl[2].data(), jl[3].data()};
  std::array<double, kRows> ra, rl;
  ASSERT_TRUE(smooth->Evaluate(at, ra.data(), pa));
  ASSERT_TRUE(linear.Evaluate(at, rl.data(), pl));
  for (int i = 0; i < kRows; ++i) EXPECT_NEAR(ra[i], rl[i], 1e-13 * std::fabs(ra[i]));  // Jets round their .a apart
  EXPECT_EQ(ja, jl);
  std::unique_ptr<ceres::CostFunction> view(
      Auto<ClearViewCost, 3>(new ClearViewCost{MakeBase(), Eigen::Vector3d(2, 3, 14), 30}));
  ExpectGradientsMatch(view.get(), RandomKnots(9, 1));
}

TEST(CostTerms, AdherenceGradient) {
  std::unique_ptr<ceres::CostFunction> cost(
      new ceres::AutoDiffCostFunction<AdherenceCost, AdherenceCost::kNumResiduals, kNumChannels>(
          new AdherenceCost{1.0, 0.05, 200, 1e-3}));
  ExpectGradientsMatch(cost.get(), {Knot{1.5, -0.7, 0.4, 0.01, -0.02, 0.1, 0.01, 0.3}});  // beyond 1 m
}

TEST(CostTerms, ClearanceGradientIsExact) {
  // A ground plane 2 m under the camera, inside the 3 m margin.
  scene::SceneMesh mesh;
  mesh.positions_enu_m = {{-100, -100, 8}, {100, -100, 8}, {100, 100, 8}, {-100, 100, 8}};
  mesh.faces = {{0, 1, 2}, {0, 2, 3}};
  const scene::SurfaceDistance surface(mesh);
  ClearanceCost cost(MakeBase(), &surface, 3.0, 100);
  ExpectGradientsMatch(&cost, RandomKnots(10, 0.3));
}

// The goals' gradients by hand (FramingCost::Gradients, SharpCost's, BackgroundBlurCost's) against automatic
// differentiation in the eight channel values, at 200 random states per functor: the same residuals, and every
// derivative within 1e-6 of the Jets' (relative, or of the row's size where the derivative is near zero), and
// the residuals exactly the functor's own in doubles. A wrong
// derivative of any field fails it; the hinges must be active at enough of the states to be checked.
template <typename Functor>
void ExpectGradientsByHandMatchJets(const Functor& f, int residuals, unsigned seed, int at_least_active) {
  using Jet = ceres::Jet<double, kNumChannels>;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  int active = 0;
  for (int trial = 0; trial < 200; ++trial) {
    SampleState<double> s{};
    s.position = f.base.position_enu_m + 5.0 * Eigen::Vector3d(u(rng), u(rng), u(rng));
    s.velocity = s.acceleration = s.jerk = Eigen::Vector3d::Zero();
    s.yaw = 0.5 * u(rng);
    s.tilt = 0.3 * u(rng);
    s.log_focal = 0.5 * u(rng);
    s.dioptre = f.base.dioptre + 0.05 * u(rng);
    s.stops = 2.0 * u(rng);
    s.yaw_rate = s.tilt_rate = s.log_focal_rate = s.dioptre_rate = s.stops_rate = 0;
    SampleState<Jet> j;
    for (int c = 0; c < 3; ++c) {
      j.position[c] = Jet(s.position[c], c);
      j.velocity[c] = j.acceleration[c] = j.jerk[c] = Jet(0.0);
    }
    j.yaw = Jet(s.yaw, kYaw);
    j.tilt = Jet(s.tilt, kTilt);
    j.log_focal = Jet(s.log_focal, kLogFocal);
    j.dioptre = Jet(s.dioptre, kDioptre);
    j.stops = Jet(s.stops, kStops);
    j.yaw_rate = j.tilt_rate = j.log_focal_rate = j.dioptre_rate = j.stops_rate = Jet(0.0);
    Jet automatic[3];
    ASSERT_TRUE(f.Residuals(j, automatic));
    double r[3];
    double g[3][kNumChannels];
    f.Gradients(s, r, g);
    double plain[3];
    ASSERT_TRUE(f.Residuals(s, plain));
    for (int i = 0; i < residuals; ++i) {
      // The Jets' values round apart from doubles (a Jet divides by multiplying with the inverse).
      EXPECT_NEAR(r[i], automatic[i].a, 1e-12 * std::fabs(automatic[i].a)) << "trial " << trial << " residual " << i;
      EXPECT_EQ(r[i], plain[i]) << "trial " << trial << " residual " << i;
      const double row = automatic[i].v.norm();
      if (row > 0) ++active;
      for (int c = 0; c < kNumChannels; ++c) {
        EXPECT_LE(std::fabs(g[i][c] - automatic[i].v[c]), 1e-6 * std::max(std::fabs(automatic[i].v[c]), 1e-6 * row))
            << "trial " << trial << " residual " << i << " channel " << c << ": " << g[i][c] << " by hand, "
            << automatic[i].v[c] << " by the Jets";
      }
    }
  }
  EXPECT_GE(active, at_least_active) << "too few states exercise the term";
}

TEST(CostTerms, TheGoalsGradientsByHandMatchAutomaticDifferentiationAtRandomStates) {
  const SampleBase b = MakeBase();
  ExpectGradientsByHandMatchJets(FramingCost{b, Eigen::Vector3d(5, 30, 2), 1.8, 24.89, 14.0, 0.4, 0.6, 0.2, 20.0}, 3,
                                 21, 600);
  ExpectGradientsByHandMatchJets(FramingCost{b, Eigen::Vector3d(5, 30, 2), 1.8, 24.89, 14.0, 0.5, 0.5, 0.0, 1.0}, 3, 22,
                                 400);  // no size goal: the third row is zero
  ExpectGradientsByHandMatchJets(SharpCost{b, Eigen::Vector3d(3, 40, 0), 3e-5, false, 10}, 1, 23, 100);
  ExpectGradientsByHandMatchJets(SharpCost{b, Eigen::Vector3d(3, 40, 0), 3e-5, true, 10}, 1, 24, 200);
  ExpectGradientsByHandMatchJets(BackgroundBlurCost{b, Eigen::Vector3d(3, 14, 6), 50.0, 500.0, 154000, 5}, 1, 25, 100);
  ExpectGradientsByHandMatchJets(
      BackgroundBlurCost{b, Eigen::Vector3d(3, 14, 6), std::numeric_limits<double>::infinity(), 500.0, 154000, 5}, 1,
      26, 100);
  // The camera's depth clamped (the aim point behind the camera): the depth's derivatives vanish.
  ExpectGradientsByHandMatchJets(
      SharpCost{b, b.position_enu_m - 30.0 * (b.world_from_camera * Eigen::Vector3d::UnitZ()), 3e-5, false, 10}, 1, 27,
      100);
}

TEST(CostTerms, ZeroChangeIsZeroCostForAPlanThatKeepsEverything) {
  SampleBase b = MakeBase();
  b.velocity_m_s = {1, 1, 0};
  b.acceleration_m_s2 = {0.1, 0, 0};
  b.jerk_m_s3 = {0.1, 0, 0};
  b.heading_rate_deg_s = 5;
  b.pitch_rate_deg_s = 1;
  b.focal_rate_mm_s = 0;
  b.aperture_rate_stops_s = 0;
  DroneProfile drone;
  CameraSpec camera;
  camera.max_focal_length_mm = 100;
  camera.min_f_number = 1.4;
  LimitsCost limits{b, drone, camera, 0.0, 0.02, 100};
  const Knot zero{};
  const double* k[4] = {zero.data(), zero.data(), zero.data(), zero.data()};
  double r[LimitsCost::kNumResiduals];
  ASSERT_TRUE(limits(k[0], k[1], k[2], k[3], r));
  for (double v : r) EXPECT_EQ(v, 0.0);
}

}  // namespace
}  // namespace cinepath::optimizer
