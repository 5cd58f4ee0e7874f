#include "optimizer/banded_solver.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <utility>

#include <ceres/ceres.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <Eigen/Core>

#include "core/error.h"
#include "optimizer/linear_cost_function.h"
#include "optimizer/state_cost_function.h"

namespace cinepath::optimizer {
namespace {

constexpr int kChannels = 8;
using Mat8 = Eigen::Matrix<double, kChannels, kChannels>;
using Vec8 = Eigen::Matrix<double, kChannels, 1>;

struct Block {
  const ceres::CostFunction* cost;
  const StateBlock* state;  // non-null: the Jacobian comes in the sample's state (StateAccumulate)
  const ceres::LossFunction* loss;
  std::vector<double*> params;
  std::vector<int> knot;  // of each parameter block
  int rows;
  // A block without a loss whose Jacobian is a constant (ConstantJacobian): its rows and their Gram matrix
  // J^T J, taken once (Solver::TakeConstantGram), as Accumulate would take them at every evaluation.
  const ConstantJacobian* constant = nullptr;
  std::vector<double> constant_rows;  // rows x (8 x params), each row as Accumulate gathers it
  std::vector<Mat8> constant_gram;    // its knot pairs' blocks: (a, c) at a x params + c
  bool constant_any = false;          // a row that is not zero
};

// The lower band of a symmetric block matrix over knots: block (i, i - d) for d = 0..band. A part of one (a chunk's,
// Solver::Evaluate) holds the rows [first, first + n) only, and the blocks whose two knots are both among them.
class BlockBand {
 public:
  BlockBand(int n, int band, int first = 0)
      : n_(n), band_(band), first_(first), blocks_(static_cast<size_t>(n) * (band + 1), Mat8::Zero()) {}
  int size() const { return n_; }
  int band() const { return band_; }
  int first() const { return first_; }
  // Block (i, j), j in [i - band, i].
  Mat8& at(int i, int j) { return blocks_[static_cast<size_t>(i - first_) * (band_ + 1) + (i - j)]; }
  const Mat8& at(int i, int j) const { return blocks_[static_cast<size_t>(i - first_) * (band_ + 1) + (i - j)]; }
  void SetZero() {
    for (Mat8& m : blocks_) m.setZero();
  }
  // Adds a part's blocks (rows [part.first(), part.first() + part.size()) of this band).
  void Add(const BlockBand& part) {
    for (int i = part.first(); i < part.first() + part.size(); ++i) {
      for (int j = std::max(part.first(), i - band_); j <= i; ++j) at(i, j) += part.at(i, j);
    }
  }

  // y = A x (A symmetric, its lower band stored).
  void Multiply(const std::vector<Vec8>& x, std::vector<Vec8>* y) const {
    y->assign(n_, Vec8::Zero());
    for (int i = 0; i < n_; ++i) {
      (*y)[i].noalias() += at(i, i).lazyProduct(x[i]);
      for (int j = std::max(0, i - band_); j < i; ++j) {
        (*y)[i].noalias() += at(i, j).lazyProduct(x[j]);
        (*y)[j].noalias() += at(i, j).transpose().lazyProduct(x[i]);
      }
    }
  }

  // In place: the band's Cholesky factor L (A = L L^T), and the inverse of each diagonal block of L; false when
  // A is not positive definite.
  bool Factor() {
    inverse_.resize(n_);
    for (int i = 0; i < n_; ++i) {
      for (int j = std::max(0, i - band_); j <= i; ++j) {
        Mat8 s = at(i, j);
        for (int k = std::max(0, i - band_); k < j; ++k) s.noalias() -= at(i, k).lazyProduct(at(j, k).transpose());
        if (j < i) {  // L(i, j) = S L(j, j)^-T
          at(i, j) = s.lazyProduct(inverse_[j].transpose());
          continue;
        }
        if (!Cholesky(&s)) return false;
        at(i, i) = s;
        inverse_[i] = LowerInverse(s);
      }
    }
    return true;
  }

