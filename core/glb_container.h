// The binary glTF (GLB 2.0) container: a 12-byte header ("glTF", version 2, total length), a JSON
// chunk, and an optional BIN chunk (Khronos glTF 2.0 specification, section 4.4). Split into its two
// chunks and put back together, with every length checked, so that a tool can add to a GLB another
// wrote without decoding (or re-encoding) what is already in it.
#pragma once

#include <string>
#include <string_view>

namespace cinepath {

struct GlbChunks {
  std::string_view json;  // the JSON chunk's text (trailing space padding included)
  std::string_view bin;   // the BIN chunk's bytes, empty when the file has none
};

// The chunks of `glb` (views into it). InputError naming `source` for a file that is not a GLB, a
// header length that is not the file's, or a chunk that reaches past the end.
GlbChunks SplitGlb(std::string_view glb, const std::string& source);

// A GLB from a JSON text and BIN bytes: the JSON padded with spaces and the BIN with zeros to 4 bytes;
// no BIN chunk when `bin` is empty.
std::string AssembleGlb(std::string_view json, std::string_view bin);

}  // namespace cinepath
