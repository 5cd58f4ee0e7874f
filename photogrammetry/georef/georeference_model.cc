#include "photogrammetry/georef/georeference_model.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>

#include <Eigen/Eigenvalues>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/fatal_signal.h"
#include "core/geoid.h"
#include "core/number_format.h"
#include "photogrammetry/georef/camera_models.h"

namespace cinepath::photogrammetry {
namespace {

double Round(double v, int decimals) { return RoundToDecimals(v, decimals); }

Json Vec(const Eigen::Vector3d& v, int decimals) {
  return Json::array({Round(v.x(), decimals), Round(v.y(), decimals), Round(v.z(), decimals)});
}

Json FitJson(const RobustFit& fit, const ModelGeoreference& r, bool with_vectors) {
  Json residuals = Json::array();
  for (size_t i = 0; i < r.pair_labels.size(); ++i) {
    Json item = Json::object();
    item[r.pair_is_gcp[i] ? "gcp" : "image"] = r.pair_labels[i];
    if (with_vectors) item["residual_enu_m"] = Vec(r.pair_final_enu_m[i] - r.pair_targets_enu_m[i], 3);
    item["residual_m"] = Round(fit.residuals_m[i], 3);
    item["inlier"] = static_cast<bool>(fit.inliers[i]);
    residuals.push_back(item);
  }
  Json j = Json::object();
  j["rmse_m"] = Round(fit.rmse_m, 4);
  j["rmse_all_m"] = Round(fit.rmse_all_m, 4);
  j["num_inliers"] = fit.num_inliers;
  j["num_references"] = static_cast<int>(fit.residuals_m.size());
  j["residuals"] = residuals;
  return j;
}

}  // namespace

const char* AltitudeDatumName(AltitudeDatum datum) {
  return datum == AltitudeDatum::kEllipsoidal ? "ellipsoidal" : "amsl_egm96";
}

ColmapModel TransformModel(const ColmapModel& model, const Similarity3& t) {
  ColmapModel out = model;
  for (auto& [id, image] : out.images) {
    const Eigen::Vector3d c = t(image.ProjectionCenter());
    image.cam_from_world_rotation = (image.cam_from_world_rotation * t.rotation.conjugate()).normalized();
    image.cam_from_world_translation = -(image.cam_from_world_rotation * c);
  }
  for (auto& [id, point] : out.points3d) point.xyz = t(point.xyz);
  return out;
}

AffineMap FitAffineBetweenModels(const ColmapModel& from, const ColmapModel& to) {
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> pairs;
  for (const auto& [id, p] : from.points3d) {
    const auto it = to.points3d.find(id);
    if (it != to.points3d.end() && p.track.size() >= 2) pairs.emplace_back(p.xyz, it->second.xyz);
  }
  if (pairs.size() < 3) {
    throw InputError("mapping the dense input into ENU: the COLMAP model has " + std::to_string(pairs.size()) +
                     " 3D points seen by two or more images; at least 3 are needed");
  }
  Eigen::Vector3d cx = Eigen::Vector3d::Zero(), cy = Eigen::Vector3d::Zero();
  for (const auto& [x, y] : pairs) cx += x, cy += y;
  cx /= static_cast<double>(pairs.size());
  cy /= static_cast<double>(pairs.size());
  Eigen::Matrix3d xx = Eigen::Matrix3d::Zero(), yx = Eigen::Matrix3d::Zero();
  for (const auto& [x, y] : pairs) {
    xx += (x - cx) * (x - cx).transpose();
    yx += (y - cy) * (x - cx).transpose();
  }
  // Guard before the solve: points on a plane or a line leave the normal equations singular, and
  // the inverse would be inf/NaN. Their spread's eigenvalues say so; then the similarity (which a plane of
  // points does determine, a line does not) maps the input.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> spread(xx);
  const Eigen::Vector3d ev = spread.eigenvalues();  // ascending
  const double kCondition = 1e-10;
  AffineMap map;
  if (!(ev(2) > 0) || ev(1) <= kCondition * ev(2)) {
    throw InputError(
        "mapping the dense input into ENU: the COLMAP model's 3D points lie on a line (or coincide); "
        "they do not fix the dense input's position");
  }
  if (ev(0) > kCondition * ev(2)) {
    map.linear = yx * xx.inverse();
    map.translation = cy - map.linear * cx;
  } else {
    std::vector<Eigen::Vector3d> source, target;
    for (const auto& [x, y] : pairs) source.push_back(x), target.push_back(y);
    const Similarity3 t = FitSimilarityLeastSquares(source, target);
    map.linear = t.scale * t.rotation.toRotationMatrix();
    map.translation = t.translation;
    map.similarity_only = true;
  }
  double sum = 0;
  for (const auto& [x, y] : pairs) sum += (map(x) - y).squaredNorm();
  map.rms_m = std::sqrt(sum / static_cast<double>(pairs.size()));
  return map;
}

PointCloud PointCloudFromModel(const ColmapModel& model) {
  PointCloud cloud;
  std::map<uint32_t, uint32_t> camera_index;
  for (const auto& [id, image] : model.images) {
    camera_index[id] = static_cast<uint32_t>(cloud.camera_centers_m.size());
    cloud.camera_centers_m.push_back(image.ProjectionCenter());
  }
  for (const auto& [id, point] : model.points3d) {
    if (point.track.size() < 2) continue;
    cloud.positions_m.push_back(point.xyz);
    cloud.colors_rgb.push_back(point.rgb);
    cloud.reprojection_error_px.push_back(point.error_px);
    std::vector<uint32_t> observers;
    for (const auto& e : point.track) observers.push_back(camera_index.at(e.image_id));
    std::sort(observers.begin(), observers.end());
    observers.erase(std::unique(observers.begin(), observers.end()), observers.end());
    cloud.observers.push_back(std::move(observers));
  }
  return cloud;
}

ModelGeoreference GeoreferenceModel(const ColmapModel& model, const std::vector<ImageReference>& references,
                                    const ModelGeoreferenceOptions& options) {
  return GeoreferenceModel(model, references, nullptr, options);
}

namespace {

// The model's images by name, and by file name without folders (references written with other paths,
// "C:/flight/DJI_0018.JPG" or "images/DJI_0018.JPG" vs COLMAP's "DJI_0018.JPG").
struct ImageNames {
  std::map<std::string, uint32_t> by_name;
  std::map<std::string, std::vector<uint32_t>> by_base;

