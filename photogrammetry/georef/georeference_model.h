// Georeferencing a COLMAP model end to end: references -> ENU, robust similarity, bundle adjustment
// with GPS and focal priors, refit; the ENU point cloud for surface reconstruction and the report that
// goes into scene.json.
//
// Steps:
//   1. References (refs_file.h or EXIF) are matched to registered images by name (else by the file name
//      without folders, when that is unique on both sides); their altitude is
//      converted to WGS84 ellipsoidal height (AltitudeDatum; EGM96 from core/geoid.h).
//   2. Origin: given, or the mean latitude, longitude and ellipsoidal height of the matched references.
//   3. enu_from_colmap: FitSimilarityRobust (georeference.h) of the camera centres to the references.
//   4. Bundle adjustment (bundle_adjust.h) of the model moved into ENU, with the inlier references as
//      camera-centre priors and the focal prior when one is known; its focal-length profile says
//      whether the images resolve focal length vs flying height. When they do not and no focal prior is
//      known, a warning says so (and by how much the heights may be off).
//   5. Refit: the similarity from the adjusted camera centres to the references (normally close to the
//      identity) is applied; its residuals are the final report.
//
// Ground control points (gcp_file.h), alone or with camera references:
//   * each GCP is triangulated in the COLMAP frame from its pixel observations (triangulation.h); one
//     with fewer than 2 usable observations, a weak triangulation angle or no elevation is reported
//     and skipped;
//   * the similarity (step 3) is fitted to the GCPs alone when 3 or more are usable (survey points are
//     centimetre-accurate, camera GPS metre-accurate: mixing them unweighted would let a biased GPS win
//     the RANSAC vote); with 1 or 2 usable GCPs they join the camera references as extra pairs. Camera
//     references are still matched and their residuals against the result reported;
//   * in the bundle adjustment (step 4) every usable GCP is a point with its observations and a
//     position prior (gcp_sigma_*); camera GPS priors are kept only for references within the inlier
//     threshold of the GCP-defined frame;
//   * the refit (step 5) uses the same pairs as step 3; each GCP is then re-triangulated in the final
//     model and its residual against the surveyed position reported (a check independent of its prior).
// The origin defaults to the mean of the matched camera references, or of the usable GCPs without them.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/geodesy.h"
#include "core/json.h"
#include "photogrammetry/georef/bundle_adjust.h"
#include "photogrammetry/georef/georeference.h"
#include "photogrammetry/georef/triangulation.h"
#include "photogrammetry/io/colmap_model.h"
#include "photogrammetry/io/gcp_file.h"
#include "photogrammetry/io/point_cloud.h"
#include "photogrammetry/io/refs_file.h"

