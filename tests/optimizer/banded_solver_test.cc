// optimizer/banded_solver.h: on least-squares problems of the optimizer's shape (knots of eight channels, blocks
// on four consecutive knots, some giving their Jacobian in the sample's state, some per knot row, some on one
// knot) the banded Levenberg-Marquardt reaches the minimum Ceres reaches, with the fixed channels held where
// they were; the state path (the 8 x 8 value Gram matrix and the 22 x 22 one of rows that read rates) gives the
// Gauss-Newton matrix the knot rows give; a block on more than four knots is refused.
#include "optimizer/banded_solver.h"

#include <cstring>
#include <memory>
#include <random>
#include <utility>

#include <ceres/ceres.h>
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "optimizer/cost_terms.h"
#include "optimizer/knot_spline.h"
#include "optimizer/linear_cost_function.h"
#include "optimizer/sample_model.h"
#include "optimizer/state_cost_function.h"

namespace cinepath::optimizer {
namespace {

using Knot = std::array<double, kNumChannels>;

// The state's 22 fields of the change at a sample (StateCostFunction's numbering).
std::array<double, kStateFields> Fields(const KnotWeights& w, double const* const* k) {
  std::array<double, kStateFields> f{};
  for (int c = 0; c < kNumChannels; ++c) {
    f[c] = Blend(w.value, k, c);
    f[kNumChannels + c] = Blend(w.d1, k, c);
  }
  for (int c = 0; c < 3; ++c) {
    f[2 * kNumChannels + c] = Blend(w.d2, k, c);
    f[2 * kNumChannels + 3 + c] = Blend(w.d3, k, c);
  }
  return f;
}

// r = A f - b in the state's fields f, with A random; `rates`: A reads every field, else the values only. Its
// Jacobian in the state is A (StateBlock) and through the weights in the knots.
class LinearStateTerm : public ceres::CostFunction, public StateBlock {
 public:
  LinearStateTerm(const KnotWeights& w, int rows, bool rates, std::mt19937* rng) : w_(w), rows_(rows) {
    std::normal_distribution<double> n(0, 1);
    a_.resize(rows * kStateFields);
    b_.resize(rows);
    for (int i = 0; i < rows * kStateFields; ++i) a_[i] = rates || i % kStateFields < kNumChannels ? n(*rng) : 0.0;
    for (double& v : b_) v = n(*rng);
    set_num_residuals(rows);
    for (int j = 0; j < 4; ++j) mutable_parameter_block_sizes()->push_back(kNumChannels);
  }
  bool Evaluate(double const* const* k, double* r, double** jacobians) const override {
    Residuals(k, r);
    if (jacobians) StateRowsToKnots(w_, a_.data(), rows_, jacobians);
    return true;
  }
  bool EvaluateStateBlock(double const* const* k, double* r, double* state_rows) const override {
    Residuals(k, r);
    if (state_rows) std::copy(a_.begin(), a_.end(), state_rows);
    return true;
  }
  const KnotWeights& knot_weights() const override { return w_; }

