#include "photogrammetry/texture/mesh_texture.h"

#include <algorithm>
#include <filesystem>
#include <map>

#include <tbb/parallel_for.h>

#include "core/error.h"
#include "photogrammetry/pipeline/step_report.h"
#include "photogrammetry/texture/texture_bake.h"
#include "scene/ray_caster.h"

namespace cinepath::photogrammetry {
namespace {

namespace fs = std::filesystem;

// Mean linear colour of face f in a photo: its centroid and three points near its corners.
Eigen::Vector3f FaceColor(const TriangleMesh& mesh, uint32_t f, const TextureView& view, const RgbImage& photo,
                          bool* ok) {
  const auto& t = mesh.faces[f];
  const Eigen::Vector3d centroid = (mesh.vertices_m[t[0]] + mesh.vertices_m[t[1]] + mesh.vertices_m[t[2]]) / 3;
  Eigen::Vector3f sum = Eigen::Vector3f::Zero();
  *ok = true;
  for (int k = -1; k < 3; ++k) {
    const Eigen::Vector3d p = k < 0 ? centroid : Eigen::Vector3d(0.6 * mesh.vertices_m[t[k]] + 0.4 * centroid);
    Eigen::Vector2d px;
    if (!view.Project(p, &px)) {
      *ok = false;
      return sum;
    }
    sum += SampleLinear(photo, px.x(), px.y());
  }
  return sum / 4.0f;
}

Json Rounded3(const Eigen::Vector3f& v, int decimals) {
  return Json::array(
      {RoundToDecimals(v.x(), decimals), RoundToDecimals(v.y(), decimals), RoundToDecimals(v.z(), decimals)});
}

// The output mesh: the input's faces in order, their vertices split where charts meet, each with its texture
// coordinates; white on faces a photo textures, the input's colours (or grey) on the others.
void SplitVerticesPerChart(const TriangleMesh& mesh, const TextureAtlas& atlas, TexturedMesh* out) {
  std::map<std::pair<int, uint32_t>, uint32_t> vertex_of;  // (chart, input vertex) -> output vertex
  const std::array<uint8_t, 3> white = {255, 255, 255}, grey = {128, 128, 128};
  out->mesh.faces.resize(mesh.num_faces());
  const float inv = 1.0f / float(atlas.size_px);
  for (uint32_t f = 0; f < mesh.num_faces(); ++f) {
    const int chart = atlas.face_chart[f];
    const bool textured = atlas.charts[size_t(chart)].view >= 0;
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = mesh.faces[f][size_t(k)];
      const auto [it, inserted] = vertex_of.emplace(std::make_pair(chart, v), uint32_t(out->mesh.vertices_m.size()));
      if (inserted) {
        out->mesh.vertices_m.push_back(mesh.vertices_m[v]);
        out->mesh.colors_rgb.push_back(textured ? white : (mesh.has_colors() ? mesh.colors_rgb[v] : grey));
        out->texcoords.push_back(atlas.corner_texel[f][size_t(k)] * inv);
      }
      out->mesh.faces[f][size_t(k)] = it->second;
    }
  }
}

// scene.json's "texture" (without times): the photos and their use, the selection, the exposure, the atlas.
Json TextureReport(const TriangleMesh& mesh, const std::vector<TextureView>& views, const ViewSelection& selection,
                   const ExposureGains& gains, const TextureAtlas& atlas, const BakeStats& bake_stats,
                   const TexturedMesh& out, const MeshTextureOptions& options) {
  Json report = Json::object();
  int64_t textured_faces = 0;
  std::vector<int64_t> faces_per_view(views.size(), 0);
  for (int l : selection.label) {
    if (l >= 0) {
      ++textured_faces;
      ++faces_per_view[size_t(l)];
    }
  }
  report["photos"] = int64_t(views.size());
  Json per_photo = Json::array();
  int photos_used = 0;
  for (size_t v = 0; v < views.size(); ++v) {
    photos_used += faces_per_view[v] > 0;
    per_photo.push_back(
        {{"image", views[v].name()}, {"faces", faces_per_view[v]}, {"gain_rgb", Rounded3(gains.gain[v], 4)}});
  }
  report["photos_used"] = photos_used;
  report["faces"] = int64_t(mesh.num_faces());
  report["faces_textured"] = textured_faces;
  report["faces_vertex_color"] = int64_t(mesh.num_faces()) - textured_faces;
  report["selection"] = {{"min_cosine", options.selection.min_cosine},
                         {"seam_penalty", options.selection.seam_penalty},
                         {"iterations", selection.iterations_run},
                         {"seam_edges_best_view", selection.seam_edges_before},
                         {"seam_edges", selection.seam_edges_after},
                         {"photo_consistency", options.selection.consistency.enabled},
                         {"views_inconsistent", selection.views_inconsistent},
                         {"faces_with_inconsistent_views", selection.faces_with_inconsistent_views}};
  report["exposure"] = {{"leveled", options.level_exposure},
                        {"pairs_used", gains.pairs_used},
                        {"pairs_rejected", gains.pairs_rejected},
                        {"rms_linear_before", RoundToDecimals(gains.rms_before, 5)},
                        {"rms_linear_after", RoundToDecimals(gains.rms_after, 5)}};
  report["atlas"] = {
      {"width_px", atlas.size_px},
      {"height_px", atlas.size_px},
      {"charts", int64_t(atlas.charts.size())},
      {"texels_per_photo_pixel", RoundToDecimals(atlas.texels_per_pixel, 4)},
      {"padding_px", atlas.padding_px},
      {"texels_covered", bake_stats.texels_covered},
      {"fill", RoundToDecimals(double(bake_stats.texels_covered) / (double(atlas.size_px) * atlas.size_px), 4)},
      {"mime_type", out.mime_type},
      {"jpeg_quality", options.format == TextureFormat::kJpeg ? Json(options.jpeg_quality) : Json(nullptr)},
      {"bytes", int64_t(out.image_bytes.size())}};
  report["vertices_out"] = int64_t(out.mesh.num_vertices());
  report["photo_gains"] = per_photo;
  return report;
}

}  // namespace

