// `cinepath view`: one self-contained HTML file that shows a plan over its scene in three.js, offline
// from disk (docs/view.md). The page holds everything: three.js as data: URLs behind an import map, the
// page's code, the plan's samples (viewer/page_data.h), the mesh (viewer/mesh_payload.h) and the
// rendered frames. Same inputs, same bytes: nothing in the page depends on the time or the machine.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace cinepath::viewer {

struct ViewOptions {
  std::filesystem::path plan;                       // plan.json
  std::optional<std::filesystem::path> scene;       // scene.json; its mesh must exist
  std::optional<std::filesystem::path> frames_dir;  // render's frame_%06d.png folder
};

struct PrevisPage {
  std::string html;
  std::vector<std::string> inputs;  // every file read, for --depfile
  size_t mesh_triangles = 0;
  size_t frames_inlined = 0;
  std::vector<std::string> notes;  // the plan reader's (core/plan_file.h TeamPlanNotes), for warnings
};

// InputError naming the file and key for a bad plan or scene, a scene whose mesh is missing, or a
// --frames that is not a folder.
PrevisPage BuildPrevisPage(const ViewOptions& options);

// Replaces each @NAME@ of `page_template` by values[NAME], in one pass (replacement text is never
// scanned again). InternalError for a placeholder without a value.
std::string FillTemplate(const std::string& page_template,
                         const std::vector<std::pair<std::string, std::string>>& values);

// JSON text safe inside <script type="application/json">: "</" becomes "<\/".
std::string JsonForScriptElement(const std::string& json_text);

}  // namespace cinepath::viewer
