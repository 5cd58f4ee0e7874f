#include "photogrammetry/io/ply_reader.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <functional>
#include <optional>
#include <sstream>
#include <vector>

#include "core/error.h"
#include "core/file_io.h"
#include "core/text_tokens.h"

namespace cinepath::photogrammetry {
namespace {

enum class Format { kAscii, kLittle, kBig };
enum class Type { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

std::optional<Type> ParseType(std::string_view s) {
  if (s == "char" || s == "int8") return Type::kInt8;
  if (s == "uchar" || s == "uint8") return Type::kUint8;
  if (s == "short" || s == "int16") return Type::kInt16;
  if (s == "ushort" || s == "uint16") return Type::kUint16;
  if (s == "int" || s == "int32") return Type::kInt32;
  if (s == "uint" || s == "uint32") return Type::kUint32;
  if (s == "float" || s == "float32") return Type::kFloat32;
  if (s == "double" || s == "float64") return Type::kFloat64;
  return std::nullopt;
}

size_t TypeSize(Type t) {
  switch (t) {
    case Type::kInt8:
    case Type::kUint8: return 1;
    case Type::kInt16:
    case Type::kUint16: return 2;
    case Type::kInt32:
    case Type::kUint32:
    case Type::kFloat32: return 4;
    case Type::kFloat64: return 8;
  }
  return 0;
}

bool IsFloat(Type t) { return t == Type::kFloat32 || t == Type::kFloat64; }

// Whether an ASCII value fits the declared integer type (floats: any finite or infinite double).
bool FitsType(Type t, double v) {
  switch (t) {
    case Type::kInt8: return v >= -128 && v <= 127;
    case Type::kUint8: return v >= 0 && v <= 255;
    case Type::kInt16: return v >= -32768 && v <= 32767;
    case Type::kUint16: return v >= 0 && v <= 65535;
    case Type::kInt32: return v >= -2147483648.0 && v <= 2147483647.0;
    case Type::kUint32: return v >= 0 && v <= 4294967295.0;
    case Type::kFloat32:
    case Type::kFloat64: return true;
  }
  return false;
}

struct Property {
  std::string name;
  Type type = Type::kFloat32;
  bool is_list = false;
  Type count_type = Type::kUint8;
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> properties;
};

// Reads values one at a time, from ASCII tokens or binary bytes, knowing where it is.
class ValueReader {
 public:
  ValueReader(std::string_view body, size_t body_offset, size_t first_line, Format format, const std::string& source)
      : body_(body), body_offset_(body_offset), line_(first_line), format_(format), source_(source) {}

  std::string Where() const {
    if (format_ == Format::kAscii) return source_ + ": line " + std::to_string(line_);
    return source_ + ": byte " + std::to_string(body_offset_ + pos_);
  }
  [[noreturn]] void Fail(const std::string& what) const { throw InputError(Located(Where(), what)); }

  // ASCII: each element instance is one line.
  void BeginInstance() {
    if (format_ != Format::kAscii) return;
    tokens_.clear();
    token_index_ = 0;
    while (true) {
      if (pos_ >= body_.size()) Fail("truncated: expected another element line");
      size_t end = body_.find('\n', pos_);
      if (end == std::string_view::npos) end = body_.size();
      const std::string_view line = body_.substr(pos_, end - pos_);
      pos_ = end + 1;
      ++line_;
      tokens_ = WhitespaceTokens(line);
      if (!tokens_.empty()) break;  // tolerate blank lines
    }
  }
  void EndInstance() {
    if (format_ == Format::kAscii && token_index_ != tokens_.size()) {
      Fail("expected " + std::to_string(token_index_) + " values, found " + std::to_string(tokens_.size()));
    }
  }

  double Read(Type type, const char* what) {
    if (format_ == Format::kAscii) {
      if (token_index_ >= tokens_.size()) Fail(std::string("missing value for ") + what);
      const std::string_view t = tokens_[token_index_++];
      double v = 0;
      const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
      if (ec != std::errc() || ptr != t.data() + t.size()) {
        Fail(std::string(what) + ": '" + std::string(t) + "' is not a number");
      }
      if (!IsFloat(type) && v != std::floor(v))
        Fail(std::string(what) + ": '" + std::string(t) + "' is not an integer");
      if (!FitsType(type, v)) Fail(std::string(what) + ": '" + std::string(t) + "' is out of range for its type");
      return v;
    }
    const size_t n = TypeSize(type);
    if (body_.size() - pos_ < n) {
      Fail(std::string("truncated: ") + what + " needs " + std::to_string(n) + " bytes, " +
           std::to_string(body_.size() - pos_) + " left");
    }
    unsigned char b[8];
    std::memcpy(b, body_.data() + pos_, n);
    pos_ += n;
    const bool swap = (format_ == Format::kBig) == (std::endian::native == std::endian::little);
    if (swap) std::reverse(b, b + n);
    switch (type) {
      case Type::kInt8: {
        int8_t v;
        std::memcpy(&v, b, 1);
        return v;
      }
      case Type::kUint8: return b[0];
      case Type::kInt16: {
        int16_t v;
        std::memcpy(&v, b, 2);
        return v;
      }
      case Type::kUint16: {
        uint16_t v;
        std::memcpy(&v, b, 2);
        return v;
      }
      case Type::kInt32: {
        int32_t v;
        std::memcpy(&v, b, 4);
        return v;
      }
      case Type::kUint32: {
        uint32_t v;
        std::memcpy(&v, b, 4);
        return v;
      }
      case Type::kFloat32: {
        float v;
        std::memcpy(&v, b, 4);
        return v;
      }
      case Type::kFloat64: {
        double v;
        std::memcpy(&v, b, 8);
        return v;
      }
    }
    return 0;
  }

