// Nuke's .chan camera track: one line per frame, `frame tx ty tz rx ry rz vfov`, separated by spaces
// (what Nuke's Camera "import chan file" reads, and Blender's bundled "Nuke Animation Format (.chan)"
// add-on). Nuke's frame is Y-up in metres here: x east, y up, z south (core/three_frame.h, the same
// mapping as the GLB); rotations are Euler angles in degrees in Nuke's default order ZXY (the camera
// is rolled about z first, then tilted about x, then panned about y: R = Ry(ry) Rx(rx) Rz(rz)); vfov is
// the vertical angle of view in degrees. Positions to 1e-6 m, angles to 1e-6 deg (docs/export.md).
#pragma once

#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "export/camera_track.h"

namespace cinepath::exporter {

// The ZXY Euler angles (rx, ry, rz) in degrees with R = Ry(ry) Rx(rx) Rz(rz) and rx in [-90, 90]. With
// `previous`, ry and rz are moved by whole turns to lie within 180 degrees of its angles, so that a
// track interpolated between keys never spins the long way round; at rx = ±90 (looking straight up or
// down, where only ry ∓ rz is defined) rz keeps the previous value.
Eigen::Vector3d ZxyEulerDeg(const Eigen::Quaterniond& rotation, const Eigen::Vector3d* previous = nullptr);

std::string WriteNukeChan(const CameraTrack& track);

}  // namespace cinepath::exporter
