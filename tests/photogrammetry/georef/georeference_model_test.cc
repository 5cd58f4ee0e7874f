#include "photogrammetry/georef/georeference_model.h"

#include <gtest/gtest.h>

#include <GeographicLib/UTMUPS.hpp>

#include <algorithm>
#include <fstream>
#include <functional>
#include <map>
#include <random>
#include <sstream>

#include "core/error.h"
#include "core/geoid.h"
#include "photogrammetry/georef/camera_models.h"
#include "photogrammetry/io/colmap_reader.h"
#include "photogrammetry/io/gcp_file.h"
#include "tests/photogrammetry/synthetic_colmap.h"
#include "tests/photogrammetry/test_paths.h"

namespace cinepath::photogrammetry {
namespace {

// ---------------------------------------------------------------------------------------------
// Synthetic: a survey generated in code, its GPS references derived from the known ENU truth.

struct SyntheticRefs {
  testing::SyntheticScene scene;
  Geodetic origin{46.84, -91.99, 160.0};
  std::vector<ImageReference> refs;
};

SyntheticRefs MakeSurvey(double gps_noise_m, double outlier_fraction, uint64_t seed,
                         Geodetic origin = Geodetic{46.84, -91.99, 160.0}) {
  SyntheticRefs s;
  s.origin = origin;
  testing::SyntheticOptions o;
  o.enu_from_colmap = testing::DefaultColmapFrame();
  s.scene = testing::MakeSyntheticScene(o);
  const EnuFrame frame(s.origin);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0, gps_noise_m);
  const int n = static_cast<int>(s.scene.camera_centers_enu_m.size());
  const int n_bad = static_cast<int>(outlier_fraction * n);
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3d p = s.scene.camera_centers_enu_m[i] + Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    if (i % (n / std::max(n_bad, 1)) == 1 && i / (n / std::max(n_bad, 1)) < n_bad) {
      p += 50 * Eigen::Vector3d(std::cos(i), std::sin(i), 0.2).normalized();
    }
    const Geodetic g = frame.GeodeticFromEnu(p);
    s.refs.push_back({s.scene.model.images.at(i + 1).name, g.lat_deg, g.lon_deg, g.height_m, "synthetic"});
  }
  return s;
}

ModelGeoreferenceOptions SyntheticOptions(const Geodetic& origin) {
  ModelGeoreferenceOptions o;
  o.origin = origin;
  return o;
}

// Two models holding the same 3D points (track length 2), the second the first under `map`.
std::pair<ColmapModel, ColmapModel> ModelsRelatedBy(const std::vector<Eigen::Vector3d>& points,
                                                    const std::function<Eigen::Vector3d(Eigen::Vector3d)>& map) {
  ColmapModel from, to;
  for (size_t i = 0; i < points.size(); ++i) {
    ColmapPoint3D p;
    p.point3d_id = i + 1;
    p.xyz = points[i];
    p.track = {{1, uint32_t(i)}, {2, uint32_t(i)}};
    from.points3d[p.point3d_id] = p;
    p.xyz = map(points[i]);
    to.points3d[p.point3d_id] = p;
  }
  return {from, to};
}

TEST(FitAffineBetweenModels, PointsSpanningAVolumeGiveTheAffineMap) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 27; ++i) points.emplace_back(i % 3, (i / 3) % 3, i / 9);
  Eigen::Matrix3d a;
  a << 2, 0.1, 0, 0, 1.5, 0.2, 0.3, 0, 0.8;  // depths rescaled unevenly: not a similarity
  const auto [from, to] =
      ModelsRelatedBy(points, [&](Eigen::Vector3d x) -> Eigen::Vector3d { return a * x + Eigen::Vector3d(5, -3, 9); });
  const AffineMap map = FitAffineBetweenModels(from, to);
  EXPECT_FALSE(map.similarity_only);
  EXPECT_LT((map.linear - a).norm(), 1e-9);
  EXPECT_LT(map.rms_m, 1e-9);
}

