// The peer for `cinepath optimize`: the same problem solved by Ipopt, the interior-point solver CineMPC
// uses, as a constrained NLP (OptimizeOptions::constrained_solver): over the same variables (a preset's
// knots, the same fixed channels) and from the same start (the plan as given), the objective is 1/2 |r|^2
// of the goal terms, the hard limits are inequality constraints g(x) <= 0 on their signed margins (the
// arguments of the product's hinges, at the values it aims at) with their exact sparse Jacobian, and the
// Hessian of the Lagrangian is the goals' Gauss-Newton J^T J (the constraints' curvature is left out).
// Ipopt runs to its own convergence (tol 1e-6, at most 3000 iterations) or to a CPU cap per solve
// (--ipopt-cpu-s, 150 s by default), whichever comes first. Both results go through the
// product's guard and feasibility check; both are measured the same way: the goal cost of the output plan
// (optimizer::PlanTermCosts) and the worst violation of a hard limit, per unit of the limit.
//   optimize_vs_ipopt [--faces N] [--quality draft|standard|final|all] [--mesh none|terrain|both]
//                     [--ipopt-cpu-s S]
// Built only when Debian's coinor-libipopt-dev is installed (bench/CMakeLists.txt).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include <ceres/crs_matrix.h>
#include <ceres/problem.h>
#include <glog/logging.h>
#include <IpIpoptApplication.hpp>
#include <IpSolveStatistics.hpp>
#include <IpTNLP.hpp>

#include "bench/optimize_bench_scene.h"
#include "optimizer/optimizer.h"
#include "optimizer/sample_model.h"

