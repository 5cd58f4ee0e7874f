#include "scene/glb_reader.h"

#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <optional>

#include <draco/compression/decode.h>
#include <draco/mesh/mesh.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/file_io.h"
#include "core/glb_container.h"
#include "core/three_frame.h"
#include "scene/tinygltf_config.h"

namespace cinepath::scene {
namespace {

constexpr const char* kDracoExtension = "KHR_draco_mesh_compression";
constexpr int kModeTriangles = 4, kModeTriangleStrip = 5, kModeTriangleFan = 6;

// Keeps images as the encoded bytes (the scene module has no codec; see scene_mesh.h).
bool KeepEncodedImage(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

class GlbDecoder {
 public:
  // Takes the encoded images' bytes out of `model` (moved into the SceneMesh, not copied).
  GlbDecoder(tinygltf::Model& model, std::string source) : model_(model), source_(std::move(source)) {}

  SceneMesh Decode();

 private:
  struct Attribute {  // one attribute of one primitive, as floats
    std::vector<float> values;
    int components = 0;
  };
  struct Primitive {
    std::vector<uint32_t> indices;  // triangle list
    Attribute position, color, texcoord;
    int material = -1;
  };

  [[noreturn]] void Fail(const std::string& where, const std::string& what) const {
    throw InputError(source_ + ": " + where + ": " + what);
  }
  Attribute ReadAccessor(int index, const std::string& where) const;
  std::vector<uint32_t> ReadIndices(int index, size_t vertex_count, const std::string& where) const;
  Primitive ReadPlainPrimitive(const tinygltf::Primitive& p, const std::string& where) const;
  Primitive ReadDracoPrimitive(const tinygltf::Value& ext, const std::string& where) const;
  void AddMesh(int mesh_index, const Eigen::Matrix4d& gltf_from_mesh, SceneMesh* out);
  void Visit(int node_index, const Eigen::Matrix4d& parent, int depth, SceneMesh* out);
  int MaterialIndex(int gltf_material, SceneMesh* out);

  tinygltf::Model& model_;
  std::string source_;
  std::vector<int> material_map_;  // glTF material -> SceneMesh material
  std::vector<int> image_map_;     // glTF image -> SceneMesh image
};

float ComponentAsFloat(const uint8_t* p, int component_type, bool normalized) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? p[0] / 255.0f : p[0];
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const auto v = static_cast<int8_t>(p[0]);
      return normalized ? std::max(v / 127.0f, -1.0f) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? v / 65535.0f : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(v / 32767.0f, -1.0f) : v;
    }
    default: return std::numeric_limits<float>::quiet_NaN();
  }
}

int ComponentSize(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

int ComponentCount(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    default: return 0;
  }
}

std::string Element(const char* array, int index) { return std::string(array) + "[" + std::to_string(index) + "]"; }

// The bytes an accessor reads, after every index and range is checked: `element` bytes every `stride`
// bytes, `count` times.
struct AccessorBytes {
  const uint8_t* base = nullptr;
  size_t count = 0;
  size_t stride = 0;
};

AccessorBytes CheckedBytes(const tinygltf::Model& model, int index, size_t element, const std::string& source) {
  const tinygltf::Accessor& a = model.accessors[index];
  const std::string at = source + ": " + Element("accessors", index);
  if (a.bufferView < 0 || static_cast<size_t>(a.bufferView) >= model.bufferViews.size()) {
    throw InputError(at + ": bufferView index out of range");
  }
  const tinygltf::BufferView& view = model.bufferViews[a.bufferView];
  const std::string view_at = source + ": " + Element("bufferViews", a.bufferView);
  if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= model.buffers.size()) {
    throw InputError(view_at + ": buffer index out of range");
  }
  const std::vector<unsigned char>& buffer = model.buffers[view.buffer].data;
  const size_t stride = view.byteStride ? view.byteStride : element;
  if (stride < element) throw InputError(view_at + ": byteStride smaller than the element");
  if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset) {
    throw InputError(view_at + ": byte range outside its buffer");
  }
  if (a.count > 0 && (a.byteOffset > view.byteLength || (a.count - 1) > (view.byteLength - a.byteOffset) / stride ||
                      (a.count - 1) * stride + element > view.byteLength - a.byteOffset)) {
    throw InputError(at + ": reads past the end of its bufferView");
  }
  return {buffer.data() + view.byteOffset + a.byteOffset, a.count, stride};
}

