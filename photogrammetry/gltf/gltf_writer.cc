#include "photogrammetry/gltf/gltf_writer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <sstream>
#include <vector>

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/core/encoder_buffer.h>
#include <draco/mesh/mesh.h>

#include "scene/tinygltf_config.h"  // the one tinygltf configuration (scene/tinygltf_impl.cc)

#include "core/error.h"
#include "core/three_frame.h"

namespace cinepath::photogrammetry {
namespace {

constexpr const char* kDracoExtension = "KHR_draco_mesh_compression";

tinygltf::Value ValueFromJson(const Json& json) {
  if (json.is_object()) {
    tinygltf::Value::Object object;
    for (auto it = json.begin(); it != json.end(); ++it) object[it.key()] = ValueFromJson(it.value());
    return tinygltf::Value(std::move(object));
  }
  if (json.is_array()) {
    tinygltf::Value::Array array;
    for (const Json& element : json) array.push_back(ValueFromJson(element));
    return tinygltf::Value(std::move(array));
  }
  if (json.is_boolean()) return tinygltf::Value(json.get<bool>());
  if (json.is_number_integer() || json.is_number_unsigned()) {
    const int64_t value = json.get<int64_t>();
    if (value >= std::numeric_limits<int>::min() && value <= std::numeric_limits<int>::max()) {
      return tinygltf::Value(static_cast<int>(value));
    }
    return tinygltf::Value(static_cast<double>(value));
  }
  if (json.is_number()) return tinygltf::Value(json.get<double>());
  if (json.is_string()) return tinygltf::Value(json.get<std::string>());
  return tinygltf::Value();
}

void AppendBytes(std::vector<unsigned char>& buffer, const void* data, size_t size) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  buffer.insert(buffer.end(), bytes, bytes + size);
}

void PadTo4(std::vector<unsigned char>& buffer) {
  while (buffer.size() % 4 != 0) buffer.push_back(0);
}

int AddBufferView(tinygltf::Model& model, size_t offset, size_t length, int target) {
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = offset;
  view.byteLength = length;
  view.target = target;
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size()) - 1;
}

struct VertexData {
  std::vector<float> positions;  // glTF frame, xyz per vertex
  std::vector<float> colors;     // linear rgb per vertex, or empty
  std::vector<float> texcoords;  // uv per vertex, or empty
  std::vector<uint32_t> indices;
};

void MinMax(const std::vector<float>& xyz, std::vector<double>& min_values, std::vector<double>& max_values) {
  min_values.assign(3, std::numeric_limits<double>::infinity());
  max_values.assign(3, -std::numeric_limits<double>::infinity());
  for (size_t i = 0; i < xyz.size(); ++i) {
    min_values[i % 3] = std::min<double>(min_values[i % 3], xyz[i]);
    max_values[i % 3] = std::max<double>(max_values[i % 3], xyz[i]);
  }
}

// Encodes with Draco and decodes the result again: the accessors must describe what a decoder
// produces (edgebreaker may split non-manifold vertices), not what went in.
struct DracoResult {
  std::vector<unsigned char> bytes;
  int position_id = -1;
  int color_id = -1;
  int texcoord_id = -1;
  size_t num_points = 0;
  size_t num_faces = 0;
  std::vector<double> position_min, position_max;
};

