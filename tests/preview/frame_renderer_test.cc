// Known answers, measured in rendered images: the blur of an edge, the plane of focus, the pinhole
// limit, a uniform emitter, a motion streak, the exposure, the sensor fit; and the same pixels at any
// thread count and far from the origin.
#include "preview/frame_renderer.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numeric>

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include "core/error.h"
#include "core/optics.h"
#include "preview/aov.h"
#include "preview/thin_lens_camera.h"

namespace cinepath::preview {
namespace {

constexpr int kWidth = 240;
constexpr int kHeight = 24;

// A wall facing the camera, `distance_m` north of `camera`, black west of the camera and white east
// of it (or all `color` when given).
scene::SceneMesh Wall(const Eigen::Vector3d& camera, double distance_m,
                      std::optional<Eigen::Vector3f> color = std::nullopt) {
  scene::SceneMesh mesh;
  const double y = camera.y() + distance_m;
  for (int half = 0; half < 2; ++half) {
    const double x0 = camera.x() + (half == 0 ? -60 : 0), x1 = camera.x() + (half == 0 ? 0 : 60);
    const uint32_t base = uint32_t(mesh.positions_enu_m.size());
    for (const auto& [x, z] : {std::pair{x0, -60.0}, {x1, -60.0}, {x1, 60.0}, {x0, 60.0}}) {
      mesh.positions_enu_m.emplace_back(x, y, camera.z() + z);
      mesh.colors_linear.push_back(color.value_or(Eigen::Vector3f::Constant(half == 0 ? 0.0f : 1.0f)));
    }
    mesh.faces.push_back({base, base + 1, base + 2});
    mesh.faces.push_back({base, base + 2, base + 3});
  }
  return mesh;
}

// Three samples at 30 Hz, the camera still at `camera` looking north, level.
Trajectory StillCamera(const Eigen::Vector3d& camera, double focal_mm, double f_number, double focus_m,
                       double shutter_s = 1.0 / 50) {
  Trajectory plan;
  plan.camera.sensor_width_mm = 36;
  plan.camera.sensor_height_mm = 24;
  plan.camera.width_px = kWidth;
  plan.camera.height_px = kHeight;
  Eigen::Matrix3d r;
  r << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  for (int k = 0; k < 3; ++k) {
    TrajectorySample s;
    s.time_s = k / 30.0;
    s.position_enu_m = camera;
    s.world_from_camera = Eigen::Quaterniond(r);
    s.focal_length_mm = focal_mm;
    s.f_number = f_number;
    s.focus_distance_m = focus_m;
    s.shutter_s = shutter_s;
    s.shot = "test";
    plan.samples.push_back(s);
  }
  return plan;
}

FrameSettings Settings(Quality quality, int max_samples) {
  FrameSettings settings;
  settings.width_px = kWidth;
  settings.height_px = kHeight;
  settings.preset = PresetFor(quality);
  settings.preset.max_samples = max_samples;
  return settings;
}

FrameImage Render(scene::SceneMesh mesh, const Trajectory& plan, const FrameSettings& settings, size_t k = 1) {
  const PreviewScene scene(std::move(mesh), plan, Shading::kFlat, SunDirection{});
  return RenderFrame(scene, plan, k, settings);
}

// A 40 x 40 m green ground patch at z = 2 m, its near edge 5 m north of the origin, seen by the level still
// camera 10 m up at the origin looking north: the patch fills part of the frame below the horizon; past its
// far edge (and beside it) the frame looks over the edge of the world.
scene::SceneMesh GroundPatch() {
  scene::SceneMesh mesh;
  for (const auto& [x, y] : {std::pair{-20.0, 5.0}, {20.0, 5.0}, {20.0, 45.0}, {-20.0, 45.0}}) {
    mesh.positions_enu_m.emplace_back(x, y, 2.0);
    mesh.colors_linear.emplace_back(0.1f, 0.6f, 0.1f);
  }
  mesh.faces = {{0, 1, 2}, {0, 2, 3}};
  return mesh;
}

// The horizon: with the ground backdrop every pixel below the horizon has a finite depth (the plane at the
// border's height, 2 m, in the border's colour hazed toward the sky), and none above it; with
// --backdrop none, the rays that miss the patch below the horizon see flat grey at infinite depth.
TEST(FrameRenderer, TheGroundContinuesPastTheMeshToTheHorizon) {
  const Trajectory plan = StillCamera({0, 0, 10}, 24, 8, 30);
  FrameSettings settings = Settings(Quality::kStandard, 4);
  settings.height_px = 160;  // tall enough to see the patch, the ground past it and the sky
  Trajectory tall = plan;
  tall.camera.height_px = 160;
  tall.camera.sensor_height_mm = 24.0;
  tall.camera.sensor_width_mm = 36.0;
  settings.width_px = 240;
  for (Backdrop backdrop : {Backdrop::kGround, Backdrop::kNone}) {
    const PreviewScene scene(GroundPatch(), tall, Shading::kFlat, SunDirection{}, backdrop);
    if (backdrop == Backdrop::kGround) {
      ASSERT_TRUE(scene.ground().has_value());
      EXPECT_DOUBLE_EQ(scene.ground()->height_m, 2.0);
      for (const Eigen::Vector3f& c : scene.ground()->sector_color) EXPECT_NEAR(c.y(), 0.6f, 1e-6);
    }
    const FrameImage image = RenderFrame(scene, tall, 1, settings);
    int below_infinite = 0, below = 0, above_finite = 0;
    for (int y = 0; y < image.height; ++y) {
      // The camera is level: rows below the middle look down, rows above look up.
      const bool looks_down = y + 0.5 > image.height / 2.0 + 1;
      const bool looks_up = y + 0.5 < image.height / 2.0 - 1;
      for (int x = 0; x < image.width; ++x) {
        const double depth = image.depth_m[size_t(y) * image.width + x];
        if (looks_down) {
          ++below;
          below_infinite += std::isinf(depth);
        }
        if (looks_up) above_finite += std::isfinite(depth);
      }
    }
    EXPECT_EQ(above_finite, 0);
    if (backdrop == Backdrop::kGround) {
      EXPECT_EQ(below_infinite, 0) << "of " << below;
    } else {
      EXPECT_GT(below_infinite, below / 4) << "of " << below;
    }
  }
}

// The ground past the edge hides no subject. The plane lies at the border's height (2 m), and a subject
// standing lower (1.8 m tall on z = 0, 15 m past the patch's far edge) is seen by rays that miss the patch
// and cross the plane before they reach it: the subject is drawn whole, in both passes, as with
// --backdrop none.
TEST(FrameRenderer, TheGroundPastTheEdgeHidesNoSubject) {
  Trajectory tall = StillCamera({0, 0, 10}, 24, 8, 60);
  tall.camera.width_px = 240;
  tall.camera.height_px = 160;
  SubjectTrack person;
  person.height_m = 1.8;
  person.positions_enu_m.assign(3, Eigen::Vector3d(0, 60, 0));
  tall.subjects.push_back(person);
  for (Quality quality : {Quality::kDraft, Quality::kStandard}) {
    FrameSettings settings = Settings(quality, 4);
    settings.width_px = 240;
    settings.height_px = 160;
    std::array<int, 2> seen{};
    for (Backdrop backdrop : {Backdrop::kGround, Backdrop::kNone}) {
      const PreviewScene scene(GroundPatch(), tall, Shading::kFlat, SunDirection{}, backdrop);
      if (backdrop == Backdrop::kGround) ASSERT_DOUBLE_EQ(scene.ground()->height_m, 2.0);
      const FrameImage image = RenderFrame(scene, tall, 1, settings);
      for (float id : image.subject_id) seen[backdrop == Backdrop::kGround ? 0 : 1] += id == 1 ? 1 : 0;
    }
    EXPECT_GT(seen[1], 4) << "quality " << int(quality);
    EXPECT_EQ(seen[0], seen[1]) << "quality " << int(quality);
  }
}

// render builds the BVH and finds the border ring beside the textures' decoding and hands them to the
// scene: the same pixels, depths and ground as the scene that builds them itself.
TEST(FrameRenderer, AScenePreparedBesideItsTexturesRendersTheSameFrame) {
  Trajectory tall = StillCamera({0, 0, 10}, 24, 8, 30);
  tall.camera.height_px = 160;
  FrameSettings settings = Settings(Quality::kStandard, 4);
  settings.height_px = 160;
  const scene::SceneMesh mesh = GroundPatch();
  const PreviewScene built(mesh, tall, Shading::kSun, SunDirection{}, Backdrop::kGround);
  PreviewScene::Prepared prepared;
  prepared.caster = std::make_shared<const scene::RayCaster>(mesh);
  prepared.ring = std::make_shared<const scene::BorderRing>(scene::FindBorderRing(mesh));
  const PreviewScene given(mesh, DecodeTextures(mesh), prepared, tall, Shading::kSun, SunDirection{},
                           Backdrop::kGround);
  ASSERT_TRUE(given.ground().has_value());
  EXPECT_EQ(given.ground()->sector_color, built.ground()->sector_color);
  const FrameImage a = RenderFrame(built, tall, 1, settings), b = RenderFrame(given, tall, 1, settings);
  EXPECT_EQ(a.rgb_linear, b.rgb_linear);
  EXPECT_EQ(a.depth_m, b.depth_m);
  // Without a ring given, the scene finds it.
  const PreviewScene no_ring(mesh, DecodeTextures(mesh), {prepared.caster, nullptr}, tall, Shading::kSun,
                             SunDirection{}, Backdrop::kGround);
  EXPECT_EQ(no_ring.ground()->sector_color, built.ground()->sector_color);
}

// A wall 50 m north of the camera at (0, 0, 10) covered by a texture of one-texel black and white checks,
// repeated so that a pixel of the 240-px frame spans ~23 texels: draft's pinhole pass, reading the level of
// the pyramid the pixel spans, shows the checks' mean (linear 0.5) in every pixel of the wall; read from
// the image itself, each pixel lands on one check (black or white: aliasing).
TEST(FrameRenderer, DraftReadsAFineTextureAtTheLevelItsPixelsSpan) {
  const Trajectory plan = StillCamera({0, 0, 10}, 24, 16, 50);
  scene::SceneMesh mesh;
  for (const auto& [x, z] : {std::pair{-40.0, -20.0}, {40.0, -20.0}, {40.0, 40.0}, {-40.0, 40.0}}) {
    mesh.positions_enu_m.emplace_back(x, 50.0, z);
    mesh.texcoords.emplace_back(float((x + 40) / 80 * 23.3), float((40 - z) / 60 * 17.7));
    mesh.colors_linear.emplace_back(1.0f, 1.0f, 1.0f);  // the texture's colour alone
  }
  mesh.faces = {{0, 1, 2}, {0, 2, 3}};
  mesh.face_material = {0, 0};
  mesh.materials.resize(1);
  mesh.materials[0].base_color_image = 0;
  mesh.images.resize(1);
  // 23.3 repeats over 80 m: 75 texels a metre, 0.31 m a pixel at 50 m (not a whole number of texels a
  // pixel, so the pixels land on both colours of the checks).
  constexpr int kSize = 256;
  std::vector<Texture> textures(1);
  Texture& checks = textures[0];
  checks.width = checks.height = kSize;
  checks.srgb.resize(size_t(kSize) * kSize * 3);
  for (size_t i = 0; i < checks.srgb.size(); ++i) {
    const size_t texel = i / 3;
    checks.srgb[i] = ((texel % kSize) + (texel / kSize)) % 2 ? 255 : 0;
  }
  std::vector<std::vector<uint8_t>> rows;
  for (int h = kSize; h >= 1; h /= 2) rows.emplace_back(size_t(h), 1);
  BuildCoarserLevels(&checks, rows);
  PreviewScene::Prepared prepared;
  prepared.caster = std::make_shared<const scene::RayCaster>(mesh);
  const PreviewScene scene(mesh, textures, prepared, plan, Shading::kFlat, SunDirection{}, Backdrop::kNone);
  // The wall's pixels: a range of the spread of their red values.
  auto spread = [&](bool texture_lod) {
    FrameSettings settings = Settings(Quality::kDraft, 4);
    settings.preset.texture_lod = texture_lod;
    const FrameImage image = RenderFrame(scene, plan, 1, settings);
    float lo = 1, hi = 0;
    for (size_t i = 0; i < image.rgb_linear.size(); ++i) {
      if (!std::isfinite(image.depth_m[i])) continue;
      lo = std::min(lo, image.rgb_linear[i].x());
      hi = std::max(hi, image.rgb_linear[i].x());
    }
    return std::pair{lo, hi};
  };
  const auto [lo, hi] = spread(true);
  EXPECT_GT(lo, 0.45f);
  EXPECT_LT(hi, 0.55f);
  // A bilinear lookup between one-texel checks gives anything from 0 to 1 (a spread of 0.36 over this frame's
  // pixels, and the edge search's four rays where neighbours differ).
  const auto [aliased_lo, aliased_hi] = spread(false);
  EXPECT_GT(aliased_hi - aliased_lo, 0.3f);
}

// The red channel averaged down each column.
std::vector<double> ColumnProfile(const FrameImage& image) {
  std::vector<double> profile(image.width, 0.0);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) profile[x] += image.rgb_linear[size_t(y) * image.width + x].x();
  }
  for (double& p : profile) p /= image.height;
  return profile;
}

