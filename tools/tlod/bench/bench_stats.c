/* Timing helpers the bench suites share: process CPU time and min/median. */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include "bench_stats.h"

#include <stdlib.h>
#include <time.h>

double bench_cpu_ms(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

double bench_thread_cpu_ms(void) {
  struct timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

static int cmp_double(const void* a, const void* b) {
  double x = *(const double*)a, y = *(const double*)b;
  return x < y ? -1 : x > y;
}

void bench_min_median(double* t, uint32_t n, double scale, double out[2]) {
  qsort(t, n, sizeof(double), cmp_double);
  out[0] = t[0] * scale;
  out[1] = (n % 2 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2])) * scale;
}