namespace {

using namespace cinepath;
using Ipopt::Index;
using Ipopt::Number;

// One evaluation of a Ceres problem over the free coordinates.
struct Evaluation {
  double cost = 0;
  std::vector<double> residuals, gradient;
  ceres::CRSMatrix jacobian;
};

// The constrained problem as Ipopt's TNLP. x: the free coordinates of every variable block, in block
// order and ascending channel order (Ceres' tangent space under a SubsetManifold, so Ceres' gradient and
// Jacobian columns line up with x). Constraint i: the i-th residual of the limits problem, <= 0.
class ConstrainedNlp : public Ipopt::TNLP {
 public:
  ConstrainedNlp(const optimizer::ConstrainedProblem& problem, std::string* status)
      : problem_(problem), status_(status) {
    for (size_t b = 0; b < problem.blocks.size(); ++b) {
      for (int c = 0; c < optimizer::kNumChannels; ++c) {
        const auto& f = problem.fixed_channels[b];
        if (std::find(f.begin(), f.end(), c) == f.end()) free_.push_back({b, c});
      }
    }
    options_.parameter_blocks = problem.blocks;
    options_.num_threads = 1;
    Evaluation goals, limits;
    Evaluate(problem_.goals, &goals, false, false, true);
    Evaluate(problem_.limits, &limits, true, false, true);
    limit_structure_ = limits.jacobian;
    m_ = limits.jacobian.num_rows;
    BuildHessianStructure(goals.jacobian);
  }

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag, IndexStyleEnum& style) override {
    n = static_cast<Index>(free_.size());
    m = m_;
    nnz_jac_g = static_cast<Index>(limit_structure_.values.size());
    nnz_h_lag = static_cast<Index>(h_row_.size());
    style = C_STYLE;
    return true;
  }
  bool get_bounds_info(Index n, Number* x_l, Number* x_u, Index m, Number* g_l, Number* g_u) override {
    std::fill(x_l, x_l + n, -2e19);
    std::fill(x_u, x_u + n, 2e19);
    std::fill(g_l, g_l + m, -2e19);
    std::fill(g_u, g_u + m, 0.0);
    return true;
  }
  bool get_starting_point(Index n, bool, Number* x, bool, Number*, Number*, Index, bool, Number*) override {
    for (Index i = 0; i < n; ++i) x[i] = problem_.blocks[free_[i].first][free_[i].second];
    return true;
  }
  // A step into non-finite values (a focal length of e^1000) is an evaluation error: Ipopt cuts it back.
  bool eval_f(Index n, const Number* x, bool, Number& obj) override {
    Evaluation e;
    if (!Evaluate(problem_.goals, &e, false, false, false, n, x)) return false;
    obj = e.cost;
    return true;
  }
  bool eval_grad_f(Index n, const Number* x, bool, Number* grad_f) override {
    Evaluation e;
    if (!Evaluate(problem_.goals, &e, false, true, false, n, x)) return false;
    std::copy(e.gradient.begin(), e.gradient.end(), grad_f);
    return true;
  }
  bool eval_g(Index n, const Number* x, bool, Index m, Number* g) override {
    Evaluation e;
    if (!Evaluate(problem_.limits, &e, true, false, false, n, x) || static_cast<Index>(e.residuals.size()) != m)
      return false;
    std::copy(e.residuals.begin(), e.residuals.end(), g);
    return true;
  }
  bool eval_jac_g(Index n, const Number* x, bool, Index, Index nele_jac, Index* i_row, Index* j_col,
                  Number* values) override {
    if (!values) {
      for (int r = 0; r < limit_structure_.num_rows; ++r) {
        for (int k = limit_structure_.rows[r]; k < limit_structure_.rows[r + 1]; ++k) {
          i_row[k] = r;
          j_col[k] = limit_structure_.cols[k];
        }
      }
      return true;
    }
    Evaluation e;
    if (!Evaluate(problem_.limits, &e, false, false, true, n, x)) return false;
    if (e.jacobian.cols != limit_structure_.cols || static_cast<Index>(e.jacobian.values.size()) != nele_jac)
      return false;
    std::copy(e.jacobian.values.begin(), e.jacobian.values.end(), values);
    return true;
  }
  bool eval_h(Index n, const Number* x, bool, Number obj_factor, Index, const Number*, bool, Index, Index* i_row,
              Index* j_col, Number* values) override;
  void finalize_solution(Ipopt::SolverReturn status, Index n, const Number* x, const Number*, const Number*, Index,
                         const Number*, const Number*, Number, const Ipopt::IpoptData*,
                         Ipopt::IpoptCalculatedQuantities*) override {
    Set(n, x);
    *status_ = status == Ipopt::SUCCESS                    ? "converged"
               : status == Ipopt::STOP_AT_ACCEPTABLE_POINT ? "acceptable"
               : status == Ipopt::MAXITER_EXCEEDED         ? "iteration cap"
               : status == Ipopt::CPUTIME_EXCEEDED         ? "CPU cap"
               : status == Ipopt::LOCAL_INFEASIBILITY      ? "infeasible"
                                                           : "failed (" + std::to_string(int(status)) + ")";
  }

 private:
  void Set(Index n, const Number* x) {
    for (Index i = 0; i < n; ++i) problem_.blocks[free_[i].first][free_[i].second] = x[i];
  }
  bool Evaluate(ceres::Problem* problem, Evaluation* e, bool residuals, bool gradient, bool jacobian, Index n = 0,
                const Number* x = nullptr) {
    if (x) Set(n, x);
    if (!problem->Evaluate(options_, &e->cost, residuals ? &e->residuals : nullptr, gradient ? &e->gradient : nullptr,
                           jacobian ? &e->jacobian : nullptr) ||
        !std::isfinite(e->cost))
      return false;
    for (double v : e->residuals) {
      if (!std::isfinite(v)) return false;
    }
    return !gradient || static_cast<Index>(e->gradient.size()) == static_cast<Index>(free_.size());
  }
  void BuildHessianStructure(const ceres::CRSMatrix& j);

  optimizer::ConstrainedProblem problem_;
  std::string* status_;
  std::vector<std::pair<size_t, int>> free_;
  ceres::Problem::EvaluateOptions options_;
  ceres::CRSMatrix limit_structure_;
  Index m_ = 0;
  // The lower triangle of J^T J: its entries, and for each pair of nonzeros of each row of J (in the
  // order eval_h walks them) the entry it adds to.
  std::vector<Index> h_row_, h_col_;
  std::vector<int> pair_entry_;
};