int DefaultTexturePx(Quality quality) {
  switch (quality) {
    case Quality::kDraft: return 2048;
    case Quality::kStandard: return 4096;
    case Quality::kFinal: return 8192;
  }
  return 4096;
}

void MeshTextureOptions::Check() const {
  if (texture_px < 64 || texture_px > 16384) {
    throw InputError("texture_px: must be between 64 and 16384, got " + std::to_string(texture_px));
  }
  if (jpeg_quality < 1 || jpeg_quality > 100) throw InputError("jpeg_quality: must be in 1..100");
}

TexturedMesh TextureMesh(const TriangleMesh& mesh, const std::vector<TextureView>& views,
                         const std::vector<RgbImage>& photos, const MeshTextureOptions& options) {
  options.Check();
  CINEPATH_CHECK(photos.size() == views.size());
  if (mesh.num_faces() == 0) throw InputError("texture: the mesh has no faces");
  Json times = Json::object();

  // 1. Which photo textures each face.
  StepTimer timer;
  scene::SceneMesh scene_mesh;
  scene_mesh.positions_enu_m = mesh.vertices_m;
  scene_mesh.faces = mesh.faces;
  const scene::RayCaster caster(scene_mesh);
  const FaceColorFn face_color = [&](uint32_t f, int v, Eigen::Vector3f* rgb) {
    bool ok = false;
    *rgb = FaceColor(mesh, f, views[size_t(v)], photos[size_t(v)], &ok);
    return ok;
  };
  const ViewSelection selection = SelectViews(mesh, views, caster, options.selection, &face_color);
  times["view_selection_s"] = timer.RoundedSeconds();

  // 2. Exposure gains from the faces two or more photos see.
  timer.Restart();
  ExposureGains gains;
  gains.gain.assign(views.size(), Eigen::Vector3f::Ones());
  if (options.level_exposure) {
    std::vector<OverlapSample> samples(mesh.num_faces());
    tbb::parallel_for(size_t(0), mesh.num_faces(), [&](size_t f) {
      if (selection.candidates[f].size() < 2) return;
      for (const FaceView& c : selection.candidates[f]) {
        bool ok = false;
        const Eigen::Vector3f color = FaceColor(mesh, uint32_t(f), views[size_t(c.view)], photos[size_t(c.view)], &ok);
        if (ok) samples[f].colors.emplace_back(c.view, color);
      }
    });
    samples.erase(
        std::remove_if(samples.begin(), samples.end(), [](const OverlapSample& s) { return s.colors.size() < 2; }),
        samples.end());
    gains = FitExposureGains(int(views.size()), samples, options.exposure);
  }
  times["exposure_s"] = timer.RoundedSeconds();

  // 3. Charts and their place in the atlas.
  timer.Restart();
  TextureAtlasOptions atlas_options;
  atlas_options.size_px = options.texture_px;
  atlas_options.padding_px = options.padding_px;
  const TextureAtlas atlas = BuildTextureAtlas(mesh, views, selection.label, atlas_options);
  times["atlas_s"] = timer.RoundedSeconds();

  // 4. The texels.
  timer.Restart();
  std::vector<const RgbImage*> photo_ptrs;
  for (const RgbImage& p : photos) photo_ptrs.push_back(&p);
  BakeStats bake_stats;
  TexturedMesh out;
  out.atlas = BakeTextureAtlas(mesh, views, photo_ptrs, gains.gain, atlas, &bake_stats);
  times["bake_s"] = timer.RoundedSeconds();

  // 5. Vertices split per chart, with their texture coordinates.
  timer.Restart();
  SplitVerticesPerChart(mesh, atlas, &out);

  // 6. The atlas encoded.
  if (options.format == TextureFormat::kJpeg) {
    out.image_bytes = EncodeJpeg(out.atlas, options.jpeg_quality);
    out.mime_type = "image/jpeg";
  } else {
    out.image_bytes = EncodePng(out.atlas);
    out.mime_type = "image/png";
  }
  times["encode_s"] = timer.RoundedSeconds();

  Json report = TextureReport(mesh, views, selection, gains, atlas, bake_stats, out, options);
  if (options.report_times) report["time_s"] = times;
  out.report = std::move(report);
  return out;
}

