// Private to the C++ import shims: the one error type they throw inside
// themselves (caught before any C boundary) and printf-style formatting.
#ifndef TESSLOD_TOOLS_IMPORT_ERROR_HPP
#define TESSLOD_TOOLS_IMPORT_ERROR_HPP

#include <cstdarg>
#include <cstdio>
#include <exception>
#include <new>
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

// Runs an importer so that no exception crosses into C: each becomes the
// job's error ("<format> parse error: ..." for foreign exceptions).
template <class F> tlod_result guarded(const _tlod_import_job* job, const char* format_name, F&& run) {
  try {
    return run();
  } catch (const ImportError& e) {
    return _tlod_import_fail(job, e.code, "%s", e.message.c_str());
  } catch (const std::bad_alloc&) {
    return _tlod_import_fail(job, TLOD_ERROR_OUT_OF_MEMORY, "out of memory");
  } catch (const std::exception& e) {
    return _tlod_import_fail(job, TLOD_ERROR_PARSE, "%s parse error: %s", format_name, e.what());
  } catch (...) {
    return _tlod_import_fail(job, TLOD_ERROR_PARSE, "%s parse error: unknown exception", format_name);
  }
}

} // namespace tlod_import_detail

#endif
