// `cinepath mesh --for-plan` against uniform decimation to the same worst projected error: faces kept
// and time. Prints one JSON document (figures for bench/RESULTS.md).
//
//   mesh_for_plan_bench --glb scene.glb --plan plan.json [--max-error-px P] [--tiles N] [--samples S]
//                       [--face-freeze-rounds R]   (0: freeze whole tiles at once, as before 2026-11-26)
//                       [--simplifier qem_tiled|meshoptimizer]   (the simplifier of both runs)
//   mesh_for_plan_bench --synthetic [--cells N] [--no-building] ...  # an orbit around a building on terrain
//   mesh_for_plan_bench --box ...    # the unit test's box on a plane
//
// For-plan: DecimateForPlan (mesh_decimate_for_plan.h), its measurement rounds included in the time.
// Uniform: the same simplifier (qem_tiled: DecimateQemTiled with the same goal at every vertex;
// meshoptimizer: DecimateMesh, kMeshoptimizerPartitioned) with one error goal for the whole mesh, the smallest allowed
// error of any seen region (the error the finest-seen region needs), halved until its worst projected error — measured
// with the same points and the same cameras (ProjectedErrorProbe) — is within the bound, as the pipeline tightens
// --max-error-m, then bisected 4 times between the last goal over and the first within. Its time counts every attempt
// and measurement; the time of the attempt kept alone is printed too.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>

#include <tbb/global_control.h>
#include <Eigen/Geometry>

#include "core/json.h"
#include "core/plan_file.h"
#include "photogrammetry/mesh/mesh_decimate.h"
#include "photogrammetry/mesh/mesh_decimate_for_plan.h"
#include "scene/glb_reader.h"

namespace {

using namespace cinepath;
using namespace cinepath::photogrammetry;

constexpr double kPi = 3.14159265358979323846;

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

void AddGrid(TriangleMesh& mesh, int cols, int rows, const std::function<Eigen::Vector3d(double, double)>& at) {
  const uint32_t base = static_cast<uint32_t>(mesh.num_vertices());
  for (int j = 0; j <= rows; ++j) {
    for (int i = 0; i <= cols; ++i) mesh.vertices_m.push_back(at(double(i) / cols, double(j) / rows));
  }
  auto id = [&](int i, int j) { return base + static_cast<uint32_t>(j * (cols + 1) + i); };
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < cols; ++i) {
      mesh.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      mesh.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
}

// Rolling terrain (800 m square, `cells`² cells, sum of sines with 3 cm ripples) and a 20 m building
// with ribbed walls (5 cm) and a pitched roof at the centre; an orbit of 600 frames, radius 60 m,
// 40 m up, 35 mm on Super 35 UHD, looking at the building.
void Synthetic(int cells, bool building, TriangleMesh* mesh, Trajectory* plan) {
  auto height = [](double e, double n) {
    return 2.0 * std::sin(e / 37) * std::cos(n / 53) + 0.7 * std::sin((e + n) / 11) +
           0.03 * std::sin(e * 1.3) * std::sin(n * 1.7);
  };
  AddGrid(*mesh, cells, cells, [&](double u, double v) {
    const double e = -400 + 800 * u, n = -400 + 800 * v;
    return Eigen::Vector3d(e, n, height(e, n));
  });
  const double half = 10, top = 20;
  for (int side = 0; side < (building ? 4 : 0); ++side) {
    const Eigen::Vector2d normal(std::cos(side * kPi / 2), std::sin(side * kPi / 2));
    const Eigen::Vector2d along(-normal.y(), normal.x());
    AddGrid(*mesh, 200, 230, [&](double u, double v) {
      const double a = (u - 0.5) * 2 * half, b = -3 + v * (top + 3);
      const Eigen::Vector2d xy = normal * (half + 0.05 * std::sin(2 * kPi * a)) + along * a;
      return Eigen::Vector3d(xy.x(), xy.y(), b);
    });
  }
  if (building)
    AddGrid(*mesh, 200, 200, [&](double u, double v) {
      const double e = (u - 0.5) * 2 * half, n = (v - 0.5) * 2 * half;
      return Eigen::Vector3d(e, n, top + 3 * (1 - std::abs(n) / half));
    });
  plan->camera.sensor_width_mm = 24.89;
  plan->camera.width_px = 3840;
  plan->camera.height_px = 2160;
  const Eigen::Vector3d target(0, 0, 10);
  const int frames = 600;
  for (int k = 0; k < frames; ++k) {
    const double a = 2 * kPi * k / frames;
    TrajectorySample s;
    s.time_s = k / 30.0;
    s.position_enu_m = Eigen::Vector3d(60 * std::cos(a), 60 * std::sin(a), 40);
    const Eigen::Vector3d z = (target - s.position_enu_m).normalized();
    const Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitZ()).normalized();
    Eigen::Matrix3d r;
    r.col(0) = x;
    r.col(1) = z.cross(x);
    r.col(2) = z;
    s.world_from_camera = Eigen::Quaterniond(r);
    s.focal_length_mm = 35;
    plan->samples.push_back(s);
  }
}