void ConstrainedNlp::BuildHessianStructure(const ceres::CRSMatrix& j) {
  const size_t n = free_.size();
  std::vector<int> entry(n * n, -1);
  for (int r = 0; r < j.num_rows; ++r) {
    for (int a = j.rows[r]; a < j.rows[r + 1]; ++a) {
      for (int b = j.rows[r]; b <= a; ++b) {
        const int hi = std::max(j.cols[a], j.cols[b]), lo = std::min(j.cols[a], j.cols[b]);
        int& e = entry[size_t(hi) * n + lo];
        if (e < 0) {
          e = static_cast<int>(h_row_.size());
          h_row_.push_back(hi);
          h_col_.push_back(lo);
        }
        pair_entry_.push_back(e);
      }
    }
  }
}

bool ConstrainedNlp::eval_h(Index n, const Number* x, bool, Number obj_factor, Index, const Number*, bool,
                            Index nele_hess, Index* i_row, Index* j_col, Number* values) {
  if (!values) {
    std::copy(h_row_.begin(), h_row_.end(), i_row);
    std::copy(h_col_.begin(), h_col_.end(), j_col);
    return true;
  }
  Evaluation e;
  if (!Evaluate(problem_.goals, &e, false, false, true, n, x)) return false;
  std::fill(values, values + nele_hess, 0.0);
  size_t p = 0;
  const ceres::CRSMatrix& j = e.jacobian;
  for (int r = 0; r < j.num_rows; ++r) {
    for (int a = j.rows[r]; a < j.rows[r + 1]; ++a) {
      for (int b = j.rows[r]; b <= a; ++b) values[pair_entry_[p++]] += obj_factor * j.values[a] * j.values[b];
    }
  }
  return p == pair_entry_.size();
}

int SolveWithIpopt(const optimizer::ConstrainedProblem& problem, double cpu_s, std::string* status) {
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  app->Options()->SetStringValue("hessian_approximation", "exact");
  app->Options()->SetIntegerValue("max_iter", 3000);
  app->Options()->SetNumericValue("tol", 1e-6);
  app->Options()->SetNumericValue("max_cpu_time", cpu_s);
  // The monotone barrier update (Ipopt's default) crawled here: 37 iterations in a minute, objective still
  // at the start's; the adaptive one reached the goal costs' scale in 200.
  app->Options()->SetStringValue("mu_strategy", "adaptive");
  app->Options()->SetIntegerValue("print_level", std::getenv("CINEPATH_IPOPT_TRACE") ? 5 : 0);
  app->Options()->SetStringValue("sb", "yes");
  if (app->Initialize() != Ipopt::Solve_Succeeded) return 0;
  Ipopt::SmartPtr<ConstrainedNlp> nlp = new ConstrainedNlp(problem, status);
  app->OptimizeTNLP(Ipopt::SmartPtr<Ipopt::TNLP>(nlp));
  const Ipopt::SmartPtr<Ipopt::SolveStatistics> stats = app->Statistics();
  return Ipopt::IsValid(stats) ? stats->IterationCount() : 0;
}

// The worst violation of a hard limit in a result's report, per unit of the limit: the feasibility
// check's limits, the clearance margin and the deviation allowed. Its name in `name`.
double WorstViolation(const Json& report, double max_deviation_m, std::string* name) {
  double worst = 0;
  *name = "none";
  const auto consider = [&](double fraction, const std::string& limit) {
    if (fraction > worst) {
      worst = fraction;
      *name = limit;
    }
  };
  for (const auto& [limit, entry] : report["limits"].items()) {
    if (entry["after"].is_null()) continue;
    const double value = entry["limit"].get<double>();
    consider(std::fabs(entry["after"].get<double>() - value) / std::max(std::fabs(value), 1e-9), limit);
  }
  if (report.contains("clearance") && !report["clearance"]["min_after_m"].is_null()) {
    const double margin = report["clearance"]["margin_m"].get<double>();
    consider((margin - report["clearance"]["min_after_m"].get<double>()) / margin, "mesh_clearance");
  }
  consider((report["max_deviation_m"].get<double>() - max_deviation_m) / max_deviation_m, "max_deviation");
  return worst;
}

