// Test helper shared by every area: the message of the InputError `f` throws, or "" when it throws none.
#pragma once

#include <functional>
#include <string>

#include "core/error.h"

namespace cinepath::testing {

inline std::string InputErrorMessage(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace cinepath::testing
