#include "export/qgc_wpl.h"

#include <sstream>

#include <gtest/gtest.h>

#include "core/error.h"
#include "export/mission_builder.h"
#include "export/mission_reader.h"
#include "sample_trajectories.h"

namespace cinepath::exporter {
namespace {

TEST(QgcWpl, TwelveTabFieldsHomeFirstAndRoundTrip) {
  MissionBuildOptions opt;
  const Mission mission = BuildMission(testing::FlybyPlan(), opt);
  const MavMission items = BuildMavMission(mission, Firmware::kArduPilot, AltitudeRef::kAmsl);
  const std::string text = WriteQgcWpl(mission, items);
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "QGC WPL 110");
  int rows = 0;
  while (std::getline(in, line)) {
    EXPECT_EQ(std::count(line.begin(), line.end(), '\t'), 11) << line;
    EXPECT_EQ(line.find(' '), std::string::npos);
    if (rows == 0) EXPECT_EQ(line.rfind("0\t1\t0\t16\t", 0), 0u) << line;
    ++rows;
  }
  EXPECT_EQ(rows, static_cast<int>(items.items.size()) + 1);

  const ReadMission back = ParseQgcWpl(text, "mission.waypoints");
  EXPECT_NEAR(back.home_amsl_m, mission.home.amsl_m, 1e-6);
  const EnuFrame frame(mission.origin);
  size_t w = 0;
  for (const auto& item : back.items) {
    if (item.command != mav::kNavWaypoint) continue;
    const MissionWaypoint& wp = mission.waypoints[w++];
    const Eigen::Vector3d enu = frame.EnuFromGeodetic(
        Geodetic{item.params[4], item.params[5], item.params[6] + (wp.ellipsoidal_height_m - wp.amsl_m)});
    EXPECT_LT((enu - wp.position_enu_m).norm(), 0.01);
  }
  EXPECT_EQ(w, mission.waypoints.size());
}

TEST(QgcWpl, ReaderNamesTheLine) {
  try {
    ParseQgcWpl("QGC WPL 110\n0\t1\t0\t16\t0\t0\t0\t0\t47\t8\t400\t1\n1\t0\t3\t16\t0\t0\t0\n", "m.waypoints");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("line 3"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ParseQgcWpl("QGC WPL 120\n", "m.waypoints"), InputError);
}

}  // namespace
}  // namespace cinepath::exporter
