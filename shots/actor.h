// Actors: the named subjects shots frame. Static (one position) or moving along timed keyframes.
//
// An actor's position is its base (feet, wheels, ground contact) in ENU metres; `height_m` is its
// size, used for framing (the aim point is the base raised by half the height). Keyframe times are
// plan time (seconds from the start of the first shot); before the first and after the last key the
// actor holds still.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/geodesy.h"
#include "core/json.h"
#include "shots/spline.h"

namespace cinepath::shots {

class Actor {
 public:
  Actor(std::string name, double height_m, double heading_deg, PathSpline path);

  const std::string& name() const { return name_; }
  double height_m() const { return height_m_; }

  Eigen::Vector3d PositionAt(double time_s) const { return path_.Position(time_s); }
  Eigen::Vector3d VelocityAt(double time_s) const { return path_.Velocity(time_s); }
  // Where cameras aim: the base raised by half the actor's height.
  Eigen::Vector3d AimPointAt(double time_s) const;
  // Compass heading of travel (degrees) when moving faster than 0.05 m/s horizontally, else the
  // actor's stated facing heading. Outside the keyframe range the heading at the nearest end holds.
  double TravelHeadingDegAt(double time_s) const;

  const PathSpline& path() const { return path_; }

 private:
  std::string name_;
  double height_m_;
  double heading_deg_;
  PathSpline path_;
};

// Parses one element of shots.json "actors" (docs/plan.md). `frame` converts lat/lon/height
// positions; without it such positions are an InputError naming the field.
Actor ParseActor(const JsonField& field, const EnuFrame* frame);

// Reads a position: [e, n, u] ENU metres under `enu_key`, or {"lat_deg", "lon_deg", and
// "height_m" (WGS84 ellipsoidal) or "amsl_m" (EGM96, core/geoid.h)} under `geo_key` (needs
// `frame`). Exactly one must be present.
Eigen::Vector3d ParsePosition(const JsonField& parent, const char* enu_key, const char* geo_key, const EnuFrame* frame);

}  // namespace cinepath::shots
