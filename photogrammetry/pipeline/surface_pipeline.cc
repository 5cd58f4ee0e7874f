#include "photogrammetry/pipeline/surface_pipeline.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>

#include <tbb/parallel_invoke.h>

#include "core/error.h"
#include "core/fatal_signal.h"
#include "photogrammetry/gltf/gltf_writer.h"
#include "photogrammetry/mesh/mesh_clean.h"
#include "photogrammetry/mesh/mesh_colors.h"
#include "photogrammetry/mesh/mesh_decimate.h"
#include "photogrammetry/mesh/mesh_distance.h"
#include "photogrammetry/mesh/mesh_remesh.h"
#include "photogrammetry/pipeline/step_report.h"
#include "photogrammetry/surface/surface_height_field.h"
#include "photogrammetry/surface/surface_orient.h"
#include "photogrammetry/surface/surface_points.h"
#include "photogrammetry/surface/surface_poisson.h"

namespace cinepath::photogrammetry {
namespace {

// The --quality presets (docs/mesh.md; figures in bench/RESULTS.md): a speed/accuracy ladder. Every
// preset simplifies with qem_tiled, quadric collapse with optimal placement in parallel tiles, the most
// accurate simplifier measured on the bench terrain at 10 %, 40 % and 80 % of its faces: at 80 % of the
// 2.5 M-face one, final's share there, its true error is proven below 0.027 m where that of CGAL's
// Garland–Heckbert (final's simplifier until 2026-11-30) is at least 0.040 m, at 9–13× CGAL's speed.
// The presets differ in the budget and in the Hausdorff samples (20 k / 200 k / 1 M). Every preset also
// measures every vertex of both meshes.
struct QualityDefaults {
  int64_t face_budget;            // default decimation target
  DecimationMethod method;        // simplifier
  int64_t hausdorff_samples;      // face samples per mesh, for the reported error
  int64_t height_field_points;    // grid thinning above this many points
  double poisson_spacing_factor;  // > 1: coarser, faster Poisson
};

QualityDefaults DefaultsFor(Quality quality) {
  switch (quality) {
    case Quality::kDraft: return {200000, DecimationMethod::kQemTiled, 20000, 250000, 2.0};
    case Quality::kStandard: return {1000000, DecimationMethod::kQemTiled, 200000, 1000000, 1.0};
    case Quality::kFinal: return {2000000, DecimationMethod::kQemTiled, 1000000, 4000000, 1.0};
  }
  return {1000000, DecimationMethod::kQemTiled, 200000, 1000000, 1.0};
}

Json BoundsJson(const TriangleMesh& mesh) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (const auto& v : mesh.vertices_m) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  Json j;
  j["bbox_min_m"] = Json::array({RoundToDecimals(lo.x(), 4), RoundToDecimals(lo.y(), 4), RoundToDecimals(lo.z(), 4)});
  j["bbox_max_m"] = Json::array({RoundToDecimals(hi.x(), 4), RoundToDecimals(hi.y(), 4), RoundToDecimals(hi.z(), 4)});
  return j;
}

// The error of a simplified mesh against the cleaned one (approximate symmetric Hausdorff, face and vertex
// samples): the cleaned mesh's AABB tree is built once, for every measurement against it.
class ErrorMeter {
 public:
  explicit ErrorMeter(int64_t samples_per_mesh) {
    hausdorff_.samples_per_mesh = samples_per_mesh;
    hausdorff_.sample_vertices = true;
    hausdorff_.seed = 1;
  }
  // The mesh every candidate is measured against: set once, before the first measurement.
  void SetCleaned(TriangleMesh cleaned) { cleaned_ = std::move(cleaned); }
  bool has_cleaned() const { return cleaned_.num_faces() > 0; }
  const TriangleMesh& cleaned() const { return cleaned_; }

