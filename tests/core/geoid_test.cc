#include "core/geoid.h"

#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "core/error.h"

namespace cinepath {
namespace {

TEST(Geoid, Egm96KnownAnswers) {
  const Egm96Geoid& geoid = Egm96Geoid::Default();
  EXPECT_NEAR(geoid.UndulationM(0, 0), 17.16, 0.05);
  EXPECT_NEAR(geoid.UndulationM(47.3977, 8.5456), 47.34, 0.05);       // Zurich (PX4 SITL home)
  EXPECT_NEAR(geoid.UndulationM(27.988, 86.925), -28.87, 0.05);       // Everest
  EXPECT_NEAR(geoid.UndulationM(46.842583, -91.993884), -28.7, 0.1);  // Brighton Beach, Duluth
}

TEST(Geoid, ExtremesWrapAndClamp) {
  const Egm96Geoid& geoid = Egm96Geoid::Default();
  // Longitude wraps: -180 == 180, and 540 == 180.
  EXPECT_NEAR(geoid.UndulationM(10, 180), geoid.UndulationM(10, -180), 1e-9);
  EXPECT_NEAR(geoid.UndulationM(10, 540), geoid.UndulationM(10, 180), 1e-9);
  // Continuous across the antimeridian.
  EXPECT_NEAR(geoid.UndulationM(-20, 179.999), geoid.UndulationM(-20, -179.999), 0.01);
  // Poles: EGM96 N(90) ~ 13.6 m, N(-90) ~ -29.5 m; every longitude agrees there.
  EXPECT_NEAR(geoid.UndulationM(90, 0), 13.6, 0.1);
  EXPECT_NEAR(geoid.UndulationM(-90, 0), -29.5, 0.1);
  EXPECT_NEAR(geoid.UndulationM(90, 123), geoid.UndulationM(90, -77), 1e-6);
  EXPECT_THROW(geoid.UndulationM(NAN, 0), InputError);
}

TEST(Geoid, AmslEllipsoidalRoundTrip) {
  const Egm96Geoid& geoid = Egm96Geoid::Default();
  const double h = geoid.EllipsoidalFromAmslM(46.84, -91.99, 184.7);
  EXPECT_NEAR(h, 184.7 + geoid.UndulationM(46.84, -91.99), 1e-12);
  EXPECT_NEAR(geoid.AmslFromEllipsoidalM(46.84, -91.99, h), 184.7, 1e-12);
  EXPECT_NEAR(geoid.AmslFromEllipsoidalM(0, 0, 10000), 10000 - 17.16, 0.05);
  EXPECT_NEAR(geoid.AmslFromEllipsoidalM(0, 0, -500), -500 - 17.16, 0.05);
}

TEST(Geoid, MalformedGridNamesTheFile) {
  const auto path = std::filesystem::temp_directory_path() / "cinepath_truncated.gtx";
  { std::ofstream(path, std::ios::binary) << "short"; }
  try {
    Egm96Geoid geoid(path);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cinepath_truncated.gtx"), std::string::npos);
  }
  std::filesystem::remove(path);
  EXPECT_THROW(Egm96Geoid("/nonexistent/egm96.gtx"), InputError);
}

}  // namespace
}  // namespace cinepath
