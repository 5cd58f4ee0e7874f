#include "core/geodesy.h"

#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "core/angles.h"
#include "core/error.h"

namespace cinepath {
namespace {

void ExpectRoundTrip(const Geodetic& origin, const Eigen::Vector3d& enu_m) {
  const EnuFrame frame(origin);
  const Geodetic g = frame.GeodeticFromEnu(enu_m);
  const Eigen::Vector3d back = frame.EnuFromGeodetic(g);
  // Double-precision ECEF has a spacing of 0.93 nm at the Earth's radius, and LocalCartesian goes
  // through ECEF both ways: the round trip is exact to a few ulps, measured <= 2.6e-9 m here.
  EXPECT_LT((back - enu_m).norm(), 3e-9) << "origin " << origin.lat_deg << "," << origin.lon_deg << " enu "
                                         << enu_m.transpose();
  const Eigen::Vector3d via_ecef = frame.EnuFromEcef(frame.EcefFromEnu(enu_m));
  EXPECT_LT((via_ecef - enu_m).norm(), 3e-9);
  // The ECEF route lands where the geodetic one does (a rotation that is wrong but orthogonal would
  // still round-trip above).
  EXPECT_LT((frame.EcefFromEnu(enu_m) - EcefFromGeodetic(g)).norm(), 1e-6);
}

TEST(Geodesy, LocalCartesianRoundTrips) {
  const Geodetic origins[] = {{46.842583, -91.993884, 161.94},
                              {0, 0, 0},
                              {-33.9, 151.2, 50},
                              {89.9999, 10, 0},
                              {-90, 0, 0},
                              {90, 0, 0},
                              {10, 180, 0},
                              {10, -180, 0},
                              {45, 179.9999, -500},
                              {-45, -179.9999, 10000}};
  const Eigen::Vector3d points[] = {{0, 0, 0}, {100, -50, 20}, {-3000, 4000, 500}, {1, 1, -500}, {20000, 0, 10000}};
  for (const auto& o : origins) {
    for (const auto& p : points) ExpectRoundTrip(o, p);
  }
}

TEST(Geodesy, EnuAxesPointEastNorthUp) {
  const EnuFrame frame({46.84, -91.99, 160});
  const Geodetic north = frame.GeodeticFromEnu({0, 1000, 0});
  EXPECT_GT(north.lat_deg, 46.84);
  EXPECT_NEAR(north.lon_deg, -91.99, 1e-9);
  const Geodetic east = frame.GeodeticFromEnu({1000, 0, 0});
  EXPECT_GT(east.lon_deg, -91.99);
  EXPECT_NEAR(frame.GeodeticFromEnu({0, 0, 25}).height_m, 185, 1e-9);
  // One degree of latitude is ~111.2 km here (WGS84 meridian arc).
  const Eigen::Vector3d one_deg = frame.EnuFromGeodetic({47.84, -91.99, 160});
  EXPECT_NEAR(one_deg.y(), 111190, 300);
}

TEST(Geodesy, AntimeridianIsContinuous) {
  const EnuFrame frame({10, 179.9995, 0});
  const Eigen::Vector3d across = frame.EnuFromGeodetic({10, -179.9995, 0});
  EXPECT_NEAR(across.x(), 0.001 * 111320 * std::cos(10 * kRadPerDeg), 0.5);
  EXPECT_NEAR(across.y(), 0, 0.01);
  const Geodetic back = frame.GeodeticFromEnu(across);
  EXPECT_NEAR(back.lon_deg, -179.9995, 1e-12);
}

TEST(Geodesy, PolesAreDefined) {
  const EnuFrame north_pole({90, 0, 0});
  const Geodetic g = north_pole.GeodeticFromEnu({0, -1000, 0});
  EXPECT_NEAR(g.lat_deg, 90 - 1000 / 111694.0, 1e-3);
  const EnuFrame south_pole({-90, 45, 0});
  EXPECT_LT((south_pole.EnuFromGeodetic({-90, 45, 100}) - Eigen::Vector3d(0, 0, 100)).norm(), 1e-9);
}

TEST(Geodesy, EcefKnownAnswers) {
  const Eigen::Vector3d equator = EcefFromGeodetic({0, 0, 0});
  EXPECT_NEAR(equator.x(), 6378137.0, 1e-6);
  const Eigen::Vector3d pole = EcefFromGeodetic({90, 0, 0});
  EXPECT_NEAR(pole.z(), 6356752.314245, 1e-5);
  const Geodetic g = GeodeticFromEcef(EcefFromGeodetic({47.3977, 8.5456, 10000}));
  EXPECT_NEAR(g.lat_deg, 47.3977, 1e-12);
  EXPECT_NEAR(g.lon_deg, 8.5456, 1e-12);
  EXPECT_NEAR(g.height_m, 10000, 1e-8);
}

TEST(Geodesy, InvalidInputIsRejected) {
  EXPECT_THROW(EnuFrame({91, 0, 0}), InputError);
  EXPECT_THROW(EnuFrame({NAN, 0, 0}), InputError);
  const EnuFrame frame({0, 0, 0});
  EXPECT_THROW(frame.EnuFromGeodetic({-90.5, 0, 0}), InputError);
  EXPECT_THROW(frame.GeodeticFromEnu({NAN, 0, 0}), InputError);
}

// GeographicLib's own CartConvert (Debian geographiclib-tools) as an oracle for the ENU frame.
TEST(Geodesy, AgreesWithCartConvert) {
  if (std::system("command -v CartConvert > /dev/null 2>&1") != 0) {
    GTEST_SKIP() << "CartConvert (geographiclib-tools) not installed";
  }
  const Geodetic origin{46.842583, -91.993884, 161.94};
  const EnuFrame frame(origin);
  const Geodetic p{46.85, -92.0, 200.5};
  char cmd[256];
  std::snprintf(cmd, sizeof cmd, "echo '%.9f %.9f %.6f' | CartConvert -p 9 -l %.9f %.9f %.6f", p.lat_deg, p.lon_deg,
                p.height_m, origin.lat_deg, origin.lon_deg, origin.height_m);
  FILE* pipe = popen(cmd, "r");
  ASSERT_NE(pipe, nullptr);
  double x, y, z;
  ASSERT_EQ(std::fscanf(pipe, "%lf %lf %lf", &x, &y, &z), 3);
  pclose(pipe);
  const Eigen::Vector3d enu = frame.EnuFromGeodetic(p);
  EXPECT_NEAR(enu.x(), x, 1e-6);
  EXPECT_NEAR(enu.y(), y, 1e-6);
  EXPECT_NEAR(enu.z(), z, 1e-6);
}

}  // namespace
}  // namespace cinepath
