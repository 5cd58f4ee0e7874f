#include "photogrammetry/io/gcp_file.h"

#include <gtest/gtest.h>

#include <GeographicLib/UTMUPS.hpp>

#include <cstdio>
#include <string>

#include "core/error.h"

namespace cinepath::photogrammetry {
namespace {

std::string Line(double x, double y, const std::string& rest) {
  char buffer[128];
  std::snprintf(buffer, sizeof(buffer), "%.4f %.4f", x, y);
  return std::string(buffer) + " " + rest + "\n";
}

// Expects an InputError whose message contains every fragment.
void ExpectInputError(const std::string& text, std::initializer_list<std::string> fragments) {
  try {
    ParseGcpFile(text, "gcp_list.txt");
    ADD_FAILURE() << "no error for:\n" << text;
  } catch (const InputError& e) {
    for (const std::string& f : fragments) EXPECT_NE(std::string(e.what()).find(f), std::string::npos) << e.what();
  }
}

TEST(GcpFile, GeographicIsLongitudeThenLatitude) {
  for (const char* header : {"EPSG:4326", "epsg:4326", "WGS84", "EPSG:4979", "+proj=longlat +datum=WGS84 +no_defs"}) {
    const GcpFile f = ParseGcpFile(std::string(header) +
                                       "\n-91.9942 46.8425 158.5 100 200 DJI_0018.JPG GCP1\n"
                                       "-91.9942 46.8425 158.5 300.5 40 DJI_0019.JPG GCP1\n",
                                   "gcp_list.txt");
    EXPECT_EQ(f.crs.kind, GcpCoordinateSystem::Kind::kGeographic) << header;
    ASSERT_EQ(f.points.size(), 1u);
    EXPECT_DOUBLE_EQ(f.points[0].lat_deg, 46.8425);
    EXPECT_DOUBLE_EQ(f.points[0].lon_deg, -91.9942);
    EXPECT_DOUBLE_EQ(*f.points[0].geo_z_m, 158.5);
    ASSERT_EQ(f.points[0].observations.size(), 2u);
    EXPECT_EQ(f.points[0].observations[1].image_name, "DJI_0019.JPG");
    EXPECT_EQ(f.points[0].observations[1].pixel_file, Eigen::Vector2d(300.5, 40));
    // OpenSfM's convention (pixel centre at integers) -> COLMAP's (corner at 0).
    EXPECT_EQ(f.points[0].observations[1].pixel_colmap, Eigen::Vector2d(301, 40.5));
  }
}

TEST(GcpFile, SwappedLatitudeLongitudeIsRefusedWithAHint) {
  ExpectInputError("EPSG:4326\n46.8425 -91.9942 158.5 100 200 a.jpg\n",
                   {"gcp_list.txt: line 2", "latitude", "outside [-90, 90]", "swapped"});
}

TEST(GcpFile, EveryUtmFormGivesTheSamePosition) {
  struct Case {
    const char* header;
    double lat, lon;
  };
  const Case cases[] = {
      {"WGS84 UTM 32N", 52.2, 9.7},
      {"wgs84 utm 32n", 52.2, 9.7},
      {"WGS84 UTM 32", 52.2, 9.7},  // a bare zone is north (OpenSfM)
      {"EPSG:32632", 52.2, 9.7},
      {"+proj=utm +zone=32 +datum=WGS84 +units=m +no_defs", 52.2, 9.7},
      {"+proj=utm +zone=32 +ellps=WGS84 +datum=WGS84 +units=m +no_defs=True +type=crs", 52.2, 9.7},
      {"'+proj=utm +zone=32 +datum=WGS84'", 52.2, 9.7},
      {"WGS84 UTM 23S", -23.5, -46.6},
      {"EPSG:32723", -23.5, -46.6},
      {"+proj=utm +zone=23 +south +ellps=WGS84 +datum=WGS84 +units=m +no_defs", -23.5, -46.6},
      {"+proj=utm +zone=23 +south=True +datum=WGS84", -23.5, -46.6},
  };
  for (const Case& c : cases) {
    int zone;
    bool north;
    double x, y;
    GeographicLib::UTMUPS::Forward(c.lat, c.lon, zone, north, x, y);
    const GcpFile f = ParseGcpFile(std::string(c.header) + "\n" + Line(x, y, "12.5 10 20 IMG_1.JPG"), "gcp_list.txt");
    EXPECT_EQ(f.crs.kind, GcpCoordinateSystem::Kind::kUtm) << c.header;
    EXPECT_EQ(f.crs.utm_zone, zone) << c.header;
    EXPECT_EQ(f.crs.utm_north, north) << c.header;
    ASSERT_EQ(f.points.size(), 1u);
    // Coordinates were printed with 0.1 mm: ~1e-9 deg.
    EXPECT_NEAR(f.points[0].lat_deg, c.lat, 1e-8) << c.header;
    EXPECT_NEAR(f.points[0].lon_deg, c.lon, 1e-8) << c.header;
    EXPECT_EQ(f.points[0].name, "gcp1");
    EXPECT_FALSE(f.points[0].named_in_file);
  }
}

TEST(GcpFile, UnsupportedCoordinateSystemsAreRefused) {
  ExpectInputError("EPSG:2056\n1 2 3 4 5 a.jpg\n", {"gcp_list.txt: line 1", "EPSG:2056 is not supported"});
  ExpectInputError("+proj=somerc +lat_0=46.95 +datum=WGS84\n1 2 3 4 5 a.jpg\n", {"line 1", "+lat_0"});
  ExpectInputError("+proj=utm +zone=32 +datum=NAD83\n1 2 3 4 5 a.jpg\n", {"line 1", "+datum=nad83", "only WGS84"});
  ExpectInputError("+proj=utm +zone=32\n1 2 3 4 5 a.jpg\n", {"line 1", "without +datum=WGS84"});
  ExpectInputError("WGS84 UTM 61N\n1 2 3 4 5 a.jpg\n", {"line 1", "zone 61 outside 1..60"});
  ExpectInputError("WGS84 UTM XN\n1 2 3 4 5 a.jpg\n", {"line 1", "WGS84 UTM <zone>N"});
  ExpectInputError("NAD83\n1 2 3 4 5 a.jpg\n", {"line 1", "unsupported coordinate system 'NAD83'"});
  // The coordinate-system line comes first: a GCP line there is refused as a system.
  ExpectInputError("# comment\n\n544256.7 5320919.9 5 3044 2622 IMG_0525.jpg\n",
                   {"line 3", "unsupported coordinate system"});
}

TEST(GcpFile, BadLinesNameTheLine) {
  const std::string h = "WGS84 UTM 10N\n";
  ExpectInputError(h + "544256.7 5320919.9 5 3044 2622\n", {"gcp_list.txt: line 2", "found 5 fields"});
  ExpectInputError(h + "# c\n544256.7 north 5 3044 2622 a.jpg\n", {"line 3", "geo_y", "'north'"});
  ExpectInputError(h + "544256.7 5320919.9 5 nan 2622 a.jpg\n", {"line 2", "im_x", "'nan'"});
  ExpectInputError(h + "544256.7 5320919.9 inf 3044 2622 a.jpg\n", {"line 2", "geo_z", "NaN for no elevation"});
  ExpectInputError(h + "544256.7 5320919.9 5 -3 2622 a.jpg\n", {"line 2", "outside the image"});
  ExpectInputError(h + "544256.7 95320919.9 5 3 2622 a.jpg\n", {"line 2", "not a valid position"});
  ExpectInputError(h + "544256.7 5320919.9 5 1 2 a.jpg P1\n544256.7 5320920.9 5 1 2 b.jpg P1\n",
                   {"line 3", "'P1' has other coordinates here than on gcp_list.txt: line 2"});
  ExpectInputError(h + "544256.7 5320919.9 5 1 2 a.jpg\n544256.7 5320919.9 5 7 8 a.jpg\n",
                   {"line 3", "already observed in image 'a.jpg'"});
  ExpectInputError("", {"gcp_list.txt", "empty"});
  ExpectInputError(h + "\n# nothing\n", {"no GCP lines"});
}

TEST(GcpFile, GroupsUnnamedLinesByCoordinatesAndKeepsNaNElevation) {
  const GcpFile f = ParseGcpFile(
      "WGS84 UTM 10N\r\n"
      "544256.7\t5320919.9\t5\t3044\t2622\tIMG_0525.jpg\r\n"
      "544157.7 5320899.2 NaN 4193 1552 IMG_0585.jpg\n"
      "544256.7 5320919.9 5 3000 2000 IMG_0526.jpg\n"
      "544157.7 5320899.2 nan 10 20 IMG_0586.jpg",
      "gcp_list.txt");
  ASSERT_EQ(f.points.size(), 2u);
  EXPECT_EQ(f.points[0].name, "gcp1");
  EXPECT_EQ(f.points[0].observations.size(), 2u);
  EXPECT_EQ(f.points[0].where, "gcp_list.txt: line 2");
  EXPECT_EQ(f.points[1].name, "gcp2");
  EXPECT_FALSE(f.points[1].geo_z_m.has_value());
  EXPECT_EQ(f.points[1].observations.size(), 2u);
  EXPECT_EQ(f.points[1].observations[1].where, "gcp_list.txt: line 5");
}

TEST(GcpFile, TheSeventhFieldNamesThePointAndExtrasAreIgnored) {
  const GcpFile f = ParseGcpFile(
      "EPSG:32610\n"
      "544256.7 5320919.9 5 3044 2622 IMG_0525.jpg corner_A some extras\n"
      "544256.7 5320919.9 5 3000 2000 IMG_0526.jpg corner_A\n"
      "544256.7 5320919.9 5 10 20 IMG_0527.jpg\n",
      "gcp_list.txt");
  ASSERT_EQ(f.points.size(), 2u);
  EXPECT_EQ(f.points[0].name, "corner_A");
  EXPECT_TRUE(f.points[0].named_in_file);
  EXPECT_EQ(f.points[0].observations.size(), 2u);
  EXPECT_EQ(f.points[1].name, "gcp1");
}

}  // namespace
}  // namespace cinepath::photogrammetry
