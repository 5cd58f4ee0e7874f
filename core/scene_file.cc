#include "core/scene_file.h"

#include "core/error.h"
#include "core/file_io.h"
#include "core/geodetic_json.h"

namespace cinepath {

namespace fs = std::filesystem;

const fs::path& SceneFile::RequireMesh() const {
  if (!mesh) throw InputError(Located(source, "mesh: missing (the GLB beside scene.json, e.g. \"scene.glb\")"));
  if (!fs::is_regular_file(*mesh)) {
    throw InputError(Located(source, "mesh: '" + mesh->string() + "' does not exist or is not a file"));
  }
  return *mesh;
}

const Geodetic& SceneFile::RequireOrigin() const {
  if (!origin) throw InputError(Located(source, "origin: missing ({\"lat_deg\", \"lon_deg\", \"height_m\"})"));
  return *origin;
}

SceneFile ParseSceneFile(const Json& document, const std::string& source, const fs::path& folder) {
  const JsonField root(document, source);
  if (!root.IsObject()) root.Fail("expected a scene (a JSON object)");
  if (auto format = root.Find("format"); format && format->AsString() != "cinepath.scene") {
    format->Fail("expected \"cinepath.scene\", got \"" + format->AsString() + "\"");
  }
  if (auto version = root.Find("version"); version && version->AsInt() != 1) {
    version->Fail("unsupported scene version " + std::to_string(version->AsInt()) + " (this build reads 1)");
  }
  SceneFile scene;
  scene.source = source;
  scene.document = document;
  if (auto origin = root.Find("origin")) scene.origin = GeodeticFromJson(*origin);
  // `cameras` (where the photos were taken, which view shows) is optional and its entries are free-form,
  // but a position given is one in the scene's frame, and bounded as plan.json's are.
  if (auto cameras = root.Find("cameras"); cameras && cameras->IsArray()) {
    for (const auto& camera : cameras->Elements()) {
      if (!camera.IsObject()) continue;
      if (auto p = camera.Find("position_enu_m")) EnuPositionFromJson(*p);
    }
  }
  if (auto mesh = root.Find("mesh")) {
    const std::string name = mesh->AsString();
    if (name.empty()) mesh->Fail("must name the GLB file");
    const fs::path p(name);
    scene.mesh = p.is_absolute() ? p : (folder / p).lexically_normal();
  }
  return scene;
}

SceneFile ReadSceneFile(const fs::path& scene_json) {
  const std::string source = scene_json.filename().string();
  const Json doc = ParseJsonText(ReadFileToString(scene_json), source);
  return ParseSceneFile(doc, source, scene_json.parent_path());
}

}  // namespace cinepath
