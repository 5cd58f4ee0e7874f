#include "shots/actor.h"

#include <algorithm>
#include <cmath>

#include "core/angles.h"
#include "core/error.h"
#include "core/geoid.h"

namespace cinepath::shots {

Actor::Actor(std::string name, double height_m, double heading_deg, PathSpline path)
    : name_(std::move(name)), height_m_(height_m), heading_deg_(heading_deg), path_(std::move(path)) {}

Actor::Actor(std::string name, double height_m, double heading_deg, PathSpline path, const Ground* ground,
             double above_ground_m)
    : Actor(std::move(name), height_m, heading_deg, std::move(path)) {
  ground_ = ground;
  above_ground_m_ = above_ground_m;
  // The smoothed height CameraBaseAt reads: at steps of 0.5 s (longer past 20,000 steps) over the keys'
  // span, the ground-kept height averaged with triangular weights over the step on either side (17 points),
  // then a natural cubic spline through those values (C2: the camera's vertical jerk stays finite). A
  // walker's half second is under a metre: the trend of the ground is kept, its centimetre noise is not.
  const std::vector<double>& times = path_.times();
  if (times.size() < 2 || !(times.back() > times.front())) return;
  constexpr double kStepS = 0.5;
  const double span_s = times.back() - times.front();
  // At most 20,000 steps: over a span longer than ~2.8 h of keys the steps grow (and smooth more).
  const int steps = static_cast<int>(std::min(std::ceil(span_s / kStepS), 20000.0));
  const double step_s = span_s / steps;
  std::vector<double> grid_s;
  std::vector<Eigen::Vector3d> heights;
  for (int j = 0; j <= steps; ++j) {
    const double t = times.front() + j * step_s;
    double sum = 0, weights = 0;
    for (int k = -8; k <= 8; ++k) {
      const double w = 9 - std::abs(k);
      sum += w * PositionAt(t + k * step_s / 8).z();
      weights += w;
    }
    grid_s.push_back(t);
    heights.emplace_back(0, 0, sum / weights);
  }
  smooth_base_up_m_.emplace(std::move(grid_s), std::move(heights), PathInterpolation::kCubicBSpline);
}

Eigen::Vector3d Actor::CameraBaseAt(double time_s) const {
  if (!smooth_base_up_m_) return PositionAt(time_s);
  Eigen::Vector3d p = path_.Position(time_s);  // PositionAt's east and north, without its ground ray
  p.z() = smooth_base_up_m_->Position(time_s).z();
  return p;
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
  if (std::hypot(v.x(), v.y()) > 0.05) return HeadingDegFromEnuYaw(std::atan2(v.y(), v.x()));
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
  const std::optional<double> above =
      parent.Has("above_ground_m") ? std::optional(parent["above_ground_m"].AsDouble()) : std::nullopt;
  if (has_enu) {
    const JsonField f = parent[enu_key];
    if (f.IsArray() && f.size() == 2) {
      const double e = f.At(0).AsDouble(), n = f.At(1).AsDouble();
      return {e, n, GroundUpM(f, context.ground, e, n) + above.value_or(0.0)};
    }
    if (!f.IsArray() || f.size() != 3) f.Fail("expected [east_m, north_m, up_m], or [east_m, north_m] on the ground");
    if (above) parent["above_ground_m"].Fail("give it with [east_m, north_m], not with an up value");
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
    }
  } else {
    times.push_back(0.0);
    points.push_back(ParsePosition(f, "position_enu_m", "position", context));
  }
  PathSpline path(std::move(times), std::move(points), kind);
  if (f.BoolOr("on_ground", false)) {
    if (!context.ground) f["on_ground"].Fail("needs the scene's mesh (`scene_mesh`)");
    return Actor(name, height_m, heading_deg, std::move(path), context.ground, f.DoubleOr("above_ground_m", 0.0));
  }
  if (!f.Has("on_ground") && f.Has("keyframes") && keys_on_ground && path.times().size() > 1) {
    return Actor(name, height_m, heading_deg, std::move(path), context.ground, *keys_above_ground_m);
  }
  return Actor(name, height_m, heading_deg, std::move(path));
}

}  // namespace cinepath::shots
