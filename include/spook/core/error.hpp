#pragma once

#include <array>
#include <charconv>
#include <cstddef>
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
void appendScalar(std::string& out, const T& value) {
  if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool> && !std::is_same_v<T, char>) {
    std::array<char, 64> buffer{};
    const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
    out.append(buffer.data(), static_cast<std::size_t>(result.ptr - buffer.data()));
  } else if constexpr (std::is_same_v<T, bool>) {
    out += value ? "true" : "false";
  } else {
    out += value;  // characters and strings
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
void appendValue(std::string& out, const T& value) {
  if constexpr (PrintedAsTuple<T>) {
    out += '(';
    for (decltype(value.size()) i = 0; i < value.size(); ++i) {
      if (i) out += ", ";
      appendScalar(out, value[i]);
    }
    out += ')';
  } else if constexpr (std::is_convertible_v<T, std::string_view>) {
    out += std::string_view(value);
  } else {
    appendScalar(out, value);
  }
}

/// "spook::RigidBody 'crate': already added to this simulation"
[[nodiscard]] inline Error makeError(std::string_view kind, std::string_view name, std::string_view what) {
  std::string message = "spook::";
  message += kind;
  if (!name.empty()) {
    message += " '";
    message += name;
    message += '\'';
  }
  message += ": ";
  message += what;
  return Error(message);
}

/// "spook::RigidBody 'crate': mass must be finite and > 0 kg, got -1"
/// (the quoted name is left out for unnamed objects).
template <class T>
[[nodiscard]] Error makeError(std::string_view kind, std::string_view name, std::string_view what, const T& value) {
  std::string message(what);
  message += ", got ";
  appendValue(message, value);
  return makeError(kind, name, message);
}

}  // namespace detail
}  // namespace spook
