#include "export/exporter.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "sample_trajectories.h"

namespace cinepath::exporter {
namespace {

ExportOptions AllFormats() {
  ExportOptions o;
  o.formats = {Format::kQgcPlan, Format::kQgcWpl, Format::kMavlinkBin,
               Format::kDjiWpml, Format::kDjiMsdkJson, Format::kLitchiCsv};
  return o;
}

TEST(Exporter, EveryFormatDeterministic) {
  const Trajectory t = testing::OrbitPlan();
  const ExportResult a = ExportMission(t, AllFormats());
  const ExportResult b = ExportMission(t, AllFormats());
  ASSERT_EQ(a.files.size(), 6u);
  for (size_t i = 0; i < a.files.size(); ++i) {
    EXPECT_FALSE(a.files[i].contents.empty());
    EXPECT_EQ(a.files[i].contents, b.files[i].contents) << a.files[i].file_name;
  }
  const Json report = ReportJson(a, AllFormats());
  EXPECT_EQ(report["waypoints"].get<int>(), static_cast<int>(a.mission.waypoints.size()));
  EXPECT_LE(report["deviation_reached_m"].get<double>(), 0.5);
}

TEST(Exporter, LimitsThrowUnlessForced) {
  Trajectory t = testing::FlybyPlan();
  for (auto& s : t.samples) s.time_s *= 0.5;  // 20 m/s
  t.drone.max_horizontal_speed_m_s = 25;
  ExportOptions o = AllFormats();
  try {
    ExportMission(t, o);
    FAIL();
  } catch (const InfeasibleError& e) {
    EXPECT_NE(std::string(e.what()).find("waypoint 0"), std::string::npos) << e.what();
  }
  o.force = true;
  const ExportResult forced = ExportMission(t, o);
  EXPECT_TRUE(forced.has_violations());
  EXPECT_NE(ReportText(forced, o).find("LIMIT"), std::string::npos);
}

TEST(Exporter, OptionChecks) {
  const Trajectory t = testing::ChasePlan();
  ExportOptions none;
  EXPECT_THROW(ExportMission(t, none), InputError);
  ExportOptions twice;
  twice.formats = {Format::kQgcPlan, Format::kQgcPlan};
  EXPECT_THROW(ExportMission(t, twice), InputError);
  ExportOptions litchi_amsl;
  litchi_amsl.formats = {Format::kLitchiCsv};
  litchi_amsl.altitude_ref = AltitudeRef::kAmsl;
  EXPECT_THROW(ExportMission(t, litchi_amsl), InputError);
  ExportOptions bad_drone;
  bad_drone.formats = {Format::kQgcPlan};
  bad_drone.drone_profile = "nope";
  EXPECT_THROW(ExportMission(t, bad_drone), InputError);
  EXPECT_THROW(ParseFormat("kml"), InputError);
}

}  // namespace
}  // namespace cinepath::exporter