// A step edge at x = 0 blurred by a disk of diameter c, then by the 1-px box of a pixel centred at x:
// the share of the disk's area east of the edge, averaged over the pixel.
double DiskEdge(double x, double c) {
  double sum = 0;
  constexpr int kSub = 32;
  for (int i = 0; i < kSub; ++i) {
    const double u = x - 0.5 + (i + 0.5) / kSub;
    const double r = c / 2;
    const double h = std::clamp(-u, -r, r);  // signed distance from the disk centre to the edge
    sum += (r * r * std::acos(h / r) - h * std::sqrt(r * r - h * h)) / (M_PI * r * r);
  }
  return sum / kSub;
}

// The diameter whose disk-edge profile fits the measured one best (least squares, 0.01 px steps).
double FitBlurDiameter(const std::vector<double>& profile, double guess) {
  double best_c = 0, best_error = std::numeric_limits<double>::infinity();
  for (double c = 0.5 * guess; c <= 1.5 * guess; c += 0.01) {
    double error = 0;
    for (int x = 0; x < int(profile.size()); ++x) {
      const double d = profile[x] - DiskEdge(x + 0.5 - kWidth / 2.0, c);
      error += d * d;
    }
    if (error < best_error) best_error = error, best_c = c;
  }
  return best_c;
}