DracoResult EncodeDraco(const VertexData& data, const GlbWriteOptions& options) {
  const size_t n = data.positions.size() / 3;
  draco::Mesh mesh;
  mesh.set_num_points(static_cast<uint32_t>(n));
  draco::GeometryAttribute position;
  position.Init(draco::GeometryAttribute::POSITION, nullptr, 3, draco::DT_FLOAT32, false, sizeof(float) * 3, 0);
  const int position_att = mesh.AddAttribute(position, true, static_cast<uint32_t>(n));
  int color_att = -1;
  if (!data.colors.empty()) {
    draco::GeometryAttribute color;
    color.Init(draco::GeometryAttribute::COLOR, nullptr, 3, draco::DT_FLOAT32, false, sizeof(float) * 3, 0);
    color_att = mesh.AddAttribute(color, true, static_cast<uint32_t>(n));
  }
  int texcoord_att = -1;
  if (!data.texcoords.empty()) {
    draco::GeometryAttribute texcoord;
    texcoord.Init(draco::GeometryAttribute::TEX_COORD, nullptr, 2, draco::DT_FLOAT32, false, sizeof(float) * 2, 0);
    texcoord_att = mesh.AddAttribute(texcoord, true, static_cast<uint32_t>(n));
  }
  for (size_t i = 0; i < n; ++i) {
    if (texcoord_att >= 0) {
      mesh.attribute(texcoord_att)
          ->SetAttributeValue(draco::AttributeValueIndex(static_cast<uint32_t>(i)), &data.texcoords[2 * i]);
    }
    mesh.attribute(position_att)
        ->SetAttributeValue(draco::AttributeValueIndex(static_cast<uint32_t>(i)), &data.positions[3 * i]);
    if (color_att >= 0) {
      mesh.attribute(color_att)->SetAttributeValue(draco::AttributeValueIndex(static_cast<uint32_t>(i)),
                                                   &data.colors[3 * i]);
    }
  }
  for (size_t f = 0; f < data.indices.size() / 3; ++f) {
    draco::Mesh::Face face;
    for (int k = 0; k < 3; ++k) face[k] = draco::PointIndex(data.indices[3 * f + k]);
    mesh.AddFace(face);
  }

  draco::Encoder encoder;
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, options.draco_position_bits);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::COLOR, options.draco_color_bits);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, options.draco_texcoord_bits);
  const int speed = 10 - std::clamp(options.draco_compression_level, 0, 10);
  encoder.SetSpeedOptions(speed, speed);
  encoder.SetEncodingMethod(draco::MESH_EDGEBREAKER_ENCODING);
  draco::EncoderBuffer buffer;
  const draco::Status status = encoder.EncodeMeshToBuffer(mesh, &buffer);
  if (!status.ok()) throw RuntimeError("glb: Draco encoding failed: " + status.error_msg_string());

  DracoResult result;
  result.bytes.assign(buffer.data(), buffer.data() + buffer.size());
  result.position_id = static_cast<int>(mesh.attribute(position_att)->unique_id());
  if (color_att >= 0) result.color_id = static_cast<int>(mesh.attribute(color_att)->unique_id());
  if (texcoord_att >= 0) result.texcoord_id = static_cast<int>(mesh.attribute(texcoord_att)->unique_id());

  draco::DecoderBuffer decode_buffer;
  decode_buffer.Init(buffer.data(), buffer.size());
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&decode_buffer);
  if (!decoded.ok()) {
    throw RuntimeError("glb: Draco round trip failed: " + decoded.status().error_msg_string());
  }
  const draco::Mesh& out = *decoded.value();
  result.num_points = out.num_points();
  result.num_faces = out.num_faces();
  const draco::PointAttribute* decoded_position = out.GetAttributeByUniqueId(static_cast<uint32_t>(result.position_id));
  CINEPATH_CHECK(decoded_position != nullptr);
  std::vector<float> xyz(3 * out.num_points());
  for (uint32_t i = 0; i < out.num_points(); ++i) {
    decoded_position->GetMappedValue(draco::PointIndex(i), &xyz[3 * i]);
  }
  MinMax(xyz, result.position_min, result.position_max);
  return result;
}

}  // namespace

float LinearFromSrgb8(uint8_t value) {
  const double c = value / 255.0;
  const double linear = c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
  return static_cast<float>(linear);
}

std::string WriteGlb(const TriangleMesh& mesh_enu, const GlbWriteOptions& options) {
  return WriteGlb(mesh_enu, nullptr, options);
}

