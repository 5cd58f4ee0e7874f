#include "export/litchi_csv.h"

#include <sstream>

#include <gtest/gtest.h>

#include "export/mission_builder.h"
#include "sample_trajectories.h"

namespace cinepath::exporter {
namespace {

TEST(LitchiCsv, FortySixColumnsAndRecordActions) {
  const Mission mission = BuildMission(testing::ChasePlan(), MissionBuildOptions{});
  const LitchiCsv csv = WriteLitchiCsv(mission);
  std::istringstream in(csv.text);
  std::string line;
  std::vector<std::string> lines;
  while (std::getline(in, line)) lines.push_back(line);
  ASSERT_EQ(lines.size(), mission.waypoints.size() + 1);
  for (const auto& l : lines) EXPECT_EQ(std::count(l.begin(), l.end(), ','), 45) << l;
  EXPECT_EQ(lines[0].rfind("latitude,longitude,altitude(m),heading(deg),", 0), 0u);
  EXPECT_NE(lines[1].find(",2,0,-1,0"), std::string::npos);      // start recording
  EXPECT_NE(lines.back().find(",3,0,-1,0"), std::string::npos);  // stop recording
  EXPECT_FALSE(csv.notes.empty());
}

}  // namespace
}  // namespace cinepath::exporter