  // Solves L L^T x = b with the factor.
  void Solve(std::vector<Vec8>* b) const {
    std::vector<Vec8>& x = *b;
    for (int i = 0; i < n_; ++i) {
      for (int k = std::max(0, i - band_); k < i; ++k) x[i].noalias() -= at(i, k).lazyProduct(x[k]);
      x[i] = inverse_[i].lazyProduct(x[i]).eval();
    }
    for (int i = n_ - 1; i >= 0; --i) {
      for (int k = i + 1; k <= std::min(n_ - 1, i + band_); ++k)
        x[i].noalias() -= at(k, i).transpose().lazyProduct(x[k]);
      x[i] = inverse_[i].transpose().lazyProduct(x[i]).eval();
    }
  }

  // In place: the Cholesky factor L of a symmetric positive definite block (A = L L^T, its upper triangle zero);
  // false when a pivot is not positive. Sizes known at compile time: Eigen's LLT and triangular solve take
  // their general paths for a block this small.
  static bool Cholesky(Mat8* a) {
    Mat8& m = *a;
    for (int j = 0; j < kChannels; ++j) {
      double d = m(j, j);
      for (int k = 0; k < j; ++k) d -= m(j, k) * m(j, k);
      if (!(d > 0)) return false;
      m(j, j) = std::sqrt(d);
      for (int i = j + 1; i < kChannels; ++i) {
        double s = m(i, j);
        for (int k = 0; k < j; ++k) s -= m(i, k) * m(j, k);
        m(i, j) = s / m(j, j);
      }
    }
    for (int j = 1; j < kChannels; ++j) m.col(j).head(j).setZero();
    return true;
  }
  // The inverse of a lower triangular block with a positive diagonal, by forward substitution.
  static Mat8 LowerInverse(const Mat8& l) {
    Mat8 inverse = Mat8::Zero();
    for (int c = 0; c < kChannels; ++c) {
      inverse(c, c) = 1.0 / l(c, c);
      for (int r = c + 1; r < kChannels; ++r) {
        double s = 0;
        for (int k = c; k < r; ++k) s -= l(r, k) * inverse(k, c);
        inverse(r, c) = s / l(r, r);
      }
    }
    return inverse;
  }

 private:
  int n_, band_, first_;
  std::vector<Mat8> blocks_;
  std::vector<Mat8> inverse_;  // of L's diagonal blocks (Factor)
};

// The scratch space of one chunk's evaluation (Solver::EvaluateChunk): a block reads at most kMaxKnots knots.
constexpr int kMaxKnots = 4;
struct Workspace {
  using Column = Eigen::Matrix<double, kMaxKnots * kChannels, 1>;
  Workspace(int most_rows, int most_params)
      : residuals(most_rows),
        jacobians(static_cast<size_t>(most_rows) * std::max(kChannels * most_params, kStateFields)),
        jacobian_ptrs(most_params) {}
  std::vector<double> residuals, jacobians;
  std::vector<double*> jacobian_ptrs;
  Eigen::Matrix<double, kMaxKnots * kChannels, kMaxKnots * kChannels> gram;
  Column gradient, row;
  Mat8 values_gram;
  Vec8 values_gradient;
};

// The gradient's entries of the knots [first, first + size) (a chunk's part of J^T r), indexed by knot.
class Gradient {
 public:
  Gradient(int first, int size) : first_(first), entries_(size, Vec8::Zero()) {}
  Vec8& operator[](int knot) { return entries_[knot - first_]; }
  const Vec8& operator[](int knot) const { return entries_[knot - first_]; }
  int first() const { return first_; }
  int size() const { return static_cast<int>(entries_.size()); }
  void SetZero() { std::fill(entries_.begin(), entries_.end(), Vec8::Zero()); }

