// A WGS84 position as JSON, the one spelling every cinepath file uses for an origin:
//   {"lat_deg": 46.84, "lon_deg": -91.99, "height_m": 163.2}   (height WGS84 ellipsoidal, metres)
// Read by shots.json, plan.json and scene.json readers alike.
#pragma once

#include "core/geodesy.h"
#include "core/json.h"

namespace cinepath {

// Reads and checks {"lat_deg", "lon_deg", "height_m"}: latitude in [-90, 90], longitude in
// [-180, 180], height in [-12000, 100000] m. InputError names the key. Other keys are left to the
// caller (scene.json's origin carries notes such as "geoid_model"; shots.json refuses them).
Geodetic GeodeticFromJson(const JsonField& field);

// A local ENU coordinate about that origin, in any file (plan.json's positions and heights, scene.json's
// camera positions): within kMaxEnuCoordinateM of the origin, where the local frame is still local and no
// product of coordinates a stage computes overflows. InputError naming the path beyond it.
inline constexpr double kMaxEnuCoordinateM = 1e7;
double EnuCoordinateFromJson(const JsonField& field);
Eigen::Vector3d EnuPositionFromJson(const JsonField& field);  // [e, n, u], each as above

// Writes it with `latlon_decimals` for the angles (1e-9 deg ~ 0.1 mm) and `height_decimals` for the height.
Json GeodeticToJson(const Geodetic& g, int latlon_decimals = 9, int height_decimals = 6);

}  // namespace cinepath
