#include "shots/lens_track.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "core/error.h"

namespace cinepath::shots {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(LensTrack, FocalLengthInLogSpace) {
  EXPECT_DOUBLE_EQ(InterpolateFocalLengthMm(24, 96, 0.0), 24);
  EXPECT_DOUBLE_EQ(InterpolateFocalLengthMm(24, 96, 1.0), 96);
  EXPECT_NEAR(InterpolateFocalLengthMm(24, 96, 0.5), 48.0, 1e-12);  // geometric mean
}

TEST(LensTrack, FocusInDioptres) {
  EXPECT_NEAR(InterpolateFocusDistanceM(2, 10, 0.5), 1.0 / 0.3, 1e-12);
  EXPECT_NEAR(InterpolateFocusDistanceM(5, kInf, 0.5), 10.0, 1e-12);
  EXPECT_TRUE(std::isinf(InterpolateFocusDistanceM(5, kInf, 1.0)));
  EXPECT_TRUE(std::isinf(InterpolateFocusDistanceM(kInf, kInf, 0.3)));
}

TEST(LensTrack, ApertureInStops) {
  EXPECT_NEAR(InterpolateFNumber(2.8, 5.6, 0.5), 2.8 * std::sqrt(2.0), 1e-12);  // one stop
  EXPECT_NEAR(InterpolateShutterS(1.0 / 50, 1.0 / 200, 0.5), 1.0 / 100, 1e-15);
}

TEST(LensTrack, FramingKnownAnswers) {
  // 1.8 m at 10 m filling half a 24 mm-high frame: f = k d h / H = 0.5 * 10000 mm * 24 / 1800.
  EXPECT_NEAR(FramingFocalLengthMm(24, 1.8, 10, 0.5), 66.6666666667, 1e-8);
  EXPECT_NEAR(ImageHeightFraction(24, 66.6666666667, 1.8, 10), 0.5, 1e-10);
  // 1200 mm at 2 km on Super 35 (18.67 mm): a 1.8 m subject fills 5.785 % of the height.
  EXPECT_NEAR(ImageHeightFraction(18.67, 1200, 1.8, 2000), 1.8 * 1200 / (2000 * 18.67), 1e-12);
  EXPECT_THROW(FramingFocalLengthMm(24, 1.8, 0, 0.5), InputError);
  EXPECT_THROW(FramingFocalLengthMm(24, 1.8, 10, 0), InputError);
}

TEST(LensTrack, KeysHoldOutsideAndInterpolateInside) {
  const std::vector<ScalarKey> keys = {{1, 2.8}, {3, 11.2}};
  EXPECT_EQ(InterpolateLensKeys(keys, 0, LensQuantity::kFNumber), 2.8);
  EXPECT_EQ(InterpolateLensKeys(keys, 9, LensQuantity::kFNumber), 11.2);
  EXPECT_NEAR(InterpolateLensKeys(keys, 2, LensQuantity::kFNumber), 5.6, 1e-12);
}

}  // namespace
}  // namespace cinepath::shots
