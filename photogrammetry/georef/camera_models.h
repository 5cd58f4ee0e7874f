// COLMAP 3.8 camera models: ids, names, parameter counts and the projection from normalized camera
// coordinates (u, v) = (X/Z, Y/Z) to pixels, templated so Ceres can differentiate it.
//
// Models and parameter order (colmap@3.8:src/base/camera_models.h):
//   id name                   #  params
//   0  SIMPLE_PINHOLE         3  f, cx, cy
//   1  PINHOLE                4  fx, fy, cx, cy
//   2  SIMPLE_RADIAL          4  f, cx, cy, k
//   3  RADIAL                 5  f, cx, cy, k1, k2
//   4  OPENCV                 8  fx, fy, cx, cy, k1, k2, p1, p2
//   5  OPENCV_FISHEYE         8  fx, fy, cx, cy, k1, k2, k3, k4
//   6  FULL_OPENCV           12  fx, fy, cx, cy, k1, k2, p1, p2, k3, k4, k5, k6
//   7  FOV                    5  fx, fy, cx, cy, omega
//   8  SIMPLE_RADIAL_FISHEYE  4  f, cx, cy, k
//   9  RADIAL_FISHEYE         5  f, cx, cy, k1, k2
//   10 THIN_PRISM_FISHEYE    12  fx, fy, cx, cy, k1, k2, p1, p2, k3, k4, sx1, sy1
// Newer COLMAP ids (11..17) are not supported: readers reject them as unknown.
//
// Pixel convention (COLMAP's): the upper-left image corner is (0, 0), the centre of the upper-left
// pixel is (0.5, 0.5). Projection: distort (u, v) -> (u', v'), then x = fx u' + cx, y = fy v' + cy.
#pragma once

#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace cinepath::photogrammetry {

enum class CameraModelId : int {
  kSimplePinhole = 0,
  kPinhole = 1,
  kSimpleRadial = 2,
  kRadial = 3,
  kOpenCv = 4,
  kOpenCvFisheye = 5,
  kFullOpenCv = 6,
  kFov = 7,
  kSimpleRadialFisheye = 8,
  kRadialFisheye = 9,
  kThinPrismFisheye = 10,
};
inline constexpr int kNumCameraModels = 11;

bool IsKnownCameraModel(int model_id);
// Number of parameters of a known model; 0 for an unknown id.
int CameraModelNumParams(int model_id);
// "SIMPLE_RADIAL", ...; empty for an unknown id.
std::string_view CameraModelName(int model_id);
std::optional<int> CameraModelIdFromName(std::string_view name);
// True for the models with a single focal length f (SIMPLE_*, RADIAL, *_FISHEYE with one f).
bool CameraModelHasSingleFocal(int model_id);
// Parameter indices of the focal length(s), the principal point, and the distortion terms.
std::vector<int> CameraModelFocalIndices(int model_id);
std::vector<int> CameraModelPrincipalPointIndices(int model_id);
std::vector<int> CameraModelExtraIndices(int model_id);

namespace camera_models_internal {

// Equidistant fisheye angle for a radius r = |(u, v)|: returns theta/r (1 near r = 0).
template <typename T>
T FisheyeScale(const T& u, const T& v) {
  using std::atan;
  using std::sqrt;
  const T r2 = u * u + v * v;
  if (r2 > T(std::numeric_limits<double>::epsilon())) {
    const T r = sqrt(r2);
    return atan(r) / r;
  }
  return T(1);
}

}  // namespace camera_models_internal