  // The symmetric distance; the two directed ones and the sampling's resolution go into `step`.
  double Measure(const TriangleMesh& candidate, Json& step) {
    std::unique_ptr<MeshDistanceIndex> candidate_index;
    if (!input_index_) {  // the first measurement builds both trees at once
      tbb::parallel_invoke([&] { input_index_ = std::make_unique<MeshDistanceIndex>(cleaned_, "input"); },
                           [&] { candidate_index = std::make_unique<MeshDistanceIndex>(candidate, "output"); });
    } else {
      candidate_index = std::make_unique<MeshDistanceIndex>(candidate, "output");
    }
    const HausdorffDistance d = ApproximateHausdorff(*input_index_, *candidate_index, hausdorff_);
    step["hausdorff_in_to_out_m"] = d.a_to_b_m;
    step["hausdorff_out_to_in_m"] = d.b_to_a_m;
    step["hausdorff_points_measured"] = d.samples_a + d.samples_b;
    // A distance reached at sampled points: at most the true distance. The mean spacing of the
    // face samples on the input says how coarse the search was (docs/mesh.md, "The error figure";
    // bench/RESULTS.md measures the gap to a proven upper bound at each preset's sample count).
    step["hausdorff_is_lower_bound"] = true;
    step["hausdorff_sample_spacing_m"] =
        RoundToDecimals(std::sqrt(input_index_->AreaM2() / std::max<double>(1.0, hausdorff_.samples_per_mesh)), 4);
    return d.symmetric_m;
  }

  void RecordSampling(Json& step) const {
    step["hausdorff_samples"] = hausdorff_.samples_per_mesh;  // face samples per mesh
    step["hausdorff_vertex_samples"] = hausdorff_.sample_vertices;
    step["hausdorff_seed"] = hausdorff_.seed;
  }

