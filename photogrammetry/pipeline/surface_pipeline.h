// The output half of `cinepath mesh`: points (or a given mesh) in local ENU metres → a cleaned,
// simplified, coloured mesh + a JSON report of every step + the GLB bytes of scene.glb.
//
//   points ──► filter ──► surface (2.5D height field | Poisson) ──► trim ──► clean ──► decimate ──► colours ──► GLB
//   mesh   ───────────────────────────────────────────►  clean ──► decimate ──► colours ──► GLB
//
// Everything stays double precision in ENU until the GLB, which stores ENU (e, n, u) as glTF
// (e, u, −n) in float32 (docs/design.md, "Conventions"). The result is deterministic: the same input and
// options give the same mesh, report (with report_times = false) and GLB bytes at any thread count.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "core/json.h"
#include "core/quality.h"
#include "photogrammetry/io/point_cloud.h"
#include "photogrammetry/mesh/mesh_decimate.h"
#include "photogrammetry/mesh/mesh_decimate_for_plan.h"
#include "photogrammetry/mesh/triangle_mesh.h"
#include "photogrammetry/surface/surface_points.h"
#include "photogrammetry/surface/surface_poisson.h"
#include "photogrammetry/surface/surface_trim.h"

namespace cinepath::photogrammetry {

// `Quality` (core/quality.h) is the speed/accuracy knob of every expensive step here (Poisson depth,
// height-field density, default face budget, simplifier, Hausdorff sample count). The table is in
// surface_pipeline.cc (QualityDefaults) and in docs/mesh.md.

enum class SurfaceMethod {
  kAuto,         // height field when the cameras look down on the points (nadir capture), else Poisson
  kHeightField,  // 2.5D Delaunay of (e, n) with u lifted, as OpenDroneMap does for nadir captures
  kPoisson,      // CGAL Poisson, normals from the cloud or estimated and oriented toward the cameras
};
SurfaceMethod ParseSurfaceMethod(const std::string& text, const std::string& where = "--surface");
const char* SurfaceMethodName(SurfaceMethod method);

struct SurfacePipelineOptions {
  Quality quality = Quality::kStandard;
  SurfaceMethod method = SurfaceMethod::kAuto;

  // Simplification goal: at most one of the two (both unset → the quality preset's face budget).
  std::optional<int64_t> target_faces;  // --target-faces N   (> 0)
  std::optional<double> max_error_m;    // --max-error-m E    (> 0, symmetric Hausdorff bound)
  // Simplifier; unset → the quality preset's. An error goal takes qem_tiled unless a meshoptimizer
  // method is asked for (the others take face budgets only).
  std::optional<DecimationMethod> decimation_method;
  // --for-plan: simplify each region only as far as the plan's cameras can tell, within
  // for_plan->max_error_px (mesh_decimate_for_plan.h). Excludes target_faces and max_error_m.
  std::optional<ForPlanOptions> for_plan;

  // --remesh-edge-m L: after simplification, CGAL isotropic remeshing toward edges of L metres
  // (mesh_remesh.h); the reported Hausdorff error is then the remeshed mesh's. Unset: no remeshing.
  std::optional<double> remesh_edge_m;

  // Point selection before surfacing (surface_points.h) and trimming after it (surface_trim.h).
  // Unset trim: no trim step (the Poisson surface then keeps its own centroid-distance trim).
  PointFilterOptions point_filter;
  std::optional<SurfaceTrimOptions> trim = SurfaceTrimOptions{};
  unsigned int poisson_seed = PoissonOptions{}.seed;  // the Poisson surface mesher's (surface_poisson.h)

  bool draco = false;  // --draco: KHR_draco_mesh_compression in the GLB

  // Written verbatim into the glTF asset.extras and scene.extras (e.g. the geo origin
  // {"origin": {"lat_deg", "lon_deg", "height_m"}, "frame": "ENU"...}). Must be an object or null.
  Json gltf_extras;

  // Encode scene.glb as the last step (result.glb and the report's "glb" step). false: the caller
  // finishes the mesh first (BuildScene textures it) and encodes it once with WriteGlbStep.
  bool write_glb = true;

  // Record wall-clock seconds per step in the report ("time_s"). Off for golden tests: times are
  // the only non-deterministic field.
  bool report_times = true;

  // Throws InputError (naming the option) for non-positive targets or both goals set.
  void Check() const;
};

struct SurfacePipelineResult {
  TriangleMesh mesh;  // final mesh, ENU metres, colours when the input had them
  // One object per step, in order, e.g.
  // {"input": {...}, "steps": [{"step": "filter_points", "points_in", "points_out",
  //   "removed_reprojection", "removed_short_track", "removed_isolated", "removed_off_plane",
  //   "criteria", "median_spacing_m", "max_off_plane_removed_m", "time_s"}, {"step": "height_field", ...},
  //   {"step": "trim", "faces_far_from_data", "border_faces_unsupported", "border_faces_stretched",
  //    "spike_vertices_flattened", "max_spike_height_m", "median_spacing_m", "criteria", ...},
  //   {"step": "clean", "degenerate_faces_removed", "duplicate_faces_removed",
  //    "non_manifold_vertices_split", "small_components_removed", "faces_in_small_components",
  //    "holes_filled", "isolated_vertices_removed", "faces_in", "faces_out", "time_s"},
  //   {"step": "decimate", "method", "faces_in", "faces_out", "hausdorff_m",
  //    "hausdorff_samples" (face samples per mesh), "hausdorff_vertex_samples", "hausdorff_seed",
  //    "hausdorff_in_to_out_m", "hausdorff_out_to_in_m", "hausdorff_points_measured", "time_s"},
  //    with for_plan: "goal": "for_plan" and "for_plan": ForPlanReport::ToJson(),
  //   {"step": "remesh", ...} (with --remesh-edge-m), {"step": "colors", ...},
  //   {"step": "glb", "draco", "bytes", "time_s", "texture" (when textured)}],
  //  "output": {"vertices", "faces", "hausdorff_m", "bbox_min_m", "bbox_max_m"}}
  Json report;
  std::string glb;  // scene.glb bytes (none with write_glb false)
};

// Reconstructs a surface from `points` (ENU metres), then cleans, simplifies, colours and encodes
// it. Throws InputError when the cloud is too small or degenerate to carry a surface, InfeasibleError
// when no surface survives cleaning.
SurfacePipelineResult BuildSurfaceFromPoints(const PointCloud& points, const SurfacePipelineOptions& options);

// Uses a given mesh (ENU metres) as is — no reconstruction — then cleans, simplifies and encodes
// it. When the mesh has no colours and `color_source` has colours, vertex colours are taken from
// the nearest points.
SurfacePipelineResult BuildSurfaceFromMesh(TriangleMesh mesh, const PointCloud* color_source,
                                           const SurfacePipelineOptions& options);

struct GlbTexture;  // gltf/gltf_writer.h

// The last step, "write": scene.glb's bytes of `mesh` (textured when `texture` is given; Draco and the
// glTF extras from `options`), its entry {"step": "glb", ...} appended to (*report)["steps"].
std::string WriteGlbStep(const TriangleMesh& mesh, const GlbTexture* texture, const SurfacePipelineOptions& options,
                         Json* report);

}  // namespace cinepath::photogrammetry