TEST(FitAffineBetweenModels, PointsOnAPlaneGiveTheSimilarityNotNaN) {
  // A flat sparse model: the affine normal equations are singular (their inverse was inf/NaN, and every
  // vertex of a dense input mapped with it became NaN). The similarity is determined and is used.
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 25; ++i) points.emplace_back(i % 5, i / 5, 0.0);
  const Eigen::Matrix3d r = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const auto [from, to] = ModelsRelatedBy(
      points, [&](Eigen::Vector3d x) -> Eigen::Vector3d { return 3.0 * (r * x) + Eigen::Vector3d(1, 2, 3); });
  const AffineMap map = FitAffineBetweenModels(from, to);
  EXPECT_TRUE(map.similarity_only);
  ASSERT_TRUE(map.linear.allFinite());
  EXPECT_LT((map.linear - 3.0 * r).norm(), 1e-9);
  EXPECT_LT(
      (map(Eigen::Vector3d(7, -4, 2)) - (3.0 * (r * Eigen::Vector3d(7, -4, 2)) + Eigen::Vector3d(1, 2, 3))).norm(),
      1e-8);
}

TEST(FitAffineBetweenModels, PointsOnALineOrTooFewAreRefused) {
  std::vector<Eigen::Vector3d> line;
  for (int i = 0; i < 10; ++i) line.emplace_back(i, 2 * i, 0.5 * i);
  const auto identity = [](Eigen::Vector3d x) -> Eigen::Vector3d { return x; };
  const auto [from_line, to_line] = ModelsRelatedBy(line, identity);
  EXPECT_THROW(FitAffineBetweenModels(from_line, to_line), InputError);
  const auto [from_two, to_two] = ModelsRelatedBy({{0, 0, 0}, {1, 0, 0}}, identity);
  EXPECT_THROW(FitAffineBetweenModels(from_two, to_two), InputError);
}

TEST(GeoreferenceModel, SyntheticSurveyRecoversTheTransform) {
  const SyntheticRefs s = MakeSurvey(0.5, 0.0, 1);
  ModelGeoreferenceOptions options = SyntheticOptions(s.origin);
  options.bundle_adjust = false;
  const ModelGeoreference r = GeoreferenceModel(s.scene.model, s.refs, options);
  const Similarity3 truth = testing::DefaultColmapFrame();
  EXPECT_NEAR(r.enu_from_colmap.scale / truth.scale, 1, 0.01);
  EXPECT_LT(Eigen::AngleAxisd(r.enu_from_colmap.rotation.conjugate() * truth.rotation).angle(), 0.5 * M_PI / 180);
  double worst = 0;
  for (const auto& [id, p] : r.model_enu.points3d)
    worst = std::max(worst, (p.xyz - s.scene.model_enu.points3d.at(id).xyz).norm());
  EXPECT_LT(worst, 0.8);
  EXPECT_EQ(r.final_fit.num_inliers, 18);
}

TEST(GeoreferenceModel, SyntheticSurveyWithThirtyPercentWrongGpsAndBundleAdjustment) {
  const SyntheticRefs s = MakeSurvey(0.5, 0.3, 2);
  ModelGeoreferenceOptions options = SyntheticOptions(s.origin);
  options.ba.focal_prior_sigma_ratio = 0.01;
  options.focal_prior_px[1] = 900;
  const ModelGeoreference r = GeoreferenceModel(s.scene.model, s.refs, options);
  EXPECT_EQ(r.first_fit.num_inliers, 18 - 5);
  ASSERT_TRUE(r.bundle_adjustment);
  EXPECT_EQ(r.bundle_adjustment->num_gps_priors, 13);
  EXPECT_LT(r.bundle_adjustment->rms_reprojection_after_px, 0.6);
  std::vector<double> err;
  for (const auto& [id, p] : r.model_enu.points3d)
    err.push_back((p.xyz - s.scene.model_enu.points3d.at(id).xyz).norm());
  std::sort(err.begin(), err.end());
  EXPECT_LT(err[err.size() / 2], 0.5);
  EXPECT_NEAR(r.bundle_adjustment->focal[0].after_px, 900, 9);
  // Determinism.
  const ModelGeoreference again = GeoreferenceModel(s.scene.model, s.refs, options);
  EXPECT_EQ(DumpJson(GeoreferenceJson(r, options, false)), DumpJson(GeoreferenceJson(again, options, false)));
}

