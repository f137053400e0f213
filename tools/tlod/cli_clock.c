/* tlod -- the monotonic clock of timings. */
#define _POSIX_C_SOURCE 200809L
#include <time.h>

#include "cli.h"

double cli_now_ms(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}
