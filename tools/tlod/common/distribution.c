/* Distributions of per-frame values by sorting (distribution.h). */
#include "distribution.h"

#include <math.h>
#include <stdlib.h>

static int compare_double(const void* a, const void* b) {
  double x = *(const double*)a, y = *(const double*)b;
  return x < y ? -1 : (x > y ? 1 : 0);
}

/* Nearest rank of p percent in n sorted values. */
static double rank_of(const double* sorted, uint32_t n, double p) {
  double rank = ceil(p / 100.0 * n);
  uint32_t i = rank < 1.0 ? 0 : (uint32_t)rank - 1;
  return sorted[i < n ? i : n - 1];
}

distribution distribution_sort(double* v, uint32_t n) {
  qsort(v, n, sizeof(double), compare_double);
  distribution d = {.min = v[0], .max = v[n - 1]};
  for (uint32_t i = 0; i < n; i++)
    d.mean += v[i];
  d.mean /= n;
  d.p50 = rank_of(v, n, 50);
  d.p95 = rank_of(v, n, 95);
  d.p99 = rank_of(v, n, 99);
  return d;
}