GlbDecoder::Attribute GlbDecoder::ReadAccessor(int index, const std::string& where) const {
  if (index < 0 || static_cast<size_t>(index) >= model_.accessors.size()) Fail(where, "accessor index out of range");
  const tinygltf::Accessor& a = model_.accessors[index];
  const std::string at = Element("accessors", index);
  if (a.sparse.isSparse) Fail(at, "sparse accessors are not supported");
  Attribute out;
  out.components = ComponentCount(a.type);
  const int size = ComponentSize(a.componentType);
  if (out.components == 0 || size == 0 || a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
    Fail(at, "unsupported type for a vertex attribute");
  }
  const AccessorBytes bytes = CheckedBytes(model_, index, static_cast<size_t>(out.components) * size, source_);
  out.values.resize(bytes.count * out.components);
  for (size_t i = 0; i < bytes.count; ++i) {
    for (int c = 0; c < out.components; ++c) {
      out.values[i * out.components + c] =
          ComponentAsFloat(bytes.base + i * bytes.stride + c * size, a.componentType, a.normalized);
    }
  }
  return out;
}

std::vector<uint32_t> GlbDecoder::ReadIndices(int index, size_t vertex_count, const std::string& where) const {
  if (index < 0 || static_cast<size_t>(index) >= model_.accessors.size()) Fail(where, "indices: accessor out of range");
  const tinygltf::Accessor& a = model_.accessors[index];
  const std::string at = Element("accessors", index);
  if (a.sparse.isSparse) Fail(at, "sparse accessors are not supported");
  const int size = ComponentSize(a.componentType);
  if (a.type != TINYGLTF_TYPE_SCALAR || (a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
                                         a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
                                         a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)) {
    Fail(at, "indices must be unsigned byte, short or int scalars");
  }
  const AccessorBytes bytes = CheckedBytes(model_, index, static_cast<size_t>(size), source_);
  std::vector<uint32_t> out(bytes.count);
  for (size_t i = 0; i < bytes.count; ++i) {
    const uint8_t* p = bytes.base + i * bytes.stride;
    uint32_t v = 0;
    if (size == 1) {
      v = p[0];
    } else if (size == 2) {
      uint16_t s;
      std::memcpy(&s, p, 2);
      v = s;
    } else {
      std::memcpy(&v, p, 4);
    }
    if (v >= vertex_count) {
      Fail(at, "index " + std::to_string(v) + " out of range (" + std::to_string(vertex_count) + " vertices)");
    }
    out[i] = v;
  }
  return out;
}

// Strips and fans -> triangle lists (glTF 2.0 §3.7.2.1); other modes give no triangles.
std::vector<uint32_t> TriangleList(const std::vector<uint32_t>& indices, int mode) {
  if (mode == kModeTriangles) {
    std::vector<uint32_t> out = indices;
    out.resize(out.size() - out.size() % 3);
    return out;
  }
  std::vector<uint32_t> out;
  if (indices.size() < 3) return out;
  for (size_t i = 2; i < indices.size(); ++i) {
    if (mode == kModeTriangleStrip) {
      const bool even = i % 2 == 0;
      out.insert(out.end(), {indices[i - 2], even ? indices[i - 1] : indices[i], even ? indices[i] : indices[i - 1]});
    } else if (mode == kModeTriangleFan) {
      out.insert(out.end(), {indices[i - 1], indices[i], indices[0]});
    }
  }
  return out;
}