TEST(FrameRenderer, AnEdgeOutOfFocusBlursOverTheBlurCircle) {
  const Eigen::Vector3d camera(0, 0, 0);
  const Trajectory plan = StillCamera(camera, 100, 1.4, 3);
  const FrameImage image = Render(Wall(camera, 20), plan, Settings(Quality::kFinal, 512));
  const double predicted = ThinLensCamera(plan.camera, kWidth, kHeight, 100, 1.4, 3).BlurPx(20);
  ASSERT_GT(predicted, 10);  // the test means something only when the blur spans many pixels
  const double fitted = FitBlurDiameter(ColumnProfile(image), predicted);
  std::printf("edge blur fitted %.3f px, predicted %.3f px\n", fitted, predicted);
  EXPECT_LT(std::abs(fitted - predicted), std::max(1.0, 0.03 * predicted))
      << "fitted " << fitted << " px, predicted " << predicted << " px";
}

TEST(FrameRenderer, ThePlaneOfFocusRendersSharp) {
  for (const Eigen::Vector3d camera : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(10000, -10000, 300)}) {
    const Trajectory plan = StillCamera(camera, 100, 1.4, 20);
    const std::vector<double> profile =
        ColumnProfile(Render(Wall(camera, 20), plan, Settings(Quality::kStandard, 128)));
    // The edge projects onto the boundary between columns 119 and 120: no float jitter at 14 km.
    EXPECT_LT(profile[118], 1e-6) << camera.transpose();
    EXPECT_LT(profile[119], 1e-6) << camera.transpose();
    EXPECT_GT(profile[120], 1 - 1e-6) << camera.transpose();
    EXPECT_GT(profile[121], 1 - 1e-6) << camera.transpose();
  }
}

