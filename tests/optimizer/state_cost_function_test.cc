// optimizer/state_cost_function.h against Ceres' automatic differentiation over the 32 knot values: the
// same residuals and Jacobians to rounding; and the limits' hinges in fewer rows: the
// same cost and gradient, and the same Gauss-Newton matrix while no more hinges are active than rows.
#include "optimizer/state_cost_function.h"

#include <ceres/autodiff_cost_function.h>
#include <gtest/gtest.h>

#include "optimizer/cost_terms.h"
#include "tests/optimizer/test_samples.h"

namespace cinepath::optimizer {
namespace {

using test_samples::Knot;

using test_samples::MakeBase;
using test_samples::RandomKnots;

// At most 19 rows (the limits) by 32 knot values. Fixed maximum sizes: no heap allocation through Eigen,
// whose out-of-line allocator would differ from Ceres' under AddressSanitizer (tests/optimizer/CMakeLists.txt).
using Jacobian = Eigen::Matrix<double, Eigen::Dynamic, 4 * kNumChannels, Eigen::RowMajor, 19, 4 * kNumChannels>;
using Gradient = Eigen::Matrix<double, 4 * kNumChannels, 1>;
using GaussNewton = Eigen::Matrix<double, 4 * kNumChannels, 4 * kNumChannels>;

// Residuals r and the dense Jacobian J (rows x 32) of a cost at the knots.
struct Evaluated {
  std::vector<double> r;
  Jacobian jacobian;
};

Evaluated Evaluate(const ceres::CostFunction& cost, const std::vector<Knot>& knots) {
  const int m = cost.num_residuals();
  std::vector<const double*> params;
  for (const auto& k : knots) params.push_back(k.data());
  Evaluated e;
  e.r.resize(m);
  std::vector<std::vector<double>> blocks(4, std::vector<double>(m * kNumChannels));
  std::vector<double*> jp;
  for (auto& b : blocks) jp.push_back(b.data());
  EXPECT_TRUE(cost.Evaluate(params.data(), e.r.data(), jp.data()));
  e.jacobian.resize(m, Eigen::NoChange);
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < m; ++i) {
      for (int c = 0; c < kNumChannels; ++c) e.jacobian(i, j * kNumChannels + c) = blocks[j][i * kNumChannels + c];
    }
  }
  std::vector<double> residuals_only(m);
  EXPECT_TRUE(cost.Evaluate(params.data(), residuals_only.data(), nullptr));
  for (int i = 0; i < m; ++i) EXPECT_NEAR(residuals_only[i], e.r[i], 1e-13 * std::fabs(e.r[i]));  // to rounding
  return e;
}

// `rows` as StateCostFunction takes it (0: not hinges; `residuals`: hinges, each in its own row).
template <int kFields, typename Functor>
void ExpectSameAsAutoDiff(const Functor& f, int residuals, unsigned seed, int rows = 0) {
  const ceres::AutoDiffCostFunction<Functor, ceres::DYNAMIC, kNumChannels, kNumChannels, kNumChannels, kNumChannels>
      automatic(new Functor(f), residuals);
  const StateCostFunction<Functor, kFields> state(new Functor(f), residuals, rows);
  const std::vector<Knot> knots = RandomKnots(seed, 0.5);
  const Evaluated a = Evaluate(automatic, knots), s = Evaluate(state, knots);
  for (size_t i = 0; i < a.r.size(); ++i) EXPECT_NEAR(a.r[i], s.r[i], 1e-13 * std::fabs(a.r[i]));
  EXPECT_GT(a.jacobian.norm(), 1e-6) << "the test point does not exercise the term";
  EXPECT_LE((a.jacobian - s.jacobian).norm(), 1e-12 * a.jacobian.norm());
}

TEST(StateCostFunction, EveryOneSampleTermMatchesAutomaticDifferentiationOverTheKnots) {
  const SampleBase b = MakeBase();
  ExpectSameAsAutoDiff<kValues>(FramingCost{b, Eigen::Vector3d(5, 30, 2), 1.8, 24.89, 14.0, 0.4, 0.6, 0.2, 20.0}, 3, 1);
  ExpectSameAsAutoDiff<kValues>(SharpCost{b, Eigen::Vector3d(3, 40, 0), 3e-5, false, 10}, 1, 2);
  ExpectSameAsAutoDiff<kValues>(SharpCost{b, Eigen::Vector3d(3, 40, 0), 3e-5, true, 10}, 1, 3);
  ExpectSameAsAutoDiff<kValues>(BackgroundBlurCost{b, Eigen::Vector3d(3, 14, 6), 50.0, 500.0, 154000, 5}, 1, 4);
  ExpectSameAsAutoDiff<kValues>(KeepOutCost{b, b.position_enu_m + Eigen::Vector3d(1, 0, -1), 1.8, 3.0, 0.02, 100}, 1,
                                5);
  ExpectSameAsAutoDiff<kValues>(ClearViewCost{b, Eigen::Vector3d(4, 5, 6), 30}, 3, 6);
  OutOfShotCost out{b, true, b.position_enu_m + Eigen::Vector3d(0.5, 8, -2.5)};
  ExpectSameAsAutoDiff<kValues>(out, 1, 7);
  DroneProfile drone;
  drone.max_horizontal_speed_m_s = 10;
  CameraSpec camera;
  camera.min_focal_length_mm = 24;
  camera.max_focal_length_mm = 48;
  ExpectSameAsAutoDiff<kValuesAndRates>(LimitsCost{b, drone, camera, 0.0, 0.02, 100}, LimitsCost::kNumResiduals, 8);
}