GlbDecoder::Primitive GlbDecoder::ReadPlainPrimitive(const tinygltf::Primitive& p, const std::string& where) const {
  Primitive out;
  const auto position = p.attributes.find("POSITION");
  if (position == p.attributes.end()) Fail(where, "no POSITION attribute");
  out.position = ReadAccessor(position->second, where + ".attributes.POSITION");
  if (out.position.components != 3) Fail(where, "POSITION must be VEC3");
  const size_t n = out.position.values.size() / 3;
  if (const auto c = p.attributes.find("COLOR_0"); c != p.attributes.end()) {
    out.color = ReadAccessor(c->second, where + ".attributes.COLOR_0");
    if (out.color.components < 3 || out.color.values.size() / out.color.components != n) {
      Fail(where, "COLOR_0 must be VEC3 or VEC4, one per vertex");
    }
  }
  if (const auto t = p.attributes.find("TEXCOORD_0"); t != p.attributes.end()) {
    out.texcoord = ReadAccessor(t->second, where + ".attributes.TEXCOORD_0");
    if (out.texcoord.components != 2 || out.texcoord.values.size() / 2 != n) {
      Fail(where, "TEXCOORD_0 must be VEC2, one per vertex");
    }
  }
  std::vector<uint32_t> indices;
  if (p.indices >= 0) {
    indices = ReadIndices(p.indices, n, where + ".indices");
  } else {
    indices.resize(n);
    for (size_t i = 0; i < n; ++i) indices[i] = static_cast<uint32_t>(i);
  }
  out.indices = TriangleList(indices, p.mode < 0 ? kModeTriangles : p.mode);
  return out;
}

GlbDecoder::Primitive GlbDecoder::ReadDracoPrimitive(const tinygltf::Value& ext, const std::string& where) const {
  const std::string at = where + ".extensions." + kDracoExtension;
  const tinygltf::Value& view_value = ext.Get("bufferView");
  const tinygltf::Value& attributes = ext.Get("attributes");
  if (!view_value.IsInt() || !attributes.IsObject()) Fail(at, "needs \"bufferView\" and \"attributes\"");
  const int view_index = view_value.Get<int>();
  if (view_index < 0 || static_cast<size_t>(view_index) >= model_.bufferViews.size()) {
    Fail(at, "bufferView index out of range");
  }
  const tinygltf::BufferView& view = model_.bufferViews[view_index];
  if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= model_.buffers.size()) {
    Fail(Element("bufferViews", view_index), "buffer index out of range");
  }
  const std::vector<unsigned char>& buffer = model_.buffers[view.buffer].data;
  if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset) {
    Fail(Element("bufferViews", view_index), "byte range outside its buffer");
  }
  draco::DecoderBuffer decoder_buffer;
  decoder_buffer.Init(reinterpret_cast<const char*>(buffer.data() + view.byteOffset), view.byteLength);
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&decoder_buffer);
  if (!decoded.ok()) Fail(at, "Draco decoding failed: " + decoded.status().error_msg_string());
  const draco::Mesh& mesh = *decoded.value();

  auto read = [&](const char* name, int want_min, int want_max) {
    Attribute a;
    const tinygltf::Value& id = attributes.Get(name);
    if (!id.IsInt()) return a;
    const draco::PointAttribute* att = mesh.GetAttributeByUniqueId(static_cast<uint32_t>(id.Get<int>()));
    if (att == nullptr) Fail(at, std::string("attributes.") + name + ": no such Draco attribute");
    const int components = att->num_components();
    if (components < want_min || components > want_max) Fail(at, std::string("attributes.") + name + ": wrong size");
    a.components = components;
    a.values.resize(static_cast<size_t>(mesh.num_points()) * components);
    for (uint32_t i = 0; i < mesh.num_points(); ++i) {
      if (!att->ConvertValue<float>(att->mapped_index(draco::PointIndex(i)), components, &a.values[i * components])) {
        Fail(at, std::string("attributes.") + name + ": cannot convert to float");
      }
    }
    // Normalized integer colours and texture coordinates come back as floats in [0, 1].
    if (att->normalized() && att->data_type() != draco::DT_FLOAT32) {
      const double scale = att->data_type() == draco::DT_UINT8    ? 255.0
                           : att->data_type() == draco::DT_UINT16 ? 65535.0
                                                                  : 1.0;
      for (float& v : a.values) v = static_cast<float>(v / scale);
    }
    return a;
  };
  Primitive out;
  out.position = read("POSITION", 3, 3);
  if (out.position.components != 3) Fail(at, "no POSITION attribute");
  out.color = read("COLOR_0", 3, 4);
  out.texcoord = read("TEXCOORD_0", 2, 2);
  out.indices.reserve(3 * mesh.num_faces());
  for (draco::FaceIndex f(0); f < mesh.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = mesh.face(f)[k].value();
      if (v >= mesh.num_points()) Fail(at, "face index out of range");
      out.indices.push_back(v);
    }
  }
  return out;
}

