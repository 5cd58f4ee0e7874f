#include "photogrammetry/pipeline/surface_pipeline.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "core/error.h"
#include "tests/photogrammetry/surface_test_meshes.h"

namespace cinepath::photogrammetry {
namespace {

const Json* FindStep(const Json& report, const std::string& name) {
  for (const Json& step : report["steps"]) {
    if (step["step"] == name) return &step;
  }
  return nullptr;
}

TEST(BuildSurfaceFromPoints, NadirCloudGivesAHeightFieldReportAndGlb) {
  PointCloud cloud = testing::TerrainCloud(60, 50, 1.0);
  cloud.reprojection_error_px[10] = 9.0;
  SurfacePipelineOptions options;
  options.target_faces = 1500;
  options.report_times = false;
  options.gltf_extras = Json::parse(R"({"origin": {"lat_deg": 1.0, "lon_deg": 2.0, "height_m": 3.0}})");
  const SurfacePipelineResult result = BuildSurfaceFromPoints(cloud, options);
  const Json& report = result.report;
  ASSERT_NE(FindStep(report, "filter_points"), nullptr);
  EXPECT_EQ((*FindStep(report, "filter_points"))["removed_reprojection"], 1);
  ASSERT_NE(FindStep(report, "height_field"), nullptr);
  ASSERT_NE(FindStep(report, "clean"), nullptr);
  const Json* decimate = FindStep(report, "decimate");
  ASSERT_NE(decimate, nullptr);
  EXPECT_EQ((*decimate)["faces_out"].get<size_t>(), result.mesh.num_faces());
  EXPECT_LE(result.mesh.num_faces(), 1800u);
  EXPECT_GT((*decimate)["hausdorff_m"].get<double>(), 0.0);
  EXPECT_LT((*decimate)["hausdorff_m"].get<double>(), 0.5);
  EXPECT_FALSE((*decimate).contains("time_s"));
  EXPECT_EQ((*FindStep(report, "colors"))["source"], "surface");
  EXPECT_EQ(report["output"]["faces"].get<size_t>(), result.mesh.num_faces());
  EXPECT_EQ(result.mesh.colors_rgb.size(), result.mesh.num_vertices());
  ASSERT_GT(result.glb.size(), 100u);
  EXPECT_EQ(result.glb.substr(0, 4), "glTF");
  EXPECT_NE(result.glb.find("\"lat_deg\""), std::string::npos);

  // Deterministic bytes and report.
  const SurfacePipelineResult again = BuildSurfaceFromPoints(cloud, options);
  EXPECT_EQ(again.glb, result.glb);
  EXPECT_EQ(DumpJson(again.report), DumpJson(result.report));
}

// The Poisson path end to end (filter, Poisson, trim, clean, decimate, colours, GLB) on a scene no
// height field can hold (a wall over a floor): the same bytes and report when run again in the same
// process, and when run on one thread.
TEST(BuildSurfaceFromPoints, PoissonPathGivesTheSameBytesAgainAndOnOneThread) {
  const PointCloud cloud = testing::LCloud();
  SurfacePipelineOptions options;
  options.method = SurfaceMethod::kPoisson;
  options.target_faces = 600;  // the trimmed surface has about 870 faces: the decimation works too
  options.report_times = false;
  const SurfacePipelineResult first = BuildSurfaceFromPoints(cloud, options);
  ASSERT_NE(FindStep(first.report, "poisson"), nullptr);
  ASSERT_NE(FindStep(first.report, "trim"), nullptr);
  const Json* decimate = FindStep(first.report, "decimate");
  ASSERT_NE(decimate, nullptr);
  EXPECT_GT((*decimate)["faces_in"].get<int64_t>(), 600);
  EXPECT_LE(first.mesh.num_faces(), 600u);
  EXPECT_GT(first.mesh.num_faces(), 500u);
  const SurfacePipelineResult again = BuildSurfaceFromPoints(cloud, options);
  SurfacePipelineResult one_thread;
  {
    const tbb::global_control cap(tbb::global_control::max_allowed_parallelism, 1);
    one_thread = BuildSurfaceFromPoints(cloud, options);
  }
  for (const SurfacePipelineResult* other : {&again, static_cast<const SurfacePipelineResult*>(&one_thread)}) {
    EXPECT_TRUE(other->glb == first.glb);
    EXPECT_EQ(DumpJson(other->report), DumpJson(first.report));
  }
}

TEST(BuildSurfaceFromPoints, ErrorBoundIsMetByTheMeasuredHausdorffDistance) {
  const PointCloud cloud = testing::TerrainCloud(60, 50, 1.0);
  SurfacePipelineOptions options;
  options.max_error_m = 0.05;
  options.draco = true;
  const SurfacePipelineResult result = BuildSurfaceFromPoints(cloud, options);
  const Json* decimate = FindStep(result.report, "decimate");
  ASSERT_NE(decimate, nullptr);
  EXPECT_LE((*decimate)["hausdorff_m"].get<double>(), 0.05);
  EXPECT_LT((*decimate)["faces_out"].get<int64_t>(), (*decimate)["faces_in"].get<int64_t>());
  EXPECT_TRUE((*decimate).contains("time_s"));
  EXPECT_NE(result.glb.find("KHR_draco_mesh_compression"), std::string::npos);
}

TEST(BuildSurfaceFromMesh, UsesTheGivenMeshAndColoursItFromPoints) {
  TriangleMesh mesh = testing::TerrainGrid(30, 30, 1.0);
  mesh.colors_rgb.clear();
  const PointCloud cloud = testing::TerrainCloud(30, 30, 1.0);
  SurfacePipelineOptions options;
  options.quality = Quality::kDraft;
  const SurfacePipelineResult result = BuildSurfaceFromMesh(mesh, &cloud, options);
  EXPECT_EQ(result.mesh.num_faces(), mesh.num_faces());  // under the draft budget: untouched
  EXPECT_EQ((*FindStep(result.report, "colors"))["source"], "nearest_points");
  EXPECT_EQ(result.mesh.colors_rgb.size(), result.mesh.num_vertices());
  EXPECT_EQ(result.report["quality"], "draft");
}

TEST(SurfacePipelineOptions, CheckRejectsConflictingOrInvalidGoals) {
  SurfacePipelineOptions options;
  options.target_faces = 10;
  options.max_error_m = 0.1;
  EXPECT_THROW(options.Check(), InputError);
  options.max_error_m.reset();
  options.target_faces = 0;
  EXPECT_THROW(options.Check(), InputError);
  options.target_faces.reset();
  options.max_error_m = -1.0;
  EXPECT_THROW(options.Check(), InputError);
  EXPECT_EQ(ParseQuality("final"), Quality::kFinal);
  EXPECT_THROW(ParseQuality("best"), InputError);
  EXPECT_EQ(ParseSurfaceMethod("poisson"), SurfaceMethod::kPoisson);
  EXPECT_THROW(ParseSurfaceMethod("marching"), InputError);
}

TEST(BuildSurfaceFromPoints, TooFewPointsIsBadInput) {
  PointCloud cloud;
  cloud.positions_m = {{0, 0, 0}, {1, 0, 0}};
  EXPECT_THROW(BuildSurfaceFromPoints(cloud, SurfacePipelineOptions{}), InputError);
}

// A slope seen from the side: `auto` picks Poisson, whose solver cannot take points that span no volume
// (all on one plane); the surface step falls back to the height field and says why. Asked for by name,
// Poisson is refused with the cause and the switch to use.
TEST(BuildSurfaceFromPoints, PointsOnOnePlaneFallBackFromPoissonToTheHeightField) {
  PointCloud cloud;
  cloud.camera_centers_m = {{-60, 0, 5}, {-60, 20, 5}, {-60, -20, 5}};
  for (int i = 0; i <= 40; ++i) {
    for (int j = 0; j <= 40; ++j) {
      const double x = i * 0.5, y = j * 0.5 - 10;  // exact in binary: the points are exactly coplanar
      cloud.positions_m.emplace_back(x, y, 0.5 * x);
      cloud.colors_rgb.push_back({120, 120, 120});
      cloud.observers.push_back({0, 1, 2});
    }
  }
  SurfacePipelineOptions options;
  options.report_times = false;
  const SurfacePipelineResult result = BuildSurfaceFromPoints(cloud, options);
  const Json* surface = FindStep(result.report, "height_field");
  ASSERT_NE(surface, nullptr) << DumpJson(result.report);
  EXPECT_EQ((*surface)["fallback_from"], "poisson");
  EXPECT_NE((*surface)["fallback_reason"].get<std::string>().find("one plane"), std::string::npos);
  EXPECT_GT(result.mesh.num_faces(), 100u);

  options.method = SurfaceMethod::kPoisson;
  try {
    BuildSurfaceFromPoints(cloud, options);
    ADD_FAILURE() << "--surface poisson accepted points on one plane";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--surface height-field"), std::string::npos) << e.what();
  }
}

TEST(BuildSurfaceFromMesh, RecordsTheHausdorffSamplingAndThePresetsMethod) {
  const TriangleMesh mesh = testing::TerrainGrid(80, 80, 0.5);  // 12,482 faces
  int64_t draft_samples = 0, final_samples = 0;
  for (Quality quality : {Quality::kDraft, Quality::kFinal}) {
    SurfacePipelineOptions options;
    options.quality = quality;
    options.target_faces = 1500;
    options.report_times = false;
    const SurfacePipelineResult result = BuildSurfaceFromMesh(mesh, nullptr, options);
    const Json* decimate = FindStep(result.report, "decimate");
    ASSERT_NE(decimate, nullptr);
    EXPECT_TRUE((*decimate)["hausdorff_vertex_samples"].get<bool>());
    EXPECT_EQ((*decimate)["hausdorff_seed"], 1);
    // Every preset's simplifier (final's too since 2026-11-30: bench/RESULTS.md, "--quality presets").
    EXPECT_EQ((*decimate)["method"], "qem_tiled");
    const int64_t samples = (*decimate)["hausdorff_samples"].get<int64_t>();
    // Every face sample and every vertex of both meshes.
    EXPECT_EQ((*decimate)["hausdorff_points_measured"].get<int64_t>(),
              2 * samples + static_cast<int64_t>(mesh.num_vertices() + result.mesh.num_vertices()));
    EXPECT_LE((*decimate)["hausdorff_in_to_out_m"].get<double>(), (*decimate)["hausdorff_m"].get<double>());
    EXPECT_EQ(std::max((*decimate)["hausdorff_in_to_out_m"].get<double>(),
                       (*decimate)["hausdorff_out_to_in_m"].get<double>()),
              (*decimate)["hausdorff_m"].get<double>());
    (quality == Quality::kDraft ? draft_samples : final_samples) = samples;
  }
  EXPECT_LT(draft_samples, final_samples);
  SurfacePipelineOptions options;
  options.target_faces = 1500;
  options.decimation_method = DecimationMethod::kCgalGarlandHeckbertProbabilistic;
  const SurfacePipelineResult result = BuildSurfaceFromMesh(mesh, nullptr, options);
  EXPECT_EQ((*FindStep(result.report, "decimate"))["method"], "cgal_garland_heckbert_probabilistic");
}

TEST(BuildSurfaceFromMesh, RemeshStepIsRecordedAndMeasured) {
  const TriangleMesh mesh = testing::TerrainGrid(41, 41, 1.0);
  SurfacePipelineOptions options;
  options.target_faces = 1000;
  // The band fraction below is the remesher's, on meshoptimizer's even output; after qem_tiled's
  // quadric collapse (long triangles on the flat parts) the same remesh reaches 0.64.
  options.decimation_method = DecimationMethod::kMeshoptimizerPartitioned;
  options.remesh_edge_m = 1.5;
  options.report_times = false;
  const SurfacePipelineResult result = BuildSurfaceFromMesh(mesh, nullptr, options);
  const Json* remesh = FindStep(result.report, "remesh");
  ASSERT_NE(remesh, nullptr);
  EXPECT_EQ((*remesh)["target_edge_m"], 1.5);
  EXPECT_EQ((*remesh)["faces_out"].get<size_t>(), result.mesh.num_faces());
  EXPECT_GT((*remesh)["edges_in_band_fraction"].get<double>(), 0.7);
  EXPECT_LT((*remesh)["hausdorff_m"].get<double>(), 0.2);
  EXPECT_EQ(result.report["output"]["hausdorff_m"], (*remesh)["hausdorff_m"]);
  EXPECT_EQ(result.mesh.colors_rgb.size(), result.mesh.num_vertices());
  options.remesh_edge_m = -1.0;
  EXPECT_THROW(options.Check(), InputError);
}

}  // namespace
}  // namespace cinepath::photogrammetry
