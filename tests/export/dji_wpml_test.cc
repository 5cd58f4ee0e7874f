#include "export/dji_wpml.h"

#include <regex>
#include <set>

#include <gtest/gtest.h>

#include "core/drone_profiles.h"

#include "core/geoid.h"
#include "export/mission_builder.h"
#include "sample_trajectories.h"

namespace cinepath::exporter {
namespace {

std::vector<std::string> All(const std::string& text, const std::string& tag) {
  std::vector<std::string> out;
  const std::regex re("<" + tag + ">([^<]*)</" + tag + ">");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator(); ++it) {
    out.push_back((*it)[1]);
  }
  return out;
}

TEST(DjiWpml, LonLatOrderContiguousIndicesUniqueGroups) {
  const Mission mission = BuildMission(testing::OrbitPlan(), MissionBuildOptions{});
  const WpmlDocuments docs = WriteWpmlDocuments(mission, *FindDroneProfile("dji-m30"), AltitudeRef::kRelative);
  for (const std::string* doc : {&docs.template_kml, &docs.waylines_wpml}) {
    const auto coords = All(*doc, "coordinates");
    ASSERT_EQ(coords.size(), mission.waypoints.size());
    const double lon = std::stod(coords[0].substr(0, coords[0].find(',')));
    EXPECT_NEAR(lon, mission.waypoints[0].lon_deg, 1e-8);  // longitude first
    const auto indices = All(*doc, "wpml:index");
    for (size_t i = 0; i < indices.size(); ++i) EXPECT_EQ(indices[i], std::to_string(i));
    const auto group_ids = All(*doc, "wpml:actionGroupId");
    EXPECT_EQ(std::set<std::string>(group_ids.begin(), group_ids.end()).size(), group_ids.size());
    for (const auto& s : All(*doc, "wpml:waypointSpeed")) {
      EXPECT_GE(std::stod(s), 1.0);
      EXPECT_LE(std::stod(s), 15.0);
    }
    EXPECT_EQ(All(*doc, "wpml:globalRTHHeight").size(), 1u);
  }
  EXPECT_EQ(All(docs.waylines_wpml, "wpml:executeHeightMode")[0], "relativeToStartPoint");
  const auto heights = All(docs.waylines_wpml, "wpml:executeHeight");
  EXPECT_NEAR(std::stod(heights[0]), mission.waypoints[0].relative_alt_m, 1e-3);
}

TEST(DjiWpml, AbsoluteHeightsUseEgm96InTemplateAndEllipsoidInWaylines) {
  MissionBuildOptions opt;
  opt.absolute_altitudes = true;
  const Mission mission = BuildMission(testing::FlybyPlan(), opt);
  const WpmlDocuments docs = WriteWpmlDocuments(mission, *FindDroneProfile("dji-m30"), AltitudeRef::kAmsl);
  EXPECT_EQ(All(docs.template_kml, "wpml:heightMode")[0], "EGM96");
  EXPECT_EQ(All(docs.waylines_wpml, "wpml:executeHeightMode")[0], "WGS84");
  const auto height = All(docs.template_kml, "wpml:height");
  const auto ellipsoid = All(docs.template_kml, "wpml:ellipsoidHeight");
  const auto execute = All(docs.waylines_wpml, "wpml:executeHeight");
  ASSERT_EQ(height.size(), mission.waypoints.size());
  for (size_t i = 0; i < height.size(); ++i) {
    const auto& wp = mission.waypoints[i];
    const double n = Egm96Geoid::Default().UndulationM(wp.lat_deg, wp.lon_deg);
    EXPECT_NEAR(std::stod(ellipsoid[i]) - std::stod(height[i]), n, 2e-3);
    EXPECT_EQ(execute[i], ellipsoid[i]);
  }
}

TEST(DjiWpml, KmzHoldsBothEntries) {
  const Mission mission = BuildMission(testing::ChasePlan(), MissionBuildOptions{});
  const WpmlDocuments docs = WriteWpmlDocuments(mission, *FindDroneProfile("dji-m30"), AltitudeRef::kRelative);
  const std::string kmz = WriteDjiKmz(docs);
  EXPECT_NE(kmz.find("wpmz/template.kml"), std::string::npos);
  EXPECT_NE(kmz.find("wpmz/waylines.wpml"), std::string::npos);
  EXPECT_NE(kmz.find(docs.waylines_wpml), std::string::npos);  // stored, not compressed
}

TEST(DjiWpml, SlowLegsFlyAtOneMetrePerSecondThenHover) {
  // 2 m in 4 s (0.5 m/s): flown at 1 m/s in 2 s, then a 2 s hover on arrival.
  Trajectory t = testing::EmptyPlan("slow", "CUSTOM", 4, 10);
  for (int i = 0; i <= 40; ++i) testing::AddSample(t, i / 10.0, Eigen::Vector3d(i * 0.05, 0, 10), 90, -10, 24, 10, 4);
  const Mission mission = BuildMission(t, MissionBuildOptions{});
  ASSERT_EQ(mission.waypoints.size(), 2u);
  const WpmlDocuments docs = WriteWpmlDocuments(mission, *FindDroneProfile("dji-m30"), AltitudeRef::kRelative);
  const auto hover = All(docs.waylines_wpml, "wpml:hoverTime");
  ASSERT_EQ(hover.size(), 1u);
  EXPECT_NEAR(std::stod(hover[0]), 2.0, 0.01);
  EXPECT_EQ(All(docs.waylines_wpml, "wpml:waypointSpeed")[0], "1.00");
  bool noted = false;
  for (const auto& n : docs.notes) noted |= n.find("slower than WPML") != std::string::npos;
  EXPECT_TRUE(noted);
}

}  // namespace
}  // namespace cinepath::exporter