// The same survey flown at a pole, across the antimeridian and on the equator, its origin left to
// cinepath (the mean of the references): the transform comes back to the millimetre everywhere.
TEST(GeoreferenceModel, SurveysAtThePolesAndTheAntimeridian) {
  for (const Geodetic& where : {Geodetic{89.9995, 10.0, 2800.0}, Geodetic{-89.9995, -170.0, 2800.0},
                                Geodetic{-16.5, 179.9995, 5.0}, Geodetic{0.0, 0.0, 0.0}}) {
    const SyntheticRefs s = MakeSurvey(0.0, 0.0, 5, where);
    ModelGeoreferenceOptions options;  // default origin
    options.bundle_adjust = false;
    const ModelGeoreference r = GeoreferenceModel(s.scene.model, s.refs, options);
    EXPECT_LT(r.final_fit.rmse_m, 1e-3) << where.lat_deg << " " << where.lon_deg;
    EXPECT_EQ(r.final_fit.num_inliers, 18);
    EXPECT_NEAR(r.enu_from_colmap.scale / testing::DefaultColmapFrame().scale, 1, 1e-6);
    // Every point lands where the truth has it, compared on the ellipsoid (the origins differ).
    const EnuFrame truth(s.origin), ours(r.origin);
    double worst_m = 0;
    for (const auto& [id, p] : r.model_enu.points3d) {
      const Geodetic g = ours.GeodeticFromEnu(p.xyz);
      worst_m = std::max(worst_m, (truth.EnuFromGeodetic(g) - s.scene.model_enu.points3d.at(id).xyz).norm());
    }
    EXPECT_LT(worst_m, 2e-3) << where.lat_deg << " " << where.lon_deg;
    // The default origin sits among the cameras (not on the far side of the Earth from an average
    // of longitudes either side of ±180°, nor off the pole).
    EXPECT_LT(truth.EnuFromGeodetic(r.origin).norm(), 200.0) << where.lat_deg << " " << where.lon_deg;
    EXPECT_LE(std::abs(r.origin.lon_deg), 180.0);
  }
}

TEST(GeoreferenceModel, AmslAltitudesAreConvertedWithEgm96) {
  SyntheticRefs s = MakeSurvey(0.0, 0.0, 3);
  const double n = Egm96Geoid::Default().UndulationM(s.origin.lat_deg, s.origin.lon_deg);
  for (auto& ref : s.refs) ref.alt_m -= Egm96Geoid::Default().UndulationM(ref.lat_deg, ref.lon_deg);  // to AMSL
  ModelGeoreferenceOptions options;
  options.bundle_adjust = false;
  options.altitude_datum = AltitudeDatum::kAmslEgm96;
  const ModelGeoreference r = GeoreferenceModel(s.scene.model, s.refs, options);
  EXPECT_NEAR(r.geoid_undulation_m, n, 1e-9);
  EXPECT_LT(r.final_fit.rmse_m, 1e-3);
  const Json j = GeoreferenceJson(r, options, false);
  EXPECT_EQ(j["georeferencing"]["altitude_datum"], "amsl_egm96");
  // The mean camera height is 40 m above the origin's (ellipsoidal) 160 m.
  EXPECT_NEAR(j["origin"]["height_m"].get<double>(), 160 + 40, 0.5);
}

TEST(GeoreferenceModel, ReferencesWithFoldersMatchByFileName) {
  SyntheticRefs s = MakeSurvey(0.0, 0.0, 4);
  for (auto& ref : s.refs) ref.image_name = "C:\\flight\\" + ref.image_name;
  ModelGeoreferenceOptions options;
  options.bundle_adjust = false;
  const ModelGeoreference r = GeoreferenceModel(s.scene.model, s.refs, options);
  EXPECT_EQ(r.final_fit.num_inliers, 18);
  EXPECT_TRUE(r.references[0].matched_by_file_name);
}

TEST(GeoreferenceModel, NoMatchingNamesIsRefused) {
  SyntheticRefs s = MakeSurvey(0.0, 0.0, 4);
  for (auto& ref : s.refs) ref.image_name = "other_" + ref.image_name;
  try {
    GeoreferenceModel(s.scene.model, s.refs, ModelGeoreferenceOptions());
    FAIL();
  } catch (const InfeasibleError& e) {
    EXPECT_NE(std::string(e.what()).find("none of the 18 references names a registered image"), std::string::npos)
        << e.what();
  }
}

// ---------------------------------------------------------------------------------------------
// Real data: Brighton Beach (tests/data/colmap/PROVENANCE.md).