 private:
  void Residuals(double const* const* k, double* r) const {
    const auto f = Fields(w_, k);
    for (int i = 0; i < rows_; ++i) {
      r[i] = -b_[i];
      for (int j = 0; j < kStateFields; ++j) r[i] += a_[i * kStateFields + j] * f[j];
    }
  }
  KnotWeights w_;
  int rows_;
  std::vector<double> a_, b_;
};

// A smooth, non-linear term per segment on its four knots, through knot rows (no state): a squared
// second difference of each channel, and a bend.
struct SegmentTerm {
  template <typename T>
  bool operator()(const T* k0, const T* k1, const T* k2, const T* k3, T* r) const {
    for (int c = 0; c < kNumChannels; ++c) r[c] = k0[c] - 2.0 * k1[c] + k2[c] + 0.1 * k3[c] * k3[c];
    return true;
  }
};

// A pull of one knot towards a point: blocks on one knot.
struct KnotPull {
  double target;
  template <typename T>
  bool operator()(const T* k, T* r) const {
    for (int c = 0; c < kNumChannels; ++c) r[c] = 0.3 * (k[c] - target * (c + 1));
    return true;
  }
};

struct Problem {
  KnotSpline spline;
  std::vector<Knot> knots;
  std::vector<std::array<bool, 8>> fixed;
  ceres::Problem problem;
  // `linear`: without the segments' bend, a linear least-squares problem (one Gauss-Newton step solves it).
  // `end_s`: the spline's length, a sample block every 0.2 s.
  Problem(unsigned seed, bool with_rates, bool linear = false, int end_s = 6) : spline(0, end_s, 1) {
    std::mt19937 rng(seed);
    knots.assign(spline.num_knots(), Knot{});
    fixed.assign(knots.size(), {});
    for (int step = 0; step <= 5 * end_s; ++step) {
      const double t = 0.2 * step;
      const KnotWeights w = spline.At(t);
      std::vector<double*> blocks;
      for (int j = 0; j < 4; ++j) blocks.push_back(knots[w.first_knot + j].data());
      const bool rates = with_rates && step % 3 == 0;
      problem.AddResidualBlock(new LinearStateTerm(w, 3, rates, &rng), nullptr, blocks);
    }
    for (int s = 0; s < spline.num_segments() && !linear; ++s) {
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<SegmentTerm, kNumChannels, kNumChannels, kNumChannels,
                                                               kNumChannels, kNumChannels>(new SegmentTerm),
                               new ceres::ScaledLoss(nullptr, 0.5, ceres::TAKE_OWNERSHIP), knots[s].data(),
                               knots[s + 1].data(), knots[s + 2].data(), knots[s + 3].data());
    }
    // Linear blocks with a constant Jacobian (the smoothness), whose J^T J the band takes once; every other one
    // under a scaled loss, which the band takes row by row.
    for (int s = 0; s < spline.num_segments(); ++s) {
      problem.AddResidualBlock(
          new LinearCostFunction<SmoothnessCost, SmoothnessCost::kNumResiduals>(new SmoothnessCost{1.0, 0.3}),
          s % 2 ? nullptr : new ceres::ScaledLoss(nullptr, 2.0, ceres::TAKE_OWNERSHIP), knots[s].data(),
          knots[s + 1].data(), knots[s + 2].data(), knots[s + 3].data());
    }
    for (size_t i = 0; i < knots.size(); ++i) {
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<KnotPull, kNumChannels, kNumChannels>(
                                   new KnotPull{0.1 * static_cast<double>(i)}),
                               nullptr, knots[i].data());
    }
  }
  // Holds channel c of knot i (a whole knot: constant), in this problem and for the banded solver.
  void Hold(const std::vector<std::pair<int, int>>& held) {
    for (const auto& [i, c] : held) fixed[i][c] = true;
    for (size_t i = 0; i < knots.size(); ++i) {
      std::vector<int> channels;
      for (int c = 0; c < kNumChannels; ++c) {
        if (fixed[i][c]) channels.push_back(c);
      }
      if (static_cast<int>(channels.size()) == kNumChannels) {
        problem.SetParameterBlockConstant(knots[i].data());
      } else if (!channels.empty()) {
        problem.SetManifold(knots[i].data(), new ceres::SubsetManifold(kNumChannels, channels));
      }
    }
  }
  double Cost() {
    double cost = 0;
    problem.Evaluate(ceres::Problem::EvaluateOptions(), &cost, nullptr, nullptr, nullptr);
    return cost;
  }
};

std::vector<Knot> SolvedByCeres(unsigned seed, bool rates, const std::vector<std::pair<int, int>>& held,
                                bool linear = false) {
  Problem p(seed, rates, linear);
  p.Hold(held);
  ceres::Solver::Options o;
  o.max_num_iterations = 500;
  o.function_tolerance = o.gradient_tolerance = o.parameter_tolerance = 1e-15;
  o.linear_solver_type = ceres::DENSE_QR;
  ceres::Solver::Summary summary;
  ceres::Solve(o, &p.problem, &summary);
  return p.knots;
}

void ExpectTheMinimumCeresReaches(unsigned seed, bool rates, const std::vector<std::pair<int, int>>& held) {
  const std::vector<Knot> expected = SolvedByCeres(seed, rates, held);
  Problem p(seed, rates);
  p.Hold(held);
  BandedSolverOptions o;
  o.max_iterations = 500;
  o.function_tolerance = 1e-15;
  const double before = p.Cost();
  const BandedSolverSummary s =
      SolveBanded(&p.problem, p.knots.front().data(), static_cast<int>(p.knots.size()), p.fixed, o);
  EXPECT_FALSE(s.failed);
  EXPECT_LT(s.final_cost, before) << s.message;
  EXPECT_NEAR(s.final_cost, p.Cost(), 1e-9 * p.Cost()) << "the summary's cost is the problem's at the knots left";
  for (size_t i = 0; i < p.knots.size(); ++i) {
    for (int c = 0; c < kNumChannels; ++c) {
      if (p.fixed[i][c]) {
        EXPECT_EQ(p.knots[i][c], 0.0) << "knot " << i << " channel " << c << " is held";
        continue;
      }
      EXPECT_NEAR(p.knots[i][c], expected[i][c], 1e-6 * (1 + std::fabs(expected[i][c])))
          << "seed " << seed << " knot " << i << " channel " << c;
    }
  }
}

