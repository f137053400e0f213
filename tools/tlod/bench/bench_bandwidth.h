/* tlod bench -- this machine's memory rates, measured in the same run as
 * the cases read against them (bench_bandwidth.c), and the bound of a
 * stage: bytes read / read rate + bytes written / write rate. */
#ifndef TLOD_TOOLS_BENCH_BANDWIDTH_H
#define TLOD_TOOLS_BENCH_BANDWIDTH_H

#include <stdbool.h>
#include <stdint.h>

/* Bytes per second on buffers larger than the last-level cache: read (a
 * sum over the buffer), write (memset), copy (memcpy, bytes copied: each
 * byte is read once and written once); per CPU-second of the process (the
 * clock the cases' figures use) and per wall-clock second (_wall). */
typedef struct bench_rates {
  double read, write, copy;
  double read_wall, write_wall, copy_wall;
} bench_rates;

/* rates[0]: one thread, rates[1]: two threads (each its half). */
typedef struct bench_bandwidth {
  bench_rates rates[2];
  uint32_t mib; /* buffer size */
} bench_bandwidth;

/* The default buffer: twice the 300 MB last-level cache of this machine
 * kind, so the rates are memory's, not the cache's. */
#define BENCH_BANDWIDTH_MIB 640u

/* Best of 5 per rate on two buffers of mib MiB (the run the host disturbed
 * least). false: out of memory. */
bool bench_bandwidth_measure(bench_bandwidth* out, uint32_t mib);
/* The rates of `threads` (1, or 2 for two and more). */
const bench_rates* bench_bandwidth_rates(const bench_bandwidth* b, uint32_t threads);
/* CPU ms a stage needs at least to move its bytes: read / read rate +
 * written / write rate. */
double bench_bound_ms(const bench_rates* r, double bytes_read, double bytes_written);
/* Prints the rates (one line) and the bound's formula. */
void bench_bandwidth_print(const bench_bandwidth* b);

#endif
