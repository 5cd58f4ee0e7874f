#include "export/gltf_camera.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "core/error.h"
#include "core/glb_container.h"
#include "core/json.h"

namespace cinepath::exporter {
namespace {

constexpr int kFloat = 5126;  // glTF componentType FLOAT
constexpr double kZNearM = 0.1;
constexpr double kZFarM = 100000;

// The glTF document and binary chunk being extended.
struct GlbBuilder {
  Json doc;
  std::string bin;

  Json& Array(const char* key) {
    if (!doc.contains(key)) doc[key] = Json::array();
    if (!doc[key].is_array()) throw InputError(std::string(key) + ": not an array");
    return doc[key];
  }

  // A float accessor over `values` (components per element), with min/max when asked.
  int AddAccessor(const std::vector<float>& values, int components, const char* type, bool bounds) {
    bin.append((4 - bin.size() % 4) % 4, '\0');
    const size_t offset = bin.size();
    bin.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(float));
    Json& views = Array("bufferViews");
    views.push_back(Json{{"buffer", 0}, {"byteOffset", offset}, {"byteLength", values.size() * sizeof(float)}});
    Json accessor{{"bufferView", views.size() - 1},
                  {"componentType", kFloat},
                  {"count", values.size() / components},
                  {"type", type}};
    if (bounds) {
      Json min = Json::array();
      Json max = Json::array();
      for (int c = 0; c < components; ++c) {
        float lo = std::numeric_limits<float>::infinity();
        float hi = -lo;
        for (size_t i = c; i < values.size(); i += components) {
          lo = std::min(lo, values[i]);
          hi = std::max(hi, values[i]);
        }
        min.push_back(lo);
        max.push_back(hi);
      }
      accessor["min"] = min;
      accessor["max"] = max;
    }
    Json& accessors = Array("accessors");
    accessors.push_back(accessor);
    return static_cast<int>(accessors.size()) - 1;
  }
};

Json FiniteOrNull(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

Json NodeExtras(const CameraTrack& track) {
  Json focal = Json::array(), focus = Json::array(), f_number = Json::array(), shutter = Json::array(),
       vfov = Json::array();
  for (const CameraKey& k : track.keys) {
    focal.push_back(k.focal_length_mm);
    focus.push_back(FiniteOrNull(k.focus_distance_m));
    f_number.push_back(k.f_number);
    shutter.push_back(k.shutter_s);
    vfov.push_back(k.vertical_fov_deg);
  }
  return Json{{"frame", track.keys.front().frame},
              {"frame_rate_hz", track.frame_rate_hz},
              {"sensor_width_mm", track.camera.sensor_width_mm},
              {"sensor_height_mm", track.camera.sensor_height_mm},
              {"width_px", track.camera.width_px},
              {"height_px", track.camera.height_px},
              {"focal_length_mm", focal},
              {"focus_distance_m", focus},
              {"f_number", f_number},
              {"shutter_s", shutter},
              {"vertical_fov_deg", vfov}};
}

void AddTrack(const CameraTrack& track, GlbBuilder& glb, Json& channels, Json& samplers, Json& scene_nodes) {
  const CameraKey& first = track.keys.front();
  Json& cameras = glb.Array("cameras");
  const double yfov = first.vertical_fov_deg * std::acos(-1.0) / 180.0;
  cameras.push_back(
      Json{{"name", track.name},
           {"type", "perspective"},
           {"perspective", Json{{"yfov", yfov},
                                {"aspectRatio", static_cast<double>(track.camera.width_px) / track.camera.height_px},
                                {"znear", kZNearM},
                                {"zfar", kZFarM}}}});
  const Eigen::Quaterniond& q0 = first.yup_from_camera;
  Json& nodes = glb.Array("nodes");
  nodes.push_back(Json{{"name", track.name},
                       {"camera", cameras.size() - 1},
                       {"translation", Json::array({static_cast<float>(first.position_yup_m.x()),
                                                    static_cast<float>(first.position_yup_m.y()),
                                                    static_cast<float>(first.position_yup_m.z())})},
                       {"rotation", Json::array({static_cast<float>(q0.x()), static_cast<float>(q0.y()),
                                                 static_cast<float>(q0.z()), static_cast<float>(q0.w())})},
                       {"extras", NodeExtras(track)}});
  const size_t node = nodes.size() - 1;
  scene_nodes.push_back(node);

  std::vector<float> times, translations, rotations;
  for (const CameraKey& k : track.keys) {
    times.push_back(static_cast<float>(k.time_s));
    for (int c = 0; c < 3; ++c) translations.push_back(static_cast<float>(k.position_yup_m(c)));
    const Eigen::Quaterniond& q = k.yup_from_camera;
    rotations.insert(rotations.end(), {static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z()),
                                       static_cast<float>(q.w())});
  }
  const int input = glb.AddAccessor(times, 1, "SCALAR", true);
  const int translation = glb.AddAccessor(translations, 3, "VEC3", false);
  const int rotation = glb.AddAccessor(rotations, 4, "VEC4", false);
  for (const auto& [path, output] : {std::pair<const char*, int>{"translation", translation}, {"rotation", rotation}}) {
    samplers.push_back(Json{{"input", input}, {"interpolation", "LINEAR"}, {"output", output}});
    channels.push_back(Json{{"sampler", samplers.size() - 1}, {"target", Json{{"node", node}, {"path", path}}}});
  }
}

}  // namespace