TEST(FrameRenderer, ALargeFNumberMatchesAPinholeRender) {
  const Eigen::Vector3d camera(0, 0, 0);
  const FrameImage pinhole =
      Render(Wall(camera, 20), StillCamera(camera, 100, 1.4, 20), Settings(Quality::kStandard, 128));
  const FrameImage stopped_down =
      Render(Wall(camera, 20), StillCamera(camera, 100, 64, 3), Settings(Quality::kStandard, 128));
  double max_difference = 0;
  for (size_t i = 0; i < pinhole.rgb_linear.size(); ++i) {
    max_difference = std::max(max_difference, double((pinhole.rgb_linear[i] - stopped_down.rgb_linear[i]).norm()));
  }
  EXPECT_LT(max_difference, 0.02);
}

TEST(FrameRenderer, AUniformEmitterGivesAUniformImage) {
  const Eigen::Vector3d camera(0, 0, 0);
  const Eigen::Vector3f color(0.3f, 0.5f, 0.7f);
  const FrameImage image =
      Render(Wall(camera, 20, color), StillCamera(camera, 100, 1.4, 3), Settings(Quality::kStandard, 64));
  for (const auto& c : image.rgb_linear) ASSERT_LT((c - color).norm(), 1e-5);
  EXPECT_GT(image.total_samples, uint64_t(kWidth) * kHeight * 16);  // it was blurred, and sampled so
}