struct ReferenceGrid {
  std::map<std::pair<int, int>, double> height_by_cell;  // ENU, 2 m cells
  static std::pair<int, int> Cell(double e, double n) {
    return {static_cast<int>(std::floor(e / 2)), static_cast<int>(std::floor(n / 2))};
  }
};

ReferenceGrid LoadReference(const EnuFrame& frame) {
  std::ifstream f(testing::TestDataDir() / "colmap" / "odm_reference_2m.txt");
  ReferenceGrid grid;
  std::string line;
  while (std::getline(f, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream is(line);
    double x, y, h;
    is >> x >> y >> h;
    double lat, lon;
    GeographicLib::UTMUPS::Reverse(15, true, x, y, lat, lon);
    const Eigen::Vector3d enu = frame.EnuFromGeodetic({lat, lon, h});
    grid.height_by_cell[ReferenceGrid::Cell(enu.x(), enu.y())] = enu.z();
  }
  return grid;
}

// Median of (sparse point height - reference height) over points whose 2 m cell has a reference value.
double MedianVerticalOffset(const ModelGeoreference& r, size_t* compared) {
  const ReferenceGrid grid = LoadReference(EnuFrame(r.origin));
  std::vector<double> dz;
  for (const auto& [id, p] : r.model_enu.points3d) {
    const auto it = grid.height_by_cell.find(ReferenceGrid::Cell(p.xyz.x(), p.xyz.y()));
    if (it != grid.height_by_cell.end()) dz.push_back(p.xyz.z() - it->second);
  }
  *compared = dz.size();
  if (dz.empty()) return NAN;
  std::nth_element(dz.begin(), dz.begin() + dz.size() / 2, dz.end());
  return dz[dz.size() / 2];
}

ModelGeoreferenceOptions BrightonOptions() {
  ModelGeoreferenceOptions options;
  // EXIF (tests/data/colmap/brighton_exif.txt): FC300S, FocalLength 3.61 mm; 6.317 mm sensor; 1600 px.
  options.focal_prior_px[1] = 3.61 / 6.317 * 1600;
  options.focal_prior_source = "test fixture";
  return options;
}

TEST(GeoreferenceModel, BrightonBeachSimilarityAloneLeavesTheGroundElevenMetresLow) {
  const ColmapModel model = ReadColmapModel(testing::TestDataDir() / "colmap" / "brighton_sparse_default");
  const auto refs = ReadReferencesFile(testing::TestDataDir() / "colmap" / "brighton_refs_gps.txt");
  ModelGeoreferenceOptions options = BrightonOptions();
  options.bundle_adjust = false;
  const ModelGeoreference r = GeoreferenceModel(model, refs, options);
  size_t n = 0;
  const double dz = MedianVerticalOffset(r, &n);
  EXPECT_GT(n, 3000u);
  EXPECT_NEAR(dz, -10.9, 0.7);  // the data README's figure for COLMAP's model_aligner
  EXPECT_LT(r.first_fit.rmse_m, 1.0);
}

TEST(GeoreferenceModel, BrightonBeachBundleAdjustmentPutsTheGroundWithinOneMetre) {
  const ColmapModel model = ReadColmapModel(testing::TestDataDir() / "colmap" / "brighton_sparse_default");
  const auto refs = ReadReferencesFile(testing::TestDataDir() / "colmap" / "brighton_refs_gps.txt");
  const ModelGeoreferenceOptions options = BrightonOptions();
  const ModelGeoreference r = GeoreferenceModel(model, refs, options);
  size_t n = 0;
  const double dz = MedianVerticalOffset(r, &n);
  EXPECT_GT(n, 3000u);
  EXPECT_LT(std::abs(dz), 1.0) << dz;
  ASSERT_TRUE(r.bundle_adjustment);
  const FocalReport& f = r.bundle_adjustment->focal.at(0);
  EXPECT_NEAR(f.before_px, 1200.3, 1.0);
  EXPECT_NEAR(f.after_px, 914.3, 25);
  EXPECT_TRUE(f.held_at_prior);
  EXPECT_DOUBLE_EQ(f.after_px, 3.61 / 6.317 * 1600);
  // COLMAP's 31 % focal drift is reported.
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings.back().find("COLMAP's focal length (1200.3 px) differs from the prior (914.4 px) by 31.3 %"),
            std::string::npos)
      << r.warnings.back();
  EXPECT_LT(r.final_fit.rmse_m, 1.5);
  for (const auto& w : r.warnings) std::cerr << "warning: " << w << "\n";
  std::cerr << "iterations " << r.bundle_adjustment->iterations << " time " << r.bundle_adjustment->time_s
            << " converged " << r.bundle_adjustment->converged << "\n";
  std::cerr << "median dz " << dz << " m over " << n << " points; focal " << f.after_px << " px; images sigma "
            << f.images_sigma_ratio.value_or(-1) << "; preferred " << f.images_preferred_px.value_or(-1) << "\n"
            << DumpJson(GeoreferenceJson(r, options, true)).substr(0, 0);
}

