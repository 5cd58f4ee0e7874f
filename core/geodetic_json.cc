#include "core/geodetic_json.h"

#include <cmath>

#include "core/number_format.h"

namespace cinepath {

Geodetic GeodeticFromJson(const JsonField& f) {
  if (!f.IsObject()) f.Fail("expected {\"lat_deg\", \"lon_deg\", \"height_m\"}");
  Geodetic g;
  g.lat_deg = f["lat_deg"].AsDouble();
  g.lon_deg = f["lon_deg"].AsDouble();
  g.height_m = f["height_m"].AsDouble();
  if (g.lat_deg < -90 || g.lat_deg > 90) f["lat_deg"].Fail("must be in [-90, 90]");
  if (g.lon_deg < -180 || g.lon_deg > 180) f["lon_deg"].Fail("must be in [-180, 180]");
  if (g.height_m < -12000 || g.height_m > 100000) f["height_m"].Fail("must be in [-12000, 100000] m");
  return g;
}

double EnuCoordinateFromJson(const JsonField& f) {
  const double v = f.AsDouble();
  if (!(std::fabs(v) <= kMaxEnuCoordinateM)) {
    f.Fail("must lie within 1e7 m of the origin, got " + FormatSignificant(v));
  }
  return v;
}

Eigen::Vector3d EnuPositionFromJson(const JsonField& f) {
  if (!f.IsArray() || f.size() != 3) f.Fail("expected [x, y, z]");
  return {EnuCoordinateFromJson(f.At(0)), EnuCoordinateFromJson(f.At(1)), EnuCoordinateFromJson(f.At(2))};
}

Json GeodeticToJson(const Geodetic& g, int latlon_decimals, int height_decimals) {
  auto r = [](double v, int d) { return std::fabs(v) > 1e15 ? v : RoundToDecimals(v, d); };
  Json j = Json::object();
  j["lat_deg"] = r(g.lat_deg, latlon_decimals);
  j["lon_deg"] = r(g.lon_deg, latlon_decimals);
  j["height_m"] = r(g.height_m, height_decimals);
  return j;
}

}  // namespace cinepath
