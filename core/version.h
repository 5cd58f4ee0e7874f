#pragma once

namespace cinepath {
inline constexpr const char* kVersion = "0.1.0";
// Every file cinepath writes carries "schema": "<kind>/<version>", e.g. "cinepath.plan/1".
inline constexpr const char* kSchemaPrefix = "cinepath.";
}  // namespace cinepath
