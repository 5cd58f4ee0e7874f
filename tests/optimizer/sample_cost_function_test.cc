// optimizer/sample_cost_function.h: a sample's terms stacked in one block give each term's own residuals and
// Jacobian rows, bit for bit, in the order they were added (also with a knot held constant, whose Jacobian
// Ceres does not ask for); the continuation's stiffness scales the stiff parts alone, as a ScaledLoss on a
// block of their own would (residuals and Jacobian times sqrt(scale)).
#include "optimizer/sample_cost_function.h"

#include <gtest/gtest.h>

#include "optimizer/cost_terms.h"
#include "tests/optimizer/test_samples.h"

namespace cinepath::optimizer {
namespace {

using test_samples::Knot;
using test_samples::MakeBase;
using test_samples::RandomKnots;

// Residuals and the four Jacobian blocks (rows x 8, row-major) of a cost at the knots; `skip` names a
// parameter block whose Jacobian is not asked for (-1: none).
struct Evaluated {
  std::vector<double> r;
  std::vector<std::vector<double>> jacobians;
};

Evaluated Evaluate(const ceres::CostFunction& cost, const std::vector<Knot>& knots, int skip = -1) {
  const int m = cost.num_residuals();
  std::vector<const double*> params;
  for (const auto& k : knots) params.push_back(k.data());
  Evaluated e;
  e.r.assign(m, -1.0);
  e.jacobians.assign(4, std::vector<double>(m * kNumChannels, -1.0));
  std::vector<double*> jp;
  for (int j = 0; j < 4; ++j) jp.push_back(j == skip ? nullptr : e.jacobians[j].data());
  EXPECT_TRUE(cost.Evaluate(params.data(), e.r.data(), jp.data()));
  std::vector<double> residuals_only(m);
  EXPECT_TRUE(cost.Evaluate(params.data(), residuals_only.data(), nullptr));
  for (int i = 0; i < m; ++i) EXPECT_NEAR(residuals_only[i], e.r[i], 1e-13 * std::fabs(e.r[i]));  // to rounding
  return e;
}

// Four terms of one sample: framing (3 rows), depth of field (1), the limits (19 hinges in 4 rows, stiff)
// and keep-out (1, stiff), each also as a cost function of its own.
struct Terms {
  SampleBase base = MakeBase();
  FramingCost framing{base, Eigen::Vector3d(5, 30, 2), 1.8, 24.89, 14.0, 0.4, 0.6, 0.2, 20.0};
  SharpCost sharp{base, Eigen::Vector3d(3, 40, 0), 3e-5, false, 10};
  LimitsCost limits;
  KeepOutCost keep_out{base, base.position_enu_m + Eigen::Vector3d(1, 0, -1), 1.8, 3.0, 0.02, 100};
  Terms() {
    DroneProfile drone;
    drone.max_horizontal_speed_m_s = 10;
    CameraSpec camera;
    camera.min_focal_length_mm = 24;
    camera.max_focal_length_mm = 48;
    limits = LimitsCost{base, drone, camera, 0.0, 0.02, 100};
  }
  // The cost functions in the order stacked, and whether each is stiff.
  std::vector<std::pair<std::unique_ptr<ceres::CostFunction>, bool>> Separate() const {
    std::vector<std::pair<std::unique_ptr<ceres::CostFunction>, bool>> out;
    out.emplace_back(std::make_unique<StateCostFunction<FramingCost, kValues>>(new FramingCost(framing), 3), false);
    out.emplace_back(std::make_unique<StateCostFunction<SharpCost, kValues>>(new SharpCost(sharp), 1), false);
    out.emplace_back(std::make_unique<StateCostFunction<LimitsCost, kValuesAndRates>>(new LimitsCost(limits),
                                                                                      LimitsCost::kNumResiduals, 4),
                     true);
    out.emplace_back(std::make_unique<StateCostFunction<KeepOutCost, kValues>>(new KeepOutCost(keep_out), 1), true);
    return out;
  }
  std::unique_ptr<SampleCostFunction> Stacked(const double* stiffness) const {
    auto block = std::make_unique<SampleCostFunction>(base, stiffness);
    block->Add(std::make_unique<StateCostFunction<FramingCost, kValues>>(new FramingCost(framing), 3), false, true);
    block->Add(std::make_unique<StateCostFunction<SharpCost, kValues>>(new SharpCost(sharp), 1), false, true);
    block->Add(std::make_unique<StateCostFunction<LimitsCost, kValuesAndRates>>(new LimitsCost(limits),
                                                                                LimitsCost::kNumResiduals, 4),
               true, false);
    block->Add(std::make_unique<StateCostFunction<KeepOutCost, kValues>>(new KeepOutCost(keep_out), 1), true, false);
    return block;
  }
};

// Every part's rows of the stacked block against the part alone, times `stiff_scale` for a stiff part.
void ExpectStackedRows(double stiffness, int skip) {
  const Terms terms;
  const auto block = terms.Stacked(&stiffness);
  ASSERT_EQ(block->num_residuals(), 3 + 1 + 4 + 1);
  ASSERT_EQ(block->parameter_block_sizes(), std::vector<int32_t>(4, kNumChannels));
  const std::vector<Knot> knots = RandomKnots(21, 0.4);
  const Evaluated stacked = Evaluate(*block, knots, skip);
  int row = 0, active = 0;
  for (const auto& [part, stiff] : terms.Separate()) {
    const Evaluated alone = Evaluate(*part, knots, skip);
    const double scale = stiff ? std::sqrt(stiffness) : 1.0;
    for (int i = 0; i < part->num_residuals(); ++i) {
      EXPECT_EQ(stacked.r[row + i], scale * alone.r[i]) << "row " << row + i;
      active += alone.r[i] != 0;
      for (int j = 0; j < 4; ++j) {
        for (int c = 0; c < kNumChannels; ++c) {
          const double expected = j == skip ? -1.0 : scale * alone.jacobians[j][i * kNumChannels + c];
          EXPECT_EQ(stacked.jacobians[j][(row + i) * kNumChannels + c], expected) << "row " << row + i << " knot " << j;
        }
      }
    }
    row += part->num_residuals();
  }
  EXPECT_GE(active, 6) << "the test point does not exercise the terms";
}

TEST(SampleCostFunction, TheStackedTermsGiveEachTermsOwnRowsBitForBit) {
  ExpectStackedRows(1.0, -1);
  ExpectStackedRows(1.0, 2);  // a knot held constant: its Jacobian block is neither asked for nor written
}

TEST(SampleCostFunction, TheStiffnessScalesTheStiffPartsAloneAsAScaledLossWould) {
  ExpectStackedRows(1e-4, -1);
  ExpectStackedRows(1e-2, 0);
}

}  // namespace
}  // namespace cinepath::optimizer
