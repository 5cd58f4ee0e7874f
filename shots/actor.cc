#include "shots/actor.h"

#include <algorithm>
#include <cmath>

#include "core/angles.h"
#include "core/error.h"
#include "core/geoid.h"

namespace cinepath::shots {

Actor::Actor(std::string name, double height_m, double heading_deg, PathSpline path)
    : name_(std::move(name)), height_m_(height_m), heading_deg_(heading_deg), path_(std::move(path)) {
  SmoothForCameras();
}

Actor::Actor(std::string name, double height_m, double heading_deg, PathSpline path, const Ground* ground,
             double above_ground_m)
    : name_(std::move(name)), height_m_(height_m), heading_deg_(heading_deg), path_(std::move(path)) {
  ground_ = ground;
  above_ground_m_ = above_ground_m;
  SmoothForCameras();
}

// What CameraBaseAt and CameraTravelHeadingDegAt read: at steps of 0.5 s (longer past 20,000 steps) over the keys'
// span, the actor's position (PositionAt: on the ground for a ground-kept one) and its velocity averaged with
// triangular weights over a second on either side (33 points), then natural cubic splines through those positions
// and through the directions of those velocities (C2: a camera's jerk stays finite). A path through keys is C0
// (linear) or C1 (Catmull-Rom) at its keys, and a ground-kept height copies every kink of the mesh; a camera
// placed rigidly from it copied each into velocity or acceleration steps. A walker's second is a metre or two:
// its trend is kept, its kinks are not. For the averages the path runs on past its end keys at its end velocities,
// so a shot that starts as its actor is keyed to be moving starts exactly with it; outside the keys' span the
// splines hold their ends, as the actor does. A shot that follows the actor past its last key (where it stops
// dead) has the planner ease the camera into the stop instead (EaseCameraIntoTheStop): the averages see the
// actor standing after the key, and the grid runs on for twice their reach. A cubic B-spline path not kept on
// the ground is C2 already and is its own camera base; its heading is still smoothed (the direction of a C2
// path turns at a rate whose second derivative steps at its keys).
void Actor::SmoothForCameras() {
  const std::vector<double>& times = path_.times();
  if (times.size() < 2 || !(times.back() > times.front())) return;
  const Eigen::Vector3d first = PositionAt(times.front());
  bool moves = false;
  for (double t : times) moves = moves || (PositionAt(t) - first).norm() > 1e-9;
  if (!moves) return;
  constexpr double kStepS = 0.5, kWindowS = 1.0;  // the grid's step; the average's reach on either side
  constexpr int kHalfPoints = 16;
  // Easing into the stop, the grid runs on past the last key for twice the averages' reach: the base is at rest
  // from one reach on, and the spline through the rest flattens before it holds its end.
  const double from_s = times.front(), last_s = times.back();
  const double span_s = last_s + (ease_into_stop_ ? 2 * kWindowS : 0.0) - from_s;
  // At most 20,000 steps: over a span longer than ~2.8 h of keys the steps grow (and smooth more).
  const int steps = static_cast<int>(std::min(std::ceil(span_s / kStepS), 20000.0));
  const double step_s = span_s / steps;
  const Eigen::Vector3d facing(std::sin(RadFromDeg(heading_deg_)), std::cos(RadFromDeg(heading_deg_)), 0.0);
  std::vector<double> grid_s;
  std::vector<Eigen::Vector3d> positions, directions;
  for (int j = 0; j <= steps; ++j) {
    const double t = from_s + j * step_s;
    Eigen::Vector3d position = Eigen::Vector3d::Zero(), velocity = Eigen::Vector3d::Zero();
    double weights = 0;
    for (int k = -kHalfPoints; k <= kHalfPoints; ++k) {
      const double w = kHalfPoints + 1 - std::abs(k), at = t + k * kWindowS / kHalfPoints;
      // Past an end key the path runs on at its end velocity (horizontally), so that a path at a steady velocity
      // is its own average up to its ends: a shot that starts as its actor is keyed to be moving starts with it.
      const double key_s = std::clamp(at, times.front(), last_s);
      Eigen::Vector3d v = VelocityAt(key_s);
      v.z() = 0;
      // Easing into the stop, the actor stands at its last key after it (for the position; the direction of
      // travel still runs on, so that a chase stays behind where the actor was going).
      const bool standing = ease_into_stop_ && at > last_s;
      position += w * (standing ? PositionAt(last_s) : Eigen::Vector3d(PositionAt(key_s) + (at - key_s) * v));
      velocity += w * v;
      weights += w;
    }
    grid_s.push_back(t);
    positions.push_back(position / weights);
    // The direction of travel; at rest the stated facing, and in between (under 0.05 m/s) a blend of the two,
    // so that the direction never jumps when the actor starts or stops.
    velocity /= weights;
    velocity.z() = 0;
    const double still = std::max(0.0, 1.0 - velocity.norm() / kMovingMS);
    Eigen::Vector3d direction = velocity + kMovingMS * still * facing;
    direction = direction.norm() > 1e-12 ? Eigen::Vector3d(direction.normalized()) : facing;
    directions.push_back(direction);
  }
  camera_travel_.emplace(grid_s, std::move(directions), PathInterpolation::kCubicBSpline);
  // A cubic B-spline path is C2 already: its camera base is the path itself, unless the ground's kinks are in it.
  if (path_.kind() != PathInterpolation::kCubicBSpline || ground_ || ease_into_stop_)
    camera_base_.emplace(std::move(grid_s), std::move(positions), PathInterpolation::kCubicBSpline);
}

void Actor::EaseCameraIntoTheStop() {
  if (ease_into_stop_) return;
  ease_into_stop_ = true;
  SmoothForCameras();
}

double Actor::SpeedAtLastKeyMS() const {
  const std::vector<double>& times = path_.times();
  if (times.size() < 2) return 0.0;
  const double last_s = times.back();
  return path_.Velocity(last_s - 1e-6 * std::max(1.0, last_s - times.front())).norm();  // from the segment before
}

Eigen::Vector3d Actor::CameraBaseAt(double time_s) const {
  return camera_base_ ? camera_base_->Position(time_s) : PositionAt(time_s);
}

double Actor::CameraTravelHeadingDegAt(double time_s) const {
  if (!camera_travel_) return TravelHeadingDegAt(time_s);
  const Eigen::Vector3d d = camera_travel_->Position(time_s);
  if (std::hypot(d.x(), d.y()) < 1e-6) return TravelHeadingDegAt(time_s);
  return HeadingDegFromEnuYaw(std::atan2(d.y(), d.x()));
}

Eigen::Vector3d Actor::PositionAt(double time_s) const {
  Eigen::Vector3d p = path_.Position(time_s);
  if (!ground_) return p;
  // The highest surface below the path point, searched from an actor's height above it (or 2 m), so
  // that ground rising between two keys is followed; where nothing lies below, the highest surface.
  const double from = p.z() - above_ground_m_ + std::max(height_m_, 2.0);
  std::optional<double> g = ground_->SurfaceUpM(p.x(), p.y(), from);
  if (!g) g = ground_->SurfaceUpM(p.x(), p.y());
  if (g) p.z() = *g + above_ground_m_;
  return p;
}

Eigen::Vector3d Actor::AimPointAt(double time_s) const {
  return PositionAt(time_s) + Eigen::Vector3d(0, 0, 0.5 * height_m_);
}

double Actor::TravelHeadingDegAt(double time_s) const {
  // Before the first key and after the last the actor holds still: keep its heading of travel there.
  const double t = std::clamp(time_s, path_.times().front(), path_.times().back());
  const Eigen::Vector3d v = VelocityAt(t);
  if (std::hypot(v.x(), v.y()) > kMovingMS) return HeadingDegFromEnuYaw(std::atan2(v.y(), v.x()));
  return NormalizeDeg360(heading_deg_);
}

namespace {

double GroundUpM(const JsonField& where, const Ground* ground, double east_m, double north_m) {
  if (!ground) where.Fail("a height above the ground needs the scene's mesh (`scene_mesh`)");
  const auto up = ground->SurfaceUpM(east_m, north_m);
  if (!up) where.Fail("no ground at this position: it lies outside " + ground->source());
  return *up;
}

// The height above the ground a position gives, when it gives one: [e, n] (with "above_ground_m"
// beside it, default 0) or {lat, lon, "above_ground_m"}; none for an absolute height.
std::optional<double> GroundOffsetM(const JsonField& parent, const char* enu_key, const char* geo_key) {
  if (auto f = parent.Find(enu_key)) {
    if (!f->IsArray() || f->size() != 2) return std::nullopt;
    return parent.Has("above_ground_m") ? parent["above_ground_m"].AsDouble() : 0.0;
  }
  if (auto g = parent.Find(geo_key)) {
    if (g->Has("above_ground_m")) return (*g)["above_ground_m"].AsDouble();
  }
  return std::nullopt;
}

}  // namespace

Eigen::Vector3d ParsePosition(const JsonField& parent, const char* enu_key, const char* geo_key,
                              const PositionContext& context) {
  const bool has_enu = parent.Has(enu_key);
  const bool has_geo = parent.Has(geo_key);
  if (has_enu == has_geo) {
    parent.Fail(std::string("give exactly one of \"") + enu_key + "\" (ENU metres) or \"" + geo_key +
                "\" (lat/lon/height)");
  }
  const bool has_above = parent.Has("above_ground_m");
  const double above_m = has_above ? parent["above_ground_m"].AsDouble() : 0.0;
  if (has_enu) {
    const JsonField f = parent[enu_key];
    if (f.IsArray() && f.size() == 2) {
      const double e = f.At(0).AsDouble(), n = f.At(1).AsDouble();
      return {e, n, GroundUpM(f, context.ground, e, n) + above_m};
    }
    if (!f.IsArray() || f.size() != 3) f.Fail("expected [east_m, north_m, up_m], or [east_m, north_m] on the ground");
    if (has_above) parent["above_ground_m"].Fail("give it with [east_m, north_m], not with an up value");
    return {f.At(0).AsDouble(), f.At(1).AsDouble(), f.At(2).AsDouble()};
  }
  const JsonField g = parent[geo_key];
  g.RejectUnknownKeys({"lat_deg", "lon_deg", "height_m", "amsl_m", "above_ground_m"});
  if (!context.frame) g.Fail("a lat/lon position needs a WGS84 origin (shots.json \"origin\" or `scene_origin`)");
  Geodetic geo;
  geo.lat_deg = g["lat_deg"].AsDouble();
  geo.lon_deg = g["lon_deg"].AsDouble();
  if (geo.lat_deg < -90 || geo.lat_deg > 90) g["lat_deg"].Fail("must be in [-90, 90]");
  if (geo.lon_deg < -180 || geo.lon_deg > 180) g["lon_deg"].Fail("must be in [-180, 180]");
  const int heights = g.Has("height_m") + g.Has("amsl_m") + g.Has("above_ground_m");
  if (heights != 1) {
    g.Fail(
        "give exactly one of \"height_m\" (WGS84 ellipsoidal), \"amsl_m\" (above mean sea level, EGM96) or "
        "\"above_ground_m\" (above the scene's mesh)");
  }
  if (g.Has("above_ground_m")) {
    geo.height_m = context.frame->origin().height_m;
    Eigen::Vector3d p = context.frame->EnuFromGeodetic(geo);
    p.z() = GroundUpM(g, context.ground, p.x(), p.y()) + g["above_ground_m"].AsDouble();
    return p;
  }
  geo.height_m = g.Has("height_m")
                     ? g["height_m"].AsDouble()
                     : Egm96Geoid::Default().EllipsoidalFromAmslM(geo.lat_deg, geo.lon_deg, g["amsl_m"].AsDouble());
  return context.frame->EnuFromGeodetic(geo);
}

Actor ParseActor(const JsonField& f, const PositionContext& context) {
  f.RejectUnknownKeys({"name", "height_m", "heading_deg", "position_enu_m", "position", "above_ground_m", "keyframes",
                       "interpolation", "on_ground"});
  const std::string name = f["name"].AsString();
  if (name.empty()) f["name"].Fail("must not be empty");
  const double height_m = f.Has("height_m") ? f["height_m"].AsPositive() : 1.8;
  const double heading_deg = f.DoubleOr("heading_deg", 0.0);
  PathInterpolation kind = PathInterpolation::kCatmullRom;
  if (auto interp = f.Find("interpolation")) {
    auto k = PathInterpolationFromName(interp->AsString());
    if (!k) interp->Fail("expected \"linear\", \"catmull_rom\" or \"cubic_bspline\"");
    kind = *k;
  }
  std::vector<double> times;
  std::vector<Eigen::Vector3d> points;
  // Whether every key stands at one height above the ground: such an actor stays on the ground between
  // its keys too (a path spline through points on uneven ground floats over the ground between them).
  std::optional<double> keys_above_ground_m;
  bool keys_on_ground = true;
  std::vector<Actor::AbsoluteHeightKey> absolute;
  // The field a key's position came from, when its height is absolute.
  const auto note_absolute = [&](const JsonField& parent, size_t key) {
    if (GroundOffsetM(parent, "position_enu_m", "position")) return;
    const JsonField given = parent.Has("position_enu_m") ? parent["position_enu_m"] : parent["position"];
    absolute.push_back({key, given.Where()});
  };
  if (auto keys = f.Find("keyframes")) {
    if (f.Has("position_enu_m") || f.Has("position")) f.Fail("give either a position or keyframes, not both");
    if (keys->size() == 0) keys->Fail("must hold at least one keyframe");
    for (const auto& k : keys->Elements()) {
      k.RejectUnknownKeys({"time_s", "position_enu_m", "position", "above_ground_m"});
      const double t = k["time_s"].AsDouble();
      if (!times.empty() && !(t >= times.back() + 1e-3))
        k["time_s"].Fail("keyframe times must increase (by 1 ms or more)");
      times.push_back(t);
      points.push_back(ParsePosition(k, "position_enu_m", "position", context));
      const std::optional<double> above = GroundOffsetM(k, "position_enu_m", "position");
      if (!above || (keys_above_ground_m && *keys_above_ground_m != *above)) keys_on_ground = false;
      keys_above_ground_m = above;
      note_absolute(k, times.size() - 1);
    }
  } else {
    times.push_back(0.0);
    points.push_back(ParsePosition(f, "position_enu_m", "position", context));
    note_absolute(f, 0);
  }
  PathSpline path(std::move(times), std::move(points), kind);
  if (f.BoolOr("on_ground", false)) {
    if (!context.ground) f["on_ground"].Fail("needs the scene's mesh (`scene_mesh`)");
    return Actor(name, height_m, heading_deg, std::move(path), context.ground, f.DoubleOr("above_ground_m", 0.0));
  }
  if (!f.Has("on_ground") && f.Has("keyframes") && keys_on_ground && path.times().size() > 1) {
    return Actor(name, height_m, heading_deg, std::move(path), context.ground, *keys_above_ground_m);
  }
  Actor actor(name, height_m, heading_deg, std::move(path));
  actor.SetAbsoluteHeightKeys(std::move(absolute));
  return actor;
}

}  // namespace cinepath::shots
