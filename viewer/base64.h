// Standard base64 (RFC 4648 alphabet, '=' padding, no line breaks): how the page carries binary data
// (the mesh, rendered frames, three.js as a data: URL).
#pragma once

#include <string>
#include <string_view>

namespace cinepath::viewer {

std::string Base64Encode(std::string_view bytes);

}  // namespace cinepath::viewer