TexturedMesh TextureMeshFromPhotos(const TriangleMesh& mesh, const ColmapModel& model_enu,
                                   const std::string& images_dir, const MeshTextureOptions& options,
                                   std::vector<std::string>* inputs) {
  options.Check();
  StepTimer timer;
  std::vector<TextureView> views;
  std::vector<fs::path> paths;
  Json missing = Json::array(), excluded = Json::array();
  for (const auto& [id, image] : model_enu.images) {
    const auto camera = model_enu.cameras.find(image.camera_id);
    if (camera == model_enu.cameras.end()) continue;
    if (std::find(options.excluded_images.begin(), options.excluded_images.end(), image.name) !=
        options.excluded_images.end()) {
      excluded.push_back(image.name);
      continue;
    }
    const fs::path path = fs::path(images_dir) / image.name;
    if (!fs::is_regular_file(path)) {
      missing.push_back(image.name);
      continue;
    }
    views.emplace_back(image, camera->second);
    paths.push_back(path);
  }
  for (const std::string& name : options.excluded_images) {
    if (std::find(excluded.begin(), excluded.end(), Json(name)) == excluded.end()) {
      throw InputError("texture_exclude: '" + name + "' is not a registered image of the model");
    }
  }
  std::vector<RgbImage> photos(views.size());
  tbb::parallel_for(size_t(0), views.size(), [&](size_t v) { photos[v] = ReadPhotoRgb8(paths[v]); });
  for (size_t v = 0; v < views.size(); ++v) {
    if (photos[v].width != views[v].width_px() || photos[v].height != views[v].height_px()) {
      throw InputError(Located(paths[v].string(), "the photo is " + std::to_string(photos[v].width) + " x " +
                                                      std::to_string(photos[v].height) + " px, its camera " +
                                                      std::to_string(views[v].width_px()) + " x " +
                                                      std::to_string(views[v].height_px())));
    }
    if (inputs) inputs->push_back(paths[v].string());
  }
  const double load_s = timer.RoundedSeconds();
  TexturedMesh out = TextureMesh(mesh, views, photos, options);
  out.report["photos_missing"] = missing;
  out.report["photos_excluded"] = excluded;
  if (options.report_times) out.report["time_s"]["read_photos_s"] = load_s;
  return out;
}

}  // namespace cinepath::photogrammetry
