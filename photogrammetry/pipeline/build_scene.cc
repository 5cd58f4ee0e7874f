#include "photogrammetry/pipeline/build_scene.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "core/error.h"
#include "core/fatal_signal.h"
#include "core/reframe.h"
#include "photogrammetry/georef/scene_cameras.h"
#include "photogrammetry/gltf/gltf_writer.h"
#include "photogrammetry/io/colmap_reader.h"
#include "photogrammetry/io/colmap_runner.h"
#include "photogrammetry/io/exif_gps.h"
#include "photogrammetry/io/gcp_file.h"
#include "photogrammetry/io/ply_reader.h"
#include "photogrammetry/io/refs_file.h"
#include "photogrammetry/mesh/view_dependent_budget.h"
#include "photogrammetry/pipeline/step_report.h"

namespace cinepath::photogrammetry {
namespace {

namespace fs = std::filesystem;

void Tell(const std::function<void(const std::string&)>& f, const std::string& text) {
  if (f) f(text);
}

// The photos: given, or an images/ folder beside or above the model (COLMAP workspaces keep images/
// at their root). Paths stay as given (relative ones too), so that messages and scene.json do not
// depend on where the command ran.
struct ImagesFolder {
  std::string dir;
  std::string note;  // how it was found
};

ImagesFolder FindImages(const SceneBuildOptions& options, const std::string& colmap_dir) {
  if (!options.images_dir.empty()) return {options.images_dir, "given"};
  const fs::path m = fs::path(colmap_dir).lexically_normal();
  for (const fs::path& candidate : {(m / "images").lexically_normal(), (m / ".." / "images").lexically_normal(),
                                    (m / ".." / ".." / "images").lexically_normal()}) {
    if (fs::is_directory(candidate)) return {candidate.string(), "found next to the model"};
  }
  return {};
}

// Focal-length priors: the given one for every camera, else the EXIF of an image of each camera.
void SetFocalPriors(const ColmapModel& model, const std::vector<ExifInfo>& exif, const SceneBuildOptions& options,
                    ModelGeoreferenceOptions* georeference) {
  for (const auto& [camera_id, camera] : model.cameras) {
    if (options.focal_prior_px) {
      georeference->focal_prior_px[camera_id] = *options.focal_prior_px;
      georeference->focal_prior_source = "a given value";
      continue;
    }
    for (const ExifInfo& e : exif) {
      const auto image = std::find_if(model.images.begin(), model.images.end(),
                                      [&](const auto& kv) { return kv.second.name == e.file_name; });
      if (image == model.images.end() || image->second.camera_id != camera_id) continue;
      if (const auto prior = FocalPriorFromExif(e, static_cast<double>(camera.width_px), options.sensor_width_mm)) {
        georeference->focal_prior_px[camera_id] = prior->focal_px;
        georeference->focal_prior_source = prior->source + " (" + e.file_name + ")";
        break;
      }
    }
  }
}

// asset.extras and scene.extras of scene.glb: the origin and the frame.
Json GltfExtras(const ModelGeoreference& geo) {
  Json extras = Json::object();
  extras["origin"] = {
      {"lat_deg", geo.origin.lat_deg}, {"lon_deg", geo.origin.lon_deg}, {"height_m", geo.origin.height_m}};
  extras["frame"] = "ENU metres about origin (glTF x = east, y = up, z = -north); heights WGS84 ellipsoidal";
  return extras;
}

// The surface from the sparse points, a dense cloud or a given mesh, all in ENU.
SurfacePipelineResult BuildSurface(const SceneBuildOptions& options, const ColmapModel& model,
                                   const ModelGeoreference& geo, const SurfacePipelineOptions& surface,
                                   std::vector<std::string>* inputs, Json* input_note) {
  surface.Check();

  PointCloud cloud = PointCloudFromModel(geo.model_enu);
  AffineMap enu_from_input;
  if (!options.points_path.empty() || !options.mesh_path.empty()) {
    const std::string& input = options.points_path.empty() ? options.mesh_path : options.points_path;
    try {
      enu_from_input = FitAffineBetweenModels(model, geo.model_enu);
    } catch (const InputError& e) {
      throw InputError(input + ": " + e.what());
    }
    (*input_note)["enu_from_input_affine_rms_m"] = RoundToDecimals(enu_from_input.rms_m, 4);
    if (enu_from_input.similarity_only) (*input_note)["enu_from_input_similarity_only"] = true;
  }
  if (!options.mesh_path.empty()) {
    PlyData ply = ReadPly(options.mesh_path);
    inputs->push_back(options.mesh_path);
    if (!ply.has_faces())
      throw InputError(options.mesh_path + ": the mesh has no faces (a point cloud is a dense cloud)");
    for (auto& v : ply.mesh.vertices_m) v = enu_from_input(v);
    (*input_note)["mesh"] = options.mesh_path;
    return BuildSurfaceFromMesh(std::move(ply.mesh), &cloud, surface);
  }
  if (!options.points_path.empty()) {
    PlyData ply = ReadPly(options.points_path);
    inputs->push_back(options.points_path);
    PointCloud dense = std::move(ply.points);
    for (auto& p : dense.positions_m) p = enu_from_input(p);
    if (dense.has_normals()) {
      const Eigen::Matrix3d normal_map = enu_from_input.linear.inverse().transpose();
      for (auto& n : dense.normals) n = (normal_map * n).normalized();
    }
    dense.camera_centers_m = cloud.camera_centers_m;
    (*input_note)["points"] = options.points_path;
    cloud = std::move(dense);
  }
  return BuildSurfaceFromPoints(cloud, surface);
}

// --for-plan: the cameras of every drone of the plan, placed on WGS84 by its origin and moved into this
// scene's frame (exactly, through ECEF: core/reframe.h), so a plan made about another origin (a shot list's
// own, or an earlier scene's) sees the mesh where it stands. A plan without an origin cannot be placed:
// InputError naming the field.
std::vector<PlanCamera> PlanCamerasInSceneFrame(const TeamPlan& plan, const std::string& path,
                                                const Geodetic& scene_origin) {
  if (!plan.origin) {
    std::ostringstream os;
    os.precision(10);
    os << "(" << scene_origin.lat_deg << ", " << scene_origin.lon_deg << ", " << scene_origin.height_m << " m)";
    throw InputError(Located(path + ": origin",
                             "null: --for-plan needs a plan placed on WGS84 (cinepath plan --scene scene.json "
                             "gives it the scene's origin " +
                                 os.str() + ", or the shot list's own)"));
  }
  std::vector<PlanCamera> cameras;
  for (const DroneFlight& flight : ReframeToOrigin(plan, scene_origin).flights) {
    std::vector<PlanCamera> more =
        CamerasFromPlan(flight.plan, plan.single ? path : path + " (drone \"" + flight.name + "\")");
    for (PlanCamera& camera : more) {
      if (!plan.single) camera.drone = flight.name;
      cameras.push_back(std::move(camera));
    }
  }
  return cameras;
}

// What `mesh` loads before georeferencing: the model, its photos' EXIF, the references and GCPs.
struct LoadedModel {
  std::string colmap_dir;
  ColmapFormat format = ColmapFormat::kText;
  ColmapModel model;
  ImagesFolder images;
  std::vector<ExifInfo> exif;
  std::optional<GcpFile> gcps;
  std::vector<ImageReference> refs;
  std::string refs_source;
};

// The model: given, or reconstructed from the photos; then the model folder inside what was given.
std::string ModelDir(const SceneBuildOptions& options, const SceneBuildLog& log) {
  std::string colmap_dir = options.colmap_dir;
  if (colmap_dir.empty()) {
    const fs::path workspace =
        options.colmap_workspace.empty() ? fs::path(options.output_dir) / "colmap" : fs::path(options.colmap_workspace);
    colmap_dir =
        RunColmapReconstruction(options.images_dir, workspace, ColmapRunOptions(), [&](const std::string& step) {
          Tell(log.colmap_step, step + " (log in " + workspace.string() + ")");
        }).string();
  }
  if (const fs::path found = FindColmapModelDir(colmap_dir); found != fs::path(colmap_dir)) {
    Tell(log.note, "using the COLMAP model in " + found.string());
    colmap_dir = found.string();
  }
  return colmap_dir;
}

// The EXIF of every registered image found in the photos folder.
std::vector<ExifInfo> ReadModelExif(const ColmapModel& model, const std::string& images_dir,
                                    std::vector<std::string>* inputs) {
  if (images_dir.empty()) return {};
  std::vector<std::string> names;
  for (const auto& [id, image] : model.images) names.push_back(image.name);
  std::vector<ExifInfo> exif = ReadExifFolder(images_dir, names);
  for (const auto& e : exif) inputs->push_back((fs::path(images_dir) / e.file_name).string());
  return exif;
}

// References: the file, else EXIF GPS; InputError when there are neither references nor GCPs.
void TakeReferences(const SceneBuildOptions& options, LoadedModel* loaded, std::vector<std::string>* inputs) {
  if (!options.refs_path.empty()) {
    loaded->refs = ReadReferencesFile(options.refs_path);
    loaded->refs_source = options.refs_path;
    inputs->push_back(options.refs_path);
  } else if (!loaded->exif.empty()) {
    loaded->refs = ReferencesFromExif(loaded->images.dir, loaded->exif);
    loaded->refs_source = "EXIF GPS of " + loaded->images.dir;
  }
  if (loaded->refs.empty() && !loaded->gcps) {
    throw InputError(
        "no references to georeference with: give a references file, photos with GPS EXIF, or ground "
        "control points" +
        std::string(loaded->images.dir.empty() ? "" : " (" + loaded->images.dir + " has no GPS EXIF)"));
  }
}

// The load step: the model, its files, the GCPs, the photos' EXIF and the references.
LoadedModel LoadModel(const SceneBuildOptions& options, const SceneBuildLog& log, std::vector<std::string>* inputs) {
  LoadedModel loaded;
  loaded.colmap_dir = ModelDir(options, log);
  loaded.model = ReadColmapModel(loaded.colmap_dir);
  loaded.format = DetectColmapFormat(loaded.colmap_dir);
  for (const char* stem : {"cameras", "images", "points3D"}) {
    inputs->push_back(
        (fs::path(loaded.colmap_dir) / (std::string(stem) + (loaded.format == ColmapFormat::kBinary ? ".bin" : ".txt")))
            .string());
  }
  if (!options.gcp_path.empty()) {
    loaded.gcps = ReadGcpFile(options.gcp_path);
    inputs->push_back(options.gcp_path);
  }
  loaded.images = FindImages(options, loaded.colmap_dir);
  loaded.exif = ReadModelExif(loaded.model, loaded.images.dir, inputs);
  TakeReferences(options, &loaded, inputs);
  return loaded;
}

// The surface pipeline's options for this scene: the GLB's extras, the times, the plan's cameras; the
// GLB is written here, after the texture.
SurfacePipelineOptions SurfaceOptionsFor(const SceneBuildOptions& options, const ModelGeoreference& geo,
                                         std::vector<std::string>* inputs) {
  SurfacePipelineOptions surface = options.surface;
  surface.report_times = options.timestamps;
  surface.gltf_extras = GltfExtras(geo);
  surface.write_glb = false;
  if (options.for_plan) {
    ForPlanOptions for_plan;
    for_plan.cameras = PlanCamerasInSceneFrame(*options.for_plan, options.for_plan_path, geo.origin);
    for_plan.plan_source = options.for_plan_path;
    for_plan.max_error_px = options.max_error_px;
    surface.for_plan = std::move(for_plan);
    inputs->push_back(options.for_plan_path);
  }
  return surface;
}

// The surface steps' fallbacks, told as warnings.
void WarnAboutFallbacks(const Json& surface_report, const SceneBuildLog& log) {
  for (const Json& step : surface_report["steps"]) {
    if (step.contains("fallback_from")) {
      Tell(log.warning, "the surface step fell back from " + step["fallback_from"].get<std::string>() + " to " +
                            step["step"].get<std::string>() + ": " + step["fallback_reason"].get<std::string>());
    }
    if (step.contains("coarser_after_failure")) {
      Tell(log.warning, "the Poisson surface was made at twice the spacing (coarser) after CGAL failed at the first: " +
                            step["coarser_after_failure"].get<std::string>());
    }
  }
}

// The texture step: the mesh textured from the photos when there are photos and it is not turned off
// (then `textured` holds it); returns scene.json's "texture".
Json TextureStep(const SceneBuildOptions& options, const TriangleMesh& mesh, const ModelGeoreference& geo,
                 const ImagesFolder& images, std::optional<TexturedMesh>* textured) {
  if (!options.texture) return {{"skipped", "--no-texture"}};
  if (images.dir.empty()) return {{"skipped", "no photos"}};
  const StepTimer timer;
  MeshTextureOptions texture_options = options.texture_options;
  texture_options.texture_px = options.texture_px.value_or(DefaultTexturePx(options.surface.quality));
  texture_options.report_times = options.timestamps;
  const CurrentStep running("texture: from the photos");
  *textured = TextureMeshFromPhotos(mesh, geo.model_enu, images.dir, texture_options, nullptr);
  Json report = (*textured)->report;
  if (options.timestamps) report["time_s"]["total_s"] = timer.RoundedSeconds();
  return report;
}

// scene.json (docs/scene-format.md): what a reader needs first, then the reports.
Json SceneJson(const SceneBuildOptions& options, const LoadedModel& loaded, const ModelGeoreference& geo,
               const ModelGeoreferenceOptions& georeference, const Json& input_note, const Json& surface_report,
               const Json& texture_report) {
  Json scene = Json::object();
  scene["format"] = "cinepath.scene";
  scene["version"] = 1;
  scene["mesh"] = "scene.glb";
  scene["frame"] = "ENU metres about origin; scene.glb stores (e, n, u) as glTF (e, u, -n)";
  Json geo_json = GeoreferenceJson(geo, georeference, options.timestamps);
  for (auto it = geo_json.begin(); it != geo_json.end(); ++it) scene[it.key()] = it.value();
  scene["georeferencing"]["references_source"] = loaded.refs_source.empty() ? Json(nullptr) : Json(loaded.refs_source);
  if (loaded.gcps) scene["georeferencing"]["gcp_source"] = options.gcp_path;
  scene["georeferencing"]["images"] =
      loaded.images.dir.empty() ? Json(nullptr) : Json(loaded.images.dir + " (" + loaded.images.note + ")");
  scene["input"] = {{"colmap", loaded.colmap_dir},
                    {"colmap_format", loaded.format == ColmapFormat::kBinary ? "binary" : "text"},
                    {"cameras", loaded.model.cameras.size()},
                    {"images", loaded.model.images.size()},
                    {"points3d", loaded.model.points3d.size()}};
  for (auto it = input_note.begin(); it != input_note.end(); ++it) scene["input"][it.key()] = it.value();
  if (options.for_plan) scene["input"]["for_plan"] = options.for_plan_path;
  scene["surface"] = surface_report;
  scene["texture"] = texture_report;
  scene["cameras"] = SceneCamerasJson(geo.model_enu);
  return scene;
}

}  // namespace

void SceneBuildOptions::Check() const {
  if (colmap_dir.empty() && images_dir.empty()) {
    throw InputError("give a COLMAP model (colmap_dir) or photos to reconstruct (images_dir)");
  }
  if (!points_path.empty() && !mesh_path.empty()) {
    throw InputError("points_path and mesh_path: give a dense cloud or a mesh, not both");
  }
  if (for_plan && (surface.target_faces || surface.max_error_m)) {
    throw InputError("for_plan_path and target_faces / max_error_m: give a plan or a simplification goal, not both");
  }
  if (!(max_error_px > 0 && std::isfinite(max_error_px))) throw InputError("max_error_px: must be a finite number > 0");
  surface.Check();
  texture_options.Check();
  if (texture_px && (*texture_px < 64 || *texture_px > 16384)) {
    throw InputError("texture_px: must be between 64 and 16384, got " + std::to_string(*texture_px));
  }
}

SceneBuildResult BuildScene(const SceneBuildOptions& options, const SceneBuildLog& log) {
  options.Check();
  SceneBuildResult result;
  std::vector<std::string>& inputs = result.inputs;
  const LoadedModel loaded = LoadModel(options, log, &inputs);

  ModelGeoreferenceOptions georeference = options.georeference;
  SetFocalPriors(loaded.model, loaded.exif, options, &georeference);
  const ModelGeoreference geo =
      GeoreferenceModel(loaded.model, loaded.refs, loaded.gcps ? &*loaded.gcps : nullptr, georeference);
  for (const std::string& w : geo.warnings) Tell(log.warning, w);

  const SurfacePipelineOptions surface = SurfaceOptionsFor(options, geo, &inputs);
  Json input_note = Json::object();
  SurfacePipelineResult built = BuildSurface(options, loaded.model, geo, surface, &inputs, &input_note);
  WarnAboutFallbacks(built.report, log);

  std::optional<TexturedMesh> textured;
  const Json texture_report = TextureStep(options, built.mesh, geo, loaded.images, &textured);
  if (textured) {
    const GlbTexture texture{textured->texcoords, textured->image_bytes, textured->mime_type};
    result.glb = WriteGlbStep(textured->mesh, &texture, surface, &built.report);
  } else {
    result.glb = WriteGlbStep(built.mesh, nullptr, surface, &built.report);
  }
  result.scene = SceneJson(options, loaded, geo, georeference, input_note, built.report, texture_report);
  return result;
}

}  // namespace cinepath::photogrammetry
