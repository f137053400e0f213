/* tlod bench -- this machine's memory copy bandwidth, the bound the
 * evaluation and scheduler rates are read against. */
#include <stdlib.h>
#include <string.h>

#include "bench_eval.h"
#include "cli.h"

/* Best memcpy rate of a 256 MiB buffer, bytes copied per second. */
double bench_memcpy_bandwidth(void) {
  size_t bytes = (size_t)256 << 20;
  char* a = malloc(bytes);
  char* b = malloc(bytes);
  double best = 0.0;
  if (a && b) {
    memset(a, 1, bytes);
    memset(b, 2, bytes);
    for (int i = 0; i < 5; i++) {
      double t0 = cli_now_ms();
      memcpy(b, a, bytes);
      double dt = (cli_now_ms() - t0) * 1e-3;
      a[i] = b[bytes - 1 - (size_t)i];
      double rate = (double)bytes / dt;
      best = rate > best ? rate : best;
    }
  }
  free(a);
  free(b);
  return best;
}