std::string WriteGltfCamera(const std::vector<CameraTrack>& tracks, std::string_view scene_glb,
                            const std::string& scene_source) {
  CINEPATH_CHECK(!tracks.empty());
  GlbBuilder glb;
  if (scene_glb.empty()) {
    glb.doc = Json{{"asset", Json{{"version", "2.0"}, {"generator", "cinepath"}}}};
  } else {
    const GlbChunks chunks = SplitGlb(scene_glb, scene_source);
    glb.doc = ParseJsonText(chunks.json, scene_source);
    if (!glb.doc.is_object()) throw InputError(scene_source + ": the GLB's JSON is not an object");
    glb.bin = std::string(chunks.bin);
  }
  try {
    // Every top-level array this adds to exists before any reference into the document is taken (an
    // ordered_json object moves its members when a key is added).
    const size_t scene =
        glb.doc.contains("scene") && glb.doc["scene"].is_number_unsigned() ? glb.doc["scene"].get<size_t>() : 0;
    glb.doc["scene"] = scene;
    for (const char* key : {"scenes", "nodes", "cameras", "animations", "accessors", "bufferViews", "buffers"}) {
      glb.Array(key);
    }
    const Json& buffers = glb.Array("buffers");
    if (buffers.size() > 1 || (buffers.size() == 1 && (!buffers[0].is_object() || buffers[0].contains("uri")))) {
      throw InputError("buffers: the data is not all in the GLB's binary chunk");
    }
    Json& scenes = glb.Array("scenes");
    if (scenes.empty()) scenes.push_back(Json{{"nodes", Json::array()}});
    if (scene >= scenes.size() || !scenes[scene].is_object()) throw InputError("scene: index out of range");
    Json& scene_json = scenes[scene];
    if (!scene_json.contains("nodes")) scene_json["nodes"] = Json::array();
    if (!scene_json["nodes"].is_array()) throw InputError("scenes[" + std::to_string(scene) + "].nodes: not an array");

    Json channels = Json::array();
    Json samplers = Json::array();
    Json scene_nodes = scene_json["nodes"];
    for (const CameraTrack& track : tracks) AddTrack(track, glb, channels, samplers, scene_nodes);
    scene_json["nodes"] = scene_nodes;
    glb.Array("animations").push_back(Json{{"name", "previs"}, {"channels", channels}, {"samplers", samplers}});

    const auto [frame_start, frame_end] = FrameRange(tracks);
    Json& extras = scene_json["extras"];
    if (!extras.is_object()) extras = Json::object();
    extras["frame_rate_hz"] = tracks.front().frame_rate_hz;
    extras["frame_start"] = frame_start;
    extras["frame_end"] = frame_end;

    glb.bin.append((4 - glb.bin.size() % 4) % 4, '\0');
    Json& all_buffers = glb.Array("buffers");
    if (all_buffers.empty()) all_buffers.push_back(Json::object());
    all_buffers[0]["byteLength"] = glb.bin.size();
  } catch (const InputError& e) {
    if (scene_glb.empty()) throw;
    throw InputError(scene_source + ": " + e.what());
  }
  return AssembleGlb(glb.doc.dump(), glb.bin);
}

}  // namespace cinepath::exporter
