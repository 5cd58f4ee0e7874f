#include "photogrammetry/georeference_model.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/error.h"
#include "core/geoid.h"
#include "photogrammetry/camera_models.h"

namespace cinepath::photogrammetry {
namespace {

std::string Fixed(double v, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.*f", decimals, v);
  return buffer;
}

double Round(double v, int decimals) { return RoundToDecimals(v, decimals); }

Json Vec(const Eigen::Vector3d& v, int decimals) {
  return Json::array({Round(v.x(), decimals), Round(v.y(), decimals), Round(v.z(), decimals)});
}

Json FitJson(const RobustFit& fit, const std::vector<ReferenceUse>& refs, const ColmapModel& model_for_centres,
             const Similarity3* apply) {
  Json residuals = Json::array();
  for (const ReferenceUse& r : refs) {
    if (!r.pair_index) continue;
    const size_t i = *r.pair_index;
    Json item = Json::object();
    item["image"] = r.reference.image_name;
    Eigen::Vector3d c = model_for_centres.images.at(*r.image_id).ProjectionCenter();
    if (apply) c = (*apply)(c);
    item["residual_enu_m"] = Vec(c - r.enu_m, 3);
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
  // Normal equations of [x 1] A = y, about the centroids for conditioning.
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> pairs;
  for (const auto& [id, p] : from.points3d) {
    const auto it = to.points3d.find(id);
    if (it != to.points3d.end() && p.track.size() >= 2) pairs.emplace_back(p.xyz, it->second.xyz);
  }
  AffineMap map;
  if (pairs.size() < 4) return map;
  Eigen::Vector3d cx = Eigen::Vector3d::Zero(), cy = Eigen::Vector3d::Zero();
  for (const auto& [x, y] : pairs) cx += x, cy += y;
  cx /= static_cast<double>(pairs.size());
  cy /= static_cast<double>(pairs.size());
  Eigen::Matrix3d xx = Eigen::Matrix3d::Zero(), yx = Eigen::Matrix3d::Zero();
  for (const auto& [x, y] : pairs) {
    xx += (x - cx) * (x - cx).transpose();
    yx += (y - cy) * (x - cx).transpose();
  }
  map.linear = yx * xx.inverse();
  map.translation = cy - map.linear * cx;
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
  ModelGeoreference result;
  std::map<std::string, uint32_t> image_by_name;
  // File names without folders, for references written with other paths ("C:/flight/DJI_0018.JPG" or
  // "images/DJI_0018.JPG" vs COLMAP's "DJI_0018.JPG"); only names that are unique on both sides.
  auto base_name = [](const std::string& name) {
    const size_t slash = name.find_last_of("/\\");
    return slash == std::string::npos ? name : name.substr(slash + 1);
  };
  std::map<std::string, std::vector<uint32_t>> image_by_base;
  for (const auto& [id, image] : model.images) {
    image_by_name[image.name] = id;
    image_by_base[base_name(image.name)].push_back(id);
  }
  std::map<std::string, int> ref_base_count;
  for (const ImageReference& ref : references) ++ref_base_count[base_name(ref.image_name)];

  // 1. Match and convert heights.
  for (const ImageReference& ref : references) {
    ReferenceUse use;
    use.reference = ref;
    use.height_ellipsoidal_m = options.altitude_datum == AltitudeDatum::kEllipsoidal
                                   ? ref.alt_m
                                   : Egm96Geoid::Default().EllipsoidalFromAmslM(ref.lat_deg, ref.lon_deg, ref.alt_m);
    const auto it = image_by_name.find(ref.image_name);
    if (it != image_by_name.end()) {
      use.image_id = it->second;
    } else {
      const std::string base = base_name(ref.image_name);
      const auto b = image_by_base.find(base);
      if (b != image_by_base.end() && b->second.size() == 1 && ref_base_count[base] == 1) {
        use.image_id = b->second.front();
        use.matched_by_file_name = true;
      }
    }
    result.references.push_back(use);
  }
  size_t matched = 0;
  for (const auto& r : result.references) matched += r.image_id ? 1 : 0;
  if (matched == 0) {
    std::string example = references.empty() ? "(none)" : references.front().image_name;
    std::string image_example = model.images.empty() ? "(none)" : model.images.begin()->second.name;
    throw InfeasibleError("georeferencing: none of the " + std::to_string(references.size()) +
                          " references names a registered image (references name e.g. '" + example +
                          "', the model's images are named e.g. '" + image_example + "')");
  }

  // 2. Origin.
  if (options.origin) {
    result.origin = *options.origin;
  } else {
    double lat = 0, lon = 0, h = 0;
    // Longitudes are averaged about the first one so that the antimeridian does no harm.
    double lon0 = 0;
    bool first = true;
    for (const auto& r : result.references) {
      if (!r.image_id) continue;
      if (first) lon0 = r.reference.lon_deg, first = false;
      lat += r.reference.lat_deg;
      lon += std::remainder(r.reference.lon_deg - lon0, 360.0);
      h += r.height_ellipsoidal_m;
    }
    const double n = static_cast<double>(matched);
    result.origin = Geodetic{lat / n, std::remainder(lon0 + lon / n, 360.0), h / n};
  }
  result.geoid_undulation_m = Egm96Geoid::Default().UndulationM(result.origin.lat_deg, result.origin.lon_deg);
  const EnuFrame frame(result.origin);

  std::vector<Eigen::Vector3d> source, target;
  std::vector<uint32_t> pair_image;
  for (auto& r : result.references) {
    r.enu_m = frame.EnuFromGeodetic({r.reference.lat_deg, r.reference.lon_deg, r.height_ellipsoidal_m});
    if (!r.image_id) continue;
    r.pair_index = source.size();
    source.push_back(model.images.at(*r.image_id).ProjectionCenter());
    target.push_back(r.enu_m);
    pair_image.push_back(*r.image_id);
  }

  // 3. First fit.
  result.first_fit = FitSimilarityRobust(source, target, options.fit, "references");
  result.enu_from_colmap = result.first_fit.target_from_source;
  result.model_enu = TransformModel(model, result.enu_from_colmap);
  result.final_fit = result.first_fit;

  // 4. Bundle adjustment with priors.
  if (options.bundle_adjust) {
    std::map<uint32_t, Eigen::Vector3d> gps;
    for (size_t i = 0; i < pair_image.size(); ++i) {
      if (result.first_fit.inliers[i]) gps[pair_image[i]] = target[i];
    }
    result.bundle_adjustment = BundleAdjustEnu(result.model_enu, gps, options.focal_prior_px, options.ba);
    // Typical depth (camera to point) for translating a focal-length uncertainty into metres.
    std::vector<double> depths;
    for (const auto& [id, point] : result.model_enu.points3d) {
      for (const auto& e : point.track) {
        const auto& im = result.model_enu.images.at(e.image_id);
        depths.push_back((im.cam_from_world_rotation * point.xyz + im.cam_from_world_translation).z());
      }
    }
    double median_depth_m = 0;
    if (!depths.empty()) {
      std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
      median_depth_m = depths[depths.size() / 2];
    }
    for (const FocalReport& f : result.bundle_adjustment->focal) {
      const std::string cam = "camera " + std::to_string(f.camera_id) + ": ";
      const BundleAdjustReport& ba = *result.bundle_adjustment;
      const std::string sigma =
          (f.images_sigma_ratio ? "formal sigma " + Fixed(100 * *f.images_sigma_ratio, 2) + " %" : std::string("formal sigma unbounded")) +
          (ba.geometry_resolves_focal ? std::string()
                                      : "; near-flat scene (depth relief " + Fixed(100 * ba.depth_relief_ratio, 1) +
                                            " %) under near-parallel views (axes within " +
                                            Fixed(ba.view_axis_spread_deg, 1) + " deg)");
      if (f.images_conflict_with_prior && f.images_preferred_px && f.prior_px) {
        result.warnings.push_back(
            cam + "the images pull the focal length to " + Fixed(*f.images_preferred_px, 1) + " px (" +
            Fixed(100 * (*f.images_preferred_px / *f.prior_px - 1), 1) + " % from the prior " + Fixed(*f.prior_px, 1) +
            " px; " + sigma +
            "): the focal-length/flying-height ambiguity of a flat scene seen from above, not a measurement; the "
            "focal length is held at the prior (" + options.focal_prior_source + ")");
      } else if (f.prior_px) {
        if (!f.images_resolve_focal) {
          result.warnings.push_back(cam + "the images cannot resolve focal length vs flying height (" + sigma +
                                    "); the focal length is held at the prior (" + options.focal_prior_source + ")");
        }
      } else if (!f.images_resolve_focal) {
        std::string what = cam + "the images cannot resolve focal length vs flying height (" + sigma +
                           ") and no focal-length prior is known (give --images with EXIF, or --focal-prior-px)";
        what += ": heights above ground scale with the focal-length error (COLMAP's focal length is taken as is; "
                "each 1 % error moves the ground by " + Fixed(0.01 * median_depth_m, 2) + " m at the median depth of " +
                Fixed(median_depth_m, 1) + " m)";
        result.warnings.push_back(what);
      }
      if (f.prior_px && std::abs(f.before_px / *f.prior_px - 1) > 0.05) {
        result.warnings.push_back(cam + "COLMAP's focal length (" + Fixed(f.before_px, 1) + " px) differs from the prior (" +
                                  Fixed(*f.prior_px, 1) + " px) by " + Fixed(100 * (f.before_px / *f.prior_px - 1), 1) +
                                  " %; adjusted to " + Fixed(f.after_px, 1) + " px");
      }
    }
    // 5. Refit.
    std::vector<Eigen::Vector3d> adjusted;
    for (uint32_t id : pair_image) adjusted.push_back(result.model_enu.images.at(id).ProjectionCenter());
    result.final_fit = FitSimilarityRobust(adjusted, target, options.fit, "references");
    result.model_enu = TransformModel(result.model_enu, result.final_fit.target_from_source);
  }
  return result;
}

Json GeoreferenceJson(const ModelGeoreference& r, const ModelGeoreferenceOptions& options, bool include_timing) {
  Json out = Json::object();
  Json origin = Json::object();
  origin["lat_deg"] = Round(r.origin.lat_deg, 9);
  origin["lon_deg"] = Round(r.origin.lon_deg, 9);
  origin["height_m"] = Round(r.origin.height_m, 4);
  origin["height_reference"] = "WGS84 ellipsoid";
  origin["geoid_undulation_m"] = Round(r.geoid_undulation_m, 3);
  origin["geoid_model"] = "EGM96";
  out["origin"] = origin;

  Json t = Json::object();
  const Similarity3& s = r.enu_from_colmap;
  t["scale"] = s.scale;
  t["rotation"] = Json::array({s.rotation.w(), s.rotation.x(), s.rotation.y(), s.rotation.z()});
  t["translation_m"] = Json::array({s.translation.x(), s.translation.y(), s.translation.z()});
  t["note"] = r.bundle_adjustment
                  ? "similarity-only fit of the COLMAP camera centres; points and cameras were then bundle-"
                    "adjusted in ENU (see georeferencing.bundle_adjustment)"
                  : "similarity applied to the COLMAP model";
  out["enu_from_colmap"] = t;

  Json g = Json::object();
  g["altitude_datum"] = AltitudeDatumName(options.altitude_datum);
  g["altitude_datum_note"] =
      options.altitude_datum == AltitudeDatum::kEllipsoidal
          ? "reference altitudes taken as WGS84 ellipsoidal heights (as COLMAP does; DJI drones write these "
            "in EXIF GPSAltitude); use --altitude-datum amsl if they are above mean sea level"
          : "reference altitudes taken as above mean sea level and converted with EGM96 (h = H + N)";
  g["inlier_threshold_m"] = options.fit.inlier_threshold_m;
  g["max_rmse_m"] = options.fit.max_rmse_m;
  g["seed"] = options.fit.seed;
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
  g["references"] = refs;
  g["similarity_fit"] = FitJson(r.first_fit, r.references, r.model_enu, nullptr);
  // The similarity fit's residuals are computed by the fit itself; recompute from the final model only
  // for the final fit.
  g["similarity_fit"].erase("residuals");
  {
    Json residuals = Json::array();
    for (const ReferenceUse& u : r.references) {
      if (!u.pair_index) continue;
      Json item = Json::object();
      item["image"] = u.reference.image_name;
      item["residual_m"] = Round(r.first_fit.residuals_m[*u.pair_index], 3);
      item["inlier"] = static_cast<bool>(r.first_fit.inliers[*u.pair_index]);
      residuals.push_back(item);
    }
    g["similarity_fit"]["residuals"] = residuals;
    g["similarity_fit"]["ransac_trials"] = r.first_fit.ransac_trials;
  }
  if (r.bundle_adjustment) {
    const BundleAdjustReport& ba = *r.bundle_adjustment;
    Json b = Json::object();
    b["images"] = ba.num_images;
    b["points"] = ba.num_points;
    b["observations"] = ba.num_observations;
    b["gps_priors"] = ba.num_gps_priors;
    b["gps_sigma_horizontal_m"] = options.ba.gps_sigma_horizontal_m;
    b["gps_sigma_vertical_m"] = options.ba.gps_sigma_vertical_m;
    b["iterations"] = ba.iterations;
    b["converged"] = ba.converged;
    b["rms_reprojection_before_px"] = Round(ba.rms_reprojection_before_px, 4);
    b["rms_reprojection_after_px"] = Round(ba.rms_reprojection_after_px, 4);
    Json focal = Json::array();
    for (const FocalReport& f : ba.focal) {
      Json item = Json::object();
      item["camera_id"] = f.camera_id;
      item["before_px"] = Round(f.before_px, 3);
      item["after_px"] = Round(f.after_px, 3);
      item["prior_px"] = f.prior_px ? Json(Round(*f.prior_px, 3)) : Json(nullptr);
      if (f.prior_px) item["prior_source"] = options.focal_prior_source;
      item["prior_sigma_ratio"] = options.ba.focal_prior_sigma_ratio;
      item["images_sigma_ratio"] = f.images_sigma_ratio ? Json(Round(*f.images_sigma_ratio, 5)) : Json(nullptr);
      item["images_preferred_px"] = f.images_preferred_px ? Json(Round(*f.images_preferred_px, 2)) : Json(nullptr);
      item["images_resolve_focal"] = f.images_resolve_focal;
      item["images_conflict_with_prior"] = f.images_conflict_with_prior;
      item["held_at_prior"] = f.held_at_prior;
      focal.push_back(item);
    }
    b["focal_length"] = focal;
    b["depth_relief_ratio"] = Round(ba.depth_relief_ratio, 4);
    b["view_axis_spread_deg"] = Round(ba.view_axis_spread_deg, 3);
    b["geometry_resolves_focal"] = ba.geometry_resolves_focal;
    if (include_timing) b["time_s"] = Round(ba.time_s, 3);
    g["bundle_adjustment"] = b;
    g["final_fit"] = FitJson(r.final_fit, r.references, r.model_enu, nullptr);
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
