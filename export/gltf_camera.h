// previs.glb: the planned cameras as glTF 2.0 camera nodes with their flight as animation, optionally
// added to the scene's GLB as `cinepath mesh` wrote it (its JSON extended, its binary chunk kept byte
// for byte: the mesh, Draco and texture are not decoded or re-encoded).
//
// Per track (export/camera_track.h): a perspective camera (yfov = the first key's vertical angle of
// view, aspectRatio = the plan's width_px / height_px, znear 0.1 m, zfar 100 km) on a node named after
// the drone, whose translation and rotation (float32, the Y-up glTF frame: x east, y up, z south) are
// the first key's, and one animation "previs" with a translation and a rotation channel per node:
// LINEAR samplers with a key at every sample (input = time_s). glTF 2.0 cannot animate a camera's
// projection without KHR_animation_pointer, which neither Blender 3.4 nor three.js's GLTFLoader
// reads, so the lens goes into the node's extras, one value per key: `focal_length_mm`,
// `focus_distance_m` (null = infinity), `f_number`, `shutter_s`, `vertical_fov_deg`, beside `frame`
// (of the first key), `frame_rate_hz`, `sensor_width_mm`, `sensor_height_mm`. The scene's extras gain
// `frame_rate_hz`, `frame_start` and `frame_end`.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "export/camera_track.h"

namespace cinepath::exporter {

// `scene_glb` empty: a GLB with the cameras alone. Otherwise the cameras join that GLB's default scene;
// InputError naming `scene_source` when it is not a GLB or keeps its data outside (a buffer with a uri).
std::string WriteGltfCamera(const std::vector<CameraTrack>& tracks, std::string_view scene_glb = {},
                            const std::string& scene_source = "");

}  // namespace cinepath::exporter
