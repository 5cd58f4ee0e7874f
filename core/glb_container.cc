#include "core/glb_container.h"

#include <cstdint>
#include <cstring>

#include "core/error.h"

namespace cinepath {
namespace {

constexpr uint32_t kJsonChunk = 0x4E4F534Au;  // "JSON"
constexpr uint32_t kBinChunk = 0x004E4942u;   // "BIN\0"

uint32_t ReadU32(std::string_view bytes, size_t offset) {
  uint32_t v;
  std::memcpy(&v, bytes.data() + offset, 4);
  return v;
}

void AppendU32(std::string& out, uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); }

}  // namespace

GlbChunks SplitGlb(std::string_view glb, const std::string& source) {
  if (glb.size() < 12 || glb.substr(0, 4) != "glTF") throw InputError(source + ": not a binary glTF (GLB) file");
  if (ReadU32(glb, 4) != 2) throw InputError(source + ": GLB version " + std::to_string(ReadU32(glb, 4)) + ", not 2");
  if (ReadU32(glb, 8) != glb.size()) {
    throw InputError(source + ": the GLB header gives " + std::to_string(ReadU32(glb, 8)) + " bytes, the file has " +
                     std::to_string(glb.size()) + " (truncated or padded)");
  }
  GlbChunks chunks;
  size_t offset = 12;
  for (int chunk = 0; offset < glb.size(); ++chunk) {
    if (glb.size() - offset < 8) {
      throw InputError(source + ": GLB chunk " + std::to_string(chunk) + ": truncated header");
    }
    const uint32_t length = ReadU32(glb, offset);
    const uint32_t type = ReadU32(glb, offset + 4);
    if (length > glb.size() - offset - 8) {
      throw InputError(source + ": GLB chunk " + std::to_string(chunk) + " claims " + std::to_string(length) +
                       " bytes, " + std::to_string(glb.size() - offset - 8) + " remain");
    }
    const std::string_view data = glb.substr(offset + 8, length);
    if (chunk == 0 && type != kJsonChunk) throw InputError(source + ": the first GLB chunk is not JSON");
    if (chunk == 0) chunks.json = data;
    if (chunk == 1 && type == kBinChunk) chunks.bin = data;
    offset += 8 + length;
  }
  if (chunks.json.data() == nullptr) throw InputError(source + ": the GLB has no JSON chunk");
  return chunks;
}

std::string AssembleGlb(std::string_view json, std::string_view bin) {
  const size_t json_padded = (json.size() + 3) / 4 * 4;
  const size_t bin_padded = (bin.size() + 3) / 4 * 4;
  const size_t total = 12 + 8 + json_padded + (bin.empty() ? 0 : 8 + bin_padded);
  CINEPATH_CHECK(total <= UINT32_MAX);
  std::string out;
  out.reserve(total);
  out.append("glTF");
  AppendU32(out, 2);
  AppendU32(out, static_cast<uint32_t>(total));
  AppendU32(out, static_cast<uint32_t>(json_padded));
  AppendU32(out, kJsonChunk);
  out.append(json);
  out.append(json_padded - json.size(), ' ');
  if (!bin.empty()) {
    AppendU32(out, static_cast<uint32_t>(bin_padded));
    AppendU32(out, kBinChunk);
    out.append(bin);
    out.append(bin_padded - bin.size(), '\0');
  }
  return out;
}

}  // namespace cinepath
