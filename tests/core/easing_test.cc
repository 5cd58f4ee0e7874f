#include "core/easing.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/angles.h"

namespace cinepath {
namespace {

struct EndSlopes {
  Easing e;
  double d0, d1;
};

TEST(Easing, EndpointsAndStatedEndDerivatives) {
  const EndSlopes cases[] = {
      {Easing::kLinear, 1, 1},         {Easing::kEaseInQuad, 0, 2},       {Easing::kEaseOutQuad, 2, 0},
      {Easing::kEaseInOutQuad, 0, 0},  {Easing::kEaseInCubic, 0, 3},      {Easing::kEaseOutCubic, 3, 0},
      {Easing::kEaseInOutCubic, 0, 0}, {Easing::kEaseInSine, 0, kPi / 2}, {Easing::kEaseOutSine, kPi / 2, 0},
      {Easing::kEaseInOutSine, 0, 0},  {Easing::kSmoothstep, 0, 0},       {Easing::kSmootherstep, 0, 0},
  };
  ASSERT_EQ(std::size(cases), AllEasings().size());
  for (const auto& c : cases) {
    SCOPED_TRACE(std::string(EasingName(c.e)));
    EXPECT_DOUBLE_EQ(Ease(c.e, 0.0), 0.0);
    EXPECT_DOUBLE_EQ(Ease(c.e, 1.0), 1.0);
    EXPECT_NEAR(EaseDerivative(c.e, 0.0), c.d0, 1e-12);
    EXPECT_NEAR(EaseDerivative(c.e, 1.0), c.d1, 1e-12);
  }
}

TEST(Easing, KnownMidpointValues) {
  EXPECT_DOUBLE_EQ(Ease(Easing::kLinear, 0.25), 0.25);
  EXPECT_DOUBLE_EQ(Ease(Easing::kEaseInQuad, 0.5), 0.25);
  EXPECT_DOUBLE_EQ(Ease(Easing::kEaseOutQuad, 0.5), 0.75);
  EXPECT_DOUBLE_EQ(Ease(Easing::kEaseInCubic, 0.5), 0.125);
  EXPECT_DOUBLE_EQ(Ease(Easing::kSmoothstep, 0.25), 0.15625);
  EXPECT_DOUBLE_EQ(Ease(Easing::kSmootherstep, 0.25), 0.103515625);
  EXPECT_NEAR(Ease(Easing::kEaseInOutSine, 0.5), 0.5, 1e-15);
  EXPECT_NEAR(Ease(Easing::kEaseInSine, 0.5), 1.0 - std::sqrt(0.5), 1e-15);
  for (Easing e : {Easing::kEaseInOutQuad, Easing::kEaseInOutCubic, Easing::kSmoothstep, Easing::kSmootherstep,
                   Easing::kEaseInOutSine}) {
    EXPECT_NEAR(Ease(e, 0.5), 0.5, 1e-15) << EasingName(e);
  }
  // Peak slopes as stated in the header.
  EXPECT_DOUBLE_EQ(EaseDerivative(Easing::kSmootherstep, 0.5), 15.0 / 8.0);
  EXPECT_DOUBLE_EQ(EaseDerivative(Easing::kSmoothstep, 0.5), 1.5);
  EXPECT_DOUBLE_EQ(EaseDerivative(Easing::kEaseInOutCubic, 0.5), 3.0);
  // smootherstep is C2 at the ends.
  EXPECT_DOUBLE_EQ(EaseSecondDerivative(Easing::kSmootherstep, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(EaseSecondDerivative(Easing::kSmootherstep, 1.0), 0.0);
  EXPECT_DOUBLE_EQ(EaseSecondDerivative(Easing::kSmoothstep, 0.0), 6.0);
}

TEST(Easing, DerivativesMatchFiniteDifferences) {
  const double h = 1e-6;
  for (Easing e : AllEasings()) {
    for (double u = 0.01; u < 0.995; u += 0.0137) {
      if (std::fabs(u - 0.5) < 2 * h) continue;  // piecewise definitions switch at 0.5
      const double fd1 = (Ease(e, u + h) - Ease(e, u - h)) / (2 * h);
      const double fd2 = (EaseDerivative(e, u + h) - EaseDerivative(e, u - h)) / (2 * h);
      EXPECT_NEAR(EaseDerivative(e, u), fd1, 1e-7) << EasingName(e) << " u=" << u;
      EXPECT_NEAR(EaseSecondDerivative(e, u), fd2, 1e-5) << EasingName(e) << " u=" << u;
    }
  }
}

TEST(Easing, MonotoneAndClamped) {
  for (Easing e : AllEasings()) {
    double prev = 0;
    for (int i = 1; i <= 1000; ++i) {
      const double v = Ease(e, i / 1000.0);
      EXPECT_GE(v, prev) << EasingName(e);
      prev = v;
    }
    EXPECT_EQ(Ease(e, -3.0), 0.0);
    EXPECT_EQ(Ease(e, 7.0), 1.0);
    EXPECT_EQ(EaseDerivative(e, 1.5), 0.0);
    EXPECT_EQ(Ease(e, std::nan("")), 0.0);
  }
}

TEST(Easing, NamesRoundTrip) {
  for (Easing e : AllEasings()) EXPECT_EQ(EasingFromName(EasingName(e)), e);
  EXPECT_FALSE(EasingFromName("ease_in_quartic").has_value());
}

}  // namespace
}  // namespace cinepath