// The model COLMAP mapped with the focal length fixed at the EXIF value: right already, and the bundle
// adjustment must keep it so.
TEST(GeoreferenceModel, BrightonBeachExifFocalModelStaysWithinOneMetre) {
  const ColmapModel model = ReadColmapModel(testing::TestDataDir() / "colmap" / "brighton_sparse_exif_focal");
  const auto refs = ReadReferencesFile(testing::TestDataDir() / "colmap" / "brighton_refs_gps.txt");
  for (bool ba : {false, true}) {
    ModelGeoreferenceOptions options = BrightonOptions();
    options.bundle_adjust = ba;
    const ModelGeoreference r = GeoreferenceModel(model, refs, options);
    size_t n = 0;
    EXPECT_LT(std::abs(MedianVerticalOffset(r, &n)), 1.0) << ba;
    EXPECT_GT(n, 3000u);
  }
}

TEST(GeoreferenceModel, BrightonBeachWithoutFocalPriorSaysItCannotResolveTheAmbiguity) {
  const ColmapModel model = ReadColmapModel(testing::TestDataDir() / "colmap" / "brighton_sparse_default");
  const auto refs = ReadReferencesFile(testing::TestDataDir() / "colmap" / "brighton_refs_gps.txt");
  const ModelGeoreference r = GeoreferenceModel(model, refs, ModelGeoreferenceOptions());
  ASSERT_TRUE(r.bundle_adjustment);
  EXPECT_FALSE(r.bundle_adjustment->geometry_resolves_focal);
  EXPECT_LT(r.bundle_adjustment->depth_relief_ratio, 0.05);
  EXPECT_LT(r.bundle_adjustment->view_axis_spread_deg, 5.0);
  EXPECT_FALSE(r.bundle_adjustment->focal.at(0).images_resolve_focal);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("cannot resolve focal length vs flying height"), std::string::npos) << r.warnings[0];
  EXPECT_NE(r.warnings[0].find("no focal-length prior is known"), std::string::npos) << r.warnings[0];
  // Without a prior nothing can put the ground back: it stays where a similarity puts it.
  size_t n = 0;
  EXPECT_LT(MedianVerticalOffset(r, &n), -9.0);
}

// ---------------------------------------------------------------------------------------------
// Ground control points: a synthetic survey with surveyed ground targets, their pixels measured with
// noise, written as an OpenDroneMap gcp_list.txt in UTM.

struct GcpSurvey {
  testing::SyntheticScene scene;
  Geodetic origin{46.84, -91.99, 160.0};
  std::vector<Eigen::Vector3d> gcp_enu_m;
  std::string gcp_text;
};

// GCP targets on the ground of the synthetic terrain (the survey covers about 75 m x 30 m).
GcpSurvey MakeGcpSurvey(double pixel_noise_px, uint64_t seed) {
  GcpSurvey s;
  testing::SyntheticOptions o;
  o.enu_from_colmap = testing::DefaultColmapFrame();
  s.scene = testing::MakeSyntheticScene(o);
  const double en[][2] = {{-30, -12}, {30, -12}, {-30, 12}, {30, 12}, {0, 0}, {-12, 6}};
  for (const auto& p : en) {
    s.gcp_enu_m.push_back({p[0], p[1], testing::SyntheticGroundHeight(p[0], p[1], o.terrain_relief_m)});
  }
  const EnuFrame frame(s.origin);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0, pixel_noise_px);
  std::ostringstream text;
  text.precision(12);
  text << "WGS84 UTM 15N\n";
  for (size_t g = 0; g < s.gcp_enu_m.size(); ++g) {
    const Geodetic geo = frame.GeodeticFromEnu(s.gcp_enu_m[g]);
    int zone;
    bool north;
    double x, y;
    GeographicLib::UTMUPS::Forward(geo.lat_deg, geo.lon_deg, zone, north, x, y, 15);
    for (const auto& [id, image] : s.scene.model_enu.images) {
      const ColmapCamera& cam = s.scene.model_enu.cameras.at(image.camera_id);
      const Eigen::Vector3d c = image.cam_from_world_rotation * s.gcp_enu_m[g] + image.cam_from_world_translation;
      double px, py;
      ProjectNormalizedToPixel(cam.model_id, cam.params.data(), c.x() / c.z(), c.y() / c.z(), &px, &py);
      if (px < 20 || py < 20 || px > cam.width_px - 20 || py > cam.height_px - 20) continue;
      // gcp_list.txt pixels: centre of the top-left pixel at (0, 0).
      text << x << " " << y << " " << geo.height_m << " " << px - 0.5 + noise(rng) << " " << py - 0.5 + noise(rng)
           << " " << image.name << " GCP" << g + 1 << "\n";
    }
  }
  s.gcp_text = text.str();
  return s;
}