 private:
  int first_;
  std::vector<Vec8> entries_;
};

// Consecutive residual blocks [begin, end) evaluated together, on one thread, into their own sums over the knots
// [lo, hi] they read.
struct Chunk {
  Chunk(size_t begin, size_t end, int lo, int hi, int band, int most_rows, int most_params)
      : begin(begin), end(end), h(hi - lo + 1, band, lo), g(lo, hi - lo + 1), work(most_rows, most_params) {}
  size_t begin, end;
  double cost = 0;
  BlockBand h;
  Gradient g;
  Workspace work;
};

// A trial step's verdict from its cost so far (Solver::Run): rejected when rho = (cost - trial) / predicted is
// not above the least relative decrease, the same expression Run takes with the whole trial cost.
struct Rejection {
  double cost, predicted, min_relative_decrease;
  bool Rejects(double trial) const { return !(predicted > 0 && (cost - trial) / predicted > min_relative_decrease); }
};

class Solver {
 public:
  Solver(ceres::Problem* problem, double* knots, int num_knots, const std::vector<std::array<bool, 8>>& fixed,
         int max_chunks)
      : knots_(knots), n_(num_knots), fixed_(fixed) {
    std::vector<ceres::ResidualBlockId> ids;
    problem->GetResidualBlocks(&ids);  // in the order they were added: a fixed order of sums
    for (const ceres::ResidualBlockId id : ids) {
      Block b;
      b.cost = problem->GetCostFunctionForResidualBlock(id);
      b.state = dynamic_cast<const StateBlock*>(b.cost);
      b.loss = problem->GetLossFunctionForResidualBlock(id);
      problem->GetParameterBlocksForResidualBlock(id, &b.params);
      b.rows = b.cost->num_residuals();
      int lo = n_, hi = -1;
      for (double* p : b.params) {
        const std::ptrdiff_t offset = p - knots_;
        if (offset < 0 || offset >= std::ptrdiff_t(n_) * kChannels || offset % kChannels != 0)
          throw RuntimeError("banded solver: a parameter block is not one of the knots");
        const int k = static_cast<int>(offset / kChannels);
        b.knot.push_back(k);
        lo = std::min(lo, k);
        hi = std::max(hi, k);
      }
      if (b.params.size() > kMaxKnots) throw RuntimeError("banded solver: a residual block reads more than four knots");
      band_ = std::max(band_, hi - lo);
      most_rows_ = std::max(most_rows_, b.rows);
      most_params_ = std::max(most_params_, static_cast<int>(b.params.size()));
      b.constant = b.loss ? nullptr : dynamic_cast<const ConstantJacobian*>(b.cost);
      blocks_.push_back(std::move(b));
    }
    Workspace ws(most_rows_, most_params_);
    for (Block& b : blocks_) {
      if (b.constant) TakeConstantGram(&b, &ws);
    }
    MakeChunks(max_chunks);
  }

