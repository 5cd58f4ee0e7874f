// Where the sun stands for a place and a moment: the azimuth and elevation `render --shading sun --sun-time`
// lights the scene from, so that a preview shows the shadows of the shooting day.
//
// The general solar position equations of NOAA's Global Monitoring Laboratory (docs/render.md, "Sun"):
// from the fractional year g (radians), the equation of time (minutes) and the declination (radians) as
// short Fourier series in g, the true solar time at the longitude, the hour angle, then the zenith and
// azimuth angles. About 0.1 deg of elevation away from sunrise and sunset (no refraction), which is far
// below what a shadow's direction shows.
#pragma once

#include <cstdint>
#include <string>

#include "core/geodesy.h"
#include "preview/render_options.h"

namespace cinepath::preview {

// Seconds since 1970-01-01T00:00:00Z from "YYYY-MM-DDTHH:MM[:SS]Z" (UTC, as --sun-time takes it);
// InputError naming `what` for anything else.
int64_t ParseUtcTime(const std::string& text, const std::string& what);

// The sun's compass azimuth (clockwise from north) and elevation above the horizon, in degrees.
SunDirection SunPositionAt(const Geodetic& where, int64_t unix_time_s);

}  // namespace cinepath::preview
