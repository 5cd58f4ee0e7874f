// scene.json: what `cinepath mesh` writes beside scene.glb, and what every later stage reads
// (plan --scene, optimize, render, export --scene, view). Format reference: docs/scene-format.md.
//
// A reader needs only two keys, so a scene.json written by hand works too:
//   "origin": {"lat_deg", "lon_deg", "height_m"}   the WGS84 origin of the ENU frame (ellipsoidal)
//   "mesh":   "scene.glb"                          the GLB, relative to scene.json's folder
// "format" ("cinepath.scene") and "version" (1) are checked when present; other keys are kept in
// `document` for the stages that use them (georeferencing report, surface report, cameras), and the
// numbers a stage reads from them are checked here: each camera's `position_enu_m` lies within 1e7 m of
// the origin (core/geodetic_json.h).
// The mesh itself is read by scene/glb_reader.h (Draco, textures), out of the start-up path.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "core/geodesy.h"
#include "core/json.h"

namespace cinepath {

struct SceneFile {
  std::string source;                         // the file name, as messages name it
  std::optional<Geodetic> origin;             // "origin"; absent = local metres only
  std::optional<std::filesystem::path> mesh;  // "mesh" resolved against scene.json's folder
  Json document;                              // the whole file

  // The mesh path; InputError ("<source>: mesh: ...") when the key is absent or the file is missing.
  const std::filesystem::path& RequireMesh() const;
  // The origin; InputError ("<source>: origin: missing") when absent.
  const Geodetic& RequireOrigin() const;
};

// Parses scene.json. InputError naming the file and the key for anything malformed. Does not open
// the mesh (RequireMesh checks that it exists).
SceneFile ReadSceneFile(const std::filesystem::path& scene_json);
SceneFile ParseSceneFile(const Json& document, const std::string& source, const std::filesystem::path& folder);

}  // namespace cinepath
