// Levenberg-Marquardt on the optimizer's own problem shape (docs/optimize.md, "Speed"): every variable is a
// knot of eight channels, and every residual block reads a few consecutive knots (a sample's four, a
// segment's four, one knot's adherence). The Gauss-Newton matrix J^T J is therefore block-banded: a knot
// couples with the next three only. This solver accumulates it straight into that band, block by block,
// skipping the rows whose Jacobian is zero (the hinges of limits that hold: most rows of a plan), and
// factors it with a banded block Cholesky in time linear in the knots. Ceres' general sparse path did the
// same work through a block-sparse Jacobian, its products and a sparse J^T J, which cost most of a solve.
//
// The steps are Levenberg-Marquardt's with Marquardt's diagonal damping and Nielsen's update of the damping
// (H. B. Nielsen, "Damping parameter in Marquardt's method", IMM-REP-1999-05, DTU), as Ceres takes them:
// a step is accepted when the cost falls by at least 1e-3 of what the model predicted. The problem is a
// ceres::Problem (cost functions, loss functions with zero curvature, as the optimizer's scaled losses), so
// the same problem can still go to Ceres (OptimizeOptions::solver).
//
// The blocks are evaluated in chunks of consecutive blocks, each on its own thread into its own cost, band and
// gradient, added afterwards in chunk order. The chunks follow from the problem alone (its blocks' rows, at
// most BandedSolverOptions::max_chunks), never from the machine's cores: a fixed order of sums, the same bytes
// on every run and any number of threads. The factorization and the step stay on the calling thread.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace ceres {
class Problem;
}

namespace cinepath::optimizer {

struct BandedSolverOptions {
  int max_iterations = 100;          // steps tried, accepted or not
  double function_tolerance = 1e-8;  // an accepted step that lowers the cost by less than this fraction ends it
  double parameter_tolerance = 1e-10;
  double gradient_tolerance = 1e-12;    // largest gradient entry, in cost per unit of a channel
  double initial_damping = 1e-4;        // lambda: the step solves (H + lambda diag(H)) dx = -g
  double min_relative_decrease = 1e-3;  // a step is accepted when the cost falls by this much of the model's
  int max_chunks = 8;  // the blocks' evaluation in at most this many chunks (threads); 1: one sum in block order
};

struct BandedSolverSummary {
  int iterations = 0;  // steps tried
  double initial_cost = 0, final_cost = 0;
  double final_damping = 0;  // lambda at the end: where the next solve of a similar problem may start
  int chunks = 0;            // the blocks' evaluation was split in this many (each its own sums, in a fixed order)
  bool failed = false;       // the cost could not be evaluated at the start
  std::string message;
};

// Solves `problem` over the knots [knots, knots + 8 * num_knots) (one contiguous array of num_knots
// parameter blocks of 8; every parameter block of the problem is one of them), leaving the solution in them.
// `fixed[i][c]`: channel c of knot i does not move (a constant block has every channel fixed).
BandedSolverSummary SolveBanded(ceres::Problem* problem, double* knots, int num_knots,
                                const std::vector<std::array<bool, 8>>& fixed, const BandedSolverOptions& options);

// The same solver kept for several solves of one problem (a continuation's stages, the rounds of
// multipliers): the set-up (the blocks read from the problem, the chunks, the constant blocks' J^T J) is
// done once. Valid while no block is added to or removed from the problem; its losses may change (a stage's
// stiffness). Each Solve is SolveBanded's, with options.max_chunks as the constructor's.
class BandedSolver {
 public:
  BandedSolver(ceres::Problem* problem, double* knots, int num_knots, std::vector<std::array<bool, 8>> fixed,
               int max_chunks);
  ~BandedSolver();
  BandedSolverSummary Solve(const BandedSolverOptions& options);
  // Whether it was set up for this problem, these knots and these fixed channels.
  bool SetUpFor(const ceres::Problem* problem, const double* knots,
                const std::vector<std::array<bool, 8>>& fixed) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cinepath::optimizer