  BandedSolverSummary Run(const BandedSolverOptions& o) {
    // (Each run: a loss may have changed since the last, as a continuation stage's stiffness does.)
    nonnegative_ = std::all_of(blocks_.begin(), blocks_.end(),
                               [](const Block& b) { return !b.loss || LinearAndNonNegative(*b.loss); });
    BandedSolverSummary summary;
    summary.chunks = static_cast<int>(chunks_.size());
    BlockBand h(n_, band_), damped(n_, band_), trial_h(n_, band_);
    std::vector<Vec8> g(n_), dx(n_), hdx(n_), trial_g(n_);
    std::vector<double> saved(knots_, knots_ + n_ * kChannels);
    double cost = Evaluate(&h, &g);
    summary.initial_cost = summary.final_cost = cost;
    if (!std::isfinite(cost)) {
      summary.failed = true;
      summary.message = "the cost is not finite at the start";
      return summary;
    }
    double lambda = o.initial_damping, nu = 2;
    summary.message = "iteration cap";
    while (summary.iterations < o.max_iterations) {
      if (lambda > kMaxDamping) {  // (Ceres' smallest trust region, 1e-32)
        summary.message = "no step lowers the cost";
        break;
      }
      if (GradientNorm(g) <= o.gradient_tolerance) {
        summary.message = "gradient tolerance";
        break;
      }
      ++summary.iterations;
      if (!Step(h, g, lambda, &damped, &dx)) {
        lambda *= nu;
        nu *= 2;
        continue;
      }
      h.Multiply(dx, &hdx);
      double predicted = 0, step_norm = 0, x_norm = 0;
      for (int i = 0; i < n_; ++i) {
        predicted -= g[i].dot(dx[i]) + 0.5 * dx[i].dot(hdx[i]);
        step_norm += dx[i].squaredNorm();
      }
      for (int i = 0; i < n_ * kChannels; ++i) x_norm += knots_[i] * knots_[i];
      if (std::sqrt(step_norm) <= o.parameter_tolerance * (std::sqrt(x_norm) + o.parameter_tolerance)) {
        summary.message = "parameter tolerance";
        break;
      }
      std::copy(knots_, knots_ + n_ * kChannels, saved.begin());
      for (int i = 0; i < n_; ++i) {
        for (int c = 0; c < kChannels; ++c) knots_[i * kChannels + c] += dx[i][c];
      }
      // The step is kept when rho = (cost - trial) / predicted > min_relative_decrease. With costs that are sums
      // of non-negative terms (nonnegative_), a partial sum of the trial's cost only grows in floating point
      // too: once rho from a partial sum says no, so does the whole sum's, and the evaluation stops there (a
      // rejected trial's cost is not used). The same steps are kept. The trial takes its J^T J and J^T r as it
      // goes (most steps are kept, and each block's residuals are then computed once, not again for the
      // Jacobian), into buffers of its own: a rejected step leaves h and g as they were.
      const Rejection rejection{cost, predicted, o.min_relative_decrease};
      const double trial = Evaluate(&trial_h, &trial_g, nonnegative_ ? &rejection : nullptr);
      const double rho = (cost - trial) / predicted;
      if (trace_)
        std::fprintf(stderr, "%4d %.6e -> %s%.6e rho %.3f lambda %.2e\n", summary.iterations, cost,
                     stopped_early_ ? "(stopped at) " : "", trial, rho, lambda);
      if (!(std::isfinite(trial) && predicted > 0 && rho > o.min_relative_decrease)) {
        std::copy(saved.begin(), saved.end(), knots_);
        lambda *= nu;
        nu *= 2;
        continue;
      }
      const double decrease = (cost - trial) / std::max(cost, std::numeric_limits<double>::min());
      cost = trial;
      std::swap(h, trial_h);
      g.swap(trial_g);
      lambda *= std::max(1.0 / 3.0, 1.0 - std::pow(2 * rho - 1, 3));
      nu = 2;
      if (decrease <= o.function_tolerance) {
        summary.message = "function tolerance";
        break;
      }
    }
    summary.final_cost = cost;
    summary.final_damping = lambda;
    return summary;
  }

 private:
  static constexpr double kMaxDamping = 1e32;
  // A loss rho(s) = a s with a >= 0 (the optimizer's: scaled by a stride or a stiffness): rho(0) = 0, rho(1) >= 0,
  // no curvature at either. Then every block's cost is non-negative.
  static bool LinearAndNonNegative(const ceres::LossFunction& loss) {
    double at0[3], at1[3];
    loss.Evaluate(0.0, at0);
    loss.Evaluate(1.0, at1);
    return at0[0] == 0 && at1[0] >= 0 && at1[1] == at1[0] && at0[2] == 0 && at1[2] == 0;
  }
  // dx from (H + lambda diag(H)) dx = -g, the fixed channels held; false when the system cannot be factored.
  bool Step(const BlockBand& h, const std::vector<Vec8>& g, double lambda, BlockBand* damped,
            std::vector<Vec8>* dx) const {
    *damped = h;
    for (int i = 0; i < n_; ++i) {
      // A fixed channel does not move: its row and column out of the system, its step zero.
      for (int j = std::max(0, i - band_); j <= i; ++j) {
        Mat8& block = damped->at(i, j);
        for (int c = 0; c < kChannels; ++c) {
          if (fixed_[i][c]) block.row(c).setZero();
          if (fixed_[j][c]) block.col(c).setZero();
        }
      }
      Mat8& d = damped->at(i, i);
      for (int c = 0; c < kChannels; ++c) {
        if (fixed_[i][c]) {
          d(c, c) = 1;
          continue;
        }
        d(c, c) += lambda * std::clamp(h.at(i, i)(c, c), 1e-6, 1e32);
      }
      (*dx)[i] = -g[i];
    }
    if (!damped->Factor()) return false;
    damped->Solve(dx);
    for (int i = 0; i < n_; ++i) {
      for (int c = 0; c < kChannels; ++c) {
        if (fixed_[i][c] || !std::isfinite((*dx)[i][c])) (*dx)[i][c] = 0;
      }
    }
    return true;
  }

