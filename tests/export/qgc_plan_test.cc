#include "export/qgc_plan.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/json.h"
#include "export/mission_builder.h"
#include "export/mission_reader.h"
#include "sample_trajectories.h"

namespace cinepath::exporter {
namespace {

TEST(QgcPlan, LoadingRulesAndRoundTrip) {
  const Mission mission = BuildMission(testing::OrbitPlan(), MissionBuildOptions{});
  const MavMission items = BuildMavMission(mission, Firmware::kPx4, AltitudeRef::kRelative);
  const std::string text = WriteQgcPlan(mission, items, Firmware::kPx4, AltitudeRef::kRelative);
  const Json plan = Json::parse(text);
  for (const char* key : {"mission", "geoFence", "rallyPoints"}) EXPECT_TRUE(plan[key].is_object()) << key;
  EXPECT_EQ(plan["fileType"], "Plan");
  EXPECT_EQ(plan["mission"]["firmwareType"], 12);
  EXPECT_TRUE(plan["mission"]["hoverSpeed"].is_number_integer());
  EXPECT_TRUE(plan["mission"]["cruiseSpeed"].is_number_integer());
  for (const auto& item : plan["mission"]["items"]) {
    EXPECT_EQ(item["params"].size(), 7u);
    EXPECT_TRUE(item["autoContinue"].is_boolean());
    const int alt_keys =
        item.contains("AltitudeMode") + item.contains("Altitude") + item.contains("AMSLAltAboveTerrain");
    EXPECT_TRUE(alt_keys == 0 || alt_keys == 3);
  }
  // Round trip through the reader `cinepath info` uses: positions within 1 cm.
  const ReadMission back = ParseQgcPlan(text, "mission.plan");
  ASSERT_EQ(back.items.size(), items.items.size());
  const EnuFrame frame(mission.origin);
  size_t w = 0;
  for (const auto& item : back.items) {
    if (item.command != mav::kNavWaypoint) continue;
    const MissionWaypoint& wp = mission.waypoints[w++];
    EXPECT_EQ(item.frame, mav::kFrameGlobalRelativeAlt);
    // Relative altitude → ellipsoidal through the home AMSL and the geoid.
    const double amsl = back.home_amsl_m + item.params[6];
    const Eigen::Vector3d enu =
        frame.EnuFromGeodetic(Geodetic{item.params[4], item.params[5], amsl + (wp.ellipsoidal_height_m - wp.amsl_m)});
    EXPECT_LT((enu - wp.position_enu_m).norm(), 0.01);
  }
  EXPECT_EQ(w, mission.waypoints.size());
}

TEST(QgcPlan, ReaderRejectsBrokenFiles) {
  EXPECT_THROW(ParseQgcPlan(R"({"fileType":"Plan","version":1,"groundStation":"x","mission":{}})", "a.plan"),
               InputError);
  const std::string six_params =
      R"({"fileType":"Plan","version":1,"groundStation":"x","geoFence":{},"rallyPoints":{},)"
      R"("mission":{"version":2,"firmwareType":12,"plannedHomePosition":[1,2,3],)"
      R"("items":[{"type":"SimpleItem","command":16,"frame":3,"autoContinue":true,"params":[0,0,0,0,1,2]}]}})";
  try {
    ParseQgcPlan(six_params, "a.plan");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("params"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace cinepath::exporter
