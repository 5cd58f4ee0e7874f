#include "photogrammetry/georeference_model.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>

#include "core/error.h"
#include "core/geoid.h"
#include "core/number_format.h"
#include "photogrammetry/camera_models.h"

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
  return GeoreferenceModel(model, references, nullptr, options);
}

ModelGeoreference GeoreferenceModel(const ColmapModel& model, const std::vector<ImageReference>& references,
                                    const GcpFile* gcp_file, const ModelGeoreferenceOptions& options) {
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

  // 1b. Ground control points: match their images (exact name, else a unique file name) and
  //     triangulate them in the COLMAP frame.
  size_t usable_gcps = 0;
  if (gcp_file) {
    result.gcp_crs = gcp_file->crs;
    for (const GroundControlPoint& p : gcp_file->points) {
      GcpUse u;
      u.gcp = p;
      std::vector<PixelObservation> obs;
      std::vector<size_t> obs_index;  // file observation of each triangulated one
      u.observation_results.resize(p.observations.size());
      for (size_t k = 0; k < p.observations.size(); ++k) {
        const std::string& name = p.observations[k].image_name;
        std::optional<uint32_t> id;
        if (const auto it = image_by_name.find(name); it != image_by_name.end()) {
          id = it->second;
        } else if (const auto b = image_by_base.find(base_name(name));
                   b != image_by_base.end() && b->second.size() == 1) {
          id = b->second.front();
        }
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
      if (p.geo_z_m) {
        u.height_ellipsoidal_m = options.gcp_altitude_datum == AltitudeDatum::kEllipsoidal
                                     ? *p.geo_z_m
                                     : Egm96Geoid::Default().EllipsoidalFromAmslM(p.lat_deg, p.lon_deg, *p.geo_z_m);
      }
      if (!p.geo_z_m) {
        u.skipped_reason = "no elevation (geo_z is NaN)";
      } else if (!u.triangulation.ok) {
        u.skipped_reason = u.triangulation.reason;
      } else {
        u.usable = true;
        ++usable_gcps;
      }
      if (!u.usable) {
        result.warnings.push_back("ground control point '" + p.name + "' (" + p.where +
                                  ") skipped: " + u.skipped_reason);
      }
      result.gcps.push_back(std::move(u));
    }
  }

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
    result.warnings.push_back("none of the " + std::to_string(references.size()) +
                              " camera references names a registered image; georeferencing with the ground control "
                              "points alone");
  }

  // 2. Origin: given, else the mean of the matched camera references, else of the usable GCPs.
  if (options.origin) {
    result.origin = *options.origin;
  } else {
    double lat = 0, lon = 0, h = 0, n = 0;
    // Longitudes are averaged about the first one so that the antimeridian does no harm.
    double lon0 = 0;
    bool first = true;
    auto add = [&](double lat_deg, double lon_deg, double height_m) {
      if (first) lon0 = lon_deg, first = false;
      lat += lat_deg;
      lon += std::remainder(lon_deg - lon0, 360.0);
      h += height_m;
      n += 1;
    };
    if (matched > 0) {
      for (const auto& r : result.references) {
        if (r.image_id) add(r.reference.lat_deg, r.reference.lon_deg, r.height_ellipsoidal_m);
      }
    } else {
      for (const auto& g : result.gcps) {
        if (g.usable) add(g.gcp.lat_deg, g.gcp.lon_deg, g.height_ellipsoidal_m);
      }
    }
    result.origin = Geodetic{lat / n, std::remainder(lon0 + lon / n, 360.0), h / n};
  }
  result.geoid_undulation_m = Egm96Geoid::Default().UndulationM(result.origin.lat_deg, result.origin.lon_deg);
  const EnuFrame frame(result.origin);

  // Pairs (source in the COLMAP frame, target in ENU): the usable GCPs alone when there are 3 or more,
  // else the camera references followed by the usable GCPs.
  const bool gcp_frame = usable_gcps >= 3;
  std::vector<Eigen::Vector3d> source, target;
  std::vector<uint32_t> pair_image;  // camera pairs: image id; GCP pairs: unused
  std::vector<size_t> pair_gcp;      // GCP pairs: index into result.gcps
  for (auto& r : result.references) {
    r.enu_m = frame.EnuFromGeodetic({r.reference.lat_deg, r.reference.lon_deg, r.height_ellipsoidal_m});
    if (!r.image_id || gcp_frame) continue;
    r.pair_index = source.size();
    source.push_back(model.images.at(*r.image_id).ProjectionCenter());
    target.push_back(r.enu_m);
    pair_image.push_back(*r.image_id);
    pair_gcp.push_back(SIZE_MAX);
    result.pair_is_gcp.push_back(false);
    result.pair_labels.push_back(r.reference.image_name);
  }
  for (size_t g = 0; g < result.gcps.size(); ++g) {
    GcpUse& u = result.gcps[g];
    u.enu_m = frame.EnuFromGeodetic({u.gcp.lat_deg, u.gcp.lon_deg, u.height_ellipsoidal_m});
    if (!u.usable) continue;
    u.pair_index = source.size();
    source.push_back(u.triangulation.xyz);
    target.push_back(u.enu_m);
    pair_image.push_back(0);
    pair_gcp.push_back(g);
    result.pair_is_gcp.push_back(true);
    result.pair_labels.push_back(u.gcp.name);
  }
  result.pair_targets_enu_m = target;
  result.fit_references = gcp_frame ? "gcps" : (usable_gcps > 0 ? "cameras+gcps" : "cameras");
  const std::string what = gcp_frame
                               ? "ground control points"
                               : (usable_gcps > 0 ? "references (cameras and ground control points)" : "references");

  // 3. First fit.
  result.first_fit = FitSimilarityRobust(source, target, options.fit, what);
  result.enu_from_colmap = result.first_fit.target_from_source;
  result.model_enu = TransformModel(model, result.enu_from_colmap);
  result.final_fit = result.first_fit;
  for (size_t i = 0; i < source.size(); ++i) result.pair_final_enu_m.push_back(result.enu_from_colmap(source[i]));

  // 4. Bundle adjustment with priors.
  if (options.bundle_adjust) {
    std::map<uint32_t, Eigen::Vector3d> gps;
    if (gcp_frame) {
      // Camera references that agree with the GCP-defined frame.
      for (const auto& r : result.references) {
        if (!r.image_id) continue;
        const Eigen::Vector3d c = result.model_enu.images.at(*r.image_id).ProjectionCenter();
        if ((c - r.enu_m).norm() <= options.fit.inlier_threshold_m) gps[*r.image_id] = r.enu_m;
      }
    } else {
      for (size_t i = 0; i < pair_image.size(); ++i) {
        if (!result.pair_is_gcp[i] && result.first_fit.inliers[i]) gps[pair_image[i]] = target[i];
      }
    }
    std::vector<ControlPointPrior> control;
    std::vector<size_t> control_pair;  // pair index of each control point
    for (size_t i = 0; i < source.size(); ++i) {
      if (!result.pair_is_gcp[i] || !result.first_fit.inliers[i]) continue;
      const GcpUse& u = result.gcps[pair_gcp[i]];
      ControlPointPrior c;
      for (size_t k = 0; k < u.observation_results.size(); ++k) {
        if (u.observation_results[k].used)
          c.observations.push_back({*u.image_ids[k], u.gcp.observations[k].pixel_colmap});
      }
      c.initial_enu_m = result.enu_from_colmap(u.triangulation.xyz);
      c.target_enu_m = u.enu_m;
      c.sigma_horizontal_m = options.gcp_sigma_horizontal_m;
      c.sigma_vertical_m = options.gcp_sigma_vertical_m;
      control.push_back(std::move(c));
      control_pair.push_back(i);
    }
    std::vector<Eigen::Vector3d> control_adjusted;
    result.bundle_adjustment =
        BundleAdjustEnu(result.model_enu, gps, options.focal_prior_px, options.ba, control, &control_adjusted);
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
          (f.images_sigma_ratio ? "formal sigma " + FormatFixed(100 * *f.images_sigma_ratio, 2) + " %"
                                : std::string("formal sigma unbounded")) +
          (ba.geometry_resolves_focal
               ? std::string()
               : "; near-flat scene (depth relief " + FormatFixed(100 * ba.depth_relief_ratio, 1) +
                     " %) under near-parallel views (axes within " + FormatFixed(ba.view_axis_spread_deg, 1) + " deg)");
      if (f.images_conflict_with_prior && f.images_preferred_px && f.prior_px) {
        result.warnings.push_back(
            cam + "the images pull the focal length to " + FormatFixed(*f.images_preferred_px, 1) + " px (" +
            FormatFixed(100 * (*f.images_preferred_px / *f.prior_px - 1), 1) + " % from the prior " +
            FormatFixed(*f.prior_px, 1) + " px; " + sigma +
            "): the focal-length/flying-height ambiguity of a flat scene seen from above, not a measurement; the "
            "focal length is held at the prior (" +
            options.focal_prior_source + ")");
      } else if (f.prior_px) {
        if (!f.images_resolve_focal) {
          result.warnings.push_back(cam + "the images cannot resolve focal length vs flying height (" + sigma +
                                    "); the focal length is held at the prior (" + options.focal_prior_source + ")");
        }
      } else if (!f.images_resolve_focal) {
        std::string what = cam + "the images cannot resolve focal length vs flying height (" + sigma +
                           ") and no focal-length prior is known (give --images with EXIF, or --focal-prior-px)";
        what +=
            ": heights above ground scale with the focal-length error (COLMAP's focal length is taken as is; "
            "each 1 % error moves the ground by " +
            FormatFixed(0.01 * median_depth_m, 2) + " m at the median depth of " + FormatFixed(median_depth_m, 1) +
            " m)";
        result.warnings.push_back(what);
      }
      if (f.prior_px && std::abs(f.before_px / *f.prior_px - 1) > 0.05) {
        result.warnings.push_back(cam + "COLMAP's focal length (" + FormatFixed(f.before_px, 1) +
                                  " px) differs from the prior (" + FormatFixed(*f.prior_px, 1) + " px) by " +
                                  FormatFixed(100 * (f.before_px / *f.prior_px - 1), 1) + " %; adjusted to " +
                                  FormatFixed(f.after_px, 1) + " px");
      }
    }
    // 5. Refit on the same pairs: adjusted camera centres; adjusted GCPs (re-triangulated when they
    //    were not in the adjustment).
    std::vector<Eigen::Vector3d> adjusted(source.size());
    for (size_t i = 0; i < source.size(); ++i) {
      if (!result.pair_is_gcp[i]) {
        adjusted[i] = result.model_enu.images.at(pair_image[i]).ProjectionCenter();
        continue;
      }
      const auto c = std::find(control_pair.begin(), control_pair.end(), i);
      if (c != control_pair.end()) {
        adjusted[i] = control_adjusted[c - control_pair.begin()];
        continue;
      }
      const GcpUse& u = result.gcps[pair_gcp[i]];
      std::vector<PixelObservation> obs;
      for (size_t k = 0; k < u.observation_results.size(); ++k) {
        if (u.observation_results[k].used) obs.push_back({*u.image_ids[k], u.gcp.observations[k].pixel_colmap});
      }
      const Triangulation t = TriangulatePoint(result.model_enu, obs, options.triangulation);
      adjusted[i] = t.ok ? t.xyz : result.enu_from_colmap(u.triangulation.xyz);
    }
    result.final_fit = FitSimilarityRobust(adjusted, target, options.fit, what);
    result.model_enu = TransformModel(result.model_enu, result.final_fit.target_from_source);
    for (size_t i = 0; i < source.size(); ++i) {
      result.pair_final_enu_m[i] = result.final_fit.target_from_source(adjusted[i]);
    }
  }

  // Camera references and GCPs against the final model.
  for (size_t i = 0; i < result.references.size(); ++i) {
    const ReferenceUse& r = result.references[i];
    if (r.image_id) {
      result.camera_residuals_m[i] = (result.model_enu.images.at(*r.image_id).ProjectionCenter() - r.enu_m).norm();
    }
  }
  double sum2 = 0;
  int n_check = 0;
  for (GcpUse& u : result.gcps) {
    if (!u.usable) continue;
    std::vector<PixelObservation> obs;
    for (size_t k = 0; k < u.observation_results.size(); ++k) {
      if (u.observation_results[k].used) obs.push_back({*u.image_ids[k], u.gcp.observations[k].pixel_colmap});
    }
    u.final_triangulation = TriangulatePoint(result.model_enu, obs, options.triangulation);
    if (!u.final_triangulation->ok) continue;
    u.final_residual_enu_m = u.final_triangulation->xyz - u.enu_m;
    sum2 += u.final_residual_enu_m->squaredNorm();
    ++n_check;
  }
  result.gcp_check_rmse_m = n_check > 0 ? std::sqrt(sum2 / n_check) : 0;
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
  if (!r.gcps.empty() || r.gcp_crs) g["fit_references"] = r.fit_references;
  g["similarity_fit"] = FitJson(r.first_fit, r, false);
  g["similarity_fit"]["ransac_trials"] = r.first_fit.ransac_trials;
  if (r.bundle_adjustment) {
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
    g["final_fit"] = FitJson(r.final_fit, r, true);
  }
  if (r.gcp_crs) {
    // Every matched camera reference against the final model (also those that were not fit pairs).
    Json cams = Json::array();
    for (const auto& [i, residual] : r.camera_residuals_m) {
      cams.push_back({{"image", r.references[i].reference.image_name}, {"residual_m", Round(residual, 3)}});
    }
    g["camera_reference_residuals"] = cams;
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
      item["observations"] = obs;
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
      usable += u.usable ? 1 : 0;
      points.push_back(item);
    }
    gcp["points"] = points;
    gcp["usable"] = usable;
    gcp["check_rmse_m"] = Round(r.gcp_check_rmse_m, 4);
    gcp["check_note"] =
        "each usable GCP re-triangulated in the final model from its pixels alone, minus its surveyed position";
    g["ground_control_points"] = gcp;
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