double MedianPointErrorM(const ColmapModel& estimate, const ColmapModel& truth) {
  std::vector<double> err;
  for (const auto& [id, p] : estimate.points3d) err.push_back((p.xyz - truth.points3d.at(id).xyz).norm());
  std::sort(err.begin(), err.end());
  return err[err.size() / 2];
}

double WorstCameraErrorM(const ColmapModel& estimate, const testing::SyntheticScene& scene) {
  double worst = 0;
  for (const auto& [id, image] : estimate.images) {
    worst = std::max(worst, (image.ProjectionCenter() - scene.camera_centers_enu_m[id - 1]).norm());
  }
  return worst;
}

TEST(GeoreferenceModelGcp, GcpsAloneRecoverTheTransform) {
  const GcpSurvey s = MakeGcpSurvey(0.5, 11);
  const GcpFile gcps = ParseGcpFile(s.gcp_text, "gcp_list.txt");
  ModelGeoreferenceOptions options;
  options.origin = s.origin;
  options.bundle_adjust = false;
  const ModelGeoreference r = GeoreferenceModel(s.scene.model, {}, &gcps, options);
  EXPECT_EQ(r.fit_references, "gcps");
  EXPECT_EQ(r.final_fit.num_inliers, 6);
  const Similarity3 truth = testing::DefaultColmapFrame();
  const double scale_error = std::abs(r.enu_from_colmap.scale / truth.scale - 1);
  const double rotation_error_deg =
      Eigen::AngleAxisd(r.enu_from_colmap.rotation.conjugate() * truth.rotation).angle() * 180 / M_PI;
  const double translation_error_m = (r.enu_from_colmap.translation - truth.translation).norm();
  EXPECT_LT(scale_error, 1e-3);
  EXPECT_LT(rotation_error_deg, 0.05);
  // The translation is the image of COLMAP's origin, ~160 m from the scene: it carries the rotation error.
  EXPECT_LT(translation_error_m, 0.15);
  EXPECT_LT(WorstCameraErrorM(r.model_enu, s.scene), 0.10);
  for (const GcpUse& u : r.gcps) {
    EXPECT_TRUE(u.usable) << u.gcp.name << ": " << u.skipped_reason;
    EXPECT_GE(u.triangulation.num_used, 3) << u.gcp.name;
    EXPECT_LT(u.triangulation.rms_reprojection_px, 1.0) << u.gcp.name;
    EXPECT_GT(u.triangulation.max_angle_deg, 10.0) << u.gcp.name;
  }
  EXPECT_LT(r.gcp_check_rmse_m, 0.05);
  std::printf(
      "GCP only (0.5 px noise, 6 GCPs): scale error %.2e, rotation %.4f deg, translation %.4f m, worst camera "
      "%.3f m, GCP check RMSE %.3f m\n",
      scale_error, rotation_error_deg, translation_error_m, WorstCameraErrorM(r.model_enu, s.scene),
      r.gcp_check_rmse_m);

  // With the bundle adjustment (GCPs as priors, no GPS at all), the scene stays put.
  options.bundle_adjust = true;
  const ModelGeoreference ba = GeoreferenceModel(s.scene.model, {}, &gcps, options);
  ASSERT_TRUE(ba.bundle_adjustment);
  EXPECT_EQ(ba.bundle_adjustment->num_gps_priors, 0);
  EXPECT_EQ(ba.bundle_adjustment->num_control_points, 6);
  // No focal prior here: the focal length is free, and camera heights move with it.
  EXPECT_LT(MedianPointErrorM(ba.model_enu, s.scene.model_enu), 0.05);
  EXPECT_LT(WorstCameraErrorM(ba.model_enu, s.scene), 0.20);
  EXPECT_LT(ba.gcp_check_rmse_m, 0.05);
  std::printf("GCP only + bundle adjustment: median point error %.3f m, worst camera %.3f m, GCP check RMSE %.3f m\n",
              MedianPointErrorM(ba.model_enu, s.scene.model_enu), WorstCameraErrorM(ba.model_enu, s.scene),
              ba.gcp_check_rmse_m);
  const Json j = GeoreferenceJson(ba, options, false);
  const Json& g = j["georeferencing"]["ground_control_points"];
  EXPECT_EQ(g["usable"], 6);
  EXPECT_EQ(g["coordinate_system"], "WGS84 UTM 15N");
  EXPECT_EQ(g["points"][0]["name"], "GCP1");
  EXPECT_LT(g["points"][0]["check_residual_m"].get<double>(), 0.1);
  EXPECT_EQ(j["georeferencing"]["fit_references"], "gcps");
}

