// Rotations: unit quaternions (Eigen, Hamilton, w x y z), SLERP / SQUAD, look-at, and the drone
// heading + gimbal angles <-> world_from_camera conversion.
//
// Frames (docs/design.md): world = local ENU (x east, y north, z up); camera x right, y down, z forward.
// world_from_camera maps camera-frame vectors into ENU, so the viewing direction is R * (0, 0, 1)
// and the top of the image points along R * (0, -1, 0).
//
// Angle conventions:
//   * Compass heading: degrees clockwise from true north, [0, 360) (core/angles.h); ENU yaw is
//     counter-clockwise from east. heading = 90 deg - yaw_enu.
//   * Gimbal pitch: 0 = level, -90 = straight down, +90 = straight up (the camera's forward axis
//     raised above the horizon). Gimbal roll: positive = image right side down (clockwise as seen
//     from behind the camera). Gimbal yaw: degrees clockwise, relative to the drone's nose.
//   * Composition (Tait-Bryan, applied yaw, then pitch, then roll):
//       world_from_camera = Rz_enu(yaw_enu(heading + gimbal_yaw)) * B * Rx_cam(pitch) * Rz_cam(roll)
//     with B the level camera looking east (x right = south, y down = -up, z forward = east).
//
// Undefined roll (looking straight down or up): a look-at direction parallel to the vertical leaves
// the rotation about the view axis free. The rule used everywhere: the camera is oriented as if it
// had pitched down (or up) from level while facing the given fallback heading. Looking straight
// down, the top of the image points toward that heading; looking straight up, it points away from
// it. This is the limit of a level-horizon look-at as the pitch reaches -90 / +90, so the rule is
// continuous with non-degenerate views at the same heading.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <limits>
#include <vector>

namespace cinepath {

// Spherical linear interpolation on the short arc: q0 at t = 0, q1 at t = 1 (exactly, up to the
// sign of q1 which is flipped onto q0's hemisphere), unit norm for any t in [0, 1]. Identical and
// antipodal inputs (q and -q are the same rotation) return that rotation for every t; inputs
// 180 deg apart as rotations (dot product 0) interpolate at constant angular speed. Inputs are
// normalized first; a zero quaternion throws InputError.
Eigen::Quaterniond Slerp(const Eigen::Quaterniond& q0, const Eigen::Quaterniond& q1, double t);

// The rotation angle between two rotations, radians in [0, pi].
double AngleBetweenRad(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b);

// Quaternion logarithm / exponential of unit quaternions (pure-imaginary log: axis * angle / 2).
Eigen::Vector3d QuaternionLog(const Eigen::Quaterniond& q);
Eigen::Quaterniond QuaternionExp(const Eigen::Vector3d& v);

// SQUAD (Shoemake): C1-continuous interpolation through a sequence of key rotations at uniform
// parameter spacing. Squad(q_i, q_{i+1}, s_i, s_{i+1}, t), with the inner control points from
// SquadControlPoints. Keys are first sign-aligned so each lies on the previous one's hemisphere.
std::vector<Eigen::Quaterniond> AlignHemispheres(const std::vector<Eigen::Quaterniond>& keys);
// Inner control points s_i = q_i exp(-(log(q_i^-1 q_{i+1}) + log(q_i^-1 q_{i-1})) / 4), with the
// end keys duplicated (s_0 = q_0, s_{n-1} = q_{n-1}). Expects aligned keys.
std::vector<Eigen::Quaterniond> SquadControlPoints(const std::vector<Eigen::Quaterniond>& aligned);
Eigen::Quaterniond Squad(const Eigen::Quaterniond& q0, const Eigen::Quaterniond& q1, const Eigen::Quaterniond& s0,
                         const Eigen::Quaterniond& s1, double t);

// Level-horizon look-at: the camera looks along `forward_enu` (any length > 0) with its x axis
// horizontal (no roll). When forward is vertical (within 1e-12 rad of straight down/up) the roll
// follows the rule above with `fallback_heading_deg` (compass). Zero or non-finite forward throws
// InputError.
Eigen::Quaterniond LookAt(const Eigen::Vector3d& forward_enu, double fallback_heading_deg = 0.0);

// Level-horizon aim with the subject placed off-centre: the camera-frame direction `ray_camera`
// (for a screen position, (x_mm, y_mm, f_mm) on the sensor, x right, y down) is made to point along
// `target_enu`, keeping the horizon level. With ray_camera = (0, 0, 1) this is LookAt. If the
// requested screen offset cannot be reached with a level horizon (target too close to vertical
// for the vertical offset), the pitch is clamped to straight down/up.
Eigen::Quaterniond AimWithScreenOffset(const Eigen::Vector3d& target_enu, const Eigen::Vector3d& ray_camera,
                                       double fallback_heading_deg = 0.0);

struct GimbalAngles {
  double drone_heading_deg = 0;  // compass heading of the drone's nose, [0, 360)
  double gimbal_pitch_deg = 0;   // -90 straight down .. +90 straight up
  double gimbal_roll_deg = 0;    // positive = image right side down
  double gimbal_yaw_deg = 0;     // clockwise from the nose, (-180, 180]
};

Eigen::Quaterniond WorldFromCameraFromGimbal(const GimbalAngles& angles);

// The camera's compass heading (where the view points, or for a vertical view the heading implied
// by the top of the image per the rule above), degrees [0, 360).
double CameraHeadingDeg(const Eigen::Quaterniond& world_from_camera);

// Decomposes world_from_camera. With `drone_heading_deg` given, the gimbal yaw takes up the
// difference between the camera's heading and the nose; without it (NaN), the drone faces the
// camera heading and the gimbal yaw is 0. At pitch +-90 the roll is reported as 0 and the
// rotation about the view axis goes into the heading (see the rule above).
GimbalAngles GimbalFromWorldFromCamera(const Eigen::Quaterniond& world_from_camera,
                                       double drone_heading_deg = std::numeric_limits<double>::quiet_NaN());

}  // namespace cinepath
