#include "core/geoid.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <mutex>

#include "core/angles.h"
#include "core/error.h"
#include "core/file_io.h"

namespace cinepath {
namespace {

// The .gtx grid is big-endian; convert to host order.
template <typename T>
T ReadBigEndian(const std::string& bytes, size_t offset) {
  static_assert(sizeof(T) == 4 || sizeof(T) == 8);
  using U = std::conditional_t<sizeof(T) == 4, uint32_t, uint64_t>;
  U u;
  std::memcpy(&u, bytes.data() + offset, sizeof(U));
  if constexpr (std::endian::native == std::endian::little) {
    if constexpr (sizeof(U) == 4)
      u = __builtin_bswap32(u);
    else
      u = __builtin_bswap64(u);
  }
  T value;
  std::memcpy(&value, &u, sizeof(T));
  return value;
}

}  // namespace

Egm96Geoid::Egm96Geoid(const std::filesystem::path& gtx_path) {
  const std::string source = gtx_path.string();
  std::string bytes;
  try {
    bytes = ReadFileToString(gtx_path);
  } catch (const InputError& e) {
    throw InputError(std::string(e.what()) +
                     " (the EGM96 grid comes with Debian's proj-data package; set CINEPATH_EGM96_GTX "
                     "to use another copy)");
  }
  constexpr size_t kHeaderBytes = 4 * 8 + 2 * 4;
  if (bytes.size() < kHeaderBytes) {
    throw InputError(source + ": byte 0: truncated .gtx header (" + std::to_string(bytes.size()) + " bytes)");
  }
  lat0_deg_ = ReadBigEndian<double>(bytes, 0);
  lon0_deg_ = ReadBigEndian<double>(bytes, 8);
  dlat_deg_ = ReadBigEndian<double>(bytes, 16);
  dlon_deg_ = ReadBigEndian<double>(bytes, 24);
  rows_ = ReadBigEndian<int32_t>(bytes, 32);
  cols_ = ReadBigEndian<int32_t>(bytes, 36);
  if (!(dlat_deg_ > 0) || !(dlon_deg_ > 0) || rows_ < 2 || cols_ < 2 || !std::isfinite(lat0_deg_) ||
      !std::isfinite(lon0_deg_) || rows_ > 100000 || cols_ > 100000) {
    throw InputError(source + ": byte 0: implausible .gtx header");
  }
  const size_t n = static_cast<size_t>(rows_) * static_cast<size_t>(cols_);
  if (bytes.size() != kHeaderBytes + 4 * n) {
    throw InputError(source + ": byte " + std::to_string(bytes.size()) + ": expected " +
                     std::to_string(kHeaderBytes + 4 * n) + " bytes for a " + std::to_string(rows_) + "x" +
                     std::to_string(cols_) + " grid");
  }
  grid_m_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const float v = ReadBigEndian<float>(bytes, kHeaderBytes + 4 * i);
    if (!std::isfinite(v) || std::fabs(v) > 200.0f) {
      throw InputError(source + ": byte " + std::to_string(kHeaderBytes + 4 * i) + ": implausible undulation");
    }
    grid_m_[i] = v;
  }
}

std::filesystem::path Egm96Geoid::DefaultPath() {
  if (const char* env = std::getenv("CINEPATH_EGM96_GTX"); env && *env) return env;
  return "/usr/share/proj/egm96_15.gtx";
}

const Egm96Geoid& Egm96Geoid::Default() {
  static std::once_flag once;
  static std::unique_ptr<Egm96Geoid> geoid;
  std::call_once(once, [] { geoid = std::make_unique<Egm96Geoid>(DefaultPath()); });
  return *geoid;
}

double Egm96Geoid::UndulationM(double lat_deg, double lon_deg) const {
  if (!std::isfinite(lat_deg) || !std::isfinite(lon_deg)) {
    throw InputError("geoid: latitude and longitude must be finite");
  }
  // Row coordinate, clamped to the grid (the grid spans the poles).
  double r = (std::clamp(lat_deg, -90.0, 90.0) - lat0_deg_) / dlat_deg_;
  r = std::clamp(r, 0.0, static_cast<double>(rows_ - 1));
  // Column coordinate, wrapped in longitude.
  const double span_deg = dlon_deg_ * cols_;
  double c = (lon_deg - lon0_deg_) / dlon_deg_;
  const bool global = std::fabs(span_deg - 360.0) < 1e-9;
  if (global) {
    c = std::fmod(c, static_cast<double>(cols_));
    if (c < 0) c += cols_;
  } else {
    c = std::clamp(c, 0.0, static_cast<double>(cols_ - 1));
  }
  const int r0 = std::min(static_cast<int>(std::floor(r)), rows_ - 2);
  int c0 = static_cast<int>(std::floor(c));
  if (c0 >= cols_) c0 = cols_ - 1;
  const double fr = r - r0;
  const double fc = c - c0;
  const int c1 = global ? (c0 + 1) % cols_ : std::min(c0 + 1, cols_ - 1);
  auto at = [&](int row, int col) { return static_cast<double>(grid_m_[static_cast<size_t>(row) * cols_ + col]); };
  const double south = at(r0, c0) * (1 - fc) + at(r0, c1) * fc;
  const double north = at(r0 + 1, c0) * (1 - fc) + at(r0 + 1, c1) * fc;
  return south * (1 - fr) + north * fr;
}

}  // namespace cinepath