TEST(BandedSolver, ReachesTheMinimumCeresReachesOnValueRows) {
  for (unsigned seed : {1u, 2u, 3u}) ExpectTheMinimumCeresReaches(seed, false, {});
}

TEST(BandedSolver, ReachesTheMinimumCeresReachesWhenRowsReadRates) {
  for (unsigned seed : {4u, 5u, 6u}) ExpectTheMinimumCeresReaches(seed, true, {});
}

TEST(BandedSolver, HeldChannelsStayAndTheRestReachTheSameMinimum) {
  std::vector<std::pair<int, int>> held;
  for (int c = 0; c < kNumChannels; ++c) held.emplace_back(0, c);  // the first knot constant
  for (int i = 0; i < 9; ++i) held.emplace_back(i, kStops);        // a channel no term may move
  held.emplace_back(4, kYaw);
  ExpectTheMinimumCeresReaches(7, true, held);
}

// On a linear problem one undamped step is the exact minimum, only if the Gauss-Newton matrix and the gradient
// the band accumulates (the value Gram matrix, the rates' one, the knot rows, the constant blocks' Gram matrix
// taken once, the one-knot blocks) are exact.
TEST(BandedSolver, OneUndampedStepSolvesALinearProblem) {
  for (const bool rates : {false, true}) {
    const std::vector<Knot> expected = SolvedByCeres(8, rates, {}, true);
    Problem p(8, rates, true);
    BandedSolverOptions o;
    o.max_iterations = 1;
    o.initial_damping = 1e-14;
    const BandedSolverSummary s =
        SolveBanded(&p.problem, p.knots.front().data(), static_cast<int>(p.knots.size()), p.fixed, o);
    EXPECT_EQ(s.iterations, 1);
    for (size_t i = 0; i < p.knots.size(); ++i) {
      for (int c = 0; c < kNumChannels; ++c) {
        EXPECT_NEAR(p.knots[i][c], expected[i][c], 1e-6 * (1 + std::fabs(expected[i][c])))
            << (rates ? "with rates" : "values only") << ", knot " << i << " channel " << c;
      }
    }
  }
}

// A long problem (1,001 sample blocks) is evaluated in chunks, each summed on its own thread: the chunks are the
// problem's, not the machine's, so the solve gives the same bytes on 1, 2 and 4 threads; and the minimum is the
// one the same solver reaches summing every block in one chunk (which the tests above hold against Ceres).
TEST(BandedSolver, ChunksGiveTheSameBytesOnAnyNumberOfThreadsAndTheMinimumOfOneChunk) {
  const auto solve = [](int threads, int max_chunks, BandedSolverSummary* summary) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    Problem p(9, true, false, 200);
    p.Hold({{0, kStops}, {100, kYaw}});
    BandedSolverOptions o;
    o.max_iterations = 200;
    o.function_tolerance = 1e-15;
    o.max_chunks = max_chunks;
    *summary = SolveBanded(&p.problem, p.knots.front().data(), static_cast<int>(p.knots.size()), p.fixed, o);
    return p.knots;
  };
  BandedSolverSummary one, two, four, single;
  const std::vector<Knot> on_one = solve(1, 8, &one), on_two = solve(2, 8, &two), on_four = solve(4, 8, &four);
  const std::vector<Knot> in_one_chunk = solve(2, 1, &single);
  EXPECT_GT(one.chunks, 1) << "the problem is long enough to be split";
  EXPECT_EQ(one.chunks % 4, 0) << "a multiple of four chunks, so that two or four threads share them evenly";
  EXPECT_EQ(single.chunks, 1);
  EXPECT_EQ(one.iterations, two.iterations);
  EXPECT_EQ(one.iterations, four.iterations);
  EXPECT_EQ(std::memcmp(&one.final_cost, &two.final_cost, sizeof(double)), 0);
  ASSERT_EQ(on_one.size(), on_two.size());
  EXPECT_EQ(std::memcmp(on_one.data(), on_two.data(), on_one.size() * sizeof(Knot)), 0) << "1 and 2 threads";
  EXPECT_EQ(std::memcmp(on_one.data(), on_four.data(), on_one.size() * sizeof(Knot)), 0) << "1 and 4 threads";
  EXPECT_NEAR(one.final_cost, single.final_cost, 1e-9 * single.final_cost);
  for (size_t i = 0; i < on_one.size(); ++i) {
    for (int c = 0; c < kNumChannels; ++c) {
      EXPECT_NEAR(on_one[i][c], in_one_chunk[i][c], 1e-6 * (1 + std::fabs(in_one_chunk[i][c])))
          << "knot " << i << " channel " << c;
    }
  }
}

