// preview/sun_position.h against what the sky does: the noon elevation 90 - |latitude - declination| at
// a solstice and an equinox, the sun east in the morning and west in the afternoon, and the UTC reader.
#include "preview/sun_position.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace cinepath::preview {
namespace {

// The highest the sun gets over a UTC day at `where`, and its azimuth then (minute steps).
SunDirection HighestOfTheDay(const Geodetic& where, const std::string& date) {
  const int64_t midnight = ParseUtcTime(date + "T00:00:00Z", "test");
  SunDirection best{0, -90};
  for (int64_t t = midnight; t < midnight + 86400; t += 60) {
    const SunDirection s = SunPositionAt(where, t);
    if (s.elevation_deg > best.elevation_deg) best = s;
  }
  return best;
}

TEST(SunPosition, NoonElevationAtTheSolsticeAndTheEquinox) {
  const Geodetic duluth{46.84265, -91.99445, 190};
  // June solstice: declination +23.44 deg, so the noon sun stands 90 - 46.84 + 23.44 = 66.60 deg high, due south.
  const SunDirection june = HighestOfTheDay(duluth, "2026-06-21");
  EXPECT_NEAR(june.elevation_deg, 66.60, 0.3);
  EXPECT_NEAR(june.azimuth_deg, 180.0, 3.0);
  // December solstice: 90 - 46.84 - 23.44 = 19.72 deg.
  EXPECT_NEAR(HighestOfTheDay(duluth, "2026-12-21").elevation_deg, 19.72, 0.3);
  // March equinox on the equator: nearly overhead.
  EXPECT_GT(HighestOfTheDay(Geodetic{0, 0, 0}, "2026-03-20").elevation_deg, 89.0);
  // Southern hemisphere in June: the noon sun due north.
  const SunDirection sydney = HighestOfTheDay(Geodetic{-33.87, 151.21, 0}, "2026-06-21");
  EXPECT_NEAR(sydney.elevation_deg, 90 - 33.87 - 23.44, 0.3);
  EXPECT_TRUE(sydney.azimuth_deg < 3.0 || sydney.azimuth_deg > 357.0) << sydney.azimuth_deg;
}

TEST(SunPosition, EastInTheMorningWestInTheAfternoon) {
  const Geodetic duluth{46.84265, -91.99445, 190};
  // Local solar noon in Duluth is about 18:10 UTC.
  const SunDirection morning = SunPositionAt(duluth, ParseUtcTime("2026-06-21T14:00:00Z", "test"));
  const SunDirection afternoon = SunPositionAt(duluth, ParseUtcTime("2026-06-21T22:00:00Z", "test"));
  EXPECT_GT(morning.elevation_deg, 10);
  EXPECT_GT(afternoon.elevation_deg, 10);
  EXPECT_GT(morning.azimuth_deg, 45);
  EXPECT_LT(morning.azimuth_deg, 135);
  EXPECT_GT(afternoon.azimuth_deg, 225);
  EXPECT_LT(afternoon.azimuth_deg, 315);
  // At 06:00 UTC (01:00 local) the sun is below the horizon.
  EXPECT_LT(SunPositionAt(duluth, ParseUtcTime("2026-06-21T06:00:00Z", "test")).elevation_deg, 0);
}

TEST(SunPosition, ParsesUtcTimes) {
  EXPECT_EQ(ParseUtcTime("1970-01-01T00:00:00Z", "t"), 0);
  EXPECT_EQ(ParseUtcTime("2000-01-01T00:00Z", "t"), 946684800);
  EXPECT_EQ(ParseUtcTime("2026-11-24T21:30:15Z", "t"), 1795555815);
  for (const char* bad : {"2026-02-30T12:00:00Z", "2026-11-24 12:00:00", "2026-11-24T25:00Z", "noon", ""}) {
    EXPECT_THROW(ParseUtcTime(bad, "--sun-time"), InputError) << bad;
  }
}

}  // namespace
}  // namespace cinepath::preview