namespace cinepath::photogrammetry {

// What the reference altitudes are measured from. EXIF GPSAltitude is defined as above sea level, but
// many drones (DJI among them, Brighton Beach's included) write WGS84 ellipsoidal heights there, and
// COLMAP treats it as ellipsoidal; default: ellipsoidal (as COLMAP's model_aligner).
enum class AltitudeDatum { kEllipsoidal, kAmslEgm96 };
const char* AltitudeDatumName(AltitudeDatum datum);  // "ellipsoidal" / "amsl_egm96"

struct ModelGeoreferenceOptions {
  RobustFitOptions fit;
  AltitudeDatum altitude_datum = AltitudeDatum::kEllipsoidal;
  std::optional<Geodetic> origin;  // default: mean of the matched references
  bool bundle_adjust = true;
  BundleAdjustOptions ba;
  std::map<uint32_t, double> focal_prior_px;  // camera id -> prior focal length (px)
  std::string focal_prior_source;             // e.g. "EXIF FocalLength 3.61 mm, sensor 6.317 mm"
  // Ground control points.
  AltitudeDatum gcp_altitude_datum = AltitudeDatum::kEllipsoidal;
  TriangulationOptions triangulation;
  double gcp_sigma_horizontal_m = 0.05;  // position prior in the bundle adjustment
  double gcp_sigma_vertical_m = 0.05;
};

struct GcpUse {
  GroundControlPoint gcp;
  std::vector<std::optional<uint32_t>> image_ids;  // per observation; unset: no registered image of that name
  double height_ellipsoidal_m = 0;
  Eigen::Vector3d enu_m = Eigen::Vector3d::Zero();     // surveyed position
  Triangulation triangulation;                         // in the input (COLMAP) frame
  std::vector<ObservationResult> observation_results;  // per file observation (gcp.observations)
  bool usable = false;
  std::string skipped_reason;                           // when not usable
  std::optional<size_t> pair_index;                     // in the fits' pair lists
  std::optional<Triangulation> final_triangulation;     // in the final ENU model
  std::optional<Eigen::Vector3d> final_residual_enu_m;  // re-triangulated minus surveyed
};

struct ReferenceUse {
  ImageReference reference;
  double height_ellipsoidal_m = 0;
  std::optional<uint32_t> image_id;   // unset: no registered image of that name
  bool matched_by_file_name = false;  // matched on the name without folders (unique on both sides)
  Eigen::Vector3d enu_m = Eigen::Vector3d::Zero();
  // Filled for matched references (index into the fits' pair lists).
  std::optional<size_t> pair_index;
};

struct ModelGeoreference {
  Geodetic origin;
  double geoid_undulation_m = 0;
  Similarity3 enu_from_colmap;  // the first, similarity-only fit
  RobustFit first_fit;
  std::optional<BundleAdjustReport> bundle_adjustment;
  RobustFit final_fit;    // adjusted camera centres vs references, after the refit
  ColmapModel model_enu;  // final model in ENU metres
  std::vector<ReferenceUse> references;
  std::vector<GcpUse> gcps;
  std::optional<GcpCoordinateSystem> gcp_crs;
  // What the fits' pairs are: "cameras", "gcps" or "cameras+gcps"; pair i is a camera reference
  // (pair_is_gcp[i] false, pair_label = image name) or a GCP (label = its name).
  std::string fit_references;
  std::vector<bool> pair_is_gcp;
  std::vector<std::string> pair_labels;
  std::vector<Eigen::Vector3d> pair_targets_enu_m;
  std::vector<Eigen::Vector3d> pair_final_enu_m;  // the pairs' sources in the final model
  // Camera references against the final model (also when they were not fit pairs): |C - ref| (m).
  std::map<size_t, double> camera_residuals_m;  // index into references
  double gcp_check_rmse_m = 0;                  // over the re-triangulated usable GCPs
  std::vector<std::string> warnings;
};

// InfeasibleError when no reference names a registered image and no GCP is usable; InfeasibleError
// from the fits.
ModelGeoreference GeoreferenceModel(const ColmapModel& model, const std::vector<ImageReference>& references,
                                    const ModelGeoreferenceOptions& options);
ModelGeoreference GeoreferenceModel(const ColmapModel& model, const std::vector<ImageReference>& references,
                                    const GcpFile* gcps, const ModelGeoreferenceOptions& options);

// The model's 3D points (tracks of length >= 2) as a PointCloud: ENU positions, colours, reprojection
// errors, camera centres and the observers of each point.
PointCloud PointCloudFromModel(const ColmapModel& model);

// Applies x -> T(x) to points and camera poses (rotations compose, centres map, intrinsics unchanged).
ColmapModel TransformModel(const ColmapModel& model, const Similarity3& target_from_source);

// The affine map taking the input model's frame to the final ENU frame, fitted by least squares over the
// 3D points both models share. After bundle adjustment it is not a similarity (depths were rescaled
// with the focal length), so a dense cloud or mesh given in COLMAP's frame is mapped with this.
struct AffineMap {
  Eigen::Matrix3d linear = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  double rms_m = 0;              // residual over the fitted points
  bool similarity_only = false;  // the points lie on a plane: a similarity, not an affine map
  Eigen::Vector3d operator()(const Eigen::Vector3d& x) const { return linear * x + translation; }
};
// The affine map from `from`'s frame to `to`'s, least squares over the 3D points both hold (seen by two or
// more images). Points on a plane give the similarity instead (`similarity_only`); fewer than 3 points, or
// points on a line, throw InputError.
AffineMap FitAffineBetweenModels(const ColmapModel& from, const ColmapModel& to);

// scene.json members this part owns: {"origin": ..., "enu_from_colmap": ..., "georeferencing": ...}.
// `include_timing` adds wall-clock times (off for byte-identical outputs).
Json GeoreferenceJson(const ModelGeoreference& result, const ModelGeoreferenceOptions& options, bool include_timing);

}  // namespace cinepath::photogrammetry