// A solver kept across solves of one problem (the optimizer's continuation stages: the same blocks, a loss whose
// scale changes between solves) gives the same bytes as one set up afresh for each solve.
TEST(BandedSolver, AKeptSolverGivesTheBytesOfAFreshOneWhenALossChangesBetweenSolves) {
  const auto solve = [](bool kept) {
    Problem p(10, true);
    p.Hold({{2, kYaw}});
    auto* stiffness = new ceres::LossFunctionWrapper(nullptr, ceres::TAKE_OWNERSHIP);  // the problem owns it
    for (size_t i = 0; i < p.knots.size(); i += 2) {
      p.problem.AddResidualBlock(new ceres::AutoDiffCostFunction<KnotPull, kNumChannels, kNumChannels>(
                                     new KnotPull{-0.3 * static_cast<double>(i)}),
                                 stiffness, p.knots[i].data());
    }
    BandedSolverOptions o;
    o.max_iterations = 7;
    std::unique_ptr<BandedSolver> solver;
    std::vector<int> iterations;
    for (const double scale : {1e-3, 1e-1, 1.0}) {
      stiffness->Reset(scale == 1.0 ? nullptr : new ceres::ScaledLoss(nullptr, scale, ceres::TAKE_OWNERSHIP),
                       ceres::TAKE_OWNERSHIP);
      const int n = static_cast<int>(p.knots.size());
      if (kept && !solver) solver = std::make_unique<BandedSolver>(&p.problem, p.knots.front().data(), n, p.fixed, 8);
      if (kept) EXPECT_TRUE(solver->SetUpFor(&p.problem, p.knots.front().data(), p.fixed));
      const BandedSolverSummary s =
          kept ? solver->Solve(o) : SolveBanded(&p.problem, p.knots.front().data(), n, p.fixed, o);
      EXPECT_FALSE(s.failed);
      iterations.push_back(s.iterations);
    }
    if (kept) {
      std::vector<std::array<bool, 8>> other = p.fixed;
      other[3][kTilt] = true;
      EXPECT_FALSE(solver->SetUpFor(&p.problem, p.knots.front().data(), other)) << "other channels held";
      ceres::Problem another;
      EXPECT_FALSE(solver->SetUpFor(&another, p.knots.front().data(), p.fixed)) << "another problem";
    }
    return std::make_pair(p.knots, iterations);
  };
  const auto [fresh, fresh_iterations] = solve(false);
  const auto [kept, kept_iterations] = solve(true);
  EXPECT_EQ(fresh_iterations, kept_iterations);
  ASSERT_EQ(fresh.size(), kept.size());
  EXPECT_EQ(std::memcmp(fresh.data(), kept.data(), fresh.size() * sizeof(Knot)), 0);
  EXPECT_NE(fresh[5], Knot{}) << "the solves moved the knots";
}

// A term on five knots: wider than a sample's four, which the band does not hold.
struct FiveKnots {
  template <typename T>
  bool operator()(const T* a, const T* b, const T* c, const T* d, const T* e, T* r) const {
    r[0] = a[0] + b[0] + c[0] + d[0] + e[0];
    return true;
  }
};

TEST(BandedSolver, ABlockOnMoreThanFourKnotsIsRefused) {
  std::vector<Knot> knots(5, Knot{});
  ceres::Problem problem;
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<FiveKnots, 1, 8, 8, 8, 8, 8>(new FiveKnots), nullptr,
                           knots[0].data(), knots[1].data(), knots[2].data(), knots[3].data(), knots[4].data());
  std::vector<std::array<bool, 8>> fixed(5);
  EXPECT_ANY_THROW(SolveBanded(&problem, knots.front().data(), 5, fixed, BandedSolverOptions()));
}

TEST(BandedSolver, AParameterBlockOutsideTheKnotsIsRefused) {
  std::vector<Knot> knots(4, Knot{});
  Knot stray{};
  ceres::Problem problem;
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<KnotPull, kNumChannels, kNumChannels>(new KnotPull{1}),
                           nullptr, stray.data());
  std::vector<std::array<bool, 8>> fixed(4);
  EXPECT_ANY_THROW(SolveBanded(&problem, knots.front().data(), 4, fixed, BandedSolverOptions()));
}

}  // namespace
}  // namespace cinepath::optimizer