// The limits as hinges (only the active ones differentiated) against automatic differentiation over the
// knots, with every one of the 19 hinges active in one of three profiles: every maximum tiny while climbing,
// then while descending, then every minimum huge with the focus beyond infinity.
TEST(StateCostFunction, EveryLimitsHingeDifferentiatedAloneMatchesAutomaticDifferentiation) {
  std::vector<bool> seen(LimitsCost::kNumResiduals, false);
  const auto check = [&](const LimitsCost& f, unsigned seed) {
    ExpectSameAsAutoDiff<kValuesAndRates>(f, LimitsCost::kNumResiduals, seed, LimitsCost::kNumResiduals);
    const std::vector<Knot> k = RandomKnots(seed, 0.5);  // the knots ExpectSameAsAutoDiff takes
    double r[LimitsCost::kNumResiduals];
    f(k[0].data(), k[1].data(), k[2].data(), k[3].data(), r);
    for (int i = 0; i < LimitsCost::kNumResiduals; ++i) seen[i] = seen[i] || r[i] > 0;
  };
  SampleBase b = MakeBase();
  DroneProfile tight;
  tight.max_horizontal_speed_m_s = tight.max_climb_rate_m_s = tight.max_descent_rate_m_s = 0.1;
  tight.max_acceleration_m_s2 = tight.max_jerk_m_s3 = tight.max_yaw_rate_deg_s = 0.1;
  tight.max_gimbal_pitch_rate_deg_s = 0.1;
  tight.max_gimbal_pitch_deg = -80;
  tight.max_altitude_m = 1;
  CameraSpec small;
  small.min_focal_length_mm = 10;
  small.max_focal_length_mm = 20;
  small.max_focal_rate_mm_s = small.max_aperture_rate_stops_s = 0.1;
  small.min_f_number = 1;
  small.max_f_number = 2;
  small.min_focus_distance_m = 20;  // closer than the focus: 1/12 > 1/20 dioptres
  b.velocity_m_s.z() = 3.0;
  check(LimitsCost{b, tight, small, 0.0, 0.02, 100}, 31);
  b.velocity_m_s.z() = -3.0;
  check(LimitsCost{b, tight, small, 0.0, 0.02, 100}, 32);
  DroneProfile low;
  low.min_gimbal_pitch_deg = 10;
  low.min_altitude_m = 100;
  CameraSpec wide;
  wide.min_focal_length_mm = 200;
  wide.max_focal_length_mm = 400;
  wide.min_f_number = 16;
  wide.max_f_number = 22;
  b.dioptre = -0.05;  // beyond infinity
  check(LimitsCost{b, low, wide, 0.0, 0.02, 100}, 33);
  for (int i = 0; i < LimitsCost::kNumResiduals; ++i) {
    EXPECT_TRUE(seen[i]) << LimitsCost::kLimitName[i] << " was never active";
  }
}

// The limits in `rows` rows against all 19: cost and gradient J^T r always, J^T J when no more hinges are
// active than rows. Returns how many hinges were active.
int ExpectSameModel(const LimitsCost& f, int rows, unsigned seed) {
  const ceres::AutoDiffCostFunction<LimitsCost, LimitsCost::kNumResiduals, kNumChannels, kNumChannels, kNumChannels,
                                    kNumChannels>
      full(new LimitsCost(f));
  const StateCostFunction<LimitsCost, kValuesAndRates> compact(new LimitsCost(f), LimitsCost::kNumResiduals, rows);
  EXPECT_EQ(compact.num_residuals(), rows);
  const std::vector<Knot> knots = RandomKnots(seed, 0.3);
  const Evaluated a = Evaluate(full, knots), c = Evaluate(compact, knots);
  using Residuals = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 19, 1>>;
  const Residuals ra(a.r.data(), Eigen::Index(a.r.size())), rc(c.r.data(), Eigen::Index(c.r.size()));
  const int active = static_cast<int>((ra.array() != 0).count());
  EXPECT_NEAR(rc.squaredNorm(), ra.squaredNorm(), 1e-12 * ra.squaredNorm());
  const Gradient ga = a.jacobian.transpose() * ra, gc = c.jacobian.transpose() * rc;
  EXPECT_LE((ga - gc).norm(), 1e-10 * ga.norm());
  if (active <= rows) {
    const GaussNewton ha = a.jacobian.transpose() * a.jacobian, hc = c.jacobian.transpose() * c.jacobian;
    EXPECT_LE((ha - hc).norm(), 1e-10 * ha.norm());
  }
  return active;
}

TEST(StateCostFunction, TheLimitsInFewerRowsKeepTheCostTheGradientAndTheGaussNewtonModel) {
  const SampleBase b = MakeBase();
  CameraSpec camera;
  camera.min_focal_length_mm = 24;
  camera.max_focal_length_mm = 200;
  DroneProfile drone;
  drone.max_horizontal_speed_m_s = 10;  // speed broken; acceleration, jerk, yaw and pitch rates held
  drone.max_acceleration_m_s2 = 20;
  drone.max_jerk_m_s3 = 20;
  drone.max_yaw_rate_deg_s = 90;
  drone.max_gimbal_pitch_rate_deg_s = 180;
  const int few = ExpectSameModel(LimitsCost{b, drone, camera, 0.0, 0.02, 100}, 4, 11);
  EXPECT_GE(few, 1);
  EXPECT_LE(few, 4);
  // Speed, acceleration, jerk, yaw and pitch rates all broken: more active hinges than rows.
  drone.max_acceleration_m_s2 = 2;
  drone.max_jerk_m_s3 = 2;
  drone.max_yaw_rate_deg_s = 20;
  drone.max_gimbal_pitch_rate_deg_s = 30;
  EXPECT_GT(ExpectSameModel(LimitsCost{b, drone, camera, 0.0, 0.02, 100}, 4, 12), 4);
}

}  // namespace
}  // namespace cinepath::optimizer
