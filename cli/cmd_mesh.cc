// cinepath mesh: COLMAP reconstruction (+ GPS references) -> cleaned, georeferenced mesh.
//   reads   COLMAP sparse model (text or binary), optional dense PLY points or a PLY mesh in the same
//           frame, references (file or EXIF), ground control points (--gcp), EXIF focal lengths
//   writes  OUTDIR/scene.glb and OUTDIR/scene.json (origin, enu_from_colmap, georeferencing report,
//           surface report), both or neither.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>

#include <unistd.h>

#include <CLI/CLI.hpp>

#include "cli/command.h"
#include "cli/command_plugin.h"
#include "cli/common_options.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/json.h"
#include "photogrammetry/colmap_reader.h"
#include "photogrammetry/colmap_runner.h"
#include "photogrammetry/exif_gps.h"
#include "photogrammetry/gcp_file.h"
#include "photogrammetry/georeference_model.h"
#include "photogrammetry/ply_reader.h"
#include "photogrammetry/refs_file.h"
#include "photogrammetry/surface_pipeline.h"

namespace cinepath::cli {
namespace {

namespace fs = std::filesystem;
using namespace cinepath::photogrammetry;

Geodetic ParseOrigin(const std::string& text) {
  Geodetic g;
  char c1 = 0, c2 = 0;
  std::istringstream is(text);
  if (!(is >> g.lat_deg >> c1 >> g.lon_deg >> c2 >> g.height_m) || c1 != ',' || c2 != ',' || !is.eof()) {
    throw InputError("--origin: expected LAT,LON,HEIGHT (degrees, degrees, metres ellipsoidal), got '" + text + "'");
  }
  ValidateGeodetic(g, "--origin");
  return g;
}

class MeshCommand : public Command {
 public:
  void Setup(CLI::App& app) override {
    app.add_option("--colmap", colmap_dir_,
                   "COLMAP sparse model folder (cameras/images/points3D .bin or .txt), or a workspace / sparse/ folder "
                   "holding one model (sparse/0). Without it, --images "
                   "is reconstructed by running the colmap binary (CPU) in --colmap-workspace");
    app.add_option("--colmap-workspace", workspace_,
                   "Where COLMAP runs for photos-only input (default OUTDIR/colmap; reused when it holds a model)");
    app.add_option("--refs", refs_path_,
                   "References: 'image_name lat lon alt' per line (COLMAP model_aligner format; '#' comments)");
    app.add_option("--gcp", gcp_path_,
                   "Ground control points, OpenDroneMap gcp_list.txt format (see docs/mesh.md); alone or with "
                   "camera references");
    app.add_option("--gcp-altitude-datum", gcp_altitude_datum_,
                   "GCP heights are WGS84 ellipsoidal (default) or above mean sea level (EGM96)")
        ->check(CLI::IsMember({"ellipsoidal", "amsl"}));
    app.add_option("--gcp-sigma-m", gcp_sigma_m_, "Bundle adjustment: GCP position sigma (m)")
        ->check(CLI::PositiveNumber);
    app.add_option("--images", images_dir_,
                   "Photos folder: EXIF GPS (when no --refs) and EXIF focal length (prior for the bundle "
                   "adjustment). Default: an images/ folder next to or above the model, when there is one");
    app.add_option("--points", points_path_, "Dense point cloud PLY (e.g. fused.ply) in the model's frame");
    app.add_option("--mesh", mesh_path_, "Mesh PLY (e.g. meshed-poisson.ply) in the model's frame, used as is");
    app.add_option("--altitude-datum", altitude_datum_,
                   "Reference altitudes are WGS84 ellipsoidal heights (default, as COLMAP and DJI EXIF) or "
                   "above mean sea level (EGM96)")
        ->check(CLI::IsMember({"ellipsoidal", "amsl"}));
    app.add_option("--origin", origin_, "ENU origin LAT,LON,HEIGHT (ellipsoidal m); default: mean of the references");
    app.add_option("--max-rmse-m", fit_.max_rmse_m, "Refuse (exit 3) when the georeferencing RMSE exceeds this")
        ->check(CLI::PositiveNumber);
    app.add_option("--inlier-threshold-m", fit_.inlier_threshold_m, "RANSAC inlier distance for references")
        ->check(CLI::PositiveNumber);
    app.add_option("--seed", fit_.seed, "RANSAC seed (deterministic)");
    app.add_flag("--no-bundle-adjust", no_bundle_adjust_, "Similarity fit only (as model_aligner)");
    app.add_option("--gps-sigma-m", gps_sigma_m_, "Bundle adjustment: GPS camera-centre sigma (m)")
        ->check(CLI::PositiveNumber);
    app.add_option("--focal-prior-px", focal_prior_px_, "Focal-length prior (px) for every camera; overrides EXIF")
        ->check(CLI::PositiveNumber);
    app.add_option("--sensor-width-mm", sensor_width_mm_, "Sensor width for EXIF FocalLength -> pixels")
        ->check(CLI::PositiveNumber);
    app.add_option("--quality", quality_, "draft | standard | final")
        ->check(CLI::IsMember({"draft", "standard", "final"}));
    app.add_option("--surface", surface_, "auto | height-field | poisson");
    app.add_option("--target-faces", target_faces_, "Simplify to at most N faces")->check(CLI::PositiveNumber);
    app.add_option("--max-error-m", max_error_m_, "Simplify within this Hausdorff error (m)")
        ->check(CLI::PositiveNumber);
    app.add_option("--remesh-edge-m", remesh_edge_m_, "After simplifying, remesh isotropically to edges of about L m")
        ->check(CLI::PositiveNumber);
    app.add_flag("--draco", draco_, "Compress the GLB with KHR_draco_mesh_compression");
    app.add_flag("--no-timestamp", no_timestamp_, "Leave wall-clock times out of scene.json (byte-identical runs)");
    app.add_option("-o,--output", output_dir_, "Output folder (scene.glb, scene.json)")->required();
    common_.Add(app);
  }