// The variance of the red channel's column profile, as a distribution along x.
double ProfileVariance(const std::vector<double>& profile) {
  double mass = 0, mean = 0, second = 0;
  for (size_t x = 0; x < profile.size(); ++x) {
    mass += profile[x];
    mean += profile[x] * (x + 0.5);
    second += profile[x] * (x + 0.5) * (x + 0.5);
  }
  mean /= mass;
  return second / mass - mean * mean;
}

TEST(FrameRenderer, AMotionStreakHasTheProjectedLengthOfSpeedTimesShutter) {
  const Eigen::Vector3d camera(0, 0, 0);
  Trajectory plan = StillCamera(camera, 100, 64, 20, 1.0 / 50);
  const double speed_m_s = 10;
  SubjectTrack runner;
  runner.name = "runner";
  runner.height_m = 1.8;
  for (const auto& s : plan.samples) runner.positions_enu_m.emplace_back(speed_m_s * s.time_s - 1.0 / 3, 20, -0.9);
  plan.subjects.push_back(runner);
  scene::SceneMesh black_wall = Wall(camera, 40, Eigen::Vector3f::Zero());
  FrameSettings settings = Settings(Quality::kFinal, 256);
  const FrameImage moving = Render(black_wall, plan, settings);
  settings.preset.motion_blur = false;
  const FrameImage still = Render(black_wall, plan, settings);
  // A box of the proxy's width convolved with a box of the streak's length: variances add, L^2 / 12.
  const double streak_px =
      std::sqrt(12 * (ProfileVariance(ColumnProfile(moving)) - ProfileVariance(ColumnProfile(still))));
  const double expected_px = speed_m_s / 50 * 100 / 20 * kWidth / 36.0;  // m -> mm on the sensor -> px
  EXPECT_NEAR(streak_px, expected_px, std::max(1.0, 0.03 * expected_px));
  std::printf("streak %.3f px, expected %.3f px\n", streak_px, expected_px);
}

