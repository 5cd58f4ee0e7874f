// Easing functions on normalized time u in [0, 1]: value, first and second derivative.
//
// Every easing maps 0 -> 0 and 1 -> 1 and is monotone on [0, 1]. Derivatives at the ends (stated so
// tests can check them):
//   linear            e = u                          e'(0) = 1,     e'(1) = 1
//   ease_in_quad      e = u^2                        e'(0) = 0,     e'(1) = 2
//   ease_out_quad     e = 1 - (1-u)^2                e'(0) = 2,     e'(1) = 0
//   ease_in_out_quad  2u^2 | 1 - 2(1-u)^2            e'(0) = 0,     e'(1) = 0   (C1, e' peak 2)
//   ease_in_cubic     e = u^3                        e'(0) = 0,     e'(1) = 3
//   ease_out_cubic    e = 1 - (1-u)^3                e'(0) = 3,     e'(1) = 0
//   ease_in_out_cubic 4u^3 | 1 - 4(1-u)^3            e'(0) = 0,     e'(1) = 0   (C2 at 0.5, e' peak 3)
//   ease_in_sine      e = 1 - cos(pi u / 2)          e'(0) = 0,     e'(1) = pi/2
//   ease_out_sine     e = sin(pi u / 2)              e'(0) = pi/2,  e'(1) = 0
//   ease_in_out_sine  e = (1 - cos(pi u)) / 2        e'(0) = 0,     e'(1) = 0   (e' peak pi/2)
//   smoothstep        e = 3u^2 - 2u^3                e'(0) = 0,     e'(1) = 0,  e'' = +-6 at the ends
//   smootherstep      e = 6u^5 - 15u^4 + 10u^3       e', e'' = 0 at both ends (e' peak 15/8)
// Inputs outside [0, 1] are clamped (the value holds at 0 or 1 and the derivatives are 0 there).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cinepath {

enum class Easing {
  kLinear,
  kEaseInQuad,
  kEaseOutQuad,
  kEaseInOutQuad,
  kEaseInCubic,
  kEaseOutCubic,
  kEaseInOutCubic,
  kEaseInSine,
  kEaseOutSine,
  kEaseInOutSine,
  kSmoothstep,
  kSmootherstep,
};

double Ease(Easing e, double u);
double EaseDerivative(Easing e, double u);        // d e / d u
double EaseSecondDerivative(Easing e, double u);  // d^2 e / d u^2

// File names: "linear", "ease_in_quad", ..., "smoothstep", "smootherstep".
std::string_view EasingName(Easing e);
std::optional<Easing> EasingFromName(std::string_view name);
const std::vector<Easing>& AllEasings();

}  // namespace cinepath
