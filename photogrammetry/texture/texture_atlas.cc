#include "photogrammetry/texture/texture_atlas.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#define STBRP_STATIC
#define STB_RECT_PACK_IMPLEMENTATION
#include <stb/stb_rect_pack.h>

#include "core/error.h"
#include "photogrammetry/mesh/union_find.h"
#include "photogrammetry/texture/texture_view_selection.h"

namespace cinepath::photogrammetry {
namespace {

int Ceil(double x) { return int(std::ceil(x - 1e-9)); }

// Packs every chart at `scale`; true when all fit.
bool Pack(std::vector<TextureChart>& charts, double scale, int size, int padding) {
  std::vector<stbrp_rect> rects(charts.size());
  for (size_t i = 0; i < charts.size(); ++i) {
    const TextureChart& c = charts[i];
    const int w = c.view < 0 ? 2 : Ceil(c.box_px.sizes().x() * scale) + 1;
    const int h = c.view < 0 ? 2 : Ceil(c.box_px.sizes().y() * scale) + 1;
    rects[i].id = int(i);
    rects[i].w = w + 2 * padding;
    rects[i].h = h + 2 * padding;
    if (rects[i].w > size || rects[i].h > size) return false;
  }
  std::vector<stbrp_node> nodes(size_t(size) * 2);
  stbrp_context context;
  stbrp_init_target(&context, size, size, nodes.data(), int(nodes.size()));
  stbrp_setup_heuristic(&context, STBRP_HEURISTIC_Skyline_BF_sortHeight);
  if (!stbrp_pack_rects(&context, rects.data(), int(rects.size()))) return false;
  for (const stbrp_rect& r : rects) {
    TextureChart& c = charts[size_t(r.id)];
    c.x = r.x;
    c.y = r.y;
    c.w = r.w;
    c.h = r.h;
  }
  return true;
}

}  // namespace

TextureAtlas BuildTextureAtlas(const TriangleMesh& mesh, const std::vector<TextureView>& views,
                               const std::vector<int>& label, const TextureAtlasOptions& options) {
  const size_t n = mesh.num_faces();
  CINEPATH_CHECK(label.size() == n);
  TextureAtlas atlas;
  atlas.size_px = options.size_px;
  atlas.padding_px = options.padding_px;
  atlas.face_chart.assign(n, -1);
  atlas.corner_texel.resize(n);

  // Charts: faces of one photo joined across their shared edges.
  UnionFind components(n);
  for (const auto& [a, b] : FaceEdgeNeighbours(mesh)) {
    if (label[a] >= 0 && label[a] == label[b]) components.Unite(a, b);
  }
  std::vector<int> chart_of_root(n, -1);
  std::vector<std::array<Eigen::Vector2d, 3>> corner_px(n);
  bool any_unseen = false;
  for (uint32_t f = 0; f < n; ++f) {
    if (label[f] < 0) {
      any_unseen = true;
      continue;
    }
    const uint32_t root = components.Find(f);
    if (chart_of_root[root] < 0) {
      chart_of_root[root] = int(atlas.charts.size());
      atlas.charts.push_back(TextureChart{label[f], {}, {}, 0, 0, 0, 0});
    }
    const int c = chart_of_root[root];
    atlas.face_chart[f] = c;
    atlas.charts[size_t(c)].faces.push_back(f);
    const TextureView& view = views[size_t(label[f])];
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector2d px;
      if (!view.Project(mesh.vertices_m[mesh.faces[f][k]], &px)) {
        throw InternalError("texture atlas: a selected face does not project into its photo");
      }
      corner_px[f][size_t(k)] = px;
      atlas.charts[size_t(c)].box_px.extend(px);
    }
  }
  if (any_unseen) {
    TextureChart unseen;
    for (uint32_t f = 0; f < n; ++f) {
      if (label[f] < 0) {
        atlas.face_chart[f] = int(atlas.charts.size());
        unseen.faces.push_back(f);
      }
    }
    atlas.charts.push_back(std::move(unseen));
  }

  double area = 0;
  for (const TextureChart& c : atlas.charts) {
    if (c.view >= 0) area += (c.box_px.sizes().x() + 1) * (c.box_px.sizes().y() + 1);
  }
  const double size = options.size_px;
  double scale = area > 0 ? std::min(options.max_texels_per_pixel, std::sqrt(0.75 * size * size / area))
                          : options.max_texels_per_pixel;
  bool packed = false;
  for (int attempt = 0; attempt < 80 && !packed; ++attempt) {
    atlas.pack_attempts = attempt + 1;
    packed = Pack(atlas.charts, scale, options.size_px, options.padding_px);
    if (!packed) scale *= 0.93;
  }
  if (!packed) {
    throw RuntimeError("texture atlas: " + std::to_string(atlas.charts.size()) + " charts do not fit in " +
                       std::to_string(options.size_px) + " x " + std::to_string(options.size_px) + " texels");
  }
  atlas.texels_per_pixel = scale;

  for (uint32_t f = 0; f < n; ++f) {
    const TextureChart& c = atlas.charts[size_t(atlas.face_chart[f])];
    const Eigen::Vector2d origin(c.x + options.padding_px, c.y + options.padding_px);
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d t = c.view < 0
                                    ? Eigen::Vector2d(origin + Eigen::Vector2d(1, 1))
                                    : Eigen::Vector2d(origin + scale * (corner_px[f][size_t(k)] - c.box_px.min()) +
                                                      Eigen::Vector2d(0.5, 0.5));
      atlas.corner_texel[f][size_t(k)] = t.cast<float>();
    }
  }
  return atlas;
}

}  // namespace cinepath::photogrammetry