// A shutter too short for anything to move a twentieth of a pixel: the rays all go at the frame's instant,
// the same pixels as with motion blur off (each ray at its own instant, they would be other rays).
TEST(FrameRenderer, AFrameWhereNothingMovesTracesEveryRayAtItsInstant) {
  const Eigen::Vector3d camera(0, 0, 0);
  Trajectory plan = StillCamera(camera, 100, 1.4, 3, 1e-6);
  for (size_t k = 0; k < plan.samples.size(); ++k) plan.samples[k].position_enu_m.x() += 0.5 * double(k);
  // Colours that change with every micrometre: a ray moved by the camera's motion within the shutter sees
  // another colour.
  scene::SceneMesh wall = Wall(camera, 20);
  for (size_t v = 0; v < wall.colors_linear.size(); ++v) {
    wall.colors_linear[v] = Eigen::Vector3f(0.1f + 0.1f * float(v), 0.9f - 0.1f * float(v), 0.3f + 0.05f * float(v));
  }
  FrameSettings settings = Settings(Quality::kFinal, 4);
  const FrameImage short_shutter = Render(wall, plan, settings);
  settings.preset.motion_blur = false;
  const FrameImage no_motion_blur = Render(wall, plan, settings);
  for (size_t i = 0; i < short_shutter.rgb_linear.size(); ++i) {
    ASSERT_EQ(short_shutter.rgb_linear[i], no_motion_blur.rgb_linear[i]) << "pixel " << i;
  }
}

TEST(FrameRenderer, PhysicalExposureDoublesWhenTheShutterDoubles) {
  const Eigen::Vector3d camera(0, 0, 0);
  const Eigen::Vector3f color(0.1f, 0.2f, 0.3f);
  FrameSettings settings = Settings(Quality::kStandard, 16);
  settings.exposure = Exposure::kPhysical;
  const FrameImage fast = Render(Wall(camera, 20, color), StillCamera(camera, 100, 4, 20, 1.0 / 100), settings);
  const FrameImage slow = Render(Wall(camera, 20, color), StillCamera(camera, 100, 4, 20, 1.0 / 50), settings);
  EXPECT_NEAR(slow.rgb_linear[100].x() / fast.rgb_linear[100].x(), 2.0, 1e-5);
  EXPECT_NEAR(slow.rgb_linear[100].z(), 0.3, 1e-6);  // 1/50 s, ISO 100, f/4 is exposure 1
}

TEST(FrameRenderer, ASubjectPlannedAtAFrameHeightFractionFillsItInTheImage) {
  // Super 35 with a 16:9 image: the image uses 24.89 x 14.00 mm of the 18.67 mm high filmback.
  const Eigen::Vector3d camera(0, 0, 0);
  Trajectory plan = StillCamera(camera, 35, 64, 20);
  plan.camera.sensor_width_mm = 24.89;
  plan.camera.sensor_height_mm = 18.67;
  plan.camera.width_px = 320;
  plan.camera.height_px = 180;
  SubjectTrack person;
  person.name = "person";
  person.height_m = 1.8;
  person.positions_enu_m.assign(3, Eigen::Vector3d(0, 20, -0.9));
  plan.subjects.push_back(person);
  FrameSettings settings = Settings(Quality::kStandard, 64);
  settings.width_px = 320;
  settings.height_px = 180;
  const FrameImage image = Render(Wall(camera, 40, Eigen::Vector3f::Zero()), plan, settings);
  double rows = 0;  // the subject's coverage down the centre column (antialiased rows count in part)
  for (int y = 0; y < image.height; ++y) rows += image.rgb_linear[size_t(y) * image.width + 160].x() / 0.9;
  const double planned = 1.8 * 35 / 20 / (24.89 * 180 / 320);
  EXPECT_NEAR(rows / image.height, planned, 1.0 / image.height);
}

