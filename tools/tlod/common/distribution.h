/* A distribution of per-frame values (frame times, triangles): the mean,
 * nearest-rank percentiles, min and max. The play summary and the run
 * comparison (tlod compare, the dashboard) both use it, so a run compared
 * with itself shows its summary's figures. */
#ifndef TLOD_TOOLS_DISTRIBUTION_H
#define TLOD_TOOLS_DISTRIBUTION_H

#include <stdint.h>

typedef struct distribution {
  double mean, p50, p95, p99, max, min;
} distribution;

/* Sorts v[0..n) in place (n >= 1) and returns its distribution. Percentile
 * p is the value at position ceil(p/100 * n) of the sorted values (nearest
 * rank, 1-based; docs/play.md). */
distribution distribution_sort(double* v, uint32_t n);

#endif
