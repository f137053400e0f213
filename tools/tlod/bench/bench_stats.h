/* Timing helpers the bench suites share (bench_stats.c). */
#ifndef TLOD_TOOLS_BENCH_STATS_H
#define TLOD_TOOLS_BENCH_STATS_H

#include <stdint.h>

/* Process CPU time (every thread), ms. */
double bench_cpu_ms(void);
/* CPU time of the calling thread, ms (with the pool's caller taking chunks
 * too, a frame's serial work shows as this exceeding process CPU / T). */
double bench_thread_cpu_ms(void);
/* Sorts the n >= 1 samples; out = {min, median} times scale. */
void bench_min_median(double* t, uint32_t n, double scale, double out[2]);

#endif