namespace {

// The refusals of WriteGlb: an empty mesh, per-vertex arrays of the wrong size, extras that are not an object.
void CheckGlbInput(const TriangleMesh& mesh_enu, const GlbTexture* texture, const GlbWriteOptions& options) {
  if (mesh_enu.num_faces() == 0 || mesh_enu.num_vertices() == 0) {
    throw InputError("glb: the mesh is empty");
  }
  if (mesh_enu.has_colors() && mesh_enu.colors_rgb.size() != mesh_enu.num_vertices()) {
    throw InputError("glb: colours: one per vertex expected");
  }
  if (!options.extras.is_null() && !options.extras.is_object()) {
    throw InputError("glb: extras: must be an object");
  }

  if (texture != nullptr) {
    if (texture->texcoords.size() != mesh_enu.num_vertices()) {
      throw InputError("glb: texture coordinates: one per vertex expected");
    }
    if (texture->image_bytes.empty() || texture->mime_type.empty()) throw InputError("glb: texture: no image");
  }
}

// The vertex and index arrays in glTF's frame and colour space (positions Y-up, colours linear).
VertexData GltfVertexData(const TriangleMesh& mesh_enu, const GlbTexture* texture) {
  VertexData data;
  if (texture != nullptr) {
    data.texcoords.reserve(2 * texture->texcoords.size());
    for (const Eigen::Vector2f& t : texture->texcoords) {
      if (!t.allFinite()) throw InputError("glb: a texture coordinate is not finite");
      data.texcoords.insert(data.texcoords.end(), {t.x(), t.y()});
    }
  }
  data.positions.reserve(3 * mesh_enu.num_vertices());
  for (const Eigen::Vector3d& v : mesh_enu.vertices_m) {
    if (!v.allFinite()) throw InputError("glb: a vertex position is not finite");
    const Eigen::Vector3f g = ThreeFromEnu(v).cast<float>();  // glTF is Y-up: (e, u, -n)
    data.positions.insert(data.positions.end(), {g.x(), g.y(), g.z()});
  }
  float srgb_to_linear[256];
  for (int i = 0; i < 256; ++i) srgb_to_linear[i] = LinearFromSrgb8(static_cast<uint8_t>(i));
  if (mesh_enu.has_colors()) {
    data.colors.reserve(3 * mesh_enu.num_vertices());
    for (const auto& c : mesh_enu.colors_rgb) {
      data.colors.insert(data.colors.end(), {srgb_to_linear[c[0]], srgb_to_linear[c[1]], srgb_to_linear[c[2]]});
    }
  }
  data.indices.reserve(3 * mesh_enu.num_faces());
  for (size_t f = 0; f < mesh_enu.num_faces(); ++f) {
    for (uint32_t index : mesh_enu.faces[f]) {
      if (index >= mesh_enu.num_vertices()) {
        throw InputError("glb: faces[" + std::to_string(f) + "]: vertex index out of range");
      }
      data.indices.push_back(index);
    }
  }
  return data;
}

// The accessors of the one primitive, each with its component type and shape; counts and views are set
// by the buffer writers below.
struct PrimitiveAccessors {
  tinygltf::Accessor index, position, color, texcoord;
  PrimitiveAccessors() {
    index.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    index.type = TINYGLTF_TYPE_SCALAR;
    position.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    position.type = TINYGLTF_TYPE_VEC3;
    color.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    color.type = TINYGLTF_TYPE_VEC3;
    texcoord.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    texcoord.type = TINYGLTF_TYPE_VEC2;
  }
};

// KHR_draco_mesh_compression: one compressed buffer view the extension points at.
void AddDracoPrimitive(const VertexData& data, const GlbWriteOptions& options, tinygltf::Model& model,
                       std::vector<unsigned char>& bin, PrimitiveAccessors& accessors, tinygltf::Primitive& primitive) {
  const DracoResult draco = EncodeDraco(data, options);
  AppendBytes(bin, draco.bytes.data(), draco.bytes.size());
  const int view = AddBufferView(model, 0, draco.bytes.size(), 0);
  PadTo4(bin);
  accessors.index.count = 3 * draco.num_faces;
  accessors.position.count = draco.num_points;
  accessors.position.minValues = draco.position_min;
  accessors.position.maxValues = draco.position_max;
  accessors.color.count = draco.num_points;
  accessors.texcoord.count = draco.num_points;

  tinygltf::Value::Object attributes;
  attributes["POSITION"] = tinygltf::Value(draco.position_id);
  if (draco.color_id >= 0) attributes["COLOR_0"] = tinygltf::Value(draco.color_id);
  if (draco.texcoord_id >= 0) attributes["TEXCOORD_0"] = tinygltf::Value(draco.texcoord_id);
  tinygltf::Value::Object extension;
  extension["bufferView"] = tinygltf::Value(view);
  extension["attributes"] = tinygltf::Value(std::move(attributes));
  primitive.extensions[kDracoExtension] = tinygltf::Value(std::move(extension));
  model.extensionsUsed.push_back(kDracoExtension);
  model.extensionsRequired.push_back(kDracoExtension);
}

// Plain buffers: one view each for the indices, positions, colours and texture coordinates.
void AddPlainPrimitive(const VertexData& data, size_t num_vertices, tinygltf::Model& model,
                       std::vector<unsigned char>& bin, PrimitiveAccessors& accessors) {
  const size_t index_offset = bin.size();
  AppendBytes(bin, data.indices.data(), data.indices.size() * sizeof(uint32_t));
  accessors.index.bufferView =
      AddBufferView(model, index_offset, bin.size() - index_offset, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  accessors.index.count = data.indices.size();
  PadTo4(bin);

  const size_t position_offset = bin.size();
  AppendBytes(bin, data.positions.data(), data.positions.size() * sizeof(float));
  accessors.position.bufferView =
      AddBufferView(model, position_offset, bin.size() - position_offset, TINYGLTF_TARGET_ARRAY_BUFFER);
  accessors.position.count = num_vertices;
  MinMax(data.positions, accessors.position.minValues, accessors.position.maxValues);

  if (!data.colors.empty()) {
    const size_t color_offset = bin.size();
    AppendBytes(bin, data.colors.data(), data.colors.size() * sizeof(float));
    accessors.color.bufferView =
        AddBufferView(model, color_offset, bin.size() - color_offset, TINYGLTF_TARGET_ARRAY_BUFFER);
    accessors.color.count = num_vertices;
  }
  if (!data.texcoords.empty()) {
    const size_t texcoord_offset = bin.size();
    AppendBytes(bin, data.texcoords.data(), data.texcoords.size() * sizeof(float));
    accessors.texcoord.bufferView =
        AddBufferView(model, texcoord_offset, bin.size() - texcoord_offset, TINYGLTF_TARGET_ARRAY_BUFFER);
    accessors.texcoord.count = num_vertices;
  }
}

// A matte material: the colour comes from COLOR_0 (multiplied with baseColorFactor 1) and, with a
// texture, from the texture multiplied by COLOR_0.
void AddMaterial(const GlbTexture* texture, tinygltf::Model& model, std::vector<unsigned char>& bin) {
  tinygltf::Material material;
  if (texture != nullptr) {
    PadTo4(bin);
    const size_t image_offset = bin.size();
    AppendBytes(bin, texture->image_bytes.data(), texture->image_bytes.size());
    tinygltf::Image image;
    image.name = "atlas";
    image.mimeType = texture->mime_type;
    image.bufferView = AddBufferView(model, image_offset, texture->image_bytes.size(), 0);
    PadTo4(bin);
    model.images.push_back(image);
    tinygltf::Sampler sampler;
    sampler.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
    sampler.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
    sampler.wrapS = TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
    sampler.wrapT = TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
    model.samplers.push_back(sampler);
    tinygltf::Texture gltf_texture;
    gltf_texture.source = 0;
    gltf_texture.sampler = 0;
    model.textures.push_back(gltf_texture);
    material.pbrMetallicRoughness.baseColorTexture.index = 0;
    material.pbrMetallicRoughness.baseColorTexture.texCoord = 0;
  }
  material.name = "terrain";
  material.pbrMetallicRoughness.metallicFactor = 0.0;
  material.pbrMetallicRoughness.roughnessFactor = 1.0;
  material.doubleSided = true;
  model.materials.push_back(material);
}

// The one mesh, its node and the scene (extras copied onto the scene too).
void AddSceneGraph(tinygltf::Primitive primitive, const GlbWriteOptions& options, tinygltf::Model& model) {
  tinygltf::Mesh mesh;
  mesh.name = "scene";
  mesh.primitives.push_back(primitive);
  model.meshes.push_back(mesh);

  tinygltf::Node node;
  node.name = "scene";
  node.mesh = 0;
  model.nodes.push_back(node);

  tinygltf::Scene scene;
  scene.name = "scene";
  scene.nodes.push_back(0);
  if (options.extras.is_object()) scene.extras = ValueFromJson(options.extras);
  model.scenes.push_back(scene);
  model.defaultScene = 0;
}

}  // namespace

std::string WriteGlb(const TriangleMesh& mesh_enu, const GlbTexture* texture, const GlbWriteOptions& options) {
  CheckGlbInput(mesh_enu, texture, options);
  const VertexData data = GltfVertexData(mesh_enu, texture);

  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "cinepath";
  if (options.extras.is_object()) model.asset.extras = ValueFromJson(options.extras);

  std::vector<unsigned char> bin;
  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  PrimitiveAccessors accessors;
  if (options.draco) {
    AddDracoPrimitive(data, options, model, bin, accessors, primitive);
  } else {
    AddPlainPrimitive(data, mesh_enu.num_vertices(), model, bin, accessors);
  }
  model.accessors.push_back(accessors.index);
  primitive.indices = 0;
  model.accessors.push_back(accessors.position);
  primitive.attributes["POSITION"] = 1;
  if (!data.colors.empty()) {
    model.accessors.push_back(accessors.color);
    primitive.attributes["COLOR_0"] = static_cast<int>(model.accessors.size()) - 1;
  }
  if (!data.texcoords.empty()) {
    model.accessors.push_back(accessors.texcoord);
    primitive.attributes["TEXCOORD_0"] = static_cast<int>(model.accessors.size()) - 1;
  }

  AddMaterial(texture, model, bin);
  primitive.material = 0;
  AddSceneGraph(primitive, options, model);

  tinygltf::Buffer buffer;
  buffer.data = std::move(bin);
  model.buffers.push_back(std::move(buffer));

  std::ostringstream stream;
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&model, stream, /*prettyPrint=*/false, /*writeBinary=*/true)) {
    throw RuntimeError("glb: tinygltf could not serialize the model");
  }
  return stream.str();
}

}  // namespace cinepath::photogrammetry
