#include "export/platform.h"
#include "export/formats.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace cinepath::exporter {
namespace {

TEST(Platform, FormatNamesRoundTrip) {
  for (Format f : {Format::kQgcPlan, Format::kQgcWpl, Format::kMavlinkBin, Format::kDjiWpml, Format::kDjiMsdkJson,
                   Format::kLitchiCsv}) {
    EXPECT_EQ(ParseFormat(FormatName(f)), f);
  }
  EXPECT_THROW(ParseFormat("QGC-PLAN"), InputError);
  EXPECT_EQ(ParseFirmware("ardupilot"), Firmware::kArduPilot);
  EXPECT_THROW(ParseFirmware("inav"), InputError);
}

TEST(Platform, LimitsFromTheSpec) {
  const FormatLimits msdk = LimitsOf(Format::kDjiMsdkJson);
  EXPECT_EQ(msdk.min_waypoints, 2);
  EXPECT_EQ(msdk.max_waypoints, 99);
  EXPECT_EQ(msdk.min_spacing_m, 0.5);
  EXPECT_EQ(msdk.max_spacing_m, 2000);
  EXPECT_EQ(msdk.max_gimbal_pitch_deg, 0);
  EXPECT_EQ(LimitsOf(Format::kLitchiCsv).max_waypoints, 10000);
  EXPECT_EQ(LimitsOf(Format::kDjiWpml).max_speed_mps, 15);
}

}  // namespace
}  // namespace cinepath::exporter
