#include "viewer/previs_page.h"

#include "core/error.h"
#include "core/file_io.h"
#include "core/json.h"
#include "core/plan_file.h"
#include "core/reframe.h"
#include "core/scene_file.h"
#include "core/three_frame.h"
#include "scene/border_ring.h"
#include "scene/glb_reader.h"
#include "viewer/base64.h"
#include "viewer/embedded_assets.h"
#include "viewer/frame_images.h"
#include "viewer/mesh_payload.h"
#include "viewer/page_data.h"

namespace cinepath::viewer {
namespace {

std::string HtmlEscape(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '<') {
      out += "&lt;";
    } else if (c == '>') {
      out += "&gt;";
    } else if (c == '&') {
      out += "&amp;";
    } else if (c == '"') {
      out += "&quot;";
    } else {
      out += c;
    }
  }
  return out;
}

std::string JsDataUrl(std::string_view code) { return "data:text/javascript;base64," + Base64Encode(code); }

std::string CompactJson(const Json& document) { return JsonForScriptElement(document.dump()); }

Json MeshJson(const MeshPayload& mesh, const std::string& source, const Json& ground) {
  return {{"source", source},
          {"vertices", mesh.num_vertices},
          {"triangles", mesh.num_triangles},
          {"has_colors", mesh.has_colors},
          {"has_texcoords", mesh.has_texcoords},
          {"texture", mesh.has_texcoords ? "data:" + mesh.texture_mime_type + ";base64," +
                                               Base64Encode(std::string(mesh.texture.begin(), mesh.texture.end()))
                                         : std::string()},
          {"index_bytes", mesh.index_bytes},
          {"min_m", mesh.min_three_m},
          {"max_m", mesh.max_three_m},
          {"inflated_bytes", mesh.inflated_bytes},
          {"ground", ground}};
}

// The ground past the mesh's edge, as `render` draws it (scene/border_ring.h; docs/render.md, "The
// horizon"), in three.js's frame: the plane's height (y), the ring's centre (x, z) and radius, and the
// border faces with their sectors. The page colours each face at its centroid from the mesh's colours
// and texture, averages them per sector as render does, and draws the plane (viewer/previs.js).
Json GroundJson(const scene::SceneMesh& mesh) {
  const scene::BorderRing ring = scene::FindBorderRing(mesh);
  const Eigen::Vector3d centre = ThreeFromEnu({ring.centre_m.x(), ring.centre_m.y(), ring.height_m});
  return {{"height_m", RoundToDecimals(centre.y(), 3)},
          {"centre_m", Json::array({RoundToDecimals(centre.x(), 3), RoundToDecimals(centre.z(), 3)})},
          {"radius_m", RoundToDecimals(ring.radius_m, 3)},
          {"sectors", scene::BorderRing::kSectors},
          {"smooth_sectors", scene::BorderRing::kSmoothSectors},
          {"faces", ring.faces},
          {"face_sectors", ring.sectors}};
}

// Where the photos that built the scene were taken (scene.json's `cameras`, written by `cinepath mesh`),
// in three.js's frame, millimetres: {name, position_m}. Absent or malformed entries are skipped: the
// page is a preview, and scene.json's reader does not require the key.
Json PhotoPositionsJson(const SceneFile& scene) {
  Json photos = Json::array();
  const auto it = scene.document.find("cameras");
  if (it == scene.document.end() || !it->is_array()) return photos;
  for (const Json& camera : *it) {
    if (!camera.is_object() || !camera.contains("position_enu_m") || !camera["position_enu_m"].is_array() ||
        camera["position_enu_m"].size() != 3 || !camera.value("image", Json()).is_string()) {
      continue;
    }
    const Json& p = camera["position_enu_m"];
    if (!p[0].is_number() || !p[1].is_number() || !p[2].is_number()) continue;
    const Eigen::Vector3d three = ThreeFromEnu({p[0].get<double>(), p[1].get<double>(), p[2].get<double>()});
    Json photo = Json::object();
    photo["name"] = camera["image"];
    photo["position_m"] =
        Json::array({RoundToDecimals(three.x(), 3), RoundToDecimals(three.y(), 3), RoundToDecimals(three.z(), 3)});
    photos.push_back(photo);
  }
  return photos;
}

Json WithPhotos(Json data, Json photos) {
  data["photos"] = std::move(photos);
  return data;
}

// The folder of one sequence that `--frames DIR` names: DIR itself when it holds frames, else (the folder
// `cinepath render -o DIR` writes for several drones: DIR/<drone>/ and DIR/edit/) the edit's sequence when
// the plan has an edit, or the primary flight's.
std::filesystem::path FramesFolderOfPlan(const std::filesystem::path& dir, const TeamPlan& team, size_t primary,
                                         size_t samples) {
  if (team.flights.size() < 2 || !FindRenderedFrames(dir, samples).empty()) return dir;
  const std::filesystem::path sequence = dir / (team.edit.empty() ? team.flights[primary].name : std::string("edit"));
  std::error_code error;
  return std::filesystem::is_directory(sequence, error) ? sequence : dir;
}

}  // namespace