 private:
  TriangleMesh cleaned_;
  std::unique_ptr<MeshDistanceIndex> input_index_;
  HausdorffOptions hausdorff_;
};

// A simplification and its measured error ("measured": ErrorMeter::Measure's fields, empty when the
// mesh was kept as it was).
struct Simplified {
  TriangleMesh mesh;
  double hausdorff_m = 0;
  Json measured = Json::object();
};

// Measures `simplified` against `mesh` when it has fewer faces (and some), `mesh` then becoming the meter's.
Simplified MeasureIfSimplified(TriangleMesh& mesh, TriangleMesh simplified, ErrorMeter& meter) {
  Simplified out;
  if (simplified.num_faces() < mesh.num_faces() && simplified.num_faces() > 0) {
    meter.SetCleaned(std::move(mesh));
    out.hausdorff_m = meter.Measure(simplified, out.measured);
  }
  out.mesh = std::move(simplified);
  return out;
}

// --for-plan: detail where the cameras look, each tile to the error its closest camera cannot see.
Simplified DecimateToPlan(TriangleMesh& mesh, const ForPlanOptions& for_plan, ErrorMeter& meter, Json& step) {
  step["goal"] = "for_plan";
  step["method"] = std::string(ForPlanSimplifierName(for_plan.simplifier)) + "_for_plan";
  ForPlanReport plan_report;
  TriangleMesh simplified = DecimateForPlan(mesh, for_plan, &plan_report);
  Simplified out = MeasureIfSimplified(mesh, std::move(simplified), meter);
  step["for_plan"] = plan_report.ToJson();
  return out;
}

// --max-error-m: the simplifier's own estimate is not a Hausdorff distance, so tighten it until the
// measured symmetric Hausdorff distance is within the bound (at most 8 halvings; the undecimated mesh
// always meets it). Every attempt is measured against the same input tree.
Simplified DecimateToError(TriangleMesh& mesh, double max_error_m, DecimateOptions decimate, ErrorMeter& meter,
                           Json& step) {
  step["goal"] = "max_error_m";
  step["max_error_m"] = max_error_m;
  // CGAL and OpenMesh take face budgets only: qem_tiled, which meets a measured bound with the
  // fewest faces on the bench terrain (bench/RESULTS.md, "Error goals").
  if (decimate.method != DecimationMethod::kMeshoptimizer &&
      decimate.method != DecimationMethod::kMeshoptimizerPartitioned &&
      decimate.method != DecimationMethod::kQemTiled) {
    decimate.method = DecimationMethod::kQemTiled;
    step["method"] = DecimationMethodName(decimate.method);
  }
  decimate.max_error_m = max_error_m;
  meter.SetCleaned(std::move(mesh));
  const TriangleMesh& cleaned = meter.cleaned();
  Simplified out;
  out.mesh = cleaned;
  DecimateStats stats;
  int attempts = 0;
  for (; attempts < 8; ++attempts) {
    TriangleMesh candidate = DecimateMesh(cleaned, decimate, &stats);
    Json attempt;
    const double d = candidate.num_faces() < cleaned.num_faces() && candidate.num_faces() > 0
                         ? meter.Measure(candidate, attempt)
                         : 0.0;
    if (candidate.num_faces() > 0 && d <= max_error_m) {
      out.mesh = std::move(candidate);
      out.hausdorff_m = d;
      out.measured = std::move(attempt);
      break;
    }
    decimate.max_error_m *= 0.5;
  }
  step["attempts"] = attempts + 1;
  return out;
}

// A face budget: --target-faces, else the quality preset's.
Simplified DecimateToBudget(TriangleMesh& mesh, const std::optional<int64_t>& target_faces, int64_t preset_budget,
                            DecimateOptions decimate, ErrorMeter& meter, Json& step) {
  decimate.target_faces = target_faces ? *target_faces : preset_budget;
  step["goal"] = target_faces ? "target_faces" : "quality_preset";
  step["target_faces"] = decimate.target_faces;
  DecimateStats stats;
  TriangleMesh simplified = DecimateMesh(mesh, decimate, &stats);
  return MeasureIfSimplified(mesh, std::move(simplified), meter);
}

void CleanStep(TriangleMesh& mesh, const SurfacePipelineOptions& options, Json& steps) {
  const StepTimer timer;
  MeshCleanReport clean_report;
  mesh = CleanMesh(mesh, MeshCleanOptions{}, &clean_report);
  Json step;
  step["step"] = "clean";
  step.update(clean_report.ToJson());
  AddStepTime(step, timer, options.report_times);
  steps.push_back(std::move(step));
  if (mesh.num_faces() == 0) {
    throw InfeasibleError("mesh: no surface is left after cleaning (see the report's steps)");
  }
}

// Simplification toward the goal (a plan, an error bound or a face budget); returns the measured error.
double DecimateStep(TriangleMesh& mesh, const SurfacePipelineOptions& options, const QualityDefaults& defaults,
                    ErrorMeter& meter, Json& steps) {
  const StepTimer timer;
  DecimateOptions decimate;
  // The simplifier of the preset (bench/mesh_decimate_bench.cc, figures in bench/RESULTS.md).
  decimate.method = options.decimation_method ? *options.decimation_method : defaults.method;
  Json step;
  step["step"] = "decimate";
  step["method"] = DecimationMethodName(decimate.method);
  step["faces_in"] = static_cast<int64_t>(mesh.num_faces());
  Simplified simplified =
      options.for_plan      ? DecimateToPlan(mesh, *options.for_plan, meter, step)
      : options.max_error_m ? DecimateToError(mesh, *options.max_error_m, decimate, meter, step)
                            : DecimateToBudget(mesh, options.target_faces, defaults.face_budget, decimate, meter, step);
  if (simplified.mesh.num_faces() == 0) {
    throw InfeasibleError("mesh: decimation left no face");
  }
  step["faces_out"] = static_cast<int64_t>(simplified.mesh.num_faces());
  step["vertices_out"] = static_cast<int64_t>(simplified.mesh.num_vertices());
  step["hausdorff_m"] = simplified.hausdorff_m;
  meter.RecordSampling(step);
  step.update(simplified.measured);
  AddStepTime(step, timer, options.report_times);
  steps.push_back(std::move(step));
  mesh = std::move(simplified.mesh);
  return simplified.hausdorff_m;
}

// --remesh-edge-m: isotropic remeshing; returns the remeshed mesh's error against the cleaned input.
double RemeshStep(TriangleMesh& mesh, double target_edge_m, ErrorMeter& meter, const SurfacePipelineOptions& options,
                  Json& steps) {
  const StepTimer timer;
  Json step;
  step["step"] = "remesh";
  step["target_edge_m"] = target_edge_m;
  step["faces_in"] = static_cast<int64_t>(mesh.num_faces());
  RemeshOptions remesh;
  remesh.target_edge_m = target_edge_m;
  RemeshReport remesh_report;
  TriangleMesh remeshed = RemeshIsotropic(mesh, remesh, &remesh_report);
  if (remeshed.num_faces() == 0) throw InfeasibleError("mesh: remeshing left no face");
  step.update(remesh_report.ToJson());
  // The error of the final mesh against the cleaned input (before decimation).
  if (!meter.has_cleaned()) meter.SetCleaned(mesh);
  Json measured = Json::object();
  const double hausdorff_m = meter.Measure(remeshed, measured);
  step["hausdorff_m"] = hausdorff_m;
  meter.RecordSampling(step);
  step.update(measured);
  AddStepTime(step, timer, options.report_times);
  steps.push_back(std::move(step));
  mesh = std::move(remeshed);
  return hausdorff_m;
}

// Vertex colours: the surface's own, else the nearest points'.
void ColorStep(TriangleMesh& mesh, const PointCloud* color_source, const SurfacePipelineOptions& options, Json& steps) {
  const StepTimer timer;
  Json step;
  step["step"] = "colors";
  if (mesh.has_colors()) {
    step["source"] = "surface";
  } else if (color_source && color_source->has_colors() && color_source->size() > 0) {
    ColorVerticesFromPoints(mesh, *color_source);
    step["source"] = "nearest_points";
  } else {
    step["source"] = "none";
  }
  AddStepTime(step, timer, options.report_times);
  steps.push_back(std::move(step));
}

Json OutputJson(const TriangleMesh& mesh, double hausdorff_m) {
  Json output;
  output["vertices"] = static_cast<int64_t>(mesh.num_vertices());
  output["faces"] = static_cast<int64_t>(mesh.num_faces());
  output["hausdorff_m"] = hausdorff_m;
  output.update(BoundsJson(mesh));
  return output;
}

// Clean → decimate → (remesh) → colours → GLB, shared by both entry points.
SurfacePipelineResult FinishSurface(TriangleMesh mesh, const PointCloud* color_source,
                                    const SurfacePipelineOptions& options, Json report) {
  const QualityDefaults defaults = DefaultsFor(options.quality);
  Json& steps = report["steps"];
  CleanStep(mesh, options, steps);
  ErrorMeter meter(defaults.hausdorff_samples);
  double hausdorff_m = DecimateStep(mesh, options, defaults, meter, steps);
  if (options.remesh_edge_m) hausdorff_m = RemeshStep(mesh, *options.remesh_edge_m, meter, options, steps);
  ColorStep(mesh, color_source, options, steps);
  SurfacePipelineResult result;
  if (options.write_glb) result.glb = WriteGlbStep(mesh, nullptr, options, &report);
  report["output"] = OutputJson(mesh, hausdorff_m);
  result.report = std::move(report);
  result.mesh = std::move(mesh);
  return result;
}

Json StartReport(const SurfacePipelineOptions& options, const char* input) {
  Json report;
  report["quality"] = QualityName(options.quality);
  report["input"] = input;
  report["steps"] = Json::array();
  return report;
}

}  // namespace