  double GradientNorm(const std::vector<Vec8>& g) const {
    double most = 0;
    for (int i = 0; i < n_; ++i) {
      for (int c = 0; c < kChannels; ++c) {
        if (!fixed_[i][c]) most = std::max(most, std::fabs(g[i][c]));
      }
    }
    return most;
  }

  // The cost 1/2 sum rho(|r|^2); with `h`, also the Gauss-Newton matrix J^T J and the gradient J^T r
  // (each block's rows and Jacobian scaled by sqrt(rho'), exact for losses without curvature). Not finite
  // when a block cannot be evaluated.
  // With `rejection` (no `h`), it stops as soon as the cost so far rejects the step, returning that partial sum.
  //
  // The blocks are evaluated in chunks (MakeChunks: fixed by the problem, never by the machine), each summing
  // its own blocks in their order into its own cost, band and gradient, on as many threads as TBB has; the chunks'
  // sums are then added in chunk order. So the numbers are the same on any number of threads.
  double Evaluate(BlockBand* h, std::vector<Vec8>* g, const Rejection* rejection = nullptr) {
    stopped_early_ = rejection && rejection->Rejects(0);
    if (stopped_early_) return 0;
    std::atomic<bool> rejected{false};
    const auto run = [&](size_t c) { EvaluateChunk(&chunks_[c], h != nullptr, rejection, &rejected); };
    if (chunks_.size() == 1) {
      run(0);
    } else {
      tbb::parallel_for(
          tbb::blocked_range<size_t>(0, chunks_.size(), 1),
          [&](const tbb::blocked_range<size_t>& r) {
            for (size_t c = r.begin(); c != r.end(); ++c) run(c);
          },
          tbb::simple_partitioner());
    }
    double cost = 0;
    for (const Chunk& chunk : chunks_) cost += chunk.cost;
    stopped_early_ = rejected.load();
    if (!h || stopped_early_ || !std::isfinite(cost)) return cost;
    h->SetZero();
    g->assign(n_, Vec8::Zero());
    for (const Chunk& chunk : chunks_) {
      h->Add(chunk.h);
      for (int i = chunk.g.first(); i < chunk.g.first() + chunk.g.size(); ++i) (*g)[i] += chunk.g[i];
    }
    return cost;
  }

  // One chunk's blocks: their cost into chunk->cost, and with `jacobian` their J^T J and J^T r into its band and
  // gradient. With `rejection`, it stops once its own cost rejects the step (the whole cost, a sum of it and other
  // non-negative costs, is not less in floating point either), or once another chunk has.
  void EvaluateChunk(Chunk* chunk, bool jacobian_wanted, const Rejection* rejection, std::atomic<bool>* rejected) {
    Workspace& ws = chunk->work;
    chunk->cost = 0;
    if (jacobian_wanted) {
      chunk->h.SetZero();
      chunk->g.SetZero();
    }
    double& cost = chunk->cost;
    for (size_t k = chunk->begin; k < chunk->end; ++k) {
      const Block& b = blocks_[k];
      const int np = static_cast<int>(b.params.size());
      for (int j = 0; j < np; ++j)
        ws.jacobian_ptrs[j] = ws.jacobians.data() + static_cast<size_t>(j) * b.rows * kChannels;
      const bool jacobian = jacobian_wanted && !b.constant;
      const bool ok = b.state ? b.state->EvaluateStateBlock(b.params.data(), ws.residuals.data(),
                                                            jacobian ? ws.jacobians.data() : nullptr)
                              : b.cost->Evaluate(b.params.data(), ws.residuals.data(),
                                                 jacobian ? ws.jacobian_ptrs.data() : nullptr);
      if (!ok) {
        cost = std::numeric_limits<double>::quiet_NaN();
        return;
      }
      double squared = 0;
      for (int i = 0; i < b.rows; ++i) squared += ws.residuals[i] * ws.residuals[i];
      double rho[3] = {squared, 1, 0};
      if (b.loss) b.loss->Evaluate(squared, rho);
      cost += 0.5 * rho[0];
      if (!std::isfinite(cost)) return;
      if (rejection) {
        if (rejection->Rejects(cost)) {
          rejected->store(true);
          return;
        }
        if (rejected->load(std::memory_order_relaxed)) return;
      }
      if (!jacobian_wanted || rho[1] <= 0) continue;
      if (b.state) {
        StateAccumulate(b, rho[1], &ws, &chunk->h, &chunk->g);
      } else if (b.constant) {
        ConstantAccumulate(b, &ws, &chunk->h, &chunk->g);
      } else {
        Accumulate(b, rho[1], &ws, &chunk->h, &chunk->g);
      }
    }
  }