int GlbDecoder::MaterialIndex(int gltf_material, SceneMesh* out) {
  if (gltf_material < 0) return -1;
  if (static_cast<size_t>(gltf_material) >= model_.materials.size()) {
    Fail("materials", "index " + std::to_string(gltf_material) + " out of range");
  }
  if (material_map_[gltf_material] >= 0) return material_map_[gltf_material];
  const tinygltf::Material& m = model_.materials[gltf_material];
  SceneMaterial material;
  const auto& factor = m.pbrMetallicRoughness.baseColorFactor;
  if (factor.size() == 4)
    material.base_color_factor = Eigen::Vector4d(factor[0], factor[1], factor[2], factor[3]).cast<float>();
  const int texture = m.pbrMetallicRoughness.baseColorTexture.index;
  if (texture >= 0) {
    if (static_cast<size_t>(texture) >= model_.textures.size())
      Fail(Element("materials", gltf_material), "texture index out of range");
    const int image = model_.textures[texture].source;
    if (image < 0 || static_cast<size_t>(image) >= model_.images.size())
      Fail(Element("textures", texture), "source out of range");
    if (image_map_[image] < 0 && !model_.images[image].image.empty()) {
      image_map_[image] = static_cast<int>(out->images.size());
      out->images.push_back({model_.images[image].mimeType, std::move(model_.images[image].image)});
    }
    material.base_color_image = image_map_[image];
  }
  material_map_[gltf_material] = static_cast<int>(out->materials.size());
  out->materials.push_back(material);
  return material_map_[gltf_material];
}

