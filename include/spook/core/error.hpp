#pragma once

#include <array>
#include <charconv>
#include <cstddef>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>

namespace spook {

/// Thrown on bad input. The message names the object and the offending value;
/// the object the call was made on is left exactly as it was.
class Error : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

namespace detail {

// Floating-point values print in their shortest round-trip form (0.1, not
// 0.10000000000000001), so a message shows exactly the value passed.
template <class T>
void appendScalar(std::ostringstream& out, const T& value) {
  if constexpr (std::is_floating_point_v<T>) {
    std::array<char, 64> buffer{};
    const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
    out << std::string_view(buffer.data(), static_cast<std::size_t>(result.ptr - buffer.data()));
  } else {
    out << value;
  }
}

// Vectors and matrices print as (a, b, c); strings and scalars as themselves.
template <class T>
concept Indexable = requires(const T& v) {
  v.size();
  v[0];
};
template <class T>
concept PrintedAsTuple = Indexable<T> && !std::is_convertible_v<T, std::string_view>;

template <class T>
void appendValue(std::ostringstream& out, const T& value) {
  if constexpr (PrintedAsTuple<T>) {
    out << '(';
    for (decltype(value.size()) i = 0; i < value.size(); ++i) {
      if (i) out << ", ";
      appendScalar(out, value[i]);
    }
    out << ')';
  } else {
    appendScalar(out, value);
  }
}

/// "spook::RigidBody 'crate': mass must be finite and > 0 kg, got -1"
/// (the quoted name is left out for unnamed objects).
template <class T>
[[nodiscard]] Error makeError(std::string_view kind, std::string_view name, std::string_view what, const T& value) {
  std::ostringstream out;
  out << "spook::" << kind;
  if (!name.empty()) out << " '" << name << "'";
  out << ": " << what << ", got ";
  appendValue(out, value);
  return Error(out.str());
}

/// "spook::RigidBody 'crate': already added to this simulation"
[[nodiscard]] inline Error makeError(std::string_view kind, std::string_view name, std::string_view what) {
  std::ostringstream out;
  out << "spook::" << kind;
  if (!name.empty()) out << " '" << name << "'";
  out << ": " << what;
  return Error(out.str());
}

}  // namespace detail
}  // namespace spook
