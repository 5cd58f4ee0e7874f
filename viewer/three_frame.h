// From the scene frame (local ENU, camera x right / y down / z forward) to three.js's frame, which the
// page draws in: glTF's and three.js's +Y is up, so ENU (e, n, u) is (e, u, -n) there, as in the GLB
// (docs/design.md, "Frames"); a three.js camera looks along its -Z with +Y up, i.e. (x, -y, -z) of the
// COLMAP/OpenCV camera frame. Also the vertical angle of view a three.js PerspectiveCamera takes.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/trajectory.h"

namespace cinepath::viewer {

Eigen::Vector3d ThreeFromEnu(const Eigen::Vector3d& enu_m);

// The orientation of a three.js camera that sees what the plan's camera sees (unit, w >= 0).
Eigen::Quaterniond ThreeCameraFromWorldFromCamera(const Eigen::Quaterniond& world_from_camera);

// Vertical angle of view in degrees under the sensor-fit rule (core/optics.h): the image's height on
// the sensor is sensor_width_mm * height_px / width_px.
double VerticalFieldOfViewDeg(const CameraSpec& camera, double focal_length_mm);

}  // namespace cinepath::viewer
