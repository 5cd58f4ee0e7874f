// scene.json's `cameras`: every registered photo as the scene sees it after georeferencing and bundle
// adjustment (docs/scene-format.md): where it was taken in ENU metres, its orientation in plan.json's
// convention (world_from_camera, camera x right, y down, z forward, [w, x, y, z]), a pinhole
// approximation of its COLMAP camera, and the distortion model with its parameters as COLMAP gives them.
// `view` shows where the photos were taken; tests can render from a photo's own viewpoint.
#pragma once

#include "core/json.h"
#include "photogrammetry/io/colmap_model.h"

namespace cinepath::photogrammetry {

// One entry per image of `model_enu` (a model already in ENU metres), in image-id order.
Json SceneCamerasJson(const ColmapModel& model_enu);

}  // namespace cinepath::photogrammetry