  // The chunks of MakeChunks: consecutive blocks of about equal work, at most max_chunks; a small problem
  // (under 2 kLeastChunkWork) is one chunk, a larger one a multiple of four chunks, so that they share two or
  // four threads evenly (three chunks on two threads take as long as four: the draft's soft stages took
  // ~25 % longer to evaluate).
  void MakeChunks(int max_chunks) {
    const auto work = [](const Block& b) { return b.constant ? 2.0 : b.state ? 4.0 * b.rows + 8 : b.rows + 4.0; };
    double total = 0;
    for (const Block& b : blocks_) total += work(b);
    double whole = std::floor(total / kLeastChunkWork);
    if (whole >= 2) whole = 4 * std::ceil(whole / 4);
    const int count = static_cast<int>(std::clamp(whole, 1.0, double(std::max(1, max_chunks))));
    double done = 0;
    size_t begin = 0;
    for (int c = 0; c < count; ++c) {
      size_t end = begin;
      const double until = total * (c + 1) / count;
      while (end < blocks_.size() && (c == count - 1 || done + work(blocks_[end]) / 2 <= until))
        done += work(blocks_[end++]);
      if (end == begin) continue;
      int lo = n_, hi = -1;
      for (size_t k = begin; k < end; ++k) {
        for (const int knot : blocks_[k].knot) {
          lo = std::min(lo, knot);
          hi = std::max(hi, knot);
        }
      }
      if (hi < lo) lo = hi = 0;
      chunks_.emplace_back(begin, end, lo, hi, band_, most_rows_, most_params_);
      begin = end;
    }
    if (chunks_.empty()) chunks_.emplace_back(0, 0, 0, 0, band_, most_rows_, most_params_);
  }

  // A block whose Jacobian came in its sample's state (ws->jacobians: rows x kStateFields). Most rows read the
  // eight channel values only (the goals, keep-out, clearance): their Gram matrix in those, 8 x 8, goes to
  // the knot pair (a, c) times value_a value_c, the spline's weights. A row that reads rates (a limit's active
  // hinge, one to three fields) goes to the knots on its own, over the few channels it reads.
  static void StateAccumulate(const Block& b, double weight, Workspace* ws, BlockBand* h, Gradient* g) {
    const KnotWeights& w = b.state->knot_weights();
    const int first = b.knot[0];
    ws->values_gram.setZero();
    ws->values_gradient.setZero();
    bool values = false;
    for (int i = 0; i < b.rows; ++i) {
      const double* d = ws->jacobians.data() + i * kStateFields;
      bool reads_rates, reads_values;
      reads_rates = (Eigen::Map<const Eigen::Array<double, kStateFields - kChannels, 1>>(d + kChannels) != 0).any();
      reads_values = (Eigen::Map<const Eigen::Array<double, kChannels, 1>>(d) != 0).any();
      if (reads_rates) {
        AddRateRow(w, first, d, weight, ws->residuals[i], h, g);
        continue;
      }
      if (!reads_values) continue;
      const Eigen::Map<const Vec8> v(d);
      ws->values_gram.noalias() += (weight * v) * v.transpose();
      ws->values_gradient.noalias() += (weight * ws->residuals[i]) * v;
      values = true;
    }
    if (!values) return;
    for (int a = 0; a < 4; ++a) {
      (*g)[first + a].noalias() += w.value[a] * ws->values_gradient;
      for (int c = 0; c <= a; ++c) h->at(first + a, first + c).noalias() += (w.value[a] * w.value[c]) * ws->values_gram;
    }
  }

