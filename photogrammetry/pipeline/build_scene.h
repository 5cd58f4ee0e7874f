// `cinepath mesh` as a library call: a COLMAP model (or photos COLMAP reconstructs first) with GPS
// references, EXIF or ground control points in, scene.glb bytes and the scene.json document out.
// Nothing is written here; cli/cmd_mesh.cc binds its flags onto SceneBuildOptions and writes the two
// files atomically.
//
// The steps: find the model (a workspace or sparse/ folder holding one model), read it, find the
// photos (given, or an images/ folder beside the model), read their EXIF, take the references (the
// refs file, else EXIF GPS), the focal-length priors (a given one, else EXIF), georeference
// (georeference_model.h), build the surface from the sparse points, a dense PLY or a given mesh
// (surface_pipeline.h), texture it from the photos (mesh_texture.h), and assemble scene.json (docs/scene-format.md,
// docs/mesh.md).
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/geodesy.h"
#include "core/json.h"
#include "core/team_plan.h"
#include "core/trajectory.h"
#include "photogrammetry/georef/georeference_model.h"
#include "photogrammetry/pipeline/surface_pipeline.h"
#include "photogrammetry/texture/mesh_texture.h"

namespace cinepath::photogrammetry {

struct SceneBuildOptions {
  std::string colmap_dir;                 // model, sparse/ or workspace; empty: reconstruct `images_dir` with colmap
  std::string colmap_workspace;           // where colmap runs for photos-only input (default output_dir/colmap)
  std::string images_dir;                 // photos (EXIF GPS and focal length); empty: found beside the model
  std::string refs_path;                  // "image_name lat lon alt" lines
  std::string gcp_path;                   // OpenDroneMap gcp_list.txt
  std::string points_path;                // dense PLY in the model's frame
  std::string mesh_path;                  // mesh PLY in the model's frame, used as is
  std::string output_dir;                 // only for the default colmap workspace
  ModelGeoreferenceOptions georeference;  // fit, datum, origin, bundle adjustment, GCP datum and sigma
  std::optional<double> focal_prior_px;   // for every camera; overrides EXIF
  std::optional<double> sensor_width_mm;  // EXIF FocalLength -> pixels
  SurfacePipelineOptions surface;
  // Texture the mesh from the photos (mesh_texture.h) when there are photos; texture.texture_px unset
  // here (texture_px) takes the quality preset's (DefaultTexturePx).
  bool texture = true;
  MeshTextureOptions texture_options;
  std::optional<int> texture_px;
  bool timestamps = true;  // wall-clock times in scene.json
  // --for-plan: the plan (read by the caller from for_plan_path; one drone or several) whose cameras, every
  // drone's, set the detail of each region (mesh_decimate_for_plan.h), moved onto the scene's origin
  // (core/reframe.h); a plan without an origin is an InputError naming the file and its "origin".
  // max_error_px: --max-error-px.
  std::optional<TeamPlan> for_plan;
  std::string for_plan_path;
  double max_error_px = 0.5;

  // InputError naming the field: neither a model nor photos; both a dense cloud and a mesh.
  void Check() const;
};

struct SceneBuildResult {
  std::string glb;                  // scene.glb bytes
  Json scene;                       // scene.json
  std::vector<std::string> inputs;  // every file read (for --depfile)
};

// Where BuildScene reports as it goes (each may be empty): the steps of a COLMAP run, notes such as
// which model folder was used, and warnings (georeferencing). Called at once, so that a later error
// still follows them.
struct SceneBuildLog {
  std::function<void(const std::string&)> colmap_step;
  std::function<void(const std::string&)> note;
  std::function<void(const std::string&)> warning;
};

SceneBuildResult BuildScene(const SceneBuildOptions& options, const SceneBuildLog& log = {});

}  // namespace cinepath::photogrammetry