  // A list's length, no more than its items could fill: the values left on the line (ASCII) or the
  // bytes left (binary).
  uint64_t ReadListCount(Type count_type, Type item_type) {
    const double count = Read(count_type, "list count");
    if (count < 0) Fail("negative list count");
    const double available = format_ == Format::kAscii ? static_cast<double>(tokens_.size() - token_index_)
                                                       : static_cast<double>(remaining_bytes() / TypeSize(item_type));
    if (count > available) {
      std::ostringstream text;
      text << count;
      Fail("list count " + text.str() + " exceeds the " +
           (format_ == Format::kAscii ? "values left on the line" : "bytes left"));
    }
    return static_cast<uint64_t>(count);
  }

  size_t remaining_bytes() const { return body_.size() - pos_; }
  void ExpectEnd() {
    if (format_ == Format::kAscii) {
      while (pos_ < body_.size()) {
        size_t end = body_.find('\n', pos_);
        if (end == std::string_view::npos) end = body_.size();
        const auto tokens = WhitespaceTokens(body_.substr(pos_, end - pos_));
        pos_ = end + 1;
        ++line_;
        if (!tokens.empty()) Fail("unexpected data after the last element");
      }
    } else if (pos_ != body_.size()) {
      Fail(std::to_string(body_.size() - pos_) + " unexpected trailing bytes after the last element");
    }
  }

