// The message of an InputError, for tests of error messages.
#pragma once
#include <functional>
#include <string>
#include "io/json_reader.h"

namespace caustica::test {

// The message of the InputError `f` throws ("" when it throws none).
inline std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace caustica::test