  int Run() override {
    std::vector<std::string> inputs;
    if (colmap_dir_.empty()) {
      if (images_dir_.empty()) throw InputError("give --colmap DIR (a sparse model) or --images DIR (photos)");
      const fs::path workspace = workspace_.empty() ? fs::path(output_dir_) / "colmap" : fs::path(workspace_);
      const bool tty = isatty(STDERR_FILENO) != 0 || common_.progress_mode() == ProgressMode::kAlways;
      colmap_dir_ = RunColmapReconstruction(images_dir_, workspace, ColmapRunOptions(), [&](const std::string& step) {
                      if (tty && common_.progress_mode() != ProgressMode::kNever) {
                        std::cerr << "cinepath mesh: colmap " << step << " (log in " << workspace.string() << ")\n";
                      }
                    }).string();
    }
    if (const fs::path found = FindColmapModelDir(colmap_dir_); found != fs::path(colmap_dir_)) {
      std::cerr << "cinepath mesh: using the COLMAP model in " << found.string() << "\n";
      colmap_dir_ = found.string();
    }
    const ColmapModel model = ReadColmapModel(colmap_dir_);
    const ColmapFormat format = DetectColmapFormat(colmap_dir_);
    for (const char* stem : {"cameras", "images", "points3D"}) {
      inputs.push_back(
          (fs::path(colmap_dir_) / (std::string(stem) + (format == ColmapFormat::kBinary ? ".bin" : ".txt"))).string());
    }

    ModelGeoreferenceOptions options;
    options.fit = fit_;
    options.altitude_datum = altitude_datum_ == "amsl" ? AltitudeDatum::kAmslEgm96 : AltitudeDatum::kEllipsoidal;
    if (!origin_.empty()) options.origin = ParseOrigin(origin_);
    options.bundle_adjust = !no_bundle_adjust_;
    if (gps_sigma_m_) options.ba.gps_sigma_horizontal_m = options.ba.gps_sigma_vertical_m = *gps_sigma_m_;
    options.gcp_altitude_datum =
        gcp_altitude_datum_ == "amsl" ? AltitudeDatum::kAmslEgm96 : AltitudeDatum::kEllipsoidal;
    options.gcp_sigma_horizontal_m = options.gcp_sigma_vertical_m = gcp_sigma_m_;
    std::optional<GcpFile> gcps;
    if (!gcp_path_.empty()) {
      gcps = ReadGcpFile(gcp_path_);
      inputs.push_back(gcp_path_);
    }

    // Images: given, or discovered next to the model (COLMAP workspaces keep images/ at their root).
    std::string images_dir = images_dir_;
    std::string images_note = images_dir_.empty() ? "" : "given (--images)";
    if (images_dir.empty()) {
      // Paths stay as the user gave them (relative ones too), so that messages and scene.json do not
      // depend on where the command ran.
      const fs::path m = fs::path(colmap_dir_).lexically_normal();
      for (const fs::path& candidate : {(m / "images").lexically_normal(), (m / ".." / "images").lexically_normal(),
                                        (m / ".." / ".." / "images").lexically_normal()}) {
        if (fs::is_directory(candidate)) {
          images_dir = candidate.string();
          images_note = "found next to the model";
          break;
        }
      }
    }
    std::vector<ExifInfo> exif;
    if (!images_dir.empty()) {
      std::vector<std::string> names;
      for (const auto& [id, image] : model.images) names.push_back(image.name);
      exif = ReadExifFolder(images_dir, names);
      for (const auto& e : exif) inputs.push_back((fs::path(images_dir) / e.file_name).string());
    }

    std::vector<ImageReference> refs;
    std::string refs_source;
    if (!refs_path_.empty()) {
      refs = ReadReferencesFile(refs_path_);
      refs_source = refs_path_;
      inputs.push_back(refs_path_);
    } else if (!exif.empty()) {
      refs = ReferencesFromExif(images_dir, exif);
      refs_source = "EXIF GPS of " + images_dir;
    }
    if (refs.empty() && !gcps) {
      throw InputError(
          "no references to georeference with: give --refs FILE, --images DIR with GPS EXIF, or --gcp FILE" +
          std::string(images_dir.empty() ? "" : " (" + images_dir + " has no GPS EXIF)"));
    }

    // Focal-length priors: --focal-prior-px, else EXIF of an image of each camera.
    for (const auto& [camera_id, camera] : model.cameras) {
      if (focal_prior_px_) {
        options.focal_prior_px[camera_id] = *focal_prior_px_;
        options.focal_prior_source = "--focal-prior-px";
        continue;
      }
      for (const ExifInfo& e : exif) {
        const auto image = std::find_if(model.images.begin(), model.images.end(),
                                        [&](const auto& kv) { return kv.second.name == e.file_name; });
        if (image == model.images.end() || image->second.camera_id != camera_id) continue;
        if (const auto prior = FocalPriorFromExif(e, static_cast<double>(camera.width_px), sensor_width_mm_)) {
          options.focal_prior_px[camera_id] = prior->focal_px;
          options.focal_prior_source = prior->source + " (" + e.file_name + ")";
          break;
        }
      }
    }

    const ModelGeoreference geo = GeoreferenceModel(model, refs, gcps ? &*gcps : nullptr, options);
    for (const std::string& w : geo.warnings) std::cerr << "cinepath mesh: warning: " << w << "\n";

    // Surface.
    SurfacePipelineOptions surface;
    surface.quality = ParseQuality(quality_);
    surface.method = ParseSurfaceMethod(surface_);
    surface.target_faces = target_faces_;
    surface.max_error_m = max_error_m_;
    surface.remesh_edge_m = remesh_edge_m_;
    surface.draco = draco_;
    surface.report_times = !no_timestamp_;
    Json extras = Json::object();
    extras["origin"] = {
        {"lat_deg", geo.origin.lat_deg}, {"lon_deg", geo.origin.lon_deg}, {"height_m", geo.origin.height_m}};
    extras["frame"] = "ENU metres about origin (glTF x = east, y = up, z = -north); heights WGS84 ellipsoidal";
    surface.gltf_extras = extras;
    surface.Check();

    PointCloud cloud = PointCloudFromModel(geo.model_enu);
    const AffineMap enu_from_input = FitAffineBetweenModels(model, geo.model_enu);
    Json input_note = Json::object();
    SurfacePipelineResult result;
    if (!points_path_.empty() || !mesh_path_.empty()) {
      input_note["enu_from_input_affine_rms_m"] = RoundToDecimals(enu_from_input.rms_m, 4);
    }
    if (!mesh_path_.empty()) {
      PlyData ply = ReadPly(mesh_path_);
      inputs.push_back(mesh_path_);
      if (!ply.has_faces()) throw InputError(mesh_path_ + ": --mesh has no faces (use --points for a point cloud)");
      for (auto& v : ply.mesh.vertices_m) v = enu_from_input(v);
      input_note["mesh"] = mesh_path_;
      result = BuildSurfaceFromMesh(std::move(ply.mesh), &cloud, surface);
    } else {
      if (!points_path_.empty()) {
        PlyData ply = ReadPly(points_path_);
        inputs.push_back(points_path_);
        PointCloud dense = std::move(ply.points);
        for (auto& p : dense.positions_m) p = enu_from_input(p);
        if (dense.has_normals()) {
          const Eigen::Matrix3d normal_map = enu_from_input.linear.inverse().transpose();
          for (auto& n : dense.normals) n = (normal_map * n).normalized();
        }
        dense.camera_centers_m = cloud.camera_centers_m;
        input_note["points"] = points_path_;
        cloud = std::move(dense);
      }
      result = BuildSurfaceFromPoints(cloud, surface);
    }

    Json scene = Json::object();
    scene["format"] = "cinepath.scene";
    scene["version"] = 1;
    scene["mesh"] = "scene.glb";
    scene["frame"] = "ENU metres about origin; scene.glb stores (e, n, u) as glTF (e, u, -n)";
    Json geo_json = GeoreferenceJson(geo, options, !no_timestamp_);
    for (auto it = geo_json.begin(); it != geo_json.end(); ++it) scene[it.key()] = it.value();
    scene["georeferencing"]["references_source"] = refs_source.empty() ? Json(nullptr) : Json(refs_source);
    if (gcps) scene["georeferencing"]["gcp_source"] = gcp_path_;
    scene["georeferencing"]["images"] =
        images_dir.empty() ? Json(nullptr) : Json(images_dir + " (" + images_note + ")");
    scene["input"] = {{"colmap", colmap_dir_},
                      {"colmap_format", format == ColmapFormat::kBinary ? "binary" : "text"},
                      {"cameras", model.cameras.size()},
                      {"images", model.images.size()},
                      {"points3d", model.points3d.size()}};
    for (auto it = input_note.begin(); it != input_note.end(); ++it) scene["input"][it.key()] = it.value();
    scene["surface"] = result.report;

    EnsureDirectory(output_dir_);
    AtomicOutputs outputs;
    const std::string glb_path = (fs::path(output_dir_) / "scene.glb").string();
    const std::string json_path = (fs::path(output_dir_) / "scene.json").string();
    outputs.Add(glb_path, result.glb);
    outputs.Add(json_path, DumpJson(scene));
    outputs.Commit();
    common_.WriteDepfileIfAsked({glb_path, json_path}, inputs);
    return 0;
  }

 private:
  std::string colmap_dir_, workspace_, refs_path_, images_dir_, points_path_, mesh_path_;
  std::string gcp_path_, gcp_altitude_datum_ = "ellipsoidal";
  double gcp_sigma_m_ = 0.05;
  std::string altitude_datum_ = "ellipsoidal";
  std::string origin_;
  RobustFitOptions fit_;
  bool no_bundle_adjust_ = false;
  std::optional<double> gps_sigma_m_, focal_prior_px_, sensor_width_mm_;
  std::string quality_ = "standard", surface_ = "auto";
  std::optional<int64_t> target_faces_;
  std::optional<double> max_error_m_;
  std::optional<double> remesh_edge_m_;
  bool draco_ = false, no_timestamp_ = false;
  std::string output_dir_;
  CommonOptions common_;
};

}  // namespace

std::unique_ptr<Command> MakeMeshCommand() { return std::make_unique<MeshCommand>(); }

}  // namespace cinepath::cli

// Built as libcinepath_cmd_mesh.so, loaded by the executable only for `cinepath mesh`.
CINEPATH_COMMAND_PLUGIN(MakeMeshCommand)