 private:
  std::string_view body_;
  size_t body_offset_;
  size_t line_;
  Format format_;
  const std::string& source_;
  size_t pos_ = 0;
  std::vector<std::string_view> tokens_;
  size_t token_index_ = 0;
};

uint8_t ColorByte(double v, Type t) {
  double c = v;
  if (IsFloat(t))
    c = v * 255.0;
  else if (t == Type::kUint16)
    c = v / 257.0;
  if (!std::isfinite(c)) c = 0;
  return static_cast<uint8_t>(std::clamp(std::lround(c), 0L, 255L));
}

// The header: the format, the elements with their properties, and where the body starts.
struct PlyHeader {
  Format format = Format::kAscii;
  std::vector<Element> elements;
  size_t body_offset = 0;
  size_t lines = 0;  // header lines, the body's first line number less one
};

// One header line: "property <type> <name>" or "property list <count type> <type> <name>".
Property ParsePropertyLine(const std::vector<std::string_view>& t,
                           const std::function<void(const std::string&)>& fail) {
  Property p;
  if (t.size() == 5 && t[1] == "list") {
    const auto ct = ParseType(t[2]);
    const auto it = ParseType(t[3]);
    if (!ct || !it || IsFloat(*ct)) fail("bad list property types");
    p.is_list = true;
    p.count_type = *ct;
    p.type = *it;
    p.name = std::string(t[4]);
  } else if (t.size() == 3) {
    const auto ty = ParseType(t[1]);
    if (!ty) fail("unknown property type '" + std::string(t[1]) + "'");
    p.type = *ty;
    p.name = std::string(t[2]);
  } else {
    fail("property line must be 'property <type> <name>' or 'property list <type> <type> <name>'");
  }
  return p;
}

PlyHeader ParseHeader(std::string_view data, const std::string& source) {
  size_t pos = 0, line_number = 0;
  auto next_line = [&](std::string_view* line) {
    if (pos >= data.size()) return false;
    size_t end = data.find('\n', pos);
    if (end == std::string_view::npos) end = data.size();
    *line = data.substr(pos, end - pos);
    pos = std::min(end + 1, data.size() + 1);
    ++line_number;
    return true;
  };
  const std::function<void(const std::string&)> fail_line = [&](const std::string& what) {
    throw InputError(Located(source + ": line " + std::to_string(line_number), what));
  };
  std::string_view line;
  if (!next_line(&line) || WhitespaceTokens(line) != std::vector<std::string_view>{"ply"}) {
    throw InputError(Located(source + ": line 1", "not a PLY file (no 'ply' magic line)"));
  }
  std::optional<Format> format;
  PlyHeader header;
  bool ended = false;
  while (next_line(&line)) {
    const auto t = WhitespaceTokens(line);
    if (t.empty()) continue;
    if (t[0] == "comment" || t[0] == "obj_info") continue;
    if (t[0] == "format") {
      if (t.size() != 3) fail_line("format line must be 'format <type> 1.0'");
      if (t[1] == "ascii")
        format = Format::kAscii;
      else if (t[1] == "binary_little_endian")
        format = Format::kLittle;
      else if (t[1] == "binary_big_endian")
        format = Format::kBig;
      else
        fail_line("unknown PLY format '" + std::string(t[1]) + "'");
    } else if (t[0] == "element") {
      if (t.size() != 3) fail_line("element line must be 'element <name> <count>'");
      Element e;
      e.name = std::string(t[1]);
      const auto [ptr, ec] = std::from_chars(t[2].data(), t[2].data() + t[2].size(), e.count);
      if (ec != std::errc() || ptr != t[2].data() + t[2].size())
        fail_line("bad element count '" + std::string(t[2]) + "'");
      header.elements.push_back(e);
    } else if (t[0] == "property") {
      if (header.elements.empty()) fail_line("property before any element");
      header.elements.back().properties.push_back(ParsePropertyLine(t, fail_line));
    } else if (t[0] == "end_header") {
      ended = true;
      break;
    } else {
      fail_line("unknown header keyword '" + std::string(t[0]) + "'");
    }
  }
  if (!ended)
    throw InputError(Located(source + ": line " + std::to_string(line_number), "truncated header: no end_header"));
  if (!format) throw InputError(Located(source, "no format line in the header"));
  header.format = *format;
  header.body_offset = std::min(pos, data.size());
  header.lines = line_number;
  return header;
}

// Guards against absurd counts before allocating (an ASCII instance takes at least a byte, a binary one
// at least its properties' fixed sizes).
void CheckElementFits(const Element& e, Format format, ValueReader& in) {
  if (format == Format::kAscii && e.count > in.remaining_bytes()) {
    in.Fail("truncated: element '" + e.name + "' declares " + std::to_string(e.count) + " lines, " +
            std::to_string(in.remaining_bytes()) + " bytes left");
  }
  if (format != Format::kAscii) {
    size_t min_size = 0;
    for (const Property& p : e.properties) min_size += p.is_list ? TypeSize(p.count_type) : TypeSize(p.type);
    if (min_size > 0 && e.count > in.remaining_bytes() / min_size) {
      in.Fail("truncated: element '" + e.name + "' declares " + std::to_string(e.count) + " instances of at least " +
              std::to_string(min_size) + " bytes, " + std::to_string(in.remaining_bytes()) + " left");
    }
  }
}

// Which property of the vertex element holds each field (-1: none).
struct VertexFields {
  int x = -1, y = -1, z = -1, nx = -1, ny = -1, nz = -1, r = -1, g = -1, b = -1;
};

VertexFields FindVertexFields(const Element& e) {
  VertexFields f;
  for (int k = 0; k < static_cast<int>(e.properties.size()); ++k) {
    const std::string& n = e.properties[k].name;
    if (e.properties[k].is_list) continue;
    if (n == "x")
      f.x = k;
    else if (n == "y")
      f.y = k;
    else if (n == "z")
      f.z = k;
    else if (n == "nx")
      f.nx = k;
    else if (n == "ny")
      f.ny = k;
    else if (n == "nz")
      f.nz = k;
    else if (n == "red" || n == "r" || n == "diffuse_red")
      f.r = k;
    else if (n == "green" || n == "g" || n == "diffuse_green")
      f.g = k;
    else if (n == "blue" || n == "b" || n == "diffuse_blue")
      f.b = k;
  }
  return f;
}

// Reads one instance of `e`: the scalar properties into `values`, the lists read past.
void ReadScalars(const Element& e, ValueReader& in, std::vector<double>* values) {
  for (size_t k = 0; k < e.properties.size(); ++k) {
    const Property& p = e.properties[k];
    if (p.is_list) {
      const uint64_t count = in.ReadListCount(p.count_type, p.type);
      for (uint64_t c = 0; c < count; ++c) in.Read(p.type, p.name.c_str());
    } else {
      (*values)[k] = in.Read(p.type, p.name.c_str());
    }
  }
}

void ReadVertices(const Element& e, ValueReader& in, PointCloud* points) {
  const VertexFields f = FindVertexFields(e);
  if (f.x < 0 || f.y < 0 || f.z < 0) in.Fail("element 'vertex' has no x, y, z properties");
  const bool normals = f.nx >= 0 && f.ny >= 0 && f.nz >= 0;
  const bool colors = f.r >= 0 && f.g >= 0 && f.b >= 0;
  points->positions_m.reserve(e.count);
  std::vector<double> values(e.properties.size());
  for (uint64_t i = 0; i < e.count; ++i) {
    in.BeginInstance();
    const std::string where = in.Where();
    ReadScalars(e, in, &values);
    in.EndInstance();
    const Eigen::Vector3d x(values[f.x], values[f.y], values[f.z]);
    if (!x.allFinite()) throw InputError(Located(where, "vertex " + std::to_string(i) + " is not finite"));
    points->positions_m.push_back(x);
    if (normals) {
      Eigen::Vector3d nrm(values[f.nx], values[f.ny], values[f.nz]);
      if (!nrm.allFinite())
        throw InputError(Located(where, "normal of vertex " + std::to_string(i) + " is not finite"));
      const double len = nrm.norm();
      points->normals.push_back(len > 0 ? Eigen::Vector3d(nrm / len) : nrm);
    }
    if (colors) {
      points->colors_rgb.push_back({ColorByte(values[f.r], e.properties[f.r].type),
                                    ColorByte(values[f.g], e.properties[f.g].type),
                                    ColorByte(values[f.b], e.properties[f.b].type)});
    }
  }
}

// The faces, each polygon as a fan of triangles about its first corner.
void ReadFaces(const Element& e, uint64_t num_vertices, ValueReader& in, TriangleMesh* mesh) {
  int il = -1;
  for (int k = 0; k < static_cast<int>(e.properties.size()); ++k) {
    const auto& p = e.properties[k];
    if (p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index")) il = k;
  }
  if (il < 0) in.Fail("element 'face' has no 'vertex_indices' list");
  std::vector<uint32_t> polygon;
  for (uint64_t i = 0; i < e.count; ++i) {
    in.BeginInstance();
    const std::string where = in.Where();
    for (int k = 0; k < static_cast<int>(e.properties.size()); ++k) {
      const Property& p = e.properties[k];
      if (!p.is_list) {
        in.Read(p.type, p.name.c_str());
        continue;
      }
      const uint64_t count = in.ReadListCount(p.count_type, p.type);
      if (k == il) polygon.clear();
      for (uint64_t c = 0; c < count; ++c) {
        const double v = in.Read(p.type, "vertex index");
        if (k != il) continue;
        if (v < 0 || v >= static_cast<double>(num_vertices)) {
          throw InputError(Located(where, "face " + std::to_string(i) + " refers to vertex " +
                                              std::to_string(static_cast<int64_t>(v)) + ", but there are " +
                                              std::to_string(num_vertices)));
        }
        polygon.push_back(static_cast<uint32_t>(v));
      }
    }
    in.EndInstance();
    if (polygon.size() < 3) {
      throw InputError(Located(where, "face " + std::to_string(i) + " has " + std::to_string(polygon.size()) +
                                          " vertices (needs 3 or more)"));
    }
    for (size_t k = 1; k + 1 < polygon.size(); ++k) mesh->faces.push_back({polygon[0], polygon[k], polygon[k + 1]});
  }
}

// Unknown element: its instances read past. Binary instances of an element without properties take no
// bytes: nothing to skip, however large the count.
void SkipElement(const Element& e, Format format, ValueReader& in) {
  if (format != Format::kAscii && e.properties.empty()) return;
  std::vector<double> values(e.properties.size());
  for (uint64_t i = 0; i < e.count; ++i) {
    in.BeginInstance();
    ReadScalars(e, in, &values);
    in.EndInstance();
  }
}

}  // namespace

PlyData ParsePly(std::string_view data, const std::string& source) {
  const PlyHeader header = ParseHeader(data, source);
  PlyData out;
  ValueReader in(data.substr(header.body_offset), header.body_offset, header.lines, header.format, source);
  uint64_t num_vertices = 0;
  bool have_vertices = false;
  for (const Element& e : header.elements) {
    CheckElementFits(e, header.format, in);
    if (e.name == "vertex") {
      have_vertices = true;
      num_vertices = e.count;
      ReadVertices(e, in, &out.points);
    } else if (e.name == "face") {
      if (!have_vertices) in.Fail("element 'face' before element 'vertex'");
      ReadFaces(e, num_vertices, in, &out.mesh);
    } else {
      SkipElement(e, header.format, in);
    }
  }
  in.ExpectEnd();
  if (!have_vertices) throw InputError(Located(source, "no 'vertex' element"));
  out.mesh.vertices_m = out.points.positions_m;
  out.mesh.colors_rgb = out.points.colors_rgb;
  return out;
}

PlyData ReadPly(const std::filesystem::path& path) { return ParsePly(ReadFileToString(path), path.string()); }

}  // namespace cinepath::photogrammetry