// The scene of tests/photogrammetry/mesh/mesh_decimate_for_plan_test.cc: a 300 m plane (1 m cells, 0.2 m
// swells 60 m long) and a 10 m box with 5 cm bumps (0.2 m cells); 120 frames orbiting it, radius 30 m,
// 25 m up, 24 mm.
void BoxScene(TriangleMesh* mesh, Trajectory* plan) {
  AddGrid(*mesh, 300, 300, [](double u, double v) {
    const double e = -150 + 300 * u, n = -150 + 300 * v;
    return Eigen::Vector3d(e, n, 0.2 * std::sin(2 * kPi * e / 60) * std::cos(2 * kPi * n / 60));
  });
  auto bump = [](double a, double b) { return 0.05 * std::sin(2 * kPi * a) * std::sin(2 * kPi * b); };
  for (int side = 0; side < 4; ++side) {
    const Eigen::Vector2d normal(std::cos(side * kPi / 2), std::sin(side * kPi / 2));
    const Eigen::Vector2d along(-normal.y(), normal.x());
    AddGrid(*mesh, 50, 55, [&](double u, double v) {
      const double a = (u - 0.5) * 10, b = v * 11;
      const Eigen::Vector2d xy = normal * (5 + bump(a, b)) + along * a;
      return Eigen::Vector3d(xy.x(), xy.y(), -1 + b);
    });
  }
  AddGrid(*mesh, 50, 50, [&](double u, double v) {
    const double e = (u - 0.5) * 10, n = (v - 0.5) * 10;
    return Eigen::Vector3d(e, n, 10 + bump(e, n));
  });
  plan->camera.sensor_width_mm = 24.89;
  plan->camera.width_px = 3840;
  plan->camera.height_px = 2160;
  const Eigen::Vector3d target(0, 0, 5);
  for (int k = 0; k < 120; ++k) {
    const double a = 2 * kPi * k / 120;
    TrajectorySample s;
    s.time_s = k / 30.0;
    s.position_enu_m = Eigen::Vector3d(30 * std::cos(a), 30 * std::sin(a), 25);
    const Eigen::Vector3d z = (target - s.position_enu_m).normalized();
    const Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitZ()).normalized();
    Eigen::Matrix3d r;
    r.col(0) = x;
    r.col(1) = z.cross(x);
    r.col(2) = z;
    s.world_from_camera = Eigen::Quaterniond(r);
    s.focal_length_mm = 24;
    plan->samples.push_back(s);
  }
}

struct BenchArgs {
  std::string glb, plan_path;
  bool synthetic = false, building = true, box = false;
  int cells = 1000, tiles = 16, threads = 0, face_freeze_rounds = ForPlanOptions{}.face_freeze_rounds;
  double max_error_px = 0.5;
  int64_t samples = 200000;
  ForPlanSimplifier simplifier = ForPlanOptions{}.simplifier;
};

