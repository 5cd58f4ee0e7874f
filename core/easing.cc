#include "core/easing.h"

#include <cmath>

#include "core/angles.h"

namespace cinepath {
namespace {

struct Values {
  double e, d1, d2;
};

Values Evaluate(Easing e, double u) {
  const double v = 1.0 - u;
  switch (e) {
    case Easing::kLinear: return {u, 1.0, 0.0};
    case Easing::kEaseInQuad: return {u * u, 2.0 * u, 2.0};
    case Easing::kEaseOutQuad: return {1.0 - v * v, 2.0 * v, -2.0};
    case Easing::kEaseInOutQuad:
      if (u < 0.5) return {2.0 * u * u, 4.0 * u, 4.0};
      return {1.0 - 2.0 * v * v, 4.0 * v, -4.0};
    case Easing::kEaseInCubic: return {u * u * u, 3.0 * u * u, 6.0 * u};
    case Easing::kEaseOutCubic: return {1.0 - v * v * v, 3.0 * v * v, -6.0 * v};
    case Easing::kEaseInOutCubic:
      if (u < 0.5) return {4.0 * u * u * u, 12.0 * u * u, 24.0 * u};
      return {1.0 - 4.0 * v * v * v, 12.0 * v * v, -24.0 * v};
    case Easing::kEaseInSine:
      return {1.0 - std::cos(kPi * u / 2.0), kPi / 2.0 * std::sin(kPi * u / 2.0),
              kPi * kPi / 4.0 * std::cos(kPi * u / 2.0)};
    case Easing::kEaseOutSine:
      return {std::sin(kPi * u / 2.0), kPi / 2.0 * std::cos(kPi * u / 2.0), -kPi * kPi / 4.0 * std::sin(kPi * u / 2.0)};
    case Easing::kEaseInOutSine:
      return {(1.0 - std::cos(kPi * u)) / 2.0, kPi / 2.0 * std::sin(kPi * u), kPi * kPi / 2.0 * std::cos(kPi * u)};
    case Easing::kSmoothstep: return {u * u * (3.0 - 2.0 * u), 6.0 * u * v, 6.0 - 12.0 * u};
    case Easing::kSmootherstep:
      return {u * u * u * (u * (6.0 * u - 15.0) + 10.0), 30.0 * u * u * v * v, 60.0 * u * v * (1.0 - 2.0 * u)};
  }
  return {u, 1.0, 0.0};
}

struct Entry {
  Easing e;
  std::string_view name;
};
constexpr Entry kNames[] = {
    {Easing::kLinear, "linear"},
    {Easing::kEaseInQuad, "ease_in_quad"},
    {Easing::kEaseOutQuad, "ease_out_quad"},
    {Easing::kEaseInOutQuad, "ease_in_out_quad"},
    {Easing::kEaseInCubic, "ease_in_cubic"},
    {Easing::kEaseOutCubic, "ease_out_cubic"},
    {Easing::kEaseInOutCubic, "ease_in_out_cubic"},
    {Easing::kEaseInSine, "ease_in_sine"},
    {Easing::kEaseOutSine, "ease_out_sine"},
    {Easing::kEaseInOutSine, "ease_in_out_sine"},
    {Easing::kSmoothstep, "smoothstep"},
    {Easing::kSmootherstep, "smootherstep"},
};

}  // namespace

double Ease(Easing e, double u) {
  if (!(u > 0.0)) return 0.0;  // also maps NaN to 0
  if (u >= 1.0) return 1.0;
  return Evaluate(e, u).e;
}

double EaseDerivative(Easing e, double u) {
  if (u < 0.0 || u > 1.0 || std::isnan(u)) return 0.0;
  return Evaluate(e, u).d1;
}

double EaseSecondDerivative(Easing e, double u) {
  if (u < 0.0 || u > 1.0 || std::isnan(u)) return 0.0;
  return Evaluate(e, u).d2;
}

std::string_view EasingName(Easing e) {
  for (const auto& entry : kNames) {
    if (entry.e == e) return entry.name;
  }
  return "linear";
}

std::optional<Easing> EasingFromName(std::string_view name) {
  for (const auto& entry : kNames) {
    if (entry.name == name) return entry.e;
  }
  return std::nullopt;
}

const std::vector<Easing>& AllEasings() {
  static const std::vector<Easing> all = [] {
    std::vector<Easing> v;
    for (const auto& entry : kNames) v.push_back(entry.e);
    return v;
  }();
  return all;
}

}  // namespace cinepath