// Applies the model's distortion to normalized coordinates (u, v), writing (u', v').
// `params` holds the model's full parameter vector. Returns false for an unknown model.
template <typename T>
bool DistortNormalized(int model_id, const T* params, const T& u, const T& v, T* ud, T* vd) {
  using camera_models_internal::FisheyeScale;
  using std::atan;
  using std::sqrt;
  using std::tan;
  switch (static_cast<CameraModelId>(model_id)) {
    case CameraModelId::kSimplePinhole:
    case CameraModelId::kPinhole:
      *ud = u;
      *vd = v;
      return true;
    case CameraModelId::kSimpleRadial: {
      const T& k = params[3];
      const T radial = k * (u * u + v * v);
      *ud = u + u * radial;
      *vd = v + v * radial;
      return true;
    }
    case CameraModelId::kRadial: {
      const T& k1 = params[3];
      const T& k2 = params[4];
      const T r2 = u * u + v * v;
      const T radial = k1 * r2 + k2 * r2 * r2;
      *ud = u + u * radial;
      *vd = v + v * radial;
      return true;
    }
    case CameraModelId::kOpenCv: {
      const T& k1 = params[4];
      const T& k2 = params[5];
      const T& p1 = params[6];
      const T& p2 = params[7];
      const T u2 = u * u, v2 = v * v, uv = u * v, r2 = u2 + v2;
      const T radial = k1 * r2 + k2 * r2 * r2;
      *ud = u + u * radial + T(2) * p1 * uv + p2 * (r2 + T(2) * u2);
      *vd = v + v * radial + T(2) * p2 * uv + p1 * (r2 + T(2) * v2);
      return true;
    }
    case CameraModelId::kOpenCvFisheye: {
      const T& k1 = params[4];
      const T& k2 = params[5];
      const T& k3 = params[6];
      const T& k4 = params[7];
      const T s = FisheyeScale(u, v);  // theta / r
      const T r2 = u * u + v * v;
      const T theta2 = s * s * r2;
      const T poly = T(1) + theta2 * (k1 + theta2 * (k2 + theta2 * (k3 + theta2 * k4)));
      *ud = u * s * poly;
      *vd = v * s * poly;
      return true;
    }
    case CameraModelId::kFullOpenCv: {
      const T& k1 = params[4];
      const T& k2 = params[5];
      const T& p1 = params[6];
      const T& p2 = params[7];
      const T& k3 = params[8];
      const T& k4 = params[9];
      const T& k5 = params[10];
      const T& k6 = params[11];
      const T u2 = u * u, v2 = v * v, uv = u * v, r2 = u2 + v2;
      const T r4 = r2 * r2, r6 = r4 * r2;
      const T radial = (T(1) + k1 * r2 + k2 * r4 + k3 * r6) / (T(1) + k4 * r2 + k5 * r4 + k6 * r6);
      *ud = u * radial + T(2) * p1 * uv + p2 * (r2 + T(2) * u2);
      *vd = v * radial + T(2) * p2 * uv + p1 * (r2 + T(2) * v2);
      return true;
    }
    case CameraModelId::kFov: {
      // factor = atan(r * 2 tan(omega / 2)) / (r * omega), with COLMAP's Taylor branches near
      // omega = 0 and r = 0.
      const T& omega = params[4];
      const T kEpsilon = T(1e-4);
      const T r2 = u * u + v * v;
      const T omega2 = omega * omega;
      T factor;
      if (omega2 < kEpsilon) {
        factor = (omega2 * r2) / T(3) - omega2 / T(12) + T(1);
      } else if (r2 < kEpsilon) {
        const T t = tan(omega / T(2));
        factor = (T(-2) * t * (T(4) * r2 * t * t - T(3))) / (T(3) * omega);
      } else {
        const T r = sqrt(r2);
        factor = atan(r * T(2) * tan(omega / T(2))) / (r * omega);
      }
      *ud = u * factor;
      *vd = v * factor;
      return true;
    }
    case CameraModelId::kSimpleRadialFisheye: {
      const T& k = params[3];
      const T s = FisheyeScale(u, v);
      const T theta2 = s * s * (u * u + v * v);
      const T poly = T(1) + k * theta2;
      *ud = u * s * poly;
      *vd = v * s * poly;
      return true;
    }
    case CameraModelId::kRadialFisheye: {
      const T& k1 = params[3];
      const T& k2 = params[4];
      const T s = FisheyeScale(u, v);
      const T theta2 = s * s * (u * u + v * v);
      const T poly = T(1) + theta2 * (k1 + k2 * theta2);
      *ud = u * s * poly;
      *vd = v * s * poly;
      return true;
    }
    case CameraModelId::kThinPrismFisheye: {
      const T& k1 = params[4];
      const T& k2 = params[5];
      const T& p1 = params[6];
      const T& p2 = params[7];
      const T& k3 = params[8];
      const T& k4 = params[9];
      const T& sx1 = params[10];
      const T& sy1 = params[11];
      // Equidistant map first, then radial + tangential + thin prism on the mapped coordinates.
      const T s = FisheyeScale(u, v);
      const T uu = u * s, vv = v * s;
      const T u2 = uu * uu, v2 = vv * vv, uv = uu * vv, r2 = u2 + v2;
      const T r4 = r2 * r2, r6 = r4 * r2, r8 = r4 * r4;
      const T radial = k1 * r2 + k2 * r4 + k3 * r6 + k4 * r8;
      *ud = uu + uu * radial + T(2) * p1 * uv + p2 * (r2 + T(2) * u2) + sx1 * r2;
      *vd = vv + vv * radial + T(2) * p2 * uv + p1 * (r2 + T(2) * v2) + sy1 * r2;
      return true;
    }
  }
  return false;
}

// Normalized camera coordinates (u, v) -> pixel (x, y). Returns false for an unknown model.
template <typename T>
bool ProjectNormalizedToPixel(int model_id, const T* params, const T& u, const T& v, T* x, T* y) {
  T ud, vd;
  if (!DistortNormalized(model_id, params, u, v, &ud, &vd)) return false;
  if (CameraModelHasSingleFocal(model_id)) {
    *x = params[0] * ud + params[1];
    *y = params[0] * vd + params[2];
  } else {
    *x = params[0] * ud + params[2];
    *y = params[1] * vd + params[3];
  }
  return true;
}

// Pixel -> normalized camera coordinates, inverting the distortion numerically (Newton iterations
// with a numeric Jacobian, as COLMAP's IterativeUndistortion). Returns false for an unknown model or
// when the iteration does not converge.
bool PixelToNormalized(int model_id, std::span<const double> params, double x, double y, double* u, double* v);

}  // namespace cinepath::photogrammetry