SurfaceMethod ParseSurfaceMethod(const std::string& text, const std::string& where) {
  if (text == "auto") return SurfaceMethod::kAuto;
  if (text == "height-field") return SurfaceMethod::kHeightField;
  if (text == "poisson") return SurfaceMethod::kPoisson;
  throw InputError(Located(where, "must be auto, height-field or poisson, not '" + text + "'"));
}

const char* SurfaceMethodName(SurfaceMethod method) {
  switch (method) {
    case SurfaceMethod::kAuto: return "auto";
    case SurfaceMethod::kHeightField: return "height-field";
    case SurfaceMethod::kPoisson: return "poisson";
  }
  return "?";
}

void SurfacePipelineOptions::Check() const {
  if (target_faces && max_error_m) {
    throw InputError("target_faces and max_error_m: give at most one of them");
  }
  if (for_plan && (target_faces || max_error_m)) {
    throw InputError("for_plan: give a plan or a simplification goal (target_faces, max_error_m), not both");
  }
  if (for_plan) for_plan->Check();
  if (target_faces && *target_faces <= 0) throw InputError("target_faces: must be > 0");
  if (max_error_m && !(*max_error_m > 0 && std::isfinite(*max_error_m))) {
    throw InputError("max_error_m: must be a finite number > 0");
  }
  if (remesh_edge_m && !(*remesh_edge_m > 0 && std::isfinite(*remesh_edge_m))) {
    throw InputError("remesh_edge_m: must be a finite number > 0");
  }
  if (!gltf_extras.is_null() && !gltf_extras.is_object()) {
    throw InputError("gltf extras: must be a JSON object");
  }
}