void GlbDecoder::AddMesh(int mesh_index, const Eigen::Matrix4d& gltf_from_mesh, SceneMesh* out) {
  if (mesh_index < 0 || static_cast<size_t>(mesh_index) >= model_.meshes.size()) {
    Fail("nodes", "mesh index " + std::to_string(mesh_index) + " out of range");
  }
  const tinygltf::Mesh& mesh = model_.meshes[mesh_index];
  for (size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
    const tinygltf::Primitive& p = mesh.primitives[pi];
    const std::string where = Element("meshes", mesh_index) + ".primitives[" + std::to_string(pi) + "]";
    const int mode = p.mode < 0 ? kModeTriangles : p.mode;
    if (mode != kModeTriangles && mode != kModeTriangleStrip && mode != kModeTriangleFan) continue;
    const auto ext = p.extensions.find(kDracoExtension);
    const Primitive prim =
        ext != p.extensions.end() ? ReadDracoPrimitive(ext->second, where) : ReadPlainPrimitive(p, where);
    if (prim.indices.empty()) continue;
    const int material = MaterialIndex(p.material, out);
    const Eigen::Vector4f factor = material >= 0 ? out->materials[material].base_color_factor : Eigen::Vector4f::Ones();
    const size_t base = out->positions_enu_m.size();
    const size_t n = prim.position.values.size() / 3;
    if (base + n > std::numeric_limits<uint32_t>::max()) Fail(where, "too many vertices");
    // Colours and texture coordinates: once any primitive has them, every vertex gets one (the
    // material's base colour, or (0, 0), where a primitive has none).
    const bool colors = !prim.color.values.empty() || out->has_colors();
    const bool texcoords = !prim.texcoord.values.empty() || out->has_texcoords();
    if (colors && !out->has_colors()) out->colors_linear.assign(base, Eigen::Vector3f::Ones());
    if (texcoords && !out->has_texcoords()) out->texcoords.assign(base, Eigen::Vector2f::Zero());
    for (size_t i = 0; i < n; ++i) {
      const Eigen::Vector4d g(prim.position.values[3 * i], prim.position.values[3 * i + 1],
                              prim.position.values[3 * i + 2], 1.0);
      const Eigen::Vector4d w = gltf_from_mesh * g;
      const Eigen::Vector3d enu = EnuFromThree(w.head<3>());
      if (!enu.allFinite()) Fail(where, "a position is not finite");
      out->positions_enu_m.push_back(enu);
      if (colors) {
        if (prim.color.values.empty()) {
          out->colors_linear.push_back(factor.head<3>());
        } else {
          const float* c = &prim.color.values[i * prim.color.components];
          out->colors_linear.emplace_back(c[0], c[1], c[2]);
        }
      }
      if (texcoords) {
        out->texcoords.push_back(prim.texcoord.values.empty()
                                     ? Eigen::Vector2f::Zero()
                                     : Eigen::Vector2f(prim.texcoord.values[2 * i], prim.texcoord.values[2 * i + 1]));
      }
    }
    const bool flip = gltf_from_mesh.topLeftCorner<3, 3>().determinant() < 0;  // mirrored: keep the winding
    for (size_t t = 0; t + 2 < prim.indices.size(); t += 3) {
      std::array<uint32_t, 3> f = {static_cast<uint32_t>(base + prim.indices[t]),
                                   static_cast<uint32_t>(base + prim.indices[t + 1]),
                                   static_cast<uint32_t>(base + prim.indices[t + 2])};
      if (flip) std::swap(f[1], f[2]);
      out->faces.push_back(f);
      if (material >= 0 || !out->face_material.empty()) {
        out->face_material.resize(out->faces.size() - 1, -1);
        out->face_material.push_back(material);
      }
    }
  }
}

Eigen::Matrix4d LocalTransform(const tinygltf::Node& node) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  if (node.matrix.size() == 16) {
    for (int c = 0; c < 4; ++c) {
      for (int r = 0; r < 4; ++r) m(r, c) = node.matrix[c * 4 + r];  // column-major
    }
    return m;
  }
  Eigen::Affine3d a = Eigen::Affine3d::Identity();
  if (node.translation.size() == 3)
    a.translate(Eigen::Vector3d(node.translation[0], node.translation[1], node.translation[2]));
  if (node.rotation.size() == 4) {
    a.rotate(Eigen::Quaterniond(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]).normalized());
  }
  if (node.scale.size() == 3) a.scale(Eigen::Vector3d(node.scale[0], node.scale[1], node.scale[2]));
  return a.matrix();
}

void GlbDecoder::Visit(int node_index, const Eigen::Matrix4d& parent, int depth, SceneMesh* out) {
  if (node_index < 0 || static_cast<size_t>(node_index) >= model_.nodes.size())
    Fail("nodes", "node index out of range");
  if (depth > 64) Fail(Element("nodes", node_index), "node hierarchy deeper than 64 (a cycle?)");
  const tinygltf::Node& node = model_.nodes[node_index];
  const Eigen::Matrix4d world = parent * LocalTransform(node);
  if (!world.allFinite()) Fail(Element("nodes", node_index), "transform is not finite");
  if (node.mesh >= 0) AddMesh(node.mesh, world, out);
  for (int child : node.children) Visit(child, world, depth + 1, out);
}

