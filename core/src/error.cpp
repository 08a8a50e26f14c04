#include "crestline/error.h"

namespace crestline {

const char* error_kind_name(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::InvalidInput:
      return "invalid input";
    case ErrorKind::Unsupported:
      return "unsupported";
    case ErrorKind::TooLarge:
      return "too large";
    case ErrorKind::Io:
      return "i/o";
    case ErrorKind::Numerical:
      return "numerical";
  }
  return "error";
}

}  // namespace crestline
