#include "export/exporter.h"
#include "export/formats.h"

#include <gtest/gtest.h>

#include "core/drone_profiles.h"
#include "core/error.h"
#include "sample_trajectories.h"

namespace cinepath::exporter {
namespace {

ExportOptions AllFormats() {
  ExportOptions o;
  o.formats = {Format::kQgcPlan, Format::kQgcWpl,      Format::kMavlinkBin,
               Format::kDjiWpml, Format::kDjiMsdkJson, Format::kLitchiCsv};
  return o;
}

TEST(Exporter, RoiAutoAndOffAndOneMissionPerFlightModel) {
  const Trajectory t = testing::FlybyPlan();
  ExportOptions options = AllFormats();
  const ExportResult on = ExportMission(t, options);
  // MAVLink + Litchi share one mission, WPML and MSDK have their own.
  ASSERT_EQ(on.missions.size(), 3u);
  EXPECT_EQ(on.reports[0].mission, on.reports[1].mission);
  EXPECT_EQ(on.reports[0].mission, on.reports[5].mission);
  EXPECT_NE(on.reports[0].mission, on.reports[3].mission);
  EXPECT_NE(on.reports[0].mission, on.reports[4].mission);
  EXPECT_EQ(on.missions[on.reports[0].mission].rois.size(), 1u);
  EXPECT_EQ(on.missions[on.reports[3].mission].rois.size(), 1u);
  EXPECT_TRUE(on.missions[on.reports[4].mission].rois.empty());
  EXPECT_NE(on.files[0].contents.find("\"command\": 195"), std::string::npos);
  EXPECT_NE(on.files[3].contents.find("towardPOI"), std::string::npos);
  EXPECT_NE(on.files[5].contents.find(",1,"), std::string::npos);
  const Json report = ReportJson(on, options);
  EXPECT_EQ(report["points_of_interest"].size(), 1u);
  EXPECT_EQ(report["outputs"][0]["waypoints"].get<int>(), 2);

  options.roi = RoiMode::kOff;
  const ExportResult off = ExportMission(t, options);
  for (const Mission& m : off.missions) EXPECT_TRUE(m.rois.empty());
  EXPECT_EQ(off.files[0].contents.find("\"command\": 195"), std::string::npos);
  EXPECT_EQ(off.files[3].contents.find("towardPOI"), std::string::npos);
  EXPECT_GT(off.missions[off.reports[0].mission].waypoints.size(), 2u);
}

// The firmware comes from the drone's profile unless --firmware says otherwise, and the report says
// when it overrides a profile that flies PX4 or ArduPilot.
TEST(Exporter, TheFirmwareIsTheProfilesUnlessOverridden) {
  for (const DroneProfile& profile : DroneProfiles()) {
    SCOPED_TRACE(profile.name);
    Trajectory t = testing::FlybyPlan();
    t.drone = profile;
    ExportOptions options;
    options.formats = {Format::kQgcPlan, Format::kLitchiCsv};
    options.force = true;  // this test is about the dialect, not about whether every drone can fly the plan
    const bool ardupilot = profile.firmware == "ardupilot";
    const ExportResult own = ExportMission(t, options);
    EXPECT_EQ(own.firmware, ardupilot ? Firmware::kArduPilot : Firmware::kPx4);
    EXPECT_EQ(ReportJson(own, options)["firmware"], ardupilot ? "ardupilot" : "px4");
    EXPECT_NE(own.files[0].contents.find(ardupilot ? "\"firmwareType\": 3" : "\"firmwareType\": 12"),
              std::string::npos);
    for (const auto& report : own.reports)
      for (const auto& note : report.notes) EXPECT_EQ(note.find("overrides"), std::string::npos) << note;

    options.firmware = ardupilot ? Firmware::kPx4 : Firmware::kArduPilot;
    const ExportResult other = ExportMission(t, options);
    EXPECT_EQ(other.firmware, *options.firmware);
    EXPECT_NE(other.files[0].contents.find(ardupilot ? "\"firmwareType\": 12" : "\"firmwareType\": 3"),
              std::string::npos);
    const bool flies_mavlink = profile.firmware == "px4" || ardupilot;
    const auto& notes = other.reports[0].notes;
    const bool said = !notes.empty() && notes.front().find("--firmware") != std::string::npos &&
                      notes.front().find(profile.name) != std::string::npos;
    EXPECT_EQ(said, flies_mavlink) << (notes.empty() ? "" : notes.front());
    for (const auto& note : other.reports[1].notes) EXPECT_EQ(note.find("--firmware"), std::string::npos) << note;
  }
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
  EXPECT_THROW(ParseFormat("kml"), InputError);
}

}  // namespace
}  // namespace cinepath::exporter