// The command line; false (after a message) on a bad one.
bool ParseArgs(int argc, char** argv, BenchArgs* a) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
    if (arg == "--glb")
      a->glb = next();
    else if (arg == "--plan")
      a->plan_path = next();
    else if (arg == "--synthetic")
      a->synthetic = true;
    else if (arg == "--box")
      a->box = true;
    else if (arg == "--no-building")
      a->building = false;
    else if (arg == "--cells")
      a->cells = std::stoi(next());
    else if (arg == "--tiles")
      a->tiles = std::stoi(next());
    else if (arg == "--samples")
      a->samples = std::stoll(next());
    else if (arg == "--max-error-px")
      a->max_error_px = std::stod(next());
    else if (arg == "--threads")
      a->threads = std::stoi(next());
    else if (arg == "--face-freeze-rounds")
      a->face_freeze_rounds = std::stoi(next());
    else if (arg == "--simplifier") {
      const std::string name = next();
      if (name == ForPlanSimplifierName(ForPlanSimplifier::kQemTiled)) {
        a->simplifier = ForPlanSimplifier::kQemTiled;
      } else if (name == ForPlanSimplifierName(ForPlanSimplifier::kMeshoptimizer)) {
        a->simplifier = ForPlanSimplifier::kMeshoptimizer;
      } else {
        std::fprintf(stderr, "--simplifier: qem_tiled or meshoptimizer\n");
        return false;
      }
    } else {
      std::fprintf(stderr,
                   "usage: mesh_for_plan_bench (--glb scene.glb --plan plan.json | --synthetic [--cells N]) "
                   "[--max-error-px P] [--tiles N] [--samples S] [--threads T] [--face-freeze-rounds R] "
                   "[--simplifier qem_tiled|meshoptimizer]\n");
      return false;
    }
  }
  return true;
}

// The mesh and plan the arguments name, and a label for the report; false (after a message) when
// neither a scene nor a synthetic case is given.
bool LoadCase(const BenchArgs& a, TriangleMesh* mesh, Trajectory* plan, std::string* label) {
  if (a.box) {
    BoxScene(mesh, plan);
    *label = "box on a plane (the unit test's scene), 120-frame orbit";
  } else if (a.synthetic) {
    Synthetic(a.cells, a.building, mesh, plan);
    *label = "synthetic orbit, " + std::to_string(a.cells) + "^2 terrain cells" + (a.building ? " + building" : "");
  } else {
    if (a.glb.empty() || a.plan_path.empty()) {
      std::fprintf(stderr, "give --glb and --plan, or --synthetic\n");
      return false;
    }
    const scene::SceneMesh scene = scene::ReadGlbFile(a.glb);
    mesh->vertices_m = scene.positions_enu_m;
    mesh->faces = scene.faces;
    *plan = ReadPlanFile(a.plan_path);
    *label = a.glb + " + " + a.plan_path;
  }
  return true;
}

struct UniformResult {
  TriangleMesh mesh;
  double goal_error_m = 0, worst_px = 0, time_s = 0, last_attempt_s = 0;
  int attempts = 0;
};

// Uniform, to the same worst projected error, measured on the same points: the same simplifier with
// one error goal for the whole mesh. Halve the goal until the bound holds, then bisect (geometrically,
// 4 steps) between the last goal over it and the first within, keeping the largest goal within.
UniformResult UniformToSameBound(const TriangleMesh& mesh, const ForPlanOptions& options, const BenchArgs& a,
                                 double start_goal_m) {
  const auto start = std::chrono::steady_clock::now();
  const ProjectedErrorProbe probe(mesh, options.cameras, a.samples, options.seed);
  DecimateOptions uniform;
  uniform.method = DecimationMethod::kMeshoptimizerPartitioned;
  UniformResult r;
  r.goal_error_m = start_goal_m;
  auto attempt = [&](double goal_m, TriangleMesh* out, double* px) {
    const auto attempt_start = std::chrono::steady_clock::now();
    DecimateOptions o = uniform;
    o.max_error_m = goal_m;
    if (a.simplifier == ForPlanSimplifier::kQemTiled) {
      const std::vector<double> goal(mesh.num_vertices(), goal_m);
      *out = internal::DecimateQemTiled(mesh, 0, o.qem.tiles, o.qem, &goal);
    } else {
      *out = DecimateMesh(mesh, o);
    }
    *px = probe.WorstPx(*out);
    ++r.attempts;
    return Seconds(attempt_start);
  };
  double over_m = 0;
  for (int k = 0; k < 12; ++k) {
    r.last_attempt_s = attempt(r.goal_error_m, &r.mesh, &r.worst_px);
    if (r.worst_px <= a.max_error_px) break;
    over_m = r.goal_error_m;
    r.goal_error_m *= 0.5;
  }
  if (r.worst_px <= a.max_error_px && over_m > 0) {
    for (int k = 0; k < 4; ++k) {
      const double goal_m = std::sqrt(r.goal_error_m * over_m);
      TriangleMesh candidate;
      double px = 0;
      const double s = attempt(goal_m, &candidate, &px);
      if (px <= a.max_error_px) {
        r.goal_error_m = goal_m;
        r.mesh = std::move(candidate);
        r.worst_px = px;
        r.last_attempt_s = s;
      } else {
        over_m = goal_m;
      }
    }
  }
  r.time_s = Seconds(start);
  return r;
}

