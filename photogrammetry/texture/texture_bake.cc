#include "photogrammetry/texture/texture_bake.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include <tbb/parallel_for.h>

#include "core/error.h"

namespace cinepath::photogrammetry {
namespace {

constexpr uint8_t kBackground = 128;

struct ChartStats {
  int64_t covered = 0, padding = 0;
};

ChartStats BakeChart(const TriangleMesh& mesh, const TextureView* view, const RgbImage* photo,
                     const Eigen::Vector3f& gain, const TextureAtlas& atlas, const TextureChart& chart, RgbImage* out) {
  ChartStats stats;
  const int w = chart.w, h = chart.h;
  std::vector<uint8_t> filled(size_t(w) * h, 0);
  std::vector<Eigen::Vector3f> color(size_t(w) * h, Eigen::Vector3f::Zero());  // linear
  if (chart.view < 0) {
    std::fill(filled.begin(), filled.end(), 1);
    std::fill(color.begin(), color.end(), Eigen::Vector3f::Ones());
  } else {
    for (uint32_t f : chart.faces) {
      const auto& t = atlas.corner_texel[f];
      const Eigen::Vector2d a = t[0].cast<double>(), b = t[1].cast<double>(), c = t[2].cast<double>();
      const double det = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
      if (std::abs(det) < 1e-12) continue;
      const int x0 = std::max(chart.x, int(std::floor(std::min({a.x(), b.x(), c.x()}) - 0.5)));
      const int x1 = std::min(chart.x + w - 1, int(std::ceil(std::max({a.x(), b.x(), c.x()}) - 0.5)));
      const int y0 = std::max(chart.y, int(std::floor(std::min({a.y(), b.y(), c.y()}) - 0.5)));
      const int y1 = std::min(chart.y + h - 1, int(std::ceil(std::max({a.y(), b.y(), c.y()}) - 0.5)));
      const Eigen::Vector3d& pa = mesh.vertices_m[mesh.faces[f][0]];
      const Eigen::Vector3d& pb = mesh.vertices_m[mesh.faces[f][1]];
      const Eigen::Vector3d& pc = mesh.vertices_m[mesh.faces[f][2]];
      for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
          const Eigen::Vector2d p(x + 0.5, y + 0.5);
          const double l1 = ((p - a).x() * (c - a).y() - (p - a).y() * (c - a).x()) / det;
          const double l2 = ((b - a).x() * (p - a).y() - (b - a).y() * (p - a).x()) / det;
          const double l0 = 1 - l1 - l2;
          constexpr double kEdge = -1e-7;
          if (l0 < kEdge || l1 < kEdge || l2 < kEdge) continue;
          const size_t i = size_t(y - chart.y) * w + size_t(x - chart.x);
          if (filled[i]) continue;  // a texel on a shared edge: the first face in index order keeps it
          Eigen::Vector2d px;
          if (!view->Project(l0 * pa + l1 * pb + l2 * pc, &px)) continue;
          color[i] = SampleLinear(*photo, px.x(), px.y()).cwiseProduct(gain);
          filled[i] = 1;
          ++stats.covered;
        }
      }
    }
    // Dilation: each ring takes the mean of its covered 8-neighbours (computed from the previous ring).
    for (int ring = 0; ring < atlas.padding_px + 2; ++ring) {
      std::vector<uint8_t> next = filled;
      for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
          const size_t i = size_t(y) * w + x;
          if (filled[i]) continue;
          Eigen::Vector3f sum = Eigen::Vector3f::Zero();
          int count = 0;
          for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
              const int xx = x + dx, yy = y + dy;
              if (xx < 0 || yy < 0 || xx >= w || yy >= h) continue;
              const size_t j = size_t(yy) * w + xx;
              if (filled[j]) {
                sum += color[j];
                ++count;
              }
            }
          }
          if (count > 0) {
            color[i] = sum / float(count);
            next[i] = 1;
            ++stats.padding;
          }
        }
      }
      filled.swap(next);
    }
  }
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      uint8_t* o = out->At(chart.x + x, chart.y + y);
      for (int k = 0; k < 3; ++k) o[k] = filled[i] ? SrgbFromLinear(color[i][k]) : kBackground;
    }
  }
  return stats;
}

}  // namespace

RgbImage BakeTextureAtlas(const TriangleMesh& mesh, const std::vector<TextureView>& views,
                          const std::vector<const RgbImage*>& photos, const std::vector<Eigen::Vector3f>& gains,
                          const TextureAtlas& atlas, BakeStats* stats) {
  CINEPATH_CHECK(photos.size() == views.size());
  RgbImage out;
  out.width = out.height = atlas.size_px;
  out.rgb.assign(size_t(atlas.size_px) * atlas.size_px * 3, kBackground);
  std::vector<ChartStats> chart_stats(atlas.charts.size());
  tbb::parallel_for(size_t(0), atlas.charts.size(), [&](size_t c) {
    const TextureChart& chart = atlas.charts[c];
    const TextureView* view = chart.view >= 0 ? &views[size_t(chart.view)] : nullptr;
    const RgbImage* photo = chart.view >= 0 ? photos[size_t(chart.view)] : nullptr;
    if (chart.view >= 0 && (photo == nullptr || photo->empty())) {
      throw InternalError("texture bake: no photo for " + view->name());
    }
    const Eigen::Vector3f gain =
        chart.view >= 0 && size_t(chart.view) < gains.size() ? gains[size_t(chart.view)] : Eigen::Vector3f::Ones();
    chart_stats[c] = BakeChart(mesh, view, photo, gain, atlas, chart, &out);
  });
  if (stats) {
    *stats = {};
    for (const ChartStats& s : chart_stats) {
      stats->texels_covered += s.covered;
      stats->texels_padding += s.padding;
    }
  }
  return out;
}

}  // namespace cinepath::photogrammetry
