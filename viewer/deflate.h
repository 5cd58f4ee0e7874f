// zlib-format deflate (RFC 1950), level 9: the mesh inside the page, which the browser inflates with
// DecompressionStream("deflate"). Deterministic: the same bytes in give the same bytes out.
#pragma once

#include <string>
#include <string_view>

namespace cinepath::viewer {

std::string DeflateZlib(std::string_view bytes);
// The inverse, for tests; RuntimeError on corrupt input.
std::string InflateZlib(std::string_view compressed);

}  // namespace cinepath::viewer
