#pragma once
// One exception type for everything the user can cause. The message is one
// sentence naming the problem; callers that know the file name prefix it.
#include <stdexcept>
#include <string>

namespace crestline {

enum class ErrorKind {
  InvalidInput,  // the data is broken: NaN, indices out of range, no triangles
  Unsupported,   // valid data we cannot read (format, extension)
  TooLarge,      // refused before allocating: beyond the configured limits
  Io,            // the file cannot be opened, read or written
  Numerical,     // a solver failed to converge or factorize
};

const char* error_kind_name(ErrorKind kind);

class Error : public std::runtime_error {
 public:
  Error(ErrorKind kind, const std::string& message) : std::runtime_error(message), kind_(kind) {}
  ErrorKind kind() const { return kind_; }

 private:
  ErrorKind kind_;
};

}  // namespace crestline
