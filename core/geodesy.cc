#include "core/geodesy.h"

#include <cmath>
#include <string>
#include <vector>

#include <GeographicLib/Geocentric.hpp>
#include <GeographicLib/LocalCartesian.hpp>

#include "core/angles.h"
#include "core/error.h"

namespace cinepath {

void ValidateGeodetic(const Geodetic& g, const char* what) {
  if (!std::isfinite(g.lat_deg) || !std::isfinite(g.lon_deg) || !std::isfinite(g.height_m)) {
    throw InputError(std::string(what) + ": latitude, longitude and height must be finite");
  }
  if (g.lat_deg < -90.0 || g.lat_deg > 90.0) {
    throw InputError(std::string(what) + ": latitude " + std::to_string(g.lat_deg) + " is outside [-90, 90] degrees");
  }
}

Eigen::Vector3d EcefFromGeodetic(const Geodetic& g) {
  ValidateGeodetic(g, "geodetic position");
  Eigen::Vector3d ecef;
  GeographicLib::Geocentric::WGS84().Forward(g.lat_deg, g.lon_deg, g.height_m, ecef.x(), ecef.y(), ecef.z());
  return ecef;
}

Geodetic GeodeticFromEcef(const Eigen::Vector3d& ecef_m) {
  Geodetic g;
  GeographicLib::Geocentric::WGS84().Reverse(ecef_m.x(), ecef_m.y(), ecef_m.z(), g.lat_deg, g.lon_deg, g.height_m);
  g.lon_deg = NormalizeDeg180(g.lon_deg);
  return g;
}

struct EnuFrame::Impl {
  GeographicLib::LocalCartesian local;
  Eigen::Vector3d origin_ecef_m;
  Eigen::Matrix3d ecef_from_enu;  // GeographicLib's M at the origin
};

EnuFrame::EnuFrame(const Geodetic& origin) : origin_(origin) {
  ValidateGeodetic(origin, "ENU origin");
  origin_.lon_deg = NormalizeDeg180(origin.lon_deg);
  impl_ = std::make_unique<Impl>(Impl{GeographicLib::LocalCartesian(origin_.lat_deg, origin_.lon_deg, origin_.height_m,
                                                                    GeographicLib::Geocentric::WGS84()),
                                      EcefFromGeodetic(origin_), Eigen::Matrix3d::Identity()});
  // Geocentric::Forward reports M (row-major) with ecef_direction = M * enu_direction at the point.
  // (LocalCartesian's M is a different matrix: the point's ENU in terms of the origin's ENU, which is
  // the identity at the origin.)
  std::vector<double> m(9);
  double x, y, z;
  GeographicLib::Geocentric::WGS84().Forward(origin_.lat_deg, origin_.lon_deg, origin_.height_m, x, y, z, m);
  impl_->ecef_from_enu = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(m.data());
}

EnuFrame::~EnuFrame() = default;
EnuFrame::EnuFrame(const EnuFrame& other) : origin_(other.origin_), impl_(std::make_unique<Impl>(*other.impl_)) {}
EnuFrame& EnuFrame::operator=(const EnuFrame& other) {
  origin_ = other.origin_;
  impl_ = std::make_unique<Impl>(*other.impl_);
  return *this;
}

Eigen::Vector3d EnuFrame::EnuFromGeodetic(const Geodetic& g) const {
  ValidateGeodetic(g, "geodetic position");
  Eigen::Vector3d enu;
  impl_->local.Forward(g.lat_deg, g.lon_deg, g.height_m, enu.x(), enu.y(), enu.z());
  return enu;
}

Geodetic EnuFrame::GeodeticFromEnu(const Eigen::Vector3d& enu_m) const {
  if (!enu_m.allFinite()) throw InputError("ENU position must be finite");
  Geodetic g;
  impl_->local.Reverse(enu_m.x(), enu_m.y(), enu_m.z(), g.lat_deg, g.lon_deg, g.height_m);
  g.lon_deg = NormalizeDeg180(g.lon_deg);
  return g;
}

Eigen::Vector3d EnuFrame::EnuFromEcef(const Eigen::Vector3d& ecef_m) const {
  return impl_->ecef_from_enu.transpose() * (ecef_m - impl_->origin_ecef_m);
}

Eigen::Vector3d EnuFrame::EcefFromEnu(const Eigen::Vector3d& enu_m) const {
  return impl_->origin_ecef_m + impl_->ecef_from_enu * enu_m;
}

Eigen::Matrix3d EnuFrame::enu_from_ecef_rotation() const { return impl_->ecef_from_enu.transpose(); }

Eigen::Matrix3d EnuFrame::LocalLevelFromEnu(const Eigen::Vector3d& enu_m, Geodetic* geodetic) const {
  if (!enu_m.allFinite()) throw InputError("ENU position must be finite");
  // LocalCartesian::Reverse's M (row-major) expresses the point's local ENU axes in this frame's:
  // frame_direction = M * local_direction, so its transpose takes this frame's into the point's.
  std::vector<double> m(9);
  Geodetic g;
  impl_->local.Reverse(enu_m.x(), enu_m.y(), enu_m.z(), g.lat_deg, g.lon_deg, g.height_m, m);
  if (geodetic) *geodetic = Geodetic{g.lat_deg, NormalizeDeg180(g.lon_deg), g.height_m};
  // At the origin itself, exactly the frame's axes (at a pole GeographicLib would name another meridian).
  if (enu_m.isZero(0)) return Eigen::Matrix3d::Identity();
  return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(m.data()).transpose();
}

}  // namespace cinepath