  // One row in the state's fields d into the knots: its Jacobian in knot a, channel ch, is the sum over the
  // fields of ch of the spline's weight of that field's derivative order in knot a times d (StateRowsToKnots).
  static void AddRateRow(const KnotWeights& w, int first, const double* d, double weight, double residual, BlockBand* h,
                         Gradient* g) {
    int channels[kChannels], m = 0;
    double u[4][kChannels];
    for (int c = 0; c < kChannels; ++c) {
      const double value = d[c], rate = d[kChannels + c];
      const double accel = c < 3 ? d[2 * kChannels + c] : 0.0, jerk = c < 3 ? d[2 * kChannels + 3 + c] : 0.0;
      if (value == 0 && rate == 0 && accel == 0 && jerk == 0) continue;
      for (int a = 0; a < 4; ++a) u[a][m] = w.value[a] * value + w.d1[a] * rate + w.d2[a] * accel + w.d3[a] * jerk;
      channels[m++] = c;
    }
    for (int a = 0; a < 4; ++a) {
      Vec8& ga = (*g)[first + a];
      for (int p = 0; p < m; ++p) ga[channels[p]] += weight * residual * u[a][p];
      for (int c = 0; c <= a; ++c) {
        Mat8& block = h->at(first + a, first + c);
        for (int q = 0; q < m; ++q) {
          const double wq = weight * u[c][q];
          for (int p = 0; p < m; ++p) block(channels[p], channels[q]) += wq * u[a][p];
        }
      }
    }
  }

  // Adds the block's rows (times weight = rho') to J^T J and J^T r: first into the block's own dense Gram
  // matrix over its knots' channels, a rank-one update per row over the columns that row reads, then into
  // the band. A row whose Jacobian is zero (a hinge of
  // a limit that holds: most rows of a plan) costs nothing.
  static void Accumulate(const Block& b, double weight, Workspace* ws, BlockBand* h, Gradient* g) {
    const int np = static_cast<int>(b.params.size());
    const int n = np * kChannels;
    ws->gram.topLeftCorner(n, n).setZero();
    ws->gradient.head(n).setZero();
    bool any = false;
    for (int i = 0; i < b.rows; ++i) {
      if (!GatherRow(ws->jacobian_ptrs.data(), np, i, &ws->row)) continue;
      any = true;
      ws->gradient.head(n) += (weight * ws->residuals[i]) * ws->row.head(n);
      for (int q = 0; q < n; ++q) {
        if (ws->row[q] == 0) continue;
        ws->gram.col(q).segment(q, n - q) += (weight * ws->row[q]) * ws->row.segment(q, n - q);
      }
    }
    if (!any) return;
    for (int q = 0; q < n; ++q) {  // the lower triangle mirrored
      for (int p = q + 1; p < n; ++p) ws->gram(q, p) = ws->gram(p, q);
    }
    Scatter(b, *ws, h, g);
  }

  // Row i of the block's Jacobians into row; false when it is zero.
  static bool GatherRow(const double* const* jacobians, int np, int i, Workspace::Column* row) {
    bool zero = true;
    for (int j = 0; j < np; ++j) {
      for (int c = 0; c < kChannels; ++c) {
        const double v = jacobians[j][i * kChannels + c];
        (*row)[j * kChannels + c] = v;
        zero = zero && v == 0;
      }
    }
    return !zero;
  }

  // The block's gradient and its Gram matrix (over its knots' channels: the workspace's, or a constant block's)
  // into the band.
  static void Scatter(const Block& b, const Workspace& ws, BlockBand* h, Gradient* g) {
    const int np = static_cast<int>(b.params.size());
    for (int a = 0; a < np; ++a) {
      (*g)[b.knot[a]] += ws.gradient.segment<kChannels>(a * kChannels);
      for (int c = 0; c < np; ++c) {
        if (b.knot[c] > b.knot[a]) continue;
        if (b.constant) {
          h->at(b.knot[a], b.knot[c]) += b.constant_gram[a * np + c];
        } else {
          h->at(b.knot[a], b.knot[c]) += ws.gram.block<kChannels, kChannels>(a * kChannels, c * kChannels);
        }
      }
    }
  }

