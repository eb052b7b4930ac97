#pragma once

#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>

namespace spook {

/// Thrown on bad input. The message names the object and the offending value;
/// the object the call was made on is left exactly as it was.
class Error : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

namespace detail {

template <class T>
void appendValue(std::ostringstream& out, const T& value) {
  if constexpr (requires { value.size(); value[0]; } && !std::is_convertible_v<T, std::string_view>) {
    out << '(';
    for (decltype(value.size()) i = 0; i < value.size(); ++i) out << (i ? ", " : "") << value[i];
    out << ')';
  } else {
    out << value;
  }
}

/// "spook::RigidBody 'crate': mass must be positive, got -1"
template <class T>
[[nodiscard]] Error makeError(std::string_view kind, std::string_view name, std::string_view what,
                              const T& value) {
  std::ostringstream out;
  out.precision(17);
  out << "spook::" << kind << " '" << name << "': " << what << ", got ";
  appendValue(out, value);
  return Error(out.str());
}

}  // namespace detail
}  // namespace spook