std::string WriteGlbStep(const TriangleMesh& mesh, const GlbTexture* texture, const SurfacePipelineOptions& options,
                         Json* report) {
  const StepTimer timer;
  GlbWriteOptions glb;
  glb.draco = options.draco;
  glb.extras = options.gltf_extras;
  std::string bytes = WriteGlb(mesh, texture, glb);
  Json step;
  step["step"] = "glb";
  step["draco"] = options.draco;
  step["bytes"] = static_cast<int64_t>(bytes.size());
  AddStepTime(step, timer, options.report_times);
  if (texture) step["texture"] = true;
  (*report)["steps"].push_back(std::move(step));
  return bytes;
}

namespace {

// Poisson is guarded before it is called: a cloud that spans no volume would crash CGAL's solver. Chosen by
// `auto`, the height field takes over and `step` says why; asked for by name, it is refused.
SurfaceMethod GuardPoisson(SurfaceMethod method, SurfaceMethod requested, const PointCloud& points, Json* step) {
  if (method != SurfaceMethod::kPoisson) return method;
  const auto problem = PoissonInputProblem(points);
  if (!problem) return method;
  if (requested == SurfaceMethod::kPoisson) {
    throw InputError("mesh: --surface poisson cannot mesh these points: " + *problem +
                     " (CGAL's Poisson solver needs points that span a volume); use --surface height-field");
  }
  (*step)["fallback_from"] = "poisson";
  (*step)["fallback_reason"] = *problem;
  return SurfaceMethod::kHeightField;
}

// The 2.5D height field of the points at the preset's density; its report goes into `step`.
TriangleMesh HeightFieldStep(const PointCloud& points, const QualityDefaults& defaults, Json* step) {
  HeightFieldOptions height_field;
  height_field.max_points = defaults.height_field_points;
  HeightFieldReport surface_report;
  const CurrentStep running("surface: height field (CGAL)");
  TriangleMesh mesh = HeightFieldSurface(points, height_field, &surface_report);
  (*step)["step"] = "height_field";
  step->update(surface_report.ToJson());
  return mesh;
}

// CGAL's Poisson reconstruction on the guarded points (PoissonInputProblem, MergeCoincidentPoints), and
// where CGAL still fails (its surface mesher meets a point twice on a nearly flat nadir cloud; the solver
// does not converge) once more at twice the spacing, a coarser surface. Nothing when both fail: `step`
// then holds the cause (fallback_reason) and the caller falls back or refuses. `options` ends as run.
std::optional<TriangleMesh> PoissonOrCoarser(const PointCloud& points, PoissonOptions* options, PoissonReport* report,
                                             Json* step) {
  const CurrentStep running("surface: Poisson reconstruction (CGAL)");
  std::string first_failure;
  for (int attempt = 0; attempt < 2; ++attempt) {
    try {
      TriangleMesh mesh = PoissonSurface(points, *options, report);
      if (attempt > 0) {
        step->erase("fallback_reason");
        (*step)["coarser_after_failure"] = first_failure;
        (*step)["spacing_factor"] = options->spacing_factor;
      }
      return mesh;
    } catch (const RuntimeError& e) {
      if (attempt == 0) first_failure = e.what();
      (*step)["fallback_reason"] =
          attempt == 0 ? first_failure : first_failure + "; at twice the spacing too: " + std::string(e.what());
      options->spacing_factor *= 2;
    }
  }
  options->spacing_factor /= 4;
  return std::nullopt;
}

// The "orient" step: each piece turned to face the cameras that saw its points (surface_orient.h).
Json OrientStep(TriangleMesh* mesh, const PointCloud& points, const SurfacePipelineOptions& options) {
  StepTimer timer;
  Json step;
  step["step"] = "orient";
  step.update(OrientTowardCameras(mesh, points).ToJson());
  AddStepTime(step, timer, options.report_times);
  return step;
}

}  // namespace

