#include "preview/sun_position.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "core/error.h"

namespace cinepath::preview {

int64_t ParseUtcTime(const std::string& text, const std::string& what) {
  int year = 0, month = 0, day = 0, hour = 0, minute = 0, second = 0, used = 0;
  const bool with_seconds = std::sscanf(text.c_str(), "%4d-%2d-%2dT%2d:%2d:%2dZ%n", &year, &month, &day, &hour, &minute,
                                        &second, &used) == 6 &&
                            used == int(text.size());
  used = 0;
  const bool without_seconds =
      !with_seconds &&
      std::sscanf(text.c_str(), "%4d-%2d-%2dT%2d:%2dZ%n", &year, &month, &day, &hour, &minute, &used) == 5 &&
      used == int(text.size());
  const std::chrono::year_month_day date{std::chrono::year(year), std::chrono::month(unsigned(month)),
                                         std::chrono::day(unsigned(day))};
  if (!(with_seconds || without_seconds) || !date.ok() || hour > 23 || minute > 59 || second > 60 || hour < 0 ||
      minute < 0 || second < 0) {
    throw InputError(what + ": expected a UTC time YYYY-MM-DDTHH:MM[:SS]Z, got '" + text + "'");
  }
  const int64_t days = std::chrono::sys_days(date).time_since_epoch().count();
  return days * 86400 + hour * 3600 + minute * 60 + second;
}

SunDirection SunPositionAt(const Geodetic& where, int64_t unix_time_s) {
  constexpr double kDeg = M_PI / 180.0;
  // Day of the year and hour, UTC.
  const int64_t days_since_epoch = unix_time_s >= 0 ? unix_time_s / 86400 : (unix_time_s - 86399) / 86400;
  const double hour_utc = double(unix_time_s - days_since_epoch * 86400) / 3600.0;
  const std::chrono::year_month_day date{std::chrono::sys_days(std::chrono::days(days_since_epoch))};
  const std::chrono::sys_days new_year{date.year() / std::chrono::January / 1};
  const double day_of_year = double((std::chrono::sys_days(date) - new_year).count()) + 1.0;  // 1 on January 1st
  const double days_in_year = date.year().is_leap() ? 366.0 : 365.0;
  // Fractional year, equation of time (minutes) and declination (radians).
  const double g = 2.0 * M_PI / days_in_year * (day_of_year - 1.0 + (hour_utc - 12.0) / 24.0);
  const double eqtime = 229.18 * (0.000075 + 0.001868 * std::cos(g) - 0.032077 * std::sin(g) -
                                  0.014615 * std::cos(2 * g) - 0.040849 * std::sin(2 * g));
  const double decl = 0.006918 - 0.399912 * std::cos(g) + 0.070257 * std::sin(g) - 0.006758 * std::cos(2 * g) +
                      0.000907 * std::sin(2 * g) - 0.002697 * std::cos(3 * g) + 0.00148 * std::sin(3 * g);
  // True solar time (minutes) at the longitude, hour angle, zenith and azimuth.
  const double solar_minutes = hour_utc * 60.0 + eqtime + 4.0 * where.lon_deg;
  const double hour_angle = (solar_minutes / 4.0 - 180.0) * kDeg;
  const double lat = where.lat_deg * kDeg;
  const double cos_zenith =
      std::clamp(std::sin(lat) * std::sin(decl) + std::cos(lat) * std::cos(decl) * std::cos(hour_angle), -1.0, 1.0);
  const double zenith = std::acos(cos_zenith);
  SunDirection sun;
  sun.elevation_deg = 90.0 - zenith / kDeg;
  // Azimuth from north, clockwise: east of south in the morning, west in the afternoon.
  const double east = -std::sin(hour_angle) * std::cos(decl);
  const double north = std::cos(lat) * std::sin(decl) - std::sin(lat) * std::cos(decl) * std::cos(hour_angle);
  double azimuth = std::atan2(east, north) / kDeg;
  if (azimuth < 0) azimuth += 360.0;
  sun.azimuth_deg = azimuth;
  return sun;
}

}  // namespace cinepath::preview
