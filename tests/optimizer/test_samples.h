// A sample and random knots the cost-term tests share: a sample whose planned rates sit near the default
// limits (so that the hinges are active at small changes), and four knots of random changes.
#pragma once

#include <array>
#include <random>
#include <vector>

#include "core/rotation.h"
#include "optimizer/sample_model.h"

namespace cinepath::optimizer::test_samples {

using Knot = std::array<double, kNumChannels>;

inline SampleBase MakeBase() {
  SampleBase b;
  KnotSpline spline(0, 2, 0.5);
  b.knots = spline.At(0.8);
  b.position_enu_m = {1, 2, 10};
  b.world_from_camera = LookAt(Eigen::Vector3d(0.2, 1, -0.3));
  b.camera_from_world = b.world_from_camera.conjugate().toRotationMatrix();
  b.focal_length_mm = 50;
  b.dioptre = 1.0 / 12;
  b.f_number = 4;
  b.pitch_deg = -15;
  b.velocity_m_s = {3, 11.9, 2.9};
  b.acceleration_m_s2 = {4, 3, 0};
  b.jerk_m_s3 = {2, 3, 3};
  b.heading_rate_deg_s = 44;
  b.pitch_rate_deg_s = -89;
  b.focal_rate_mm_s = 19;
  b.aperture_rate_stops_s = 2.9;
  b.has_rates = b.has_jerk = true;
  return b;
}

inline std::vector<Knot> RandomKnots(unsigned seed, double scale) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Knot> knots(4);
  for (auto& k : knots) {
    for (int c = 0; c < kNumChannels; ++c) k[c] = scale * u(rng) * (c < 3 ? 1.0 : 0.05);
  }
  return knots;
}

}  // namespace cinepath::optimizer::test_samples