namespace {

// The "filter_points" step (surface_points.h); InputError when too few points are left for a surface.
PointCloud FilterStep(const PointCloud& points, const SurfacePipelineOptions& options, Json& steps) {
  const StepTimer timer;
  PointFilterReport filter_report;
  PointCloud filtered = FilterPoints(points, options.point_filter, &filter_report);
  Json step;
  step["step"] = "filter_points";
  step.update(filter_report.ToJson());
  AddStepTime(step, timer, options.report_times);
  steps.push_back(std::move(step));
  if (filtered.size() < 3) {
    throw InputError("mesh: only " + std::to_string(filtered.size()) +
                     " points are left after filtering: too few for a surface");
  }
  return filtered;
}

// The surface the points carry, and how it was made.
struct Surface {
  TriangleMesh mesh;
  SurfaceMethod method = SurfaceMethod::kHeightField;
  double poisson_resolution_m = 0;  // the Poisson mesher's facet size (0 for the height field)
};

// The surface step: the height field or Poisson (guarded, coarser on failure, the height field as the
// fallback when `auto` chose Poisson); its entry is "height_field" or "poisson".
Surface SurfaceStep(const PointCloud& filtered, const SurfacePipelineOptions& options, const QualityDefaults& defaults,
                    Json& steps) {
  SurfaceMethod method = options.method;
  if (method == SurfaceMethod::kAuto) {
    method = LooksLikeNadirCapture(filtered) ? SurfaceMethod::kHeightField : SurfaceMethod::kPoisson;
  }
  TriangleMesh mesh;
  double poisson_resolution_m = 0;
  const StepTimer timer;
  Json step;
  method = GuardPoisson(method, options.method, filtered, &step);
  if (method == SurfaceMethod::kHeightField) {
    mesh = HeightFieldStep(filtered, defaults, &step);
  } else {
    PoissonOptions poisson;
    poisson.spacing_factor = defaults.poisson_spacing_factor;
    poisson.seed = options.poisson_seed;
    if (options.trim) poisson.trim_factor = 0;  // the trim step below trims, against the local spacing
    PoissonReport surface_report;
    std::optional<TriangleMesh> poisson_mesh = PoissonOrCoarser(filtered, &poisson, &surface_report, &step);
    if (poisson_mesh) {
      mesh = std::move(*poisson_mesh);
      // The mesher's facets are about this large: the trim cannot ask the surface to be closer.
      poisson_resolution_m = surface_report.average_spacing_m * poisson.spacing_factor * poisson.radius_factor;
      step["step"] = "poisson";
      step.update(surface_report.ToJson());
    } else if (options.method == SurfaceMethod::kPoisson) {
      throw InputError("mesh: surface step (Poisson): " + step["fallback_reason"].get<std::string>() +
                       "; use --surface height-field");
    } else {
      method = SurfaceMethod::kHeightField;
      step["fallback_from"] = "poisson";
      mesh = HeightFieldStep(filtered, defaults, &step);
    }
  }
  step["method_requested"] = SurfaceMethodName(options.method);
  AddStepTime(step, timer, options.report_times);
  steps.push_back(std::move(step));
  if (mesh.num_faces() == 0) {
    throw InfeasibleError("mesh: the surface reconstruction produced no face");
  }
  return {std::move(mesh), method, poisson_resolution_m};
}

// The "trim" step (surface_trim.h), with each surface's criteria.
void TrimStep(TriangleMesh& mesh, SurfaceMethod method, double poisson_resolution_m, const PointCloud& filtered,
              const SurfacePipelineOptions& options, Json& steps) {
  const StepTimer timer;
  SurfaceTrimReport trim_report;
  SurfaceTrimOptions trim = *options.trim;
  trim.min_spacing_m = std::max(trim.min_spacing_m, poisson_resolution_m);
  // Poisson: settle the surface onto the points where they lie on a plane (step 4 of the trim).
  if (method == SurfaceMethod::kPoisson && trim.settle_factor == 0) trim.settle_factor = 3.0;
  // And where they hold an edge (two planes), onto the edge's two half-planes: Poisson rounds it.
  if (method == SurfaceMethod::kPoisson) trim.settle_creases = true;
  // And judge it against at most 4 median spacings: beyond, the points are too thin to carry a surface
  // that lies on them (bench/RESULTS.md, "Oblique scenes with exact truth": 8 kept the whole ring at
  // 81 % within 0.3 m of the truth, 4 meets rule 1 and ends the mesh where the points thin out).
  if (method == SurfaceMethod::kPoisson && trim.max_spacing_ratio == 0) trim.max_spacing_ratio = 4.0;
  if (method == SurfaceMethod::kHeightField) {
    // The height field's vertices are the points themselves and its faces span only the hull: the
    // distance tests would cut the sparse, clumped areas of a sparse SfM cloud into islands (measured
    // on the Brighton Beach sample: 1,012 faces cut, 19 islands dropped). Nor is its border peeled
    // ring by ring: the height field trims its own long-edge triangles, and peeling its border by
    // edge length ate 31 rings (389 faces) into the sample's sparse rocks, where the shot list's
    // keeper stands, and took the ground from under the plan's first sample. Stretched ears and
    // strays (a few passes at most) are still cut and spikes still flattened.
    trim.far_factor = 0;
    trim.border_factor = 0;
    trim.border_edge_factor = 0;
    trim.border_extend_factor = 0;  // its border vertices are points of the data's border already
  }
  mesh = TrimSurfaceToData(mesh, filtered, trim, &trim_report);
  Json step;
  step["step"] = "trim";
  step.update(trim_report.ToJson());
  AddStepTime(step, timer, options.report_times);
  steps.push_back(std::move(step));
  if (mesh.num_faces() == 0) {
    throw InfeasibleError("mesh: no surface is left after trimming it to the points (see the report's steps)");
  }
}

}  // namespace