TEST(GeoreferenceModelGcp, GcpsCorrectBiasedCameraGps) {
  const GcpSurvey s = MakeGcpSurvey(0.5, 12);
  const GcpFile gcps = ParseGcpFile(s.gcp_text, "gcp_list.txt");
  // Camera GPS 6.2 m off (a datum or antenna-offset mistake), with 0.5 m noise.
  const Eigen::Vector3d bias(3.0, -2.0, 5.0);
  const EnuFrame frame(s.origin);
  std::mt19937_64 rng(5);
  std::normal_distribution<double> noise(0, 0.5);
  std::vector<ImageReference> refs;
  for (const auto& [id, image] : s.scene.model.images) {
    const Eigen::Vector3d p =
        s.scene.camera_centers_enu_m[id - 1] + bias + Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    const Geodetic g = frame.GeodeticFromEnu(p);
    refs.push_back({image.name, g.lat_deg, g.lon_deg, g.height_m, "synthetic"});
  }
  ModelGeoreferenceOptions options;
  options.origin = s.origin;
  options.focal_prior_px[1] = 900;
  // Camera GPS alone: the scene lands where the biased GPS says.
  const ModelGeoreference gps_only = GeoreferenceModel(s.scene.model, refs, options);
  const double gps_only_error = MedianPointErrorM(gps_only.model_enu, s.scene.model_enu);
  EXPECT_GT(gps_only_error, 5.0);
  // With the GCPs: back within centimetres; the camera references' residuals show the bias.
  const ModelGeoreference r = GeoreferenceModel(s.scene.model, refs, &gcps, options);
  EXPECT_EQ(r.fit_references, "gcps");
  const double error = MedianPointErrorM(r.model_enu, s.scene.model_enu);
  EXPECT_LT(error, 0.05);
  EXPECT_LT(WorstCameraErrorM(r.model_enu, s.scene), 0.10);
  EXPECT_LT(r.gcp_check_rmse_m, 0.05);
  ASSERT_EQ(r.camera_residuals_m.size(), 18u);
  for (const auto& [i, residual] : r.camera_residuals_m) EXPECT_NEAR(residual, bias.norm(), 1.5);
  // The GPS is 6.2 m off, beyond the 5 m inlier threshold: no GPS prior pulls against the GCPs.
  EXPECT_LT(r.bundle_adjustment->num_gps_priors, 18);
  std::printf(
      "camera GPS biased by %.1f m: GPS only median point error %.2f m; with 6 GCPs %.3f m (GCP check RMSE "
      "%.3f m)\n",
      bias.norm(), gps_only_error, error, r.gcp_check_rmse_m);
}

