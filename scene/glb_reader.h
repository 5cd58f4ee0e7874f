// scene.glb -> SceneMesh in local ENU metres. Reads what cinepath mesh writes and what other tools
// write (Blender, glTF-Transform): every triangle primitive of the default scene, node transforms
// applied, KHR_draco_mesh_compression decoded, COLOR_0 and TEXCOORD_0 with the base-colour texture.
//
// Frames (docs/design.md): glTF +Y is up and a GLB stores ENU (e, n, u) as glTF (e, u, -n), so
// ENU = (x, -z, y) of the glTF position after the node transforms.
// Triangle strips and fans are split into triangles; points and lines are skipped. Sparse accessors
// are refused. Every index and byte range is checked: a malformed file is an InputError naming the
// file and the glTF element ("scene.glb: accessors[3]: ..."), never a crash.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "scene/scene_mesh.h"

namespace cinepath::scene {

// InputError when the file is not a GLB, is malformed, or holds no triangles.
SceneMesh ReadGlbFile(const std::filesystem::path& path);
SceneMesh ReadGlbBytes(std::string_view bytes, const std::string& source);

}  // namespace cinepath::scene