  static std::string BaseName(const std::string& name) {
    const size_t slash = name.find_last_of("/\\");
    return slash == std::string::npos ? name : name.substr(slash + 1);
  }
  // The exact name, else a file name unique among the images (and, when `unique_base_in_refs` is
  // given, unique among the references too).
  std::optional<uint32_t> Find(const std::string& name, bool* by_file_name = nullptr,
                               const std::map<std::string, int>* unique_base_in_refs = nullptr) const {
    if (const auto it = by_name.find(name); it != by_name.end()) return it->second;
    const std::string base = BaseName(name);
    const auto b = by_base.find(base);
    if (b == by_base.end() || b->second.size() != 1) return std::nullopt;
    if (unique_base_in_refs && unique_base_in_refs->at(base) != 1) return std::nullopt;
    if (by_file_name) *by_file_name = true;
    return b->second.front();
  }
};

ImageNames IndexImageNames(const ColmapModel& model) {
  ImageNames names;
  for (const auto& [id, image] : model.images) {
    names.by_name[image.name] = id;
    names.by_base[ImageNames::BaseName(image.name)].push_back(id);
  }
  return names;
}

double EllipsoidalHeightM(AltitudeDatum datum, double lat_deg, double lon_deg, double height_m) {
  return datum == AltitudeDatum::kEllipsoidal ? height_m
                                              : Egm96Geoid::Default().EllipsoidalFromAmslM(lat_deg, lon_deg, height_m);
}

// Step 1: each camera reference matched to a registered image, its height made ellipsoidal.
std::vector<ReferenceUse> MatchReferences(const std::vector<ImageReference>& references, const ImageNames& names,
                                          const ModelGeoreferenceOptions& options) {
  std::map<std::string, int> ref_base_count;
  for (const ImageReference& ref : references) ++ref_base_count[ImageNames::BaseName(ref.image_name)];
  std::vector<ReferenceUse> uses;
  for (const ImageReference& ref : references) {
    ReferenceUse use;
    use.reference = ref;
    use.height_ellipsoidal_m = EllipsoidalHeightM(options.altitude_datum, ref.lat_deg, ref.lon_deg, ref.alt_m);
    use.image_id = names.Find(ref.image_name, &use.matched_by_file_name, &ref_base_count);
    uses.push_back(use);
  }
  return uses;
}

// The pixel observations of a GCP that its triangulation used (the one filter for every re-triangulation).
std::vector<PixelObservation> UsedObservations(const GcpUse& u) {
  std::vector<PixelObservation> obs;
  for (size_t k = 0; k < u.observation_results.size(); ++k) {
    if (u.observation_results[k].used) obs.push_back({*u.image_ids[k], u.gcp.observations[k].pixel_colmap});
  }
  return obs;
}

// Step 2: ground control points, their images matched and the points triangulated in the COLMAP frame.
std::vector<GcpUse> TriangulateGcps(const GcpFile& file, const ColmapModel& model, const ImageNames& names,
                                    const ModelGeoreferenceOptions& options, std::vector<std::string>* warnings) {
  std::vector<GcpUse> uses;
  for (const GroundControlPoint& p : file.points) {
    GcpUse u;
    u.gcp = p;
    std::vector<PixelObservation> obs;
    std::vector<size_t> obs_index;  // file observation of each triangulated one
    u.observation_results.resize(p.observations.size());
    for (size_t k = 0; k < p.observations.size(); ++k) {
      const std::optional<uint32_t> id = names.Find(p.observations[k].image_name);
      u.image_ids.push_back(id);
      if (!id) {
        u.observation_results[k].note = "no registered image of that name";
        continue;
      }
      obs.push_back({*id, p.observations[k].pixel_colmap});
      obs_index.push_back(k);
    }
    u.triangulation = TriangulatePoint(model, obs, options.triangulation);
    for (size_t j = 0; j < obs.size(); ++j) u.observation_results[obs_index[j]] = u.triangulation.observations[j];
    if (p.geo_z_m)
      u.height_ellipsoidal_m = EllipsoidalHeightM(options.gcp_altitude_datum, p.lat_deg, p.lon_deg, *p.geo_z_m);
    if (!p.geo_z_m) {
      u.skipped_reason = "no elevation (geo_z is NaN)";
    } else if (!u.triangulation.ok) {
      u.skipped_reason = u.triangulation.reason;
    } else {
      u.usable = true;
    }
    if (!u.usable)
      warnings->push_back("ground control point '" + p.name + "' (" + p.where + ") skipped: " + u.skipped_reason);
    uses.push_back(std::move(u));
  }
  return uses;
}

// Step 3: refuse when nothing can be fitted; warn when GCPs alone are.
void RequireSomethingToFit(const ColmapModel& model, const std::vector<ImageReference>& references,
                           const GcpFile* gcp_file, size_t matched, size_t usable_gcps,
                           std::vector<std::string>* warnings) {
  if (matched == 0 && usable_gcps == 0) {
    std::string example = references.empty() ? "(none)" : references.front().image_name;
    std::string image_example = model.images.empty() ? "(none)" : model.images.begin()->second.name;
    if (gcp_file) {
      throw InfeasibleError("georeferencing: none of the " + std::to_string(gcp_file->points.size()) +
                            " ground control points is usable (see the warnings above)" +
                            (references.empty() ? std::string()
                                                : " and none of the " + std::to_string(references.size()) +
                                                      " references names a registered image"));
    }
    throw InfeasibleError("georeferencing: none of the " + std::to_string(references.size()) +
                          " references names a registered image (references name e.g. '" + example +
                          "', the model's images are named e.g. '" + image_example + "')");
  }
  if (gcp_file && !references.empty() && matched == 0) {
    warnings->push_back("none of the " + std::to_string(references.size()) +
                        " camera references names a registered image; georeferencing with the ground control "
                        "points alone");
  }
}

// Step 4: the origin: given, else the mean of the matched camera references, else of the usable GCPs.
// Longitudes are averaged about the first one so that the antimeridian does no harm.
Geodetic ChooseOrigin(const ModelGeoreference& r, const ModelGeoreferenceOptions& options, size_t matched) {
  if (options.origin) return *options.origin;
  double lat = 0, lon = 0, h = 0, n = 0, lon0 = 0;
  bool first = true;
  auto add = [&](double lat_deg, double lon_deg, double height_m) {
    if (first) lon0 = lon_deg, first = false;
    lat += lat_deg;
    lon += std::remainder(lon_deg - lon0, 360.0);
    h += height_m;
    n += 1;
  };
  if (matched > 0) {
    for (const auto& u : r.references) {
      if (u.image_id) add(u.reference.lat_deg, u.reference.lon_deg, u.height_ellipsoidal_m);
    }
  } else {
    for (const auto& g : r.gcps) {
      if (g.usable) add(g.gcp.lat_deg, g.gcp.lon_deg, g.height_ellipsoidal_m);
    }
  }
  return Geodetic{lat / n, std::remainder(lon0 + lon / n, 360.0), h / n};
}

// The fits' pairs: source in the COLMAP frame, target in ENU.
struct FitPairs {
  std::vector<Eigen::Vector3d> source, target;
  std::vector<uint32_t> image;  // camera pairs: image id; GCP pairs: unused
  std::vector<size_t> gcp;      // GCP pairs: index into ModelGeoreference::gcps
  std::string what;             // for messages
};

// Step 5: the usable GCPs alone when there are 3 or more, else the camera references followed by the
// usable GCPs. Also puts every reference and GCP into ENU.
FitPairs BuildFitPairs(ModelGeoreference& r, const ColmapModel& model, const EnuFrame& frame, size_t usable_gcps) {
  const bool gcp_frame = usable_gcps >= 3;
  FitPairs pairs;
  for (auto& u : r.references) {
    u.enu_m = frame.EnuFromGeodetic({u.reference.lat_deg, u.reference.lon_deg, u.height_ellipsoidal_m});
    if (!u.image_id || gcp_frame) continue;
    u.pair_index = pairs.source.size();
    pairs.source.push_back(model.images.at(*u.image_id).ProjectionCenter());
    pairs.target.push_back(u.enu_m);
    pairs.image.push_back(*u.image_id);
    pairs.gcp.push_back(SIZE_MAX);
    r.pair_is_gcp.push_back(false);
    r.pair_labels.push_back(u.reference.image_name);
  }
  for (size_t g = 0; g < r.gcps.size(); ++g) {
    GcpUse& u = r.gcps[g];
    u.enu_m = frame.EnuFromGeodetic({u.gcp.lat_deg, u.gcp.lon_deg, u.height_ellipsoidal_m});
    if (!u.usable) continue;
    u.pair_index = pairs.source.size();
    pairs.source.push_back(u.triangulation.xyz);
    pairs.target.push_back(u.enu_m);
    pairs.image.push_back(0);
    pairs.gcp.push_back(g);
    r.pair_is_gcp.push_back(true);
    r.pair_labels.push_back(u.gcp.name);
  }
  r.pair_targets_enu_m = pairs.target;
  r.fit_references = gcp_frame ? "gcps" : (usable_gcps > 0 ? "cameras+gcps" : "cameras");
  pairs.what = gcp_frame ? "ground control points"
                         : (usable_gcps > 0 ? "references (cameras and ground control points)" : "references");
  return pairs;
}

// GPS priors for the bundle adjustment: in a GCP-defined frame, the camera references that agree with
// it; else the inlier camera pairs of the first fit.
std::map<uint32_t, Eigen::Vector3d> GpsPriors(const ModelGeoreference& r, const FitPairs& pairs,
                                              const ModelGeoreferenceOptions& options) {
  std::map<uint32_t, Eigen::Vector3d> gps;
  if (r.fit_references == "gcps") {
    for (const auto& u : r.references) {
      if (!u.image_id) continue;
      const Eigen::Vector3d c = r.model_enu.images.at(*u.image_id).ProjectionCenter();
      if ((c - u.enu_m).norm() <= options.fit.inlier_threshold_m) gps[*u.image_id] = u.enu_m;
    }
  } else {
    for (size_t i = 0; i < pairs.image.size(); ++i) {
      if (!r.pair_is_gcp[i] && r.first_fit.inliers[i]) gps[pairs.image[i]] = pairs.target[i];
    }
  }
  return gps;
}

// The inlier GCP pairs as control-point priors; `control_pair` receives each one's pair index.
std::vector<ControlPointPrior> ControlPriors(const ModelGeoreference& r, const FitPairs& pairs,
                                             const ModelGeoreferenceOptions& options,
                                             std::vector<size_t>* control_pair) {
  std::vector<ControlPointPrior> control;
  for (size_t i = 0; i < pairs.source.size(); ++i) {
    if (!r.pair_is_gcp[i] || !r.first_fit.inliers[i]) continue;
    const GcpUse& u = r.gcps[pairs.gcp[i]];
    ControlPointPrior c;
    c.observations = UsedObservations(u);
    c.initial_enu_m = r.enu_from_colmap(u.triangulation.xyz);
    c.target_enu_m = u.enu_m;
    c.sigma_horizontal_m = options.gcp_sigma_horizontal_m;
    c.sigma_vertical_m = options.gcp_sigma_vertical_m;
    control.push_back(std::move(c));
    control_pair->push_back(i);
  }
  return control;
}

// The median camera-to-point depth, to translate a focal-length uncertainty into metres.
double MedianPointDepthM(const ColmapModel& model) {
  std::vector<double> depths;
  for (const auto& [id, point] : model.points3d) {
    for (const auto& e : point.track) {
      const auto& im = model.images.at(e.image_id);
      depths.push_back((im.cam_from_world_rotation * point.xyz + im.cam_from_world_translation).z());
    }
  }
  if (depths.empty()) return 0;
  std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
  return depths[depths.size() / 2];
}

// What the bundle adjustment found about each camera's focal length, as warnings a crew can act on.
void AddFocalWarnings(const BundleAdjustReport& ba, double median_depth_m, const ModelGeoreferenceOptions& options,
                      std::vector<std::string>* warnings) {
  for (const FocalReport& f : ba.focal) {
    const std::string cam = "camera " + std::to_string(f.camera_id) + ": ";
    const std::string sigma =
        (f.images_sigma_ratio ? "formal sigma " + FormatFixed(100 * *f.images_sigma_ratio, 2) + " %"
                              : std::string("formal sigma unbounded")) +
        (ba.geometry_resolves_focal
             ? std::string()
             : "; near-flat scene (depth relief " + FormatFixed(100 * ba.depth_relief_ratio, 1) +
                   " %) under near-parallel views (axes within " + FormatFixed(ba.view_axis_spread_deg, 1) + " deg)");
    if (f.images_conflict_with_prior && f.images_preferred_px && f.prior_px) {
      warnings->push_back(cam + "the images pull the focal length to " + FormatFixed(*f.images_preferred_px, 1) +
                          " px (" + FormatFixed(100 * (*f.images_preferred_px / *f.prior_px - 1), 1) +
                          " % from the prior " + FormatFixed(*f.prior_px, 1) + " px; " + sigma +
                          "): the focal-length/flying-height ambiguity of a flat scene seen from above, not a "
                          "measurement; the focal length is held at the prior (" +
                          options.focal_prior_source + ")");
    } else if (f.prior_px) {
      if (!f.images_resolve_focal) {
        warnings->push_back(cam + "the images cannot resolve focal length vs flying height (" + sigma +
                            "); the focal length is held at the prior (" + options.focal_prior_source + ")");
      }
    } else if (!f.images_resolve_focal) {
      warnings->push_back(cam + "the images cannot resolve focal length vs flying height (" + sigma +
                          ") and no focal-length prior is known (neither the photos' EXIF nor a given prior)" +
                          ": heights above ground scale with the focal-length error (COLMAP's focal length is taken "
                          "as is; each 1 % error moves the ground by " +
                          FormatFixed(0.01 * median_depth_m, 2) + " m at the median depth of " +
                          FormatFixed(median_depth_m, 1) + " m)");
    }
    if (f.measured_by_images && f.prior_px && std::abs(f.after_px / *f.prior_px - 1) > 0.02) {
      warnings->push_back(cam + "the focal length the photos measure (" + FormatFixed(f.after_px, 1) + " px; " + sigma +
                          ") is kept; the prior (" + FormatFixed(*f.prior_px, 1) + " px, " +
                          options.focal_prior_source + ") is " + FormatFixed(100 * (*f.prior_px / f.after_px - 1), 1) +
                          " % off it (EXIF 35 mm equivalents are rounded)");
    } else if (f.prior_px && std::abs(f.before_px / *f.prior_px - 1) > 0.05) {
      warnings->push_back(cam + "COLMAP's focal length (" + FormatFixed(f.before_px, 1) +
                          " px) differs from the prior (" + FormatFixed(*f.prior_px, 1) + " px) by " +
                          FormatFixed(100 * (f.before_px / *f.prior_px - 1), 1) + " %; adjusted to " +
                          FormatFixed(f.after_px, 1) + " px");
    }
  }
}

// The pairs' sources in the adjusted model: camera centres; adjusted GCPs, re-triangulated when they
// were not in the adjustment.
std::vector<Eigen::Vector3d> AdjustedPairSources(const ModelGeoreference& r, const FitPairs& pairs,
                                                 const std::vector<size_t>& control_pair,
                                                 const std::vector<Eigen::Vector3d>& control_adjusted,
                                                 const ModelGeoreferenceOptions& options) {
  std::vector<Eigen::Vector3d> adjusted(pairs.source.size());
  for (size_t i = 0; i < pairs.source.size(); ++i) {
    if (!r.pair_is_gcp[i]) {
      adjusted[i] = r.model_enu.images.at(pairs.image[i]).ProjectionCenter();
      continue;
    }
    const auto c = std::find(control_pair.begin(), control_pair.end(), i);
    if (c != control_pair.end()) {
      adjusted[i] = control_adjusted[c - control_pair.begin()];
      continue;
    }
    const GcpUse& u = r.gcps[pairs.gcp[i]];
    const Triangulation t = TriangulatePoint(r.model_enu, UsedObservations(u), options.triangulation);
    adjusted[i] = t.ok ? t.xyz : r.enu_from_colmap(u.triangulation.xyz);
  }
  return adjusted;
}

// Step 7: bundle adjustment in ENU with GPS and GCP priors, then a refit on the same pairs.
void BundleAdjustAndRefit(ModelGeoreference& r, const FitPairs& pairs, const ModelGeoreferenceOptions& options) {
  const std::map<uint32_t, Eigen::Vector3d> gps = GpsPriors(r, pairs, options);
  std::vector<size_t> control_pair;
  const std::vector<ControlPointPrior> control = ControlPriors(r, pairs, options, &control_pair);
  std::vector<Eigen::Vector3d> control_adjusted;
  const CurrentStep running("georeference: bundle adjustment (Ceres)");
  r.bundle_adjustment =
      BundleAdjustEnu(r.model_enu, gps, options.focal_prior_px, options.ba, control, &control_adjusted);
  AddFocalWarnings(*r.bundle_adjustment, MedianPointDepthM(r.model_enu), options, &r.warnings);
  const std::vector<Eigen::Vector3d> adjusted = AdjustedPairSources(r, pairs, control_pair, control_adjusted, options);
  r.final_fit = FitSimilarityRobust(adjusted, pairs.target, options.fit, pairs.what);
  r.model_enu = TransformModel(r.model_enu, r.final_fit.target_from_source);
  for (size_t i = 0; i < pairs.source.size(); ++i) r.pair_final_enu_m[i] = r.final_fit.target_from_source(adjusted[i]);
}

// Step 8: camera references and GCPs against the final model.
void ComputeResiduals(ModelGeoreference& r, const ModelGeoreferenceOptions& options) {
  for (size_t i = 0; i < r.references.size(); ++i) {
    const ReferenceUse& u = r.references[i];
    if (u.image_id) r.camera_residuals_m[i] = (r.model_enu.images.at(*u.image_id).ProjectionCenter() - u.enu_m).norm();
  }
  double sum2 = 0;
  int n_check = 0;
  for (GcpUse& u : r.gcps) {
    if (!u.usable) continue;
    u.final_triangulation = TriangulatePoint(r.model_enu, UsedObservations(u), options.triangulation);
    if (!u.final_triangulation->ok) continue;
    u.final_residual_enu_m = u.final_triangulation->xyz - u.enu_m;
    sum2 += u.final_residual_enu_m->squaredNorm();
    ++n_check;
  }
  r.gcp_check_rmse_m = n_check > 0 ? std::sqrt(sum2 / n_check) : 0;
}

}  // namespace

ModelGeoreference GeoreferenceModel(const ColmapModel& model, const std::vector<ImageReference>& references,
                                    const GcpFile* gcp_file, const ModelGeoreferenceOptions& options) {
  ModelGeoreference result;
  const ImageNames names = IndexImageNames(model);
  result.references = MatchReferences(references, names, options);
  if (gcp_file) {
    result.gcp_crs = gcp_file->crs;
    result.gcps = TriangulateGcps(*gcp_file, model, names, options, &result.warnings);
  }
  const size_t matched = std::count_if(result.references.begin(), result.references.end(),
                                       [](const ReferenceUse& u) { return u.image_id.has_value(); });
  const size_t usable_gcps =
      std::count_if(result.gcps.begin(), result.gcps.end(), [](const GcpUse& u) { return u.usable; });
  RequireSomethingToFit(model, references, gcp_file, matched, usable_gcps, &result.warnings);

  result.origin = ChooseOrigin(result, options, matched);
  result.geoid_undulation_m = Egm96Geoid::Default().UndulationM(result.origin.lat_deg, result.origin.lon_deg);
  const FitPairs pairs = BuildFitPairs(result, model, EnuFrame(result.origin), usable_gcps);

  // Step 6: the first, similarity-only fit.
  result.first_fit = FitSimilarityRobust(pairs.source, pairs.target, options.fit, pairs.what);
  result.enu_from_colmap = result.first_fit.target_from_source;
  result.model_enu = TransformModel(model, result.enu_from_colmap);
  result.final_fit = result.first_fit;
  for (const Eigen::Vector3d& source : pairs.source) result.pair_final_enu_m.push_back(result.enu_from_colmap(source));

  if (options.bundle_adjust) BundleAdjustAndRefit(result, pairs, options);
  ComputeResiduals(result, options);
  return result;
}

namespace {

Json OriginJson(const ModelGeoreference& r) {
  Json origin = Json::object();
  origin["lat_deg"] = Round(r.origin.lat_deg, 9);
  origin["lon_deg"] = Round(r.origin.lon_deg, 9);
  origin["height_m"] = Round(r.origin.height_m, 4);
  origin["height_reference"] = "WGS84 ellipsoid";
  origin["geoid_undulation_m"] = Round(r.geoid_undulation_m, 3);
  origin["geoid_model"] = "EGM96";
  return origin;
}

Json EnuFromColmapJson(const ModelGeoreference& r) {
  Json t = Json::object();
  const Similarity3& s = r.enu_from_colmap;
  t["scale"] = s.scale;
  t["rotation"] = Json::array({s.rotation.w(), s.rotation.x(), s.rotation.y(), s.rotation.z()});
  t["translation_m"] = Json::array({s.translation.x(), s.translation.y(), s.translation.z()});
  t["note"] = r.bundle_adjustment
                  ? "similarity-only fit of the COLMAP camera centres; points and cameras were then bundle-"
                    "adjusted in ENU (see georeferencing.bundle_adjustment)"
                  : "similarity applied to the COLMAP model";
  return t;
}

Json ReferencesJson(const ModelGeoreference& r) {
  Json refs = Json::array();
  for (const ReferenceUse& u : r.references) {
    Json item = Json::object();
    item["image"] = u.reference.image_name;
    item["lat_deg"] = u.reference.lat_deg;
    item["lon_deg"] = u.reference.lon_deg;
    item["alt_m"] = u.reference.alt_m;
    item["height_ellipsoidal_m"] = Round(u.height_ellipsoidal_m, 4);
    item["enu_m"] = Vec(u.enu_m, 4);
    item["matched"] = u.image_id.has_value();
    if (u.matched_by_file_name) item["matched_by"] = "file name without folder";
    refs.push_back(item);
  }
  return refs;
}

Json FocalJson(const FocalReport& f, const ModelGeoreferenceOptions& options) {
  Json item = Json::object();
  item["camera_id"] = f.camera_id;
  item["before_px"] = Round(f.before_px, 3);
  item["after_px"] = Round(f.after_px, 3);
  item["prior_px"] = f.prior_px ? Json(Round(*f.prior_px, 3)) : Json(nullptr);
  if (f.prior_px) item["prior_source"] = options.focal_prior_source;
  item["prior_sigma_ratio"] =
      f.measured_by_images ? options.ba.measured_focal_prior_sigma_ratio : options.ba.focal_prior_sigma_ratio;
  item["images_sigma_ratio"] = f.images_sigma_ratio ? Json(Round(*f.images_sigma_ratio, 5)) : Json(nullptr);
  item["images_preferred_px"] = f.images_preferred_px ? Json(Round(*f.images_preferred_px, 2)) : Json(nullptr);
  item["images_resolve_focal"] = f.images_resolve_focal;
  item["images_conflict_with_prior"] = f.images_conflict_with_prior;
  item["held_at_prior"] = f.held_at_prior;
  item["measured_by_images"] = f.measured_by_images;
  return item;
}

Json BundleAdjustmentJson(const ModelGeoreference& r, const ModelGeoreferenceOptions& options, bool include_timing) {
  const BundleAdjustReport& ba = *r.bundle_adjustment;
  Json b = Json::object();
  b["images"] = ba.num_images;
  b["points"] = ba.num_points;
  b["observations"] = ba.num_observations;
  b["gps_priors"] = ba.num_gps_priors;
  if (r.gcp_crs) b["gcp_priors"] = ba.num_control_points;
  b["gps_sigma_horizontal_m"] = options.ba.gps_sigma_horizontal_m;
  b["gps_sigma_vertical_m"] = options.ba.gps_sigma_vertical_m;
  b["iterations"] = ba.iterations;
  b["converged"] = ba.converged;
  b["rms_reprojection_before_px"] = Round(ba.rms_reprojection_before_px, 4);
  b["rms_reprojection_after_px"] = Round(ba.rms_reprojection_after_px, 4);
  Json focal = Json::array();
  for (const FocalReport& f : ba.focal) focal.push_back(FocalJson(f, options));
  b["focal_length"] = focal;
  b["depth_relief_ratio"] = Round(ba.depth_relief_ratio, 4);
  b["view_axis_spread_deg"] = Round(ba.view_axis_spread_deg, 3);
  b["geometry_resolves_focal"] = ba.geometry_resolves_focal;
  if (include_timing) b["time_s"] = Round(ba.time_s, 3);
  return b;
}

Json GcpObservationsJson(const GcpUse& u) {
  Json obs = Json::array();
  for (size_t k = 0; k < u.gcp.observations.size(); ++k) {
    const GcpObservation& o = u.gcp.observations[k];
    const ObservationResult& res = u.observation_results[k];
    Json oj = Json::object();
    oj["image"] = o.image_name;
    oj["pixel"] = Json::array({o.pixel_file.x(), o.pixel_file.y()});
    oj["used"] = res.used;
    oj["reprojection_px"] = res.reprojection_px >= 0 ? Json(Round(res.reprojection_px, 3)) : Json(nullptr);
    if (!res.note.empty()) oj["note"] = res.note;
    obs.push_back(oj);
  }
  return obs;
}

Json GcpPointJson(const GcpUse& u) {
  Json item = Json::object();
  item["name"] = u.gcp.name;
  item["where"] = u.gcp.where;
  item["geo_x"] = u.gcp.geo_x;
  item["geo_y"] = u.gcp.geo_y;
  item["geo_z"] = u.gcp.geo_z_m ? Json(*u.gcp.geo_z_m) : Json(nullptr);
  item["lat_deg"] = Round(u.gcp.lat_deg, 9);
  item["lon_deg"] = Round(u.gcp.lon_deg, 9);
  item["height_ellipsoidal_m"] = u.gcp.geo_z_m ? Json(Round(u.height_ellipsoidal_m, 4)) : Json(nullptr);
  item["enu_m"] = u.gcp.geo_z_m ? Vec(u.enu_m, 4) : Json(nullptr);
  item["used"] = u.usable;
  if (!u.usable) item["skipped"] = u.skipped_reason;
  item["observations"] = GcpObservationsJson(u);
  if (u.triangulation.num_used > 0) {
    item["triangulation"] = {{"observations_used", u.triangulation.num_used},
                             {"rms_reprojection_px", Round(u.triangulation.rms_reprojection_px, 3)},
                             {"angle_deg", Round(u.triangulation.max_angle_deg, 2)}};
  }
  if (u.final_residual_enu_m) {
    item["check_residual_enu_m"] = Vec(*u.final_residual_enu_m, 3);
    item["check_residual_m"] = Round(u.final_residual_enu_m->norm(), 3);
    item["check_rms_reprojection_px"] = Round(u.final_triangulation->rms_reprojection_px, 3);
  }
  return item;
}

Json GroundControlJson(const ModelGeoreference& r, const ModelGeoreferenceOptions& options) {
  Json gcp = Json::object();
  gcp["coordinate_system"] = r.gcp_crs->header;
  gcp["coordinate_system_read_as"] = r.gcp_crs->description;
  gcp["altitude_datum"] = AltitudeDatumName(options.gcp_altitude_datum);
  gcp["pixel_convention"] = "im_x, im_y with the centre of the top-left pixel at (0, 0) (OpenSfM/ODM); COLMAP = +0.5";
  gcp["sigma_horizontal_m"] = options.gcp_sigma_horizontal_m;
  gcp["sigma_vertical_m"] = options.gcp_sigma_vertical_m;
  gcp["max_reprojection_px"] = options.triangulation.max_reprojection_px;
  gcp["min_triangulation_angle_deg"] = options.triangulation.min_angle_deg;
  Json points = Json::array();
  int usable = 0;
  for (const GcpUse& u : r.gcps) {
    usable += u.usable ? 1 : 0;
    points.push_back(GcpPointJson(u));
  }
  gcp["points"] = points;
  gcp["usable"] = usable;
  gcp["check_rmse_m"] = Round(r.gcp_check_rmse_m, 4);
  gcp["check_note"] =
      "each usable GCP re-triangulated in the final model from its pixels alone, minus its surveyed position";
  return gcp;
}

}  // namespace

Json GeoreferenceJson(const ModelGeoreference& r, const ModelGeoreferenceOptions& options, bool include_timing) {
  Json out = Json::object();
  out["origin"] = OriginJson(r);
  out["enu_from_colmap"] = EnuFromColmapJson(r);

  Json g = Json::object();
  g["altitude_datum"] = AltitudeDatumName(options.altitude_datum);
  g["altitude_datum_note"] =
      options.altitude_datum == AltitudeDatum::kEllipsoidal
          ? "reference altitudes taken as WGS84 ellipsoidal heights (as COLMAP does; DJI drones write these "
            "in EXIF GPSAltitude); choose the AMSL datum if they are above mean sea level"
          : "reference altitudes taken as above mean sea level and converted with EGM96 (h = H + N)";
  g["inlier_threshold_m"] = options.fit.inlier_threshold_m;
  g["max_rmse_m"] = options.fit.max_rmse_m;
  g["seed"] = options.fit.seed;
  g["references"] = ReferencesJson(r);
  if (!r.gcps.empty() || r.gcp_crs) g["fit_references"] = r.fit_references;
  g["similarity_fit"] = FitJson(r.first_fit, r, false);
  g["similarity_fit"]["ransac_trials"] = r.first_fit.ransac_trials;
  if (r.bundle_adjustment) {
    g["bundle_adjustment"] = BundleAdjustmentJson(r, options, include_timing);
    g["final_fit"] = FitJson(r.final_fit, r, true);
  }
  if (r.gcp_crs) {
    // Every matched camera reference against the final model (also those that were not fit pairs).
    Json cams = Json::array();
    for (const auto& [i, residual] : r.camera_residuals_m) {
      cams.push_back({{"image", r.references[i].reference.image_name}, {"residual_m", Round(residual, 3)}});
    }
    g["camera_reference_residuals"] = cams;
    g["ground_control_points"] = GroundControlJson(r, options);
  }
  g["rmse_m"] = Round(r.final_fit.rmse_m, 4);
  g["inliers"] = r.final_fit.num_inliers;
  Json warnings = Json::array();
  for (const auto& w : r.warnings) warnings.push_back(w);
  g["warnings"] = warnings;
  out["georeferencing"] = g;
  return out;
}

}  // namespace cinepath::photogrammetry
