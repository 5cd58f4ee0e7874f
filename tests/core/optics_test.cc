#include "core/optics.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "core/error.h"

namespace cinepath {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The exact paraxial form, c = A |d - s| / d * f / (s - f), as an independent reference.
double BlurExactMm(double f_mm, double n, double s_m, double d_m) {
  const double f = f_mm / 1000.0, a = f / n;
  return 1000.0 * a * std::fabs(d_m - s_m) / d_m * f / (s_m - f);
}

// A lens's terms kept for many points (FocusedLens, the render's per-pixel blur) give the written-out
// formula's bits, for 4-1200 mm, focus near and at infinity, points from 1 mm to 100 km and at infinity.
TEST(Optics, FocusedLensGivesTheFormulasBits) {
  for (const double focal_m : {0.004, 0.05, 1.2}) {
    for (const double f_number : {1.0, 2.8, 22.0}) {
      for (const double focus_dioptre : {0.0, 1.0 / 250, 1.0 / 1.3}) {
        const FocusedLens<double> lens(focal_m, f_number, focus_dioptre);
        for (double d = 1e-3; d < 2e5; d *= 1.9) {
          for (const double point_dioptre : {1.0 / d, 0.0}) {
            const double expected = focal_m * focal_m / f_number * std::abs(focus_dioptre - point_dioptre) /
                                    (1.0 - focal_m * focus_dioptre);
            ASSERT_EQ(lens.BlurCircleDiameterM(point_dioptre), expected) << focal_m << " " << d;
            ASSERT_EQ(BlurCircleDiameterM(focal_m, f_number, focus_dioptre, point_dioptre), expected);
          }
        }
      }
    }
  }
}

TEST(Optics, StopsBetweenApertures) {
  EXPECT_NEAR(StopsBetween(2.8, 5.6), 2.0, 1e-12);
  EXPECT_NEAR(StopsBetween(4, 2), -2.0, 1e-12);
  EXPECT_NEAR(StopsBetween(1.4, 1.4 * std::sqrt(2.0)), 1.0, 1e-12);
}

TEST(Optics, HyperfocalKnownAnswer) {
  // 50 mm f/2.8, c = 0.03 mm: H = 2500/(2.8*0.03) + 50 mm = 29811.9 mm.
  EXPECT_NEAR(HyperfocalDistanceM(50, 2.8, 0.03), 29.81190476, 1e-8);
  // Known answers (H = f^2/(N c0) + f): 12 mm f/2.8 ~ 1.7 m; 1200 mm f/8 ~ 6 km.
  EXPECT_NEAR(HyperfocalDistanceM(12, 2.8, 0.03), 1.726, 1e-3);
  EXPECT_NEAR(HyperfocalDistanceM(1200, 8, 0.03), 6001.2, 1e-6);
}

TEST(Optics, BlurAtInfinityFocusIsFSquaredOverND) {
  for (double f : {4.0, 24.0, 50.0, 1200.0}) {
    for (double d : {2.0, 10.0, 5000.0}) {
      const double f_m = f / 1000;
      if (d <= f_m) continue;
      const double expect = 1000 * f_m * f_m / (2.8 * d);
      EXPECT_NEAR(BlurCircleMm(f, 2.8, kInf, d), expect, 1e-14 * expect) << "f=" << f << " d=" << d;
    }
  }
}

TEST(Optics, StableFormMatchesExactForm) {
  for (double f : {4.0, 50.0, 400.0, 1200.0}) {
    for (double n : {0.95, 2.8, 64.0}) {
      for (double s : {0.5, 3.0, 100.0, 2000.0}) {
        for (double d : {0.4, 2.0, 50.0, 5000.0}) {
          if (s * 1000 <= f || d * 1000 <= f) continue;
          const double expect = BlurExactMm(f, n, s, d);
          EXPECT_NEAR(BlurCircleMm(f, n, s, d), expect, 1e-12 + 1e-12 * expect)
              << f << " " << n << " " << s << " " << d;
        }
      }
    }
  }
}

TEST(Optics, BlurIsZeroInFocusAndSpecKnownAnswer) {
  EXPECT_EQ(BlurCircleMm(50, 2.8, 10, 10), 0.0);
  // Known answer: 1200 mm f/8 focused at 2 km blurs an object at 1 km to ~0.09 mm.
  EXPECT_NEAR(BlurCircleMm(1200, 8, 2000, 1000), 0.09, 0.001);
}

TEST(Optics, DepthOfFieldLimits) {
  const auto dof = DepthOfFieldLimits(50, 2.8, 10, 0.03);
  const double h = 29.81190476190476, f = 0.05, s = 10;
  EXPECT_NEAR(dof.near_m, s * (h - f) / (h + s - 2 * f), 1e-12);
  EXPECT_NEAR(dof.far_m, s * (h - f) / (h - s), 1e-12);
  // At the limits the blur equals the acceptable blur (consistency of the two formulas).
  EXPECT_NEAR(BlurCircleMm(50, 2.8, 10, dof.near_m), 0.03, 1e-9);
  EXPECT_NEAR(BlurCircleMm(50, 2.8, 10, dof.far_m), 0.03, 1e-9);
}

TEST(Optics, FocusAtOrBeyondHyperfocalHasInfiniteFarLimit) {
  const double h = HyperfocalDistanceM(50, 2.8, 0.03);
  EXPECT_TRUE(std::isinf(DepthOfFieldLimits(50, 2.8, h, 0.03).far_m));
  EXPECT_TRUE(std::isinf(DepthOfFieldLimits(50, 2.8, 100, 0.03).far_m));
  const auto inf = DepthOfFieldLimits(50, 2.8, kInf, 0.03);
  EXPECT_TRUE(std::isinf(inf.far_m));
  EXPECT_NEAR(inf.near_m, h - 0.05, 1e-12);
  // Focused at the hyperfocal distance, everything from H/2 (approximately) is sharp.
  EXPECT_NEAR(DepthOfFieldLimits(50, 2.8, h, 0.03).near_m, (h - 0.05) * h / (2 * h - 0.1), 1e-12);
}

TEST(Optics, Extremes) {
  // 4 mm f/0.95 focused at 0.1 m, subject at 5 km.
  const double c = BlurCircleMm(4, 0.95, 0.1, 5000);
  EXPECT_NEAR(c, BlurExactMm(4, 0.95, 0.1, 5000), 1e-12);
  EXPECT_GT(c, 0.17);
  // 1200 mm f/64 at infinity, subject at 5 km: f^2/(N d).
  EXPECT_NEAR(BlurCircleMm(1200, 64, kInf, 5000), 1.44 / (64 * 5000) * 1000, 1e-15);
  // Subject at infinity with finite focus.
  EXPECT_NEAR(BlurCircleMm(50, 2.8, 10, kInf), 1000 * (0.0025 / 2.8) * 0.1 / (1 - 0.005), 1e-12);
  // Field of view on full frame across 4..1200 mm (2 atan(18/4) and 2 atan(18/1200)).
  EXPECT_NEAR(FieldOfViewRad(36, 4) * 180 / M_PI, 154.942385, 1e-6);
  EXPECT_NEAR(FieldOfViewRad(36, 1200) * 180 / M_PI, 1.718744, 1e-6);
  EXPECT_NEAR(FieldOfViewRad(36, 50) * 180 / M_PI, 39.597752, 1e-6);  // the classic 39.6 deg
}

TEST(Optics, DomainErrorsAreExplicit) {
  EXPECT_THROW(BlurCircleMm(50, 2.8, 10, 0.05), InputError);  // d <= f
  EXPECT_THROW(BlurCircleMm(50, 2.8, 0.04, 10), InputError);  // s <= f
  EXPECT_THROW(BlurCircleMm(50, 0, 10, 10), InputError);      // N <= 0
  EXPECT_THROW(BlurCircleMm(50, -2, 10, 10), InputError);
  EXPECT_THROW(BlurCircleMm(NAN, 2.8, 10, 10), InputError);  // non-finite
  EXPECT_THROW(BlurCircleMm(50, 2.8, NAN, 10), InputError);
  EXPECT_THROW(BlurCircleMm(50, 2.8, 10, NAN), InputError);
  EXPECT_THROW(BlurCircleMm(kInf, 2.8, 10, 10), InputError);
  EXPECT_THROW(HyperfocalDistanceM(50, 2.8, 0), InputError);
  EXPECT_THROW(DepthOfFieldLimits(50, 2.8, -3, 0.03), InputError);
  EXPECT_THROW(FieldOfViewRad(36, 0), InputError);
  try {
    ValidateFocusDistanceM(0.03, 50, "--focus-m");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--focus-m"), std::string::npos);
  }
}

TEST(Optics, FilmbacksAndDefaultCoc) {
  ASSERT_TRUE(FindFilmback("super35"));
  EXPECT_DOUBLE_EQ(FindFilmback("super35")->width_mm, 24.89);
  EXPECT_DOUBLE_EQ(FindFilmback("digital-film-16x9")->height_mm, 13.365);
  for (auto name : {"full-frame", "aps-c", "micro-four-thirds", "one-inch"}) {
    EXPECT_TRUE(FindFilmback(name)) << name;
  }
  EXPECT_FALSE(FindFilmback("imax"));
  EXPECT_NEAR(DefaultCocMm(36, 24), 0.03, 1e-15);
  EXPECT_NEAR(DefaultCocMm(17.3, 13.0), 0.015, 0.0005);  // half of full frame's diagonal
}

TEST(Optics, FocalLengthForFieldOfViewInvertsFieldOfView) {
  for (double f : {4.0, 35.0, 1200.0}) {
    EXPECT_NEAR(FocalLengthForFieldOfViewMm(24.89, FieldOfViewRad(24.89, f)), f, 1e-9 * f);
  }
  EXPECT_NEAR(MagnificationAt(50, 10.05), 0.005, 1e-15);
  EXPECT_NEAR(MmToPixels(0.03, 36, 3840), 3.2, 1e-12);
}

TEST(Optics, SensorFitSpansTheWidthAndScalesTheHeightByTheImageAspect) {
  // 16:9 on the 4:3 Super 35 filmback: 24.89 x 14.000625 mm (Cycles' HORIZONTAL fit).
  const ImageExtentMm e = ImageExtentOnSensorMm(24.89, 3840, 2160);
  EXPECT_DOUBLE_EQ(e.width_mm, 24.89);
  EXPECT_NEAR(e.height_mm, 14.000625, 1e-12);
  // A 4:3 image on the same filmback uses its full height.
  EXPECT_NEAR(ImageExtentOnSensorMm(24.89, 4000, 3000).height_mm, 18.6675, 1e-12);
  EXPECT_THROW(ImageExtentOnSensorMm(0, 3840, 2160), InputError);
  EXPECT_THROW(ImageExtentOnSensorMm(24.89, 0, 2160), InputError);
  EXPECT_THROW(ImageExtentOnSensorMm(24.89, 3840, -1), InputError);
}

}  // namespace
}  // namespace cinepath