TEST(FrameRenderer, TheMaskAovLabelsEachSubjectAndNothingElse) {
  // Two subjects side by side in front of a wall: the mask holds 1 on the first, 2 on the second, 0 on
  // the wall, and each label covers the pixels the pinhole pass sees it at (none of the other).
  const Eigen::Vector3d camera(0, 0, 0);
  Trajectory plan = StillCamera(camera, 35, 64, 20);
  plan.camera.width_px = 320;
  plan.camera.height_px = 180;
  for (double east : {-1.5, 1.5}) {
    SubjectTrack person;
    person.height_m = 1.8;
    person.positions_enu_m.assign(3, Eigen::Vector3d(east, 20, -0.9));
    plan.subjects.push_back(person);
  }
  FrameSettings settings = Settings(Quality::kStandard, 4);
  settings.width_px = 320;
  settings.height_px = 180;
  const FrameImage image = Render(Wall(camera, 40, Eigen::Vector3f::Zero()), plan, settings);
  ASSERT_EQ(image.subject_id.size(), size_t(320 * 180));
  std::array<int, 3> count{};
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const float id = image.subject_id[size_t(y) * image.width + x];
      ASSERT_TRUE(id == 0 || id == 1 || id == 2) << id;
      ++count[size_t(id)];
      if (id == 1) EXPECT_LT(x, 160);  // the first subject stands west (left)
      if (id == 2) EXPECT_GT(x, 160);
    }
  }
  EXPECT_GT(count[1], 100);
  EXPECT_EQ(count[1], count[2]);  // mirror images of each other
  EXPECT_GT(count[0], 320 * 180 / 2);
  EXPECT_EQ(&AovValues(image, Aov::kMask), &image.subject_id);
}

TEST(FrameRenderer, AovListFollowsTheTable) {
  EXPECT_EQ(ParseAovList("mask,depth"), (std::vector<Aov>{Aov::kDepth, Aov::kMask}));
  EXPECT_EQ(ParseAovList("blur,blur"), (std::vector<Aov>{Aov::kBlur}));
  EXPECT_THROW(ParseAovList("depth,normal"), InputError);
  EXPECT_THROW(ParseAovList(""), InputError);
  for (size_t i = 0; i < AovTable().size(); ++i) EXPECT_EQ(size_t(AovTable()[i].aov), i);
}

TEST(FrameRenderer, TheSamePixelsOnOneThreadAndOnAll) {
  const Eigen::Vector3d camera(0, 0, 0);
  const Trajectory plan = StillCamera(camera, 100, 1.4, 3);
  const FrameSettings settings = Settings(Quality::kStandard, 64);
  const FrameImage all = Render(Wall(camera, 20), plan, settings);
  FrameImage one;
  tbb::task_arena arena(1);
  arena.execute([&] { one = Render(Wall(camera, 20), plan, settings); });
  ASSERT_EQ(all.rgb_linear.size(), one.rgb_linear.size());
  EXPECT_EQ(std::memcmp(all.rgb_linear.data(), one.rgb_linear.data(), all.rgb_linear.size() * sizeof(Eigen::Vector3f)),
            0);
}

TEST(FrameRenderer, ShutterIntervalStaysWithinTheShot) {
  Trajectory plan = StillCamera(Eigen::Vector3d::Zero(), 50, 2, 10, 1.0 / 50);
  auto [t0, t1] = ShutterInterval(plan, 1);
  EXPECT_NEAR(t0, 1.0 / 30 - 0.01, 1e-12);
  EXPECT_NEAR(t1, 1.0 / 30 + 0.01, 1e-12);
  plan.samples[2].shot = "next";  // a cut after sample 1
  std::tie(t0, t1) = ShutterInterval(plan, 1);
  EXPECT_NEAR(t1, 1.0 / 30, 1e-12);
}