  // A constant block's rows and Gram matrix, once: Accumulate's at weight 1 (a block without a loss), so the
  // same numbers as Accumulate at every evaluation.
  static void TakeConstantGram(Block* b, Workspace* ws) {
    const int np = static_cast<int>(b->params.size());
    const int n = np * kChannels;
    std::vector<const double*> jacobians(np);
    for (int j = 0; j < np; ++j) jacobians[j] = b->constant->constant_jacobian(j);
    b->constant_rows.assign(static_cast<size_t>(b->rows) * n, 0.0);
    ws->gram.topLeftCorner(n, n).setZero();
    for (int i = 0; i < b->rows; ++i) {
      if (!GatherRow(jacobians.data(), np, i, &ws->row)) continue;
      b->constant_any = true;
      std::copy(ws->row.data(), ws->row.data() + n, b->constant_rows.data() + static_cast<size_t>(i) * n);
      for (int q = 0; q < n; ++q) {
        if (ws->row[q] == 0) continue;
        ws->gram.col(q).segment(q, n - q) += (1.0 * ws->row[q]) * ws->row.segment(q, n - q);
      }
    }
    for (int q = 0; q < n; ++q) {
      for (int p = q + 1; p < n; ++p) ws->gram(q, p) = ws->gram(p, q);
    }
    for (int a = 0; a < np; ++a) {
      for (int c = 0; c < np; ++c)
        b->constant_gram.push_back(ws->gram.block<kChannels, kChannels>(a * kChannels, c * kChannels));
    }
  }

  // A constant block (weight 1): its gradient from its rows, its Gram matrix as taken once.
  static void ConstantAccumulate(const Block& b, Workspace* ws, BlockBand* h, Gradient* g) {
    if (!b.constant_any) return;
    const int n = static_cast<int>(b.params.size()) * kChannels;
    ws->gradient.head(n).setZero();
    for (int i = 0; i < b.rows; ++i) {
      const double* row = b.constant_rows.data() + static_cast<size_t>(i) * n;
      if (std::all_of(row, row + n, [](double v) { return v == 0; })) continue;
      const double scale = 1.0 * ws->residuals[i];
      for (int q = 0; q < n; ++q) ws->gradient[q] += scale * row[q];
    }
    Scatter(b, *ws, h, g);
  }

  static constexpr double kLeastChunkWork = 4000;  // MakeChunks' work units: about 100 sample blocks

  bool trace_ = std::getenv("CINEPATH_CERES_TRACE") != nullptr;  // each step on stderr
  double* knots_;
  int n_;
  const std::vector<std::array<bool, 8>>& fixed_;
  std::vector<Block> blocks_;
  std::vector<Chunk> chunks_;
  int band_ = 0, most_rows_ = 0, most_params_ = 0;
  bool nonnegative_ = true;     // every block's cost >= 0: no loss, or LinearAndNonNegative
  bool stopped_early_ = false;  // the last Evaluate, by its rejection
};

}  // namespace

BandedSolverSummary SolveBanded(ceres::Problem* problem, double* knots, int num_knots,
                                const std::vector<std::array<bool, 8>>& fixed, const BandedSolverOptions& options) {
  Solver solver(problem, knots, num_knots, fixed, options.max_chunks);
  return solver.Run(options);
}

struct BandedSolver::Impl {
  Impl(ceres::Problem* problem, double* knots, int num_knots, std::vector<std::array<bool, 8>> fixed_channels,
       int max_chunks)
      : problem(problem),
        knots(knots),
        fixed(std::move(fixed_channels)),
        solver(problem, knots, num_knots, fixed, max_chunks) {}
  const ceres::Problem* problem;
  const double* knots;
  const std::vector<std::array<bool, 8>> fixed;  // before the solver, which holds a reference to it
  Solver solver;
};

BandedSolver::BandedSolver(ceres::Problem* problem, double* knots, int num_knots,
                           std::vector<std::array<bool, 8>> fixed, int max_chunks)
    : impl_(std::make_unique<Impl>(problem, knots, num_knots, std::move(fixed), max_chunks)) {}

BandedSolver::~BandedSolver() = default;

BandedSolverSummary BandedSolver::Solve(const BandedSolverOptions& options) { return impl_->solver.Run(options); }

bool BandedSolver::SetUpFor(const ceres::Problem* problem, const double* knots,
                            const std::vector<std::array<bool, 8>>& fixed) const {
  return impl_->problem == problem && impl_->knots == knots && impl_->fixed == fixed;
}

}  // namespace cinepath::optimizer