TEST(GeoreferenceModelGcp, UnusableGcpsAreReportedAndSkipped) {
  GcpSurvey s = MakeGcpSurvey(0.3, 13);
  // GCP7 in one image only; GCP8 without elevation; GCP9 in images the model does not have.
  std::istringstream lines(s.gcp_text);
  std::string header, first_obs;
  std::getline(lines, header);
  std::getline(lines, first_obs);
  std::istringstream is(first_obs);
  double x, y, z, px, py;
  std::string image;
  is >> x >> y >> z >> px >> py >> image;
  std::ostringstream extra;
  extra.precision(12);
  extra << x + 5 << " " << y << " " << z << " 100 100 " << image << " GCP7\n";
  extra << x << " " << y + 5 << " NaN 100 100 IMG_1001.JPG GCP8\n"
        << x << " " << y + 5 << " NaN 200 100 IMG_1002.JPG GCP8\n";
  extra << x << " " << y - 5 << " " << z << " 100 100 other1.jpg GCP9\n"
        << x << " " << y - 5 << " " << z << " 100 100 other2.jpg GCP9\n";
  const GcpFile gcps = ParseGcpFile(s.gcp_text + extra.str(), "gcp_list.txt");
  ModelGeoreferenceOptions options;
  options.origin = s.origin;
  options.bundle_adjust = false;
  const ModelGeoreference r = GeoreferenceModel(s.scene.model, {}, &gcps, options);
  ASSERT_EQ(r.gcps.size(), 9u);
  EXPECT_FALSE(r.gcps[6].usable);
  EXPECT_NE(r.gcps[6].skipped_reason.find("fewer than 2 usable observations"), std::string::npos);
  EXPECT_FALSE(r.gcps[7].usable);
  EXPECT_NE(r.gcps[7].skipped_reason.find("no elevation"), std::string::npos);
  EXPECT_FALSE(r.gcps[8].usable);
  EXPECT_EQ(r.gcps[8].observation_results[0].note, "no registered image of that name");
  EXPECT_EQ(r.final_fit.num_inliers, 6);
  int warnings = 0;
  for (const auto& w : r.warnings) warnings += w.find("ground control point 'GCP") != std::string::npos ? 1 : 0;
  EXPECT_EQ(warnings, 3);
}

TEST(GeoreferenceModelGcp, TooFewGcpsWithoutCameraReferencesIsRefused) {
  const GcpSurvey s = MakeGcpSurvey(0.3, 14);
  // Keep GCP1 and GCP2 only.
  std::string text = "WGS84 UTM 15N\n";
  std::istringstream is(s.gcp_text);
  std::string line;
  std::getline(is, line);
  while (std::getline(is, line)) {
    if (line.ends_with(" GCP1") || line.ends_with(" GCP2")) text += line + "\n";
  }
  const GcpFile gcps = ParseGcpFile(text, "gcp_list.txt");
  ModelGeoreferenceOptions options;
  options.origin = s.origin;
  try {
    GeoreferenceModel(s.scene.model, {}, &gcps, options);
    FAIL();
  } catch (const InfeasibleError& e) {
    EXPECT_NE(std::string(e.what()).find("at least 3 usable references (cameras and ground control points), found 2"),
              std::string::npos)
        << e.what();
  }
}

TEST(GeoreferenceModelGcp, TwoGcpsJoinTheCameraReferences) {
  const GcpSurvey s = MakeGcpSurvey(0.3, 15);
  std::string text = "WGS84 UTM 15N\n";
  std::istringstream is(s.gcp_text);
  std::string line;
  std::getline(is, line);
  while (std::getline(is, line)) {
    if (line.ends_with(" GCP1") || line.ends_with(" GCP4")) text += line + "\n";
  }
  const GcpFile gcps = ParseGcpFile(text, "gcp_list.txt");
  const EnuFrame frame(s.origin);
  std::vector<ImageReference> refs;
  for (const auto& [id, image] : s.scene.model.images) {
    const Geodetic g = frame.GeodeticFromEnu(s.scene.camera_centers_enu_m[id - 1]);
    refs.push_back({image.name, g.lat_deg, g.lon_deg, g.height_m, "synthetic"});
  }
  ModelGeoreferenceOptions options;
  options.origin = s.origin;
  options.bundle_adjust = false;
  const ModelGeoreference r = GeoreferenceModel(s.scene.model, refs, &gcps, options);
  EXPECT_EQ(r.fit_references, "cameras+gcps");
  EXPECT_EQ(r.final_fit.num_inliers, 20);
  EXPECT_EQ(r.pair_labels.back(), "GCP4");
  EXPECT_LT(r.gcp_check_rmse_m, 0.05);
}

}  // namespace
}  // namespace cinepath::photogrammetry