Json ResultJson(const BenchArgs& a, const std::string& label, const TriangleMesh& mesh, const Trajectory& plan,
                const ForPlanReport& report, double for_plan_s, const UniformResult& uniform) {
  Json out = Json::object();
  out["case"] = label;
  out["threads"] = a.threads > 0 ? Json(a.threads) : Json("all");
  out["faces_in"] = static_cast<int64_t>(mesh.num_faces());
  out["frames"] = static_cast<int64_t>(plan.samples.size());
  out["max_error_px"] = a.max_error_px;
  out["simplifier"] = ForPlanSimplifierName(a.simplifier);
  out["tiles_per_side"] = a.tiles;
  out["points_measured"] = report.points_measured;
  out["points_seen"] = report.points_seen;
  out["for_plan"] = {{"faces_out", report.faces_out},
                     {"worst_projected_px", RoundToDecimals(report.worst_projected_px, 4)},
                     {"rounds", report.rounds},
                     {"time_s", RoundToDecimals(for_plan_s, 3)},
                     {"min_allowed_error_m", RoundToDecimals(report.min_allowed_error_m, 6)},
                     {"max_allowed_error_m", RoundToDecimals(report.max_allowed_error_m, 6)},
                     {"tiles_seen", report.tiles_seen},
                     {"tiles_unseen", report.tiles_unseen},
                     {"tiles_frozen", report.tiles_frozen},
                     {"faces_frozen", report.faces_frozen},
                     {"freeze_rounds", report.freeze_rounds},
                     {"bound_met", report.bound_met}};
  out["uniform"] = {{"faces_out", static_cast<int64_t>(uniform.mesh.num_faces())},
                    {"bound_met", uniform.worst_px <= a.max_error_px},
                    {"worst_projected_px", RoundToDecimals(uniform.worst_px, 4)},
                    {"goal_error_m", RoundToDecimals(uniform.goal_error_m, 6)},
                    {"attempts", uniform.attempts},
                    {"time_s", RoundToDecimals(uniform.time_s, 3)},
                    {"last_attempt_time_s", RoundToDecimals(uniform.last_attempt_s, 3)}};
  out["faces_ratio_for_plan_over_uniform"] =
      RoundToDecimals(static_cast<double>(report.faces_out) / std::max<size_t>(1, uniform.mesh.num_faces()), 4);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  BenchArgs a;
  if (!ParseArgs(argc, argv, &a)) return 2;
  std::unique_ptr<tbb::global_control> limit;
  if (a.threads > 0) {
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, a.threads);
  }
  TriangleMesh mesh;
  Trajectory plan;
  std::string label;
  if (!LoadCase(a, &mesh, &plan, &label)) return 2;

  ForPlanOptions options;
  options.cameras = CamerasFromPlan(plan, a.plan_path.empty() ? "synthetic" : a.plan_path);
  options.max_error_px = a.max_error_px;
  options.tiles_per_side = a.tiles;
  options.measure_samples = a.samples;
  options.face_freeze_rounds = a.face_freeze_rounds;
  options.simplifier = a.simplifier;

  const auto start = std::chrono::steady_clock::now();
  ForPlanReport report;
  const TriangleMesh for_plan = DecimateForPlan(mesh, options, &report);
  const double for_plan_s = Seconds(start);
  const UniformResult uniform = UniformToSameBound(mesh, options, a, report.min_allowed_error_m);
  (void)for_plan;
  std::printf("%s\n", DumpJson(ResultJson(a, label, mesh, plan, report, for_plan_s, uniform)).c_str());
  return 0;
}
