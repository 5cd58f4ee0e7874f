// From the scene frame (local ENU, camera x right / y down / z forward) to the Y-up frame that three.js
// (the previs page), glTF and Nuke share: ENU (e, n, u) is (e, u, -n) there, as in the GLB
// (docs/design.md, "Frames"); a camera of those three looks along its -Z with +Y up, i.e. (x, -y, -z) of
// the COLMAP/OpenCV camera frame. Also the vertical angle of view a three.js PerspectiveCamera, a glTF
// camera's yfov and a Nuke camera's vertical field of view take.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/trajectory.h"

namespace cinepath {

// The one axis swap between the scene frame and the Y-up frame: the GLB writer, the GLB reader, the
// previs page and the camera-track exports all go through these two.
Eigen::Vector3d ThreeFromEnu(const Eigen::Vector3d& enu_m);  // (e, n, u) -> (e, u, -n)
Eigen::Vector3d EnuFromThree(const Eigen::Vector3d& three);  // (x, y, z) -> (x, -z, y)

// The orientation of a three.js camera that sees what the plan's camera sees (unit, w >= 0).
Eigen::Quaterniond ThreeCameraFromWorldFromCamera(const Eigen::Quaterniond& world_from_camera);

// Vertical angle of view in degrees under the sensor-fit rule (core/optics.h): the image's height on
// the sensor is sensor_width_mm * height_px / width_px.
double VerticalFieldOfViewDeg(const CameraSpec& camera, double focal_length_mm);

}  // namespace cinepath
