#include "photogrammetry/georef/scene_cameras.h"

#include "photogrammetry/georef/camera_models.h"

namespace cinepath::photogrammetry {
namespace {

constexpr int kMetres = 6;  // plan.json's precision (docs/plan-format.md)
constexpr int kQuaternion = 9;
constexpr int kPixels = 6;

Json Rounded(double v, int decimals) { return Json(RoundToDecimals(v, decimals)); }

}  // namespace

Json SceneCamerasJson(const ColmapModel& model_enu) {
  Json cameras = Json::array();
  for (const auto& [id, image] : model_enu.images) {
    const auto camera_it = model_enu.cameras.find(image.camera_id);
    if (camera_it == model_enu.cameras.end()) continue;
    const ColmapCamera& camera = camera_it->second;
    Json c = Json::object();
    c["image"] = image.name;
    const Eigen::Vector3d centre = image.ProjectionCenter();
    c["position_enu_m"] =
        Json::array({Rounded(centre.x(), kMetres), Rounded(centre.y(), kMetres), Rounded(centre.z(), kMetres)});
    Eigen::Quaterniond q = image.cam_from_world_rotation.normalized().conjugate();
    if (q.w() < 0) q.coeffs() = -q.coeffs();  // one sign for the same rotation
    c["world_from_camera"] = Json::array({Rounded(q.w(), kQuaternion), Rounded(q.x(), kQuaternion),
                                          Rounded(q.y(), kQuaternion), Rounded(q.z(), kQuaternion)});
    const std::vector<int> focal = CameraModelFocalIndices(camera.model_id);
    const std::vector<int> principal = CameraModelPrincipalPointIndices(camera.model_id);
    if (!focal.empty()) {
      c["focal_px"] = Rounded(camera.params[focal[0]], kPixels);
      if (focal.size() > 1) c["focal_y_px"] = Rounded(camera.params[focal[1]], kPixels);
    }
    if (principal.size() == 2) {
      c["principal_point_px"] =
          Json::array({Rounded(camera.params[principal[0]], kPixels), Rounded(camera.params[principal[1]], kPixels)});
    }
    c["width_px"] = camera.width_px;
    c["height_px"] = camera.height_px;
    Json distortion = Json::object();
    distortion["model"] = std::string(CameraModelName(camera.model_id));
    Json params = Json::array();
    for (int i : CameraModelExtraIndices(camera.model_id)) params.push_back(camera.params[i]);
    distortion["params"] = params;
    c["distortion"] = distortion;
    cameras.push_back(c);
  }
  return cameras;
}

}  // namespace cinepath::photogrammetry
