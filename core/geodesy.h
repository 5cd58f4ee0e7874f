// Geodesy through GeographicLib: WGS84 geodetic coordinates, ECEF, and the local ENU scene frame.
//
// Frames:
//   * Geodetic: latitude and longitude in degrees (WGS84), height in metres above the WGS84
//     ellipsoid (ellipsoidal; never AMSL inside cinepath — see geoid.h for AMSL).
//   * ECEF: WGS84 earth-centred, earth-fixed, metres.
//   * ENU: the scene frame, x east, y north, z up, metres, tangent to the ellipsoid at an origin.
#pragma once

#include <Eigen/Core>
#include <memory>

namespace cinepath {

struct Geodetic {
  double lat_deg = 0;   // [-90, 90]
  double lon_deg = 0;   // any; normalized to [-180, 180) on output
  double height_m = 0;  // WGS84 ellipsoidal height
};

// Throws InputError (naming `what`) for a latitude outside [-90, 90] or non-finite values.
void ValidateGeodetic(const Geodetic& g, const char* what);

Eigen::Vector3d EcefFromGeodetic(const Geodetic& g);
Geodetic GeodeticFromEcef(const Eigen::Vector3d& ecef_m);

// A local ENU frame about a WGS84 origin (GeographicLib::LocalCartesian). Exact, not a flat-earth
// approximation: round trips are good to ~1e-9 m at km distances.
class EnuFrame {
 public:
  explicit EnuFrame(const Geodetic& origin);
  ~EnuFrame();
  EnuFrame(const EnuFrame&);
  EnuFrame& operator=(const EnuFrame&);

  const Geodetic& origin() const { return origin_; }

  Eigen::Vector3d EnuFromGeodetic(const Geodetic& g) const;
  Geodetic GeodeticFromEnu(const Eigen::Vector3d& enu_m) const;
  Eigen::Vector3d EnuFromEcef(const Eigen::Vector3d& ecef_m) const;
  Eigen::Vector3d EcefFromEnu(const Eigen::Vector3d& enu_m) const;
  // Rotation taking ECEF direction vectors into ENU (rows are east, north, up in ECEF).
  Eigen::Matrix3d enu_from_ecef_rotation() const;
  // Rotation taking this frame's ENU direction vectors into the local ENU axes (east, north, up of
  // the ellipsoid) at the point `enu_m` of the frame: the identity at the origin; at a point away
  // from it, true north there is turned by the meridian convergence and up tilted (core/local_level.h).
  // `geodetic`: when given, also the point's geodetic position (GeodeticFromEnu, from the same step).
  Eigen::Matrix3d LocalLevelFromEnu(const Eigen::Vector3d& enu_m, Geodetic* geodetic = nullptr) const;

 private:
  Geodetic origin_;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cinepath
