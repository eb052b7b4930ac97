#pragma once

#include <string>

#include <spook/core/error.hpp>

namespace spook::test {

/// The message of the spook::Error that `make()` throws, or "no error".
template <class F>
std::string errorMessage(F&& make) {
  try {
    make();
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace spook::test
