/* tlod -- one-line error messages. */
#include <stdarg.h>

#include "cli.h"

/* The last message, for a summary that must say why a run failed (a
 * command runs once per process: one buffer is enough). */
static char last_error[1024];

int cli_error(int code, const char* fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(last_error, sizeof(last_error), fmt, ap);
  va_end(ap);
  fprintf(stderr, "tlod: error: %s\n", last_error);
  return code;
}

const char* cli_last_error(void) { return last_error; }
