#include "preview/texture.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include <tbb/parallel_for.h>

#include "core/error.h"

namespace cinepath::preview {
namespace {

float SrgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

// Linear light of each 8-bit sRGB value, as OpenImageIO's 8-bit to float conversion gives it (v times
// 1/255 in float; measured: all 256 values equal) and then converted: the same texels as decoding to
// floats first.
// (Filled when the module loads, so a lookup reads it without a guard.)
const std::array<float, 256> kLinearFromSrgb8 = [] {
  std::array<float, 256> t{};
  for (int v = 0; v < 256; ++v) t[size_t(v)] = SrgbToLinear(float(v) * (1.0f / 255.0f));
  return t;
}();

// floor() without the library call (SSE2 has no rounding instruction): exact for |x| < 2^23, where every
// float's truncation is an integer held exactly; anything else (huge, NaN) goes to std::floor.
float FloorOf(float x) {
  if (!(std::fabs(x) < 8388608.0f)) return std::floor(x);
  const float t = float(long(x));
  return t > x ? t - 1 : t;
}

}  // namespace

Eigen::Vector3f TextureLevel::Sample(const Eigen::Vector2f& uv) const {
  if (srgb.empty()) return Eigen::Vector3f::Ones();
  const float x = uv.x() * width - 0.5f, y = uv.y() * height - 0.5f;
  const float fx = FloorOf(x), fy = FloorOf(y);
  const float wx = x - fx, wy = y - fy;
  const float* linear = kLinearFromSrgb8.data();
  // Wrapped once per axis (a division each, only off the texture), not per texel: the neighbour is the
  // next or the first.
  auto wrap = [](long i, long n) { return i >= 0 && i < n ? i : ((i % n) + n) % n; };
  const long i0 = wrap(long(fx), width), j0 = wrap(long(fy), height);
  const size_t step_x = i0 + 1 == width ? size_t(0) - size_t(i0) * 3 : 3;  // to the next texel, or back to the first
  const size_t row = size_t(width) * 3;
  const size_t step_y = j0 + 1 == height ? size_t(0) - size_t(j0) * row : row;
  const uint8_t* p00 = srgb.data() + size_t(j0) * row + size_t(i0) * 3;
  const uint8_t* p10 = p00 + step_x;
  const uint8_t* p01 = p00 + step_y;
  const uint8_t* p11 = p01 + step_x;
  // Per channel, in the order of the vector expression it replaces, (1 - wy) ((1 - wx) t00 + wx t10) +
  // wy ((1 - wx) t01 + wx t11): the same floats. Written out channel by channel (no loop to count).
  const float ax = 1 - wx, ay = 1 - wy;
  auto channel = [&](int c) {
    const float top = ax * linear[p00[c]] + wx * linear[p10[c]];
    const float bottom = ax * linear[p01[c]] + wx * linear[p11[c]];
    return ay * top + wy * bottom;
  };
  return Eigen::Vector3f(channel(0), channel(1), channel(2));
}

std::vector<uint8_t> TextureRowsSampled(const scene::SceneMesh& mesh, size_t image, int height) {
  std::vector<uint8_t> rows(size_t(std::max(0, height)), 0);
  if (height <= 0 || !mesh.has_texcoords() || mesh.face_material.size() != mesh.faces.size()) return rows;
  const long h = height;
  constexpr long kRowMargin = 2;
  // First the vertices' whole v range (a few instructions a vertex): when its rows, as below, span the
  // texture, so may the faces' (a mesh mapped over its whole texture: the large scene's million faces
  // cost 83 M instructions face by face), and every row is taken without looking at the faces.
  const Eigen::Vector2f* uv = mesh.texcoords.data();
  float v_min = uv[0].y(), v_max = uv[0].y();
  for (size_t i = 0; i < mesh.texcoords.size(); ++i) {
    v_min = std::min(v_min, uv[i].y());
    v_max = std::max(v_max, uv[i].y());
  }
  if (!(v_min > -1e6f && v_max < 1e6f) ||  // an infinity, a far-off v: any row (a NaN is found face by face)
      std::floor(double(v_max) * h - 0.5) - std::floor(double(v_min) * h - 0.5) + 1 + 2 * kRowMargin + 1 >= h) {
    std::fill(rows.begin(), rows.end(), 1);
    return rows;
  }
  // A difference array over the rows: +1 where a face's rows begin, -1 after they end.
  std::vector<int> starts(size_t(height) + 1, 0);
  std::vector<uint8_t> takes_image(mesh.materials.size());  // per material: its base colour is this image
  for (size_t m = 0; m < takes_image.size(); ++m) takes_image[m] = mesh.materials[m].base_color_image == int(image);
  for (size_t face = 0; face < mesh.faces.size(); ++face) {
    const size_t m = size_t(mesh.face_material[face]);  // -1 (none) wraps past the end
    if (m >= takes_image.size() || !takes_image[m]) continue;
    const auto& f = mesh.faces[face];
    const float v0 = uv[f[0]].y(), v1 = uv[f[1]].y(), v2 = uv[f[2]].y();
    // A NaN, infinite or far-off v (the texture repeated a million times over): any row.
    constexpr float kFar = 1e6f;
    if (!(std::fabs(v0) < kFar && std::fabs(v1) < kFar && std::fabs(v2) < kFar)) {
      std::fill(rows.begin(), rows.end(), 1);
      return rows;
    }
    const double lo_v = std::min(v0, std::min(v1, v2)), hi_v = std::max(v0, std::max(v1, v2));
    // TextureLevel::Sample reads rows floor(v h - 1/2) and the next; kRowMargin more each side for the
    // barycentric interpolation's rounding (a hit's u, v and the uv are floats). (A floor by truncation:
    // exact here, where |v h| < 2^52, and without a library call for each of a million faces.)
    auto floor_of = [](double y) {
      const double t = double(long(y));
      return long(t > y ? t - 1 : t);
    };
    const long lo_y = floor_of(lo_v * h - 0.5) - kRowMargin, hi_y = floor_of(hi_v * h - 0.5) + 1 + kRowMargin;
    if (hi_y - lo_y + 1 >= h) {
      std::fill(rows.begin(), rows.end(), 1);
      return rows;
    }
    const long lo = lo_y >= 0 && lo_y < h ? lo_y : ((lo_y % h) + h) % h;  // REPEAT: rows wrap
    const long hi = lo + (hi_y - lo_y);
    if (hi < h) {
      ++starts[size_t(lo)];
      --starts[size_t(hi) + 1];
    } else {
      ++starts[size_t(lo)];
      --starts[size_t(h)];
      ++starts[0];
      --starts[size_t(hi - h) + 1];
    }
  }
  int open = 0;
  for (size_t r = 0; r < rows.size(); ++r) rows[r] = (open += starts[r]) > 0;
  return rows;
}

int PyramidLevels(int width, int height, int max_levels) {
  int levels = 1;
  for (int side = std::min(width, height); side > 1 && levels < max_levels; side /= 2) ++levels;
  return levels;
}

std::vector<std::vector<uint8_t>> TextureLevelRowsSampled(const scene::SceneMesh& mesh, size_t image, int height,
                                                          int levels) {
  std::vector<int> heights{std::max(0, height)};
  for (int k = 1; k < levels; ++k) heights.push_back(std::max(1, heights.back() / 2));
  std::vector<std::vector<uint8_t>> rows(heights.size());
  for (size_t k = heights.size(); k-- > 0;) {
    rows[k] = TextureRowsSampled(mesh, image, heights[k]);
    if (k + 1 == heights.size()) continue;
    // The rows of this level that the next level's wanted rows are averaged from.
    const std::vector<uint8_t>& below = rows[k + 1];
    for (size_t j = 0; j < below.size(); ++j) {
      if (!below[j]) continue;
      rows[k][std::min(2 * j, rows[k].size() - 1)] = 1;
      rows[k][std::min(2 * j + 1, rows[k].size() - 1)] = 1;
    }
  }
  return rows;
}

void BuildCoarserLevels(Texture* texture, const std::vector<std::vector<uint8_t>>& rows) {
  texture->coarser.clear();
  if (texture->srgb.empty()) return;
  const float* linear = kLinearFromSrgb8.data();
  for (size_t k = 1; k < rows.size(); ++k) {
    const TextureLevel& above = k == 1 ? static_cast<const TextureLevel&>(*texture) : texture->coarser[k - 2];
    TextureLevel level;
    level.width = std::max(1, above.width / 2);
    level.height = std::max(1, above.height / 2);
    if (rows[k].size() != size_t(level.height)) throw InternalError("BuildCoarserLevels: rows of another height");
    level.srgb.resize(size_t(level.width) * level.height * 3);
    const size_t above_row = size_t(above.width) * 3;
    tbb::parallel_for(tbb::blocked_range<int>(0, level.height), [&](const tbb::blocked_range<int>& range) {
      std::vector<float> mean(size_t(level.width) * 3);  // a row's linear means, then encoded at once
      for (int j = range.begin(); j < range.end(); ++j) {
        if (!rows[k][size_t(j)]) continue;
        const uint8_t* top = above.srgb.data() + size_t(std::min(2 * j, above.height - 1)) * above_row;
        const uint8_t* bottom = above.srgb.data() + size_t(std::min(2 * j + 1, above.height - 1)) * above_row;
        for (int i = 0; i < level.width; ++i) {
          const size_t left = size_t(std::min(2 * i, above.width - 1)) * 3;
          const size_t right = size_t(std::min(2 * i + 1, above.width - 1)) * 3;
          for (int c = 0; c < 3; ++c) {
            mean[size_t(i) * 3 + c] = 0.25f * ((linear[top[left + c]] + linear[top[right + c]]) +
                                               (linear[bottom[left + c]] + linear[bottom[right + c]]));
          }
        }
        LinearToSrgb8ByTable(mean.data(), mean.size(), level.srgb.data() + size_t(j) * level.width * 3);
      }
    });
    texture->coarser.push_back(std::move(level));
  }
}

namespace {

Texture DecodeTexture(const scene::SceneMesh& mesh, size_t index, int max_levels) {
  const scene::SceneImage& image = mesh.images[index];
  std::vector<std::vector<uint8_t>> rows;
  Srgb8Image decoded = DecodeSrgb8(
      image.encoded, "images[" + std::to_string(index) + "] (" + image.mime_type + ")", [&](int width, int height) {
        rows = TextureLevelRowsSampled(mesh, index, height, PyramidLevels(width, height, max_levels));
        return rows[0];
      });
  Texture texture;
  texture.width = decoded.width;
  texture.height = decoded.height;
  texture.srgb = std::move(decoded.rgb);
  // A PNG is decoded in full, without asking for its rows.
  if (rows.empty())
    rows =
        TextureLevelRowsSampled(mesh, index, texture.height, PyramidLevels(texture.width, texture.height, max_levels));
  BuildCoarserLevels(&texture, rows);
  return texture;
}

}  // namespace

std::vector<Texture> DecodeTextures(const scene::SceneMesh& mesh, int max_levels) {
  std::vector<Texture> textures;
  for (size_t i = 0; i < mesh.images.size(); ++i) textures.push_back(DecodeTexture(mesh, i, max_levels));
  return textures;
}

std::vector<float> FaceTexelsPerMetre(const scene::SceneMesh& mesh, const std::vector<Texture>& textures) {
  std::vector<float> density(mesh.faces.size(), 0.0f);
  if (!mesh.has_texcoords() || mesh.face_material.size() != mesh.faces.size()) return density;
  for (size_t face = 0; face < mesh.faces.size(); ++face) {
    const int m = mesh.face_material[face];
    if (m < 0 || size_t(m) >= mesh.materials.size()) continue;
    const int image = mesh.materials[size_t(m)].base_color_image;
    if (image < 0 || size_t(image) >= textures.size() || textures[size_t(image)].srgb.empty()) continue;
    const Texture& texture = textures[size_t(image)];
    const auto& f = mesh.faces[face];
    const Eigen::Vector2d t0 = mesh.texcoords[f[0]].cast<double>(), t1 = mesh.texcoords[f[1]].cast<double>(),
                          t2 = mesh.texcoords[f[2]].cast<double>();
    const Eigen::Vector2d a = (t1 - t0).cwiseProduct(Eigen::Vector2d(texture.width, texture.height));
    const Eigen::Vector2d b = (t2 - t0).cwiseProduct(Eigen::Vector2d(texture.width, texture.height));
    const double texels2 = 0.5 * std::fabs(a.x() * b.y() - a.y() * b.x());
    const Eigen::Vector3d& p0 = mesh.positions_enu_m[f[0]];
    const double metres2 = 0.5 * (mesh.positions_enu_m[f[1]] - p0).cross(mesh.positions_enu_m[f[2]] - p0).norm();
    if (metres2 > 0 && std::isfinite(texels2 / metres2)) density[face] = float(std::sqrt(texels2 / metres2));
  }
  return density;
}

}  // namespace cinepath::preview
