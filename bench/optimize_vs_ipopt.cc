// The peer for `cinepath optimize`: the same problem (every cost term, weight and continuation stage,
// the same variables and fixed channels, the same start) solved by Ipopt, the interior-point solver
// CineMPC uses, in place of Ceres' Levenberg-Marquardt (OptimizeOptions::external_solver). Ipopt sees
// the objective 1/2 |r|^2 and its gradient J^T r, evaluated by Ceres, with a limited-memory quasi-Newton
// Hessian (the problem has no explicit constraints: the limits are penalties in both). Prints time and
// final cost of each on the 60 s shot, without a mesh and against the 1 M-face terrain.
//   optimize_vs_ipopt [--faces N] [--quality draft|standard|final]
// Built only when Debian's coinor-libipopt-dev is installed (bench/CMakeLists.txt).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

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

// The free coordinates of every block, in block order and ascending channel order: the order of Ceres'
// tangent space under a SubsetManifold, so Ceres' gradient lines up with Ipopt's x.
class CeresObjective : public Ipopt::TNLP {
 public:
  CeresObjective(ceres::Problem* problem, const std::vector<double*>& blocks,
                 const std::vector<std::vector<int>>& fixed)
      : problem_(problem), blocks_(blocks) {
    for (size_t b = 0; b < blocks.size(); ++b) {
      for (int c = 0; c < optimizer::kNumChannels; ++c) {
        bool is_fixed = false;
        for (int f : fixed[b]) is_fixed = is_fixed || f == c;
        if (!is_fixed) free_.push_back({b, c});
      }
    }
    options_.parameter_blocks = blocks_;
    options_.num_threads = 1;
  }

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag, IndexStyleEnum& style) override {
    n = static_cast<Index>(free_.size());
    m = 0;
    nnz_jac_g = 0;
    nnz_h_lag = 0;
    style = C_STYLE;
    return true;
  }
  bool get_bounds_info(Index n, Number* x_l, Number* x_u, Index, Number*, Number*) override {
    for (Index i = 0; i < n; ++i) {
      x_l[i] = -2e19;
      x_u[i] = 2e19;
    }
    return true;
  }
  bool get_starting_point(Index n, bool, Number* x, bool, Number*, Number*, Index, bool, Number*) override {
    for (Index i = 0; i < n; ++i) x[i] = blocks_[free_[i].first][free_[i].second];
    return true;
  }
  bool eval_f(Index n, const Number* x, bool, Number& obj) override {
    Set(n, x);
    double cost = 0;
    // A step into non-finite values (a focal length of e^1000) is an evaluation error: Ipopt cuts it back.
    if (!problem_->Evaluate(options_, &cost, nullptr, nullptr, nullptr) || !std::isfinite(cost)) return false;
    obj = cost;
    return true;
  }
  bool eval_grad_f(Index n, const Number* x, bool, Number* grad_f) override {
    Set(n, x);
    double cost = 0;
    std::vector<double> gradient;
    if (!problem_->Evaluate(options_, &cost, nullptr, &gradient, nullptr)) return false;
    if (static_cast<Index>(gradient.size()) != n) return false;
    for (Index i = 0; i < n; ++i) grad_f[i] = gradient[i];
    return true;
  }
  bool eval_g(Index, const Number*, bool, Index, Number*) override { return true; }
  bool eval_jac_g(Index, const Number*, bool, Index, Index, Index*, Index*, Number*) override { return true; }
  void finalize_solution(Ipopt::SolverReturn, Index n, const Number* x, const Number*, const Number*, Index,
                         const Number*, const Number*, Number, const Ipopt::IpoptData*,
                         Ipopt::IpoptCalculatedQuantities*) override {
    Set(n, x);
  }

 private:
  void Set(Index n, const Number* x) {
    for (Index i = 0; i < n; ++i) blocks_[free_[i].first][free_[i].second] = x[i];
  }
  ceres::Problem* problem_;
  std::vector<double*> blocks_;
  std::vector<std::pair<size_t, int>> free_;
  ceres::Problem::EvaluateOptions options_;
};

int SolveWithIpopt(ceres::Problem* problem, const std::vector<double*>& blocks,
                   const std::vector<std::vector<int>>& fixed, int max_iterations) {
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  app->Options()->SetStringValue("hessian_approximation", "limited-memory");
  app->Options()->SetIntegerValue("max_iter", max_iterations);
  app->Options()->SetNumericValue("tol", 1e-8);
  app->Options()->SetIntegerValue("print_level", 0);
  app->Options()->SetStringValue("sb", "yes");
  if (app->Initialize() != Ipopt::Solve_Succeeded) return 0;
  Ipopt::SmartPtr<CeresObjective> nlp = new CeresObjective(problem, blocks, fixed);
  app->OptimizeTNLP(Ipopt::SmartPtr<Ipopt::TNLP>(nlp));
  const Ipopt::SmartPtr<Ipopt::SolveStatistics> stats = app->Statistics();
  return Ipopt::IsValid(stats) ? stats->IterationCount() : 0;
}

}  // namespace

int main(int argc, char** argv) {
  FLAGS_minloglevel = 2;  // Ceres reports every rejected trial point at warning level
  google::InitGoogleLogging(argv[0]);
  size_t faces = 1'000'000;
  std::string quality = "draft";
  for (int i = 1; i + 1 < argc; ++i) {
    if (!std::strcmp(argv[i], "--faces")) faces = std::stoul(argv[i + 1]);
    if (!std::strcmp(argv[i], "--quality")) quality = argv[i + 1];
  }
  const Trajectory plan = bench::SixtySecondShot();
  const scene::SceneMesh terrain = bench::Terrain(faces);
  std::printf("plan: %zu samples; terrain %zu faces; quality %s\n\n", plan.samples.size(), terrain.num_faces(),
              quality.c_str());
  std::printf(
      "| mesh | solver | wall (s) | iterations | cost before | cost after | feasible after |\n"
      "|---|---|---|---|---|---|---|\n");
  for (const bool with_mesh : {false, true}) {
    for (const bool ipopt : {false, true}) {
      optimizer::OptimizeOptions options = optimizer::OptimizeOptions::ForQuality(ParseQuality(quality));
      const int max_iterations = options.max_iterations;
      if (ipopt) {
        options.external_solver = [max_iterations](ceres::Problem* p, const std::vector<double*>& b,
                                                   const std::vector<std::vector<int>>& f) {
          return SolveWithIpopt(p, b, f, max_iterations);
        };
      }
      optimizer::OptimizeInput in;
      in.plan = plan;
      in.plan_source = "bench_plan.json";
      in.mesh = with_mesh ? &terrain : nullptr;
      in.scene_source = "terrain";
      const auto start = std::chrono::steady_clock::now();
      const auto r = optimizer::OptimizePlan(in, options);
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::printf("| %s | %s | %.3f | %d | %.4g | %.4g | %s |\n", with_mesh ? "1 M faces" : "none",
                  ipopt ? "Ipopt 3.11 (L-BFGS)" : "Ceres LM (cinepath)", s, r.report["solver"]["iterations"].get<int>(),
                  r.report["total"]["before"].get<double>(), r.report["total"]["after"].get<double>(),
                  r.report["feasible_after"].get<bool>() ? "yes" : "no");
    }
  }
  return 0;
}