SceneMesh GlbDecoder::Decode() {
  material_map_.assign(model_.materials.size(), -1);
  image_map_.assign(model_.images.size(), -1);
  SceneMesh out;
  if (!model_.scenes.empty()) {
    const int s = model_.defaultScene >= 0 ? model_.defaultScene : 0;
    if (static_cast<size_t>(s) >= model_.scenes.size()) Fail("scene", "index out of range");
    for (int node : model_.scenes[s].nodes) Visit(node, Eigen::Matrix4d::Identity(), 0, &out);
  } else {
    for (size_t m = 0; m < model_.meshes.size(); ++m) AddMesh(static_cast<int>(m), Eigen::Matrix4d::Identity(), &out);
  }
  if (!out.face_material.empty()) out.face_material.resize(out.faces.size(), -1);
  if (out.faces.empty()) throw InputError(source_ + ": holds no triangles");
  return out;
}

// tinygltf (built without Draco, scene/tinygltf_impl.cc) insists that an index accessor has a
// bufferView, which a Draco primitive's does not. Draco primitives therefore reach tinygltf without
// "indices" (the decoder below takes the faces from the Draco mesh), in a GLB rebuilt with that JSON.
// The container is checked first (core/glb_container.h): the header's total length is the file's, and
// every chunk lies inside it — tinygltf (2.8, Debian 12) trusts the BIN chunk's length and copies past
// the end of a truncated file. Empty when the GLB needs no change (it is then read as it is, not copied).
std::optional<std::string> WithoutDracoIndices(std::string_view glb, const std::string& source) {
  const GlbChunks chunks = SplitGlb(glb, source);
  if (chunks.json.find(kDracoExtension) == std::string_view::npos) return std::nullopt;
  nlohmann::json doc = nlohmann::json::parse(chunks.json, nullptr, /*allow_exceptions=*/false);
  if (doc.is_discarded() || !doc.is_object()) throw InputError(source + ": the GLB's JSON chunk is not valid JSON");
  bool changed = false;
  if (auto meshes = doc.find("meshes"); meshes != doc.end() && meshes->is_array()) {
    for (auto& mesh : *meshes) {
      if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
      for (auto& prim : mesh["primitives"]) {
        if (!prim.is_object() || !prim.contains("extensions") || !prim["extensions"].is_object()) continue;
        if (!prim["extensions"].contains(kDracoExtension)) continue;
        changed = prim.erase("indices") > 0 || changed;
      }
    }
  }
  if (!changed) return std::nullopt;
  return AssembleGlb(doc.dump(), chunks.bin);
}

}  // namespace

SceneMesh ReadGlbBytes(std::string_view bytes, const std::string& source) {
  if (bytes.size() > std::numeric_limits<unsigned int>::max()) throw InputError(source + ": larger than 4 GiB");
  if (bytes.size() < 12 || bytes.substr(0, 4) != "glTF") throw InputError(source + ": not a binary glTF (GLB) file");
  const std::optional<std::string> rebuilt = WithoutDracoIndices(bytes, source);
  const std::string_view glb = rebuilt ? std::string_view(*rebuilt) : bytes;
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&KeepEncodedImage, nullptr);
  std::string err, warn;
  const bool ok = loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(glb.data()),
                                              static_cast<unsigned int>(glb.size()));
  if (!ok) {
    while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
    throw InputError(source + ": not a valid GLB: " + (err.empty() ? std::string("unreadable") : err));
  }
  return GlbDecoder(model, source).Decode();
}

SceneMesh ReadGlbFile(const std::filesystem::path& path) {
  return ReadGlbBytes(ReadFileToString(path), path.filename().string());
}

}  // namespace cinepath::scene