std::string FillTemplate(const std::string& page_template,
                         const std::vector<std::pair<std::string, std::string>>& values) {
  std::string out;
  size_t pos = 0;
  while (true) {
    const size_t open = page_template.find('@', pos);
    if (open == std::string::npos) break;
    const size_t close = page_template.find('@', open + 1);
    if (close == std::string::npos) break;
    const std::string name = page_template.substr(open + 1, close - open - 1);
    const std::pair<std::string, std::string>* value = nullptr;
    for (const auto& v : values) {
      if (v.first == name) value = &v;
    }
    if (value == nullptr) {
      // Not a placeholder (an '@' in the text): keep it and look on from the second '@'.
      out.append(page_template, pos, close - pos);
      pos = close;
      continue;
    }
    out.append(page_template, pos, open - pos);
    out += value->second;
    pos = close + 1;
  }
  out.append(page_template, pos, std::string::npos);
  return out;
}

std::string JsonForScriptElement(const std::string& json_text) {
  std::string out;
  out.reserve(json_text.size());
  for (size_t i = 0; i < json_text.size(); ++i) {
    out += json_text[i];
    if (json_text[i] == '<' && i + 1 < json_text.size() && json_text[i + 1] == '/') out += '\\';
  }
  return out;
}

PrevisPage BuildPrevisPage(const ViewOptions& options) {
  PrevisPage page;
  TeamPlan team = ReadTeamPlanFile(options.plan);
  page.notes = TeamPlanNotes(team);
  // Several drones: the page is drawn about the longest flight (the first of the longest), and the team
  // code shows every flight over it.
  size_t primary = 0;
  for (size_t f = 0; f < team.flights.size(); ++f) {
    if (team.flights[f].plan.samples.size() > team.flights[primary].plan.samples.size()) primary = f;
  }
  page.inputs.push_back(options.plan.string());
  std::optional<Geodetic> origin = team.origin;
  std::optional<MeshPayload> mesh;
  std::string mesh_source;
  Json ground;
  Json photos = Json::array();
  if (options.scene) {
    const SceneFile scene = ReadSceneFile(*options.scene);
    page.inputs.push_back(options.scene->string());
    const std::filesystem::path& glb = scene.RequireMesh();  // InputError when absent or missing
    page.inputs.push_back(glb.string());
    if (scene.origin) {
      team = ReframeToOrigin(std::move(team), *scene.origin);  // a plan without an origin is left as it is
      origin = scene.origin;
    }
    photos = PhotoPositionsJson(scene);
    const scene::SceneMesh scene_mesh = scene::ReadGlbFile(glb);
    mesh = EncodeMeshPayload(scene_mesh);
    ground = GroundJson(scene_mesh);
    mesh_source = glb.filename().string();
    page.mesh_triangles = mesh->num_triangles;
  }
  Json frames = Json::object();
  if (options.frames_dir) {
    const size_t samples = team.flights[primary].plan.samples.size();
    const std::filesystem::path dir = FramesFolderOfPlan(*options.frames_dir, team, primary, samples);
    for (const auto& [k, image] : FindRenderedFrames(dir, samples)) {
      frames[std::to_string(k)] = "data:" + image.mime_type + ";base64," + Base64Encode(ReadFileToString(image.path));
      page.inputs.push_back(image.path.string());
      ++page.frames_inlined;
    }
    if (page.frames_inlined == 0) {
      page.notes.push_back("--frames " + options.frames_dir->string() +
                           ": no frame_NNNNNN.png / .jpg of this plan's samples there; the camera view shows the "
                           "live picture only");
    }
  }
  const std::string plan_name = options.plan.filename().string();
  const Json data = PageDataJson(team, primary, plan_name, origin);
  page.html =
      FillTemplate(std::string(PrevisHtml()),
                   {{"TITLE", HtmlEscape("cinepath view: " + plan_name)},
                    {"THREE_URL", JsDataUrl(ThreeModuleJs())},
                    {"CONTROLS_URL", JsDataUrl(OrbitControlsJs())},
                    {"DATA_JSON", CompactJson(WithPhotos(data, photos))},
                    {"MESH_JSON", mesh ? CompactJson(MeshJson(*mesh, mesh_source, ground)) : std::string("null")},
                    {"MESH_BASE64", mesh ? Base64Encode(mesh->deflated) : std::string()},
                    {"FRAMES_JSON", CompactJson(frames)},
                    {"PREVIS_JS", std::string(PrevisJs())}});
  return page;
}

}  // namespace cinepath::viewer