// One run and its row of the table.
void RunAndPrint(const optimizer::OptimizeInput& in, Quality quality, bool ipopt, double ipopt_cpu_s) {
  const optimizer::OptimizeOptions preset = optimizer::OptimizeOptions::ForQuality(quality);
  optimizer::OptimizeOptions options = preset;
  std::string status = "—";
  if (ipopt) {
    // One stage over the preset's knots from the plan as given (no ladder: Ipopt runs to convergence).
    options = optimizer::OptimizeOptions::ForQuality(Quality::kDraft);
    options.knot_spacing_s = preset.knot_spacing_s;
    options.visibility_rounds = preset.visibility_rounds;
    options.constrained_solver = [&status, ipopt_cpu_s](const optimizer::ConstrainedProblem& p) {
      return SolveWithIpopt(p, ipopt_cpu_s, &status);
    };
  }
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpu_start = std::clock();
  const optimizer::OptimizeResult r = optimizer::OptimizePlan(in, options);
  const double cpu_s = double(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const Json terms = optimizer::PlanTermCosts(in, r.plan, preset);
  double goal = 0;
  for (const char* t : {"framing", "depth_of_field", "background_blur"}) {
    if (terms.contains(t)) goal += terms[t].get<double>();
  }
  std::string worst_name;
  const double worst = WorstViolation(r.report, preset.max_deviation_m, &worst_name);
  const std::string solver = ipopt ? "Ipopt 3.11.9, knots of " : "cinepath ";
  std::printf("| %s | %s%s | %.2f | %.2f | %d | %s | %.6g | %.3g (%s) | %s | %.3g |\n", in.mesh ? "1 M faces" : "none",
              solver.c_str(), QualityName(quality), wall_s, cpu_s, r.report["solver"]["iterations"].get<int>(),
              status.c_str(), goal, worst, worst_name.c_str(), r.report["feasible_after"].get<bool>() ? "yes" : "no",
              r.report["guard"]["alpha"].get<double>());
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  FLAGS_minloglevel = 2;  // Ceres reports every rejected trial point at warning level
  google::InitGoogleLogging(argv[0]);
  size_t faces = 1'000'000;
  std::string quality = "all", mesh = "both";
  double ipopt_cpu_s = 150;  // per Ipopt solve
  for (int i = 1; i + 1 < argc; ++i) {
    if (!std::strcmp(argv[i], "--faces")) faces = std::stoul(argv[i + 1]);
    if (!std::strcmp(argv[i], "--quality")) quality = argv[i + 1];
    if (!std::strcmp(argv[i], "--mesh")) mesh = argv[i + 1];
    if (!std::strcmp(argv[i], "--ipopt-cpu-s")) ipopt_cpu_s = std::stod(argv[i + 1]);
  }
  const Trajectory plan = bench::SixtySecondShot();
  const scene::SceneMesh terrain = bench::Terrain(mesh == "none" ? 2 : faces);
  std::printf("plan: %zu samples; terrain %zu faces\n\n", plan.samples.size(), terrain.num_faces());
  std::printf(
      "| mesh | solver | wall (s) | CPU (s) | iterations | Ipopt status | goal cost | worst violation (limit) | "
      "feasible | guard alpha |\n|---|---|---|---|---|---|---|---|---|---|\n");
  std::vector<Quality> qualities = {Quality::kDraft, Quality::kStandard, Quality::kFinal};
  if (quality != "all") qualities = {ParseQuality(quality)};
  for (const bool with_mesh : {false, true}) {
    if ((with_mesh && mesh == "none") || (!with_mesh && mesh == "terrain")) continue;
    optimizer::OptimizeInput in;
    in.plan = plan;
    in.plan_source = "bench_plan.json";
    in.mesh = with_mesh ? &terrain : nullptr;
    in.scene_source = "terrain";
    for (const Quality q : qualities) {
      for (const bool ipopt : {false, true}) RunAndPrint(in, q, ipopt, ipopt_cpu_s);
    }
  }
  return 0;
}
