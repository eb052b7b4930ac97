#pragma once

#include <spook/core/scalar.hpp>

namespace spook {

/// Simulated time (s), the argument of every listener callback: AGX's
/// agx::TimeStamp, a plain scalar. Callbacks take it by const reference, as
/// in the seeds: `void pre(const spook::TimeStamp& t) override`.
template <Scalar S>
using TimeStampT = S;

using TimeStamp = TimeStampT<double>;
namespace f32 {
using TimeStamp = TimeStampT<float>;
}  // namespace f32

}  // namespace spook
