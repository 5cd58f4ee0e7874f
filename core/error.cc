#include "core/error.h"

namespace cinepath {

void ThrowInternal(const char* file, int line, const char* condition) {
  throw InternalError(std::string("internal error: ") + file + ":" + std::to_string(line) +
                      ": check failed: " + condition);
}

}  // namespace cinepath
