// Private to the C++ import shims: the one error type they throw inside
// themselves (caught before any C boundary) and printf-style formatting.
#ifndef TESSLOD_TOOLS_IMPORT_ERROR_HPP
#define TESSLOD_TOOLS_IMPORT_ERROR_HPP

#include <cstdarg>
#include <cstdio>
#include <string>

#include "import_internal.h"

namespace tlod_import_detail {

struct ImportError {
  tlod_result code;
  std::string message;
};

inline std::string format(const char* fmt, ...) _TLOD_IMPORT_PRINTF(1, 2);
inline std::string format(const char* fmt, ...) {
  char buf[512];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  return buf;
}

[[noreturn]] inline void fail(tlod_result code, const std::string& message) { throw ImportError{code, message}; }

} // namespace tlod_import_detail

#endif