SurfacePipelineResult BuildSurfaceFromPoints(const PointCloud& points, const SurfacePipelineOptions& options) {
  options.Check();
  const QualityDefaults defaults = DefaultsFor(options.quality);
  Json report = StartReport(options, "points");
  Json& steps = report["steps"];
  const PointCloud filtered = FilterStep(points, options, steps);
  Surface surface = SurfaceStep(filtered, options, defaults, steps);
  if (options.trim) TrimStep(surface.mesh, surface.method, surface.poisson_resolution_m, filtered, options, steps);
  // Poisson's winding is its implicit function's sign, which an open surface does not fix; the height
  // field's faces are counter-clockwise from above by construction.
  if (surface.method == SurfaceMethod::kPoisson) steps.push_back(OrientStep(&surface.mesh, filtered, options));
  return FinishSurface(std::move(surface.mesh), &filtered, options, std::move(report));
}

SurfacePipelineResult BuildSurfaceFromMesh(TriangleMesh mesh, const PointCloud* color_source,
                                           const SurfacePipelineOptions& options) {
  options.Check();
  Json report = StartReport(options, "mesh");
  Json step;
  step["step"] = "input_mesh";
  step["vertices"] = static_cast<int64_t>(mesh.num_vertices());
  step["faces"] = static_cast<int64_t>(mesh.num_faces());
  step["colors"] = mesh.has_colors();
  report["steps"].push_back(std::move(step));
  if (mesh.num_faces() == 0) throw InputError("mesh: the given mesh has no face");
  return FinishSurface(std::move(mesh), color_source, options, std::move(report));
}

}  // namespace cinepath::photogrammetry
