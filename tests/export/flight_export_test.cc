#include "export/flight_export.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "sample_trajectories.h"

namespace cinepath::exporter {
namespace {

FlightExportOptions QgcPlan() {
  FlightExportOptions o;
  o.shared.formats = {Format::kQgcPlan};
  o.plan_name = "plan.json";
  return o;
}

TeamPlan TeamOf(const std::vector<std::string>& names, bool single) {
  TeamPlan team;
  team.single = single;
  for (const auto& name : names) team.flights.push_back({name, std::nullopt, testing::FlybyPlan()});
  team.origin = team.flights.front().plan.origin;
  return team;
}

TEST(FlightExport, ATeamOfOneExportsAsExportMissionDoes) {
  const FlightExportOptions options = QgcPlan();
  const std::vector<FlightExport> exports = ExportFlights(TeamOf({"px4-multirotor"}, true), options);
  ASSERT_EQ(exports.size(), 1u);
  ExportOptions direct = options.shared;
  direct.build.plan_name = "plan.json";
  const ExportResult expected = ExportMission(testing::FlybyPlan(), direct);
  ASSERT_EQ(exports[0].result.files.size(), expected.files.size());
  EXPECT_EQ(exports[0].result.files[0].contents, expected.files[0].contents);
  EXPECT_EQ(exports[0].options.build.plan_name, "plan.json");
}

TEST(FlightExport, EachDroneOfSeveralIsNamedAndHomeIsRefused) {
  FlightExportOptions options = QgcPlan();
  const std::vector<FlightExport> exports = ExportFlights(TeamOf({"north", "south"}, false), options);
  ASSERT_EQ(exports.size(), 2u);
  EXPECT_EQ(exports[1].name, "south");
  EXPECT_EQ(exports[1].options.build.plan_name, "plan.json (drone south)");
  options.shared.build.home = HomeSpec{47.3977419, 8.545594, 500};
  EXPECT_THROW(ExportFlights(TeamOf({"north", "south"}, false), options), InputError);
  EXPECT_NO_THROW(ExportFlights(TeamOf({"one"}, true), options));
}

TEST(FlightExport, AHomeInEnuNeedsAnOrigin) {
  TeamPlan team = TeamOf({"north", "south"}, false);
  for (auto& flight : team.flights) {
    flight.plan.origin.reset();
    flight.home_enu_m = Eigen::Vector3d(0, 30, 0);
  }
  try {
    ExportFlights(team, QgcPlan());
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("flights[north].home_enu_m"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace cinepath::exporter
