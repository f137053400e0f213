/* tlod -- one-line error messages. */
#include <stdarg.h>

#include "cli.h"

int cli_error(int code, const char* fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  fputs("tlod: error: ", stderr);
  vfprintf(stderr, fmt, ap);
  fputc('\n', stderr);
  va_end(ap);
  return code;
}
