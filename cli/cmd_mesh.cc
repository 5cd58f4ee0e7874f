// cinepath mesh: COLMAP reconstruction (+ GPS references) -> cleaned, georeferenced mesh.
//   reads   COLMAP sparse model (text or binary), optional dense PLY points or a PLY mesh in the same
//           frame, references (file or EXIF), ground control points (--gcp), EXIF focal lengths
//           photos (--images, or found beside the model): EXIF, and the texture
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
#include "core/heap_pages.h"
#include "core/json.h"
#include "core/plan_file.h"
#include "photogrammetry/pipeline/build_scene.h"

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
    app.add_option("--colmap", options_.colmap_dir,
                   "COLMAP sparse model folder (cameras/images/points3D .bin or .txt), or a workspace / sparse/ folder "
                   "holding one model (sparse/0). Without it, --images "
                   "is reconstructed by running the colmap binary (CPU) in --colmap-workspace");
    app.add_option("--colmap-workspace", options_.colmap_workspace,
                   "Where COLMAP runs for photos-only input (default OUTDIR/colmap; reused when it holds a model)");
    app.add_option("--refs", options_.refs_path,
                   "References: 'image_name lat lon alt' per line (COLMAP model_aligner format; '#' comments)");
    app.add_option("--gcp", options_.gcp_path,
                   "Ground control points, OpenDroneMap gcp_list.txt format (see docs/mesh.md); alone or with "
                   "camera references");
    app.add_option("--gcp-altitude-datum", gcp_altitude_datum_,
                   "GCP heights are WGS84 ellipsoidal (default) or above mean sea level (EGM96)")
        ->check(CLI::IsMember({"ellipsoidal", "amsl"}));
    app.add_option("--gcp-sigma-m", gcp_sigma_m_, "Bundle adjustment: GCP position sigma (m)")->check(PositiveFinite());
    app.add_option("--images", options_.images_dir,
                   "Photos folder: EXIF GPS (when no --refs) and EXIF focal length (prior for the bundle "
                   "adjustment). Default: an images/ folder next to or above the model, when there is one");
    app.add_option("--points", options_.points_path, "Dense point cloud PLY (e.g. fused.ply) in the model's frame");
    app.add_option("--mesh", options_.mesh_path, "Mesh PLY (e.g. meshed-poisson.ply) in the model's frame, used as is");
    app.add_option("--altitude-datum", altitude_datum_,
                   "Reference altitudes are WGS84 ellipsoidal heights (default, as COLMAP and DJI EXIF) or "
                   "above mean sea level (EGM96)")
        ->check(CLI::IsMember({"ellipsoidal", "amsl"}));
    app.add_option("--origin", origin_, "ENU origin LAT,LON,HEIGHT (ellipsoidal m); default: mean of the references");
    app.add_option("--max-rmse-m", fit_.max_rmse_m, "Refuse (exit 3) when the georeferencing RMSE exceeds this")
        ->check(PositiveFinite());
    app.add_option("--inlier-threshold-m", fit_.inlier_threshold_m, "RANSAC inlier distance for references")
        ->check(PositiveFinite());
    app.add_option("--seed", fit_.seed, "RANSAC seed (deterministic)");
    app.add_flag("--no-bundle-adjust", no_bundle_adjust_, "Similarity fit only (as model_aligner)");
    app.add_option("--gps-sigma-m", gps_sigma_m_, "Bundle adjustment: GPS camera-centre sigma (m)")
        ->check(PositiveFinite());
    app.add_option("--focal-prior-px", options_.focal_prior_px,
                   "Focal-length prior (px) for every camera; overrides EXIF")
        ->check(PositiveFinite());
    app.add_option("--sensor-width-mm", options_.sensor_width_mm, "Sensor width for EXIF FocalLength -> pixels")
        ->check(PositiveFinite());
    AddQualityOption(app, &quality_, "Poisson depth, height-field density, face budget, simplifier, texture size");
    app.add_option("--surface", surface_, "auto | height-field | poisson");
    app.add_option("--target-faces", options_.surface.target_faces, "Simplify to at most N faces")
        ->check(PositiveFinite());
    app.add_option("--max-error-m", options_.surface.max_error_m, "Simplify within this Hausdorff error (m)")
        ->check(PositiveFinite());
    app.add_option("--remesh-edge-m", options_.surface.remesh_edge_m,
                   "After simplifying, remesh isotropically to edges of about L m")
        ->check(PositiveFinite());
    app.add_flag("--no-texture", no_texture_, "Vertex colours only: do not texture the mesh from the photos");
    app.add_option("--texture-px", texture_px_,
                   "Texture atlas size in texels (square; default per --quality: draft 2048, standard 4096, "
                   "final 8192)")
        ->check(CLI::Range(64, 16384));
    app.add_option("--texture-format", texture_format_, "jpeg (default, quality --texture-jpeg-quality) | png")
        ->check(CLI::IsMember({"jpeg", "png"}));
    app.add_option("--texture-jpeg-quality", options_.texture_options.jpeg_quality, "JPEG quality 1..100 (default 90)")
        ->check(CLI::Range(1, 100));
    app.add_option("--texture-exclude", options_.texture_options.excluded_images,
                   "Never texture from this photo (image name as in the model; repeatable)");
    app.add_option("--for-plan", for_plan_path_,
                   "plan.json (one drone or several): simplify each region only as far as the plan's closest camera "
                   "that sees it can tell (placed by its origin; excludes --target-faces, --max-error-m)");
    app.add_option("--max-error-px", options_.max_error_px,
                   "With --for-plan: the largest geometric error, projected into that camera, in pixels")
        ->check(PositiveFinite());
    app.add_flag("--draco", draco_, "Compress the GLB with KHR_draco_mesh_compression");
    app.add_flag("--no-timestamp", no_timestamp_, "Leave wall-clock times out of scene.json (byte-identical runs)");
    app.add_option("-o,--output", output_dir_, "Output folder (scene.glb, scene.json)")->required();
    common_.Add(app);
  }

  int Run() override {
    // The cleaning and the decimation allocate arrays over every face and vertex, and each tile its own:
    // freed memory kept and the main thread's heap in 2 MiB pages (core/heap_pages.h).
    PrepareHeapForLargeBuffers(kCommandHeapReserveBytes);
    options_.georeference.fit = fit_;
    options_.georeference.altitude_datum =
        altitude_datum_ == "amsl" ? AltitudeDatum::kAmslEgm96 : AltitudeDatum::kEllipsoidal;
    if (!origin_.empty()) options_.georeference.origin = ParseOrigin(origin_);
    options_.georeference.bundle_adjust = !no_bundle_adjust_;
    if (gps_sigma_m_) {
      options_.georeference.ba.gps_sigma_horizontal_m = options_.georeference.ba.gps_sigma_vertical_m = *gps_sigma_m_;
    }
    options_.georeference.gcp_altitude_datum =
        gcp_altitude_datum_ == "amsl" ? AltitudeDatum::kAmslEgm96 : AltitudeDatum::kEllipsoidal;
    options_.georeference.gcp_sigma_horizontal_m = options_.georeference.gcp_sigma_vertical_m = gcp_sigma_m_;
    options_.surface.quality = ParseQuality(quality_);
    options_.surface.method = ParseSurfaceMethod(surface_);
    options_.surface.draco = draco_;
    options_.timestamps = !no_timestamp_;
    options_.texture = !no_texture_;
    options_.texture_px = texture_px_;
    options_.texture_options.format = texture_format_ == "png" ? TextureFormat::kPng : TextureFormat::kJpeg;
    options_.output_dir = output_dir_;
    if (!for_plan_path_.empty()) {
      options_.for_plan = ReadTeamPlanFile(for_plan_path_);  // one drone or several; InputError naming the file
      PrintWarnings("mesh", TeamPlanNotes(*options_.for_plan));
      options_.for_plan_path = for_plan_path_;
    }

    const bool tty = isatty(STDERR_FILENO) != 0 || common_.progress_mode() == ProgressMode::kAlways;
    SceneBuildLog log;
    log.colmap_step = [&](const std::string& step) {
      if (tty && common_.progress_mode() != ProgressMode::kNever) std::cerr << "cinepath mesh: colmap " << step << "\n";
    };
    log.note = [](const std::string& note) { std::cerr << "cinepath mesh: " << note << "\n"; };
    log.warning = [this](const std::string& w) {
      std::cerr << "cinepath mesh: warning: " << WithFlagNames(w, field_flags()) << "\n";
    };
    const SceneBuildResult result = BuildScene(options_, log);

    EnsureDirectory(output_dir_);
    AtomicOutputs outputs;
    const std::string glb_path = (fs::path(output_dir_) / "scene.glb").string();
    const std::string json_path = (fs::path(output_dir_) / "scene.json").string();
    outputs.Add(glb_path, result.glb);
    outputs.Add(json_path, DumpJson(result.scene));
    outputs.Commit();
    common_.WriteDepfileIfAsked({glb_path, json_path}, result.inputs);
    return 0;
  }

  FieldFlags field_flags() const override {
    return {{"colmap_dir", "--colmap"},
            {"images_dir", "--images"},
            {"refs_path", "--refs"},
            {"gcp_path", "--gcp"},
            {"points_path", "--points"},
            {"mesh_path", "--mesh"},
            {"target_faces", "--target-faces"},
            {"max_error_m", "--max-error-m"},
            {"remesh_edge_m", "--remesh-edge-m"},
            {"for_plan_path", "--for-plan"},
            {"max_error_px", "--max-error-px"},
            {"max_rmse_m", "--max-rmse-m"},
            {"altitude_datum", "--altitude-datum"},
            {"focal_prior_px", "--focal-prior-px"},
            {"texture_px", "--texture-px"},
            {"jpeg_quality", "--texture-jpeg-quality"},
            {"texture_exclude", "--texture-exclude"},
            {"progress", "--progress"}};
  }

 private:
  SceneBuildOptions options_;
  std::string gcp_altitude_datum_ = "ellipsoidal";
  double gcp_sigma_m_ = 0.05;
  std::string altitude_datum_ = "ellipsoidal";
  std::string origin_;
  RobustFitOptions fit_;
  bool no_bundle_adjust_ = false;
  std::optional<double> gps_sigma_m_;
  std::string quality_ = "standard", surface_ = "auto";
  bool draco_ = false, no_timestamp_ = false, no_texture_ = false;
  std::optional<int> texture_px_;
  std::string texture_format_ = "jpeg";
  std::string output_dir_;
  std::string for_plan_path_;
  CommonOptions common_;
};

}  // namespace

std::unique_ptr<Command> MakeMeshCommand() { return std::make_unique<MeshCommand>(); }

}  // namespace cinepath::cli

// Built as libcinepath_cmd_mesh.so, loaded by the executable only for `cinepath mesh`.
CINEPATH_COMMAND_PLUGIN(MakeMeshCommand)
