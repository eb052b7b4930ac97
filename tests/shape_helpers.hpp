#pragma once

// Helpers shared by the shape, mesh, geometry and space tests.

#include <string>

#include <doctest/doctest.h>

#include <spook/core/error.hpp>
#include <spook/core/math.hpp>

namespace spook::test {

/// `make()` throws spook::Error whose message names `kind` and reads "got `value`".
template <class F>
void checkRejects(F&& make, const std::string& kind, const std::string& value) {
  try {
    make();
    FAIL("no spook::Error for " << kind << " " << value);
  } catch (const spook::Error& e) {
    const std::string what = e.what();
    CHECK_MESSAGE(what.find(kind) != std::string::npos, what);
    CHECK_MESSAGE(what.find("got " + value) != std::string::npos, what);
  }
}

template <class S>
TransformT<S> at(double x, double y, double z, const QuatT<S>& q = QuatT<S>::Identity()) {
  return makeTransform<S>(Vec3T<S>(S(x), S(y), S(z)), q);
}

/// Frobenius norm of a − b relative to that of b.
template <class S>
S relative(const Mat3T<S>& a, const Mat3T<S>& b) {
  return (a - b).norm() / b.norm();
}

}  // namespace spook::test