TEST(FrameRenderer, OutputSizeKeepsTheCamerasAspect) {
  CameraSpec camera;
  EXPECT_EQ(OutputSize(camera, std::nullopt), (std::pair{3840, 2160}));
  EXPECT_EQ(OutputSize(camera, 640), (std::pair{640, 360}));
}

}  // namespace
}  // namespace cinepath::preview

namespace cinepath::preview {
namespace {

TEST(FrameRenderer, OneRayPerPixelStillGoesThroughTheLens) {
  // One ray per pixel of an out-of-focus edge: noisy, but averaged down the columns the edge spreads over
  // the blur circle; a copy of the pinhole pass would leave a step one column wide.
  const Eigen::Vector3d camera(0, 0, 0);
  const Trajectory plan = StillCamera(camera, 100, 1.4, 3);
  const double predicted = ThinLensCamera(plan.camera, kWidth, kHeight, 100, 1.4, 3).BlurPx(20);
  ASSERT_GT(predicted, 10);
  const std::vector<double> profile = ColumnProfile(Render(Wall(camera, 20), plan, Settings(Quality::kFinal, 1)));
  int between = 0;
  for (double p : profile) between += p > 0.05 && p < 0.95 ? 1 : 0;
  EXPECT_GT(between, predicted / 2) << "columns between dark and bright: " << between;
}

// Few lens rays of an out-of-focus edge, denoised: closer to the converged frame than the same rays without
// the filter (by the root-mean-square error over the image), and the edge about as wide as the blur circle.
TEST(FrameRenderer, DenoisingFewLensRaysComesCloserToTheConvergedFrame) {
  const Eigen::Vector3d camera(0, 0, 0);
  const Trajectory plan = StillCamera(camera, 100, 1.4, 3);
  const FrameImage converged = Render(Wall(camera, 20), plan, Settings(Quality::kFinal, 512));
  const double predicted = ThinLensCamera(plan.camera, kWidth, kHeight, 100, 1.4, 3).BlurPx(20);
  auto rms = [&](const FrameImage& image) {
    double sum = 0;
    for (size_t i = 0; i < image.rgb_linear.size(); ++i) {
      sum += (image.rgb_linear[i] - converged.rgb_linear[i]).squaredNorm() / 3;
    }
    return std::sqrt(sum / double(image.rgb_linear.size()));
  };
  for (int rays : {1, 2, 4}) {
    FrameSettings settings = Settings(Quality::kFinal, rays);
    const FrameImage noisy = Render(Wall(camera, 20), plan, settings);
    settings.preset.denoise = true;
    const FrameImage denoised = Render(Wall(camera, 20), plan, settings);
    const double fitted = FitBlurDiameter(ColumnProfile(denoised), predicted);
    std::printf("%d rays: rms %.4f -> %.4f denoised; edge blur fitted %.2f px, predicted %.2f px\n", rays, rms(noisy),
                rms(denoised), fitted, predicted);
    EXPECT_LT(rms(denoised), rms(noisy) / 2) << rays << " rays";
    // The kernel's own width, 0.2 blur / sqrt(rays) as a standard deviation, widens the edge a little.
    EXPECT_LT(std::abs(fitted - predicted), 0.2 * predicted / std::sqrt(rays)) << rays << " rays";
  }
}

TEST(FrameRenderer, MinSamplesReachesEveryPixelSharpOnesToo) {
  const Eigen::Vector3d camera(0, 0, 0);
  FrameSettings settings = Settings(Quality::kStandard, 64);
  settings.preset.min_samples = 8;
  const FrameImage image = Render(Wall(camera, 20), StillCamera(camera, 100, 1.4, 20), settings);
  for (uint16_t n : image.samples) ASSERT_GE(n, 8);
}

}  // namespace
}  // namespace cinepath::preview
