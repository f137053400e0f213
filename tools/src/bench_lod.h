/* tlod bench suites for the scheduler (bench_lod.c). */
#ifndef TLOD_TOOLS_BENCH_LOD_H
#define TLOD_TOOLS_BENCH_LOD_H

#include "cli.h"
#include "tesslod/lod.h"

typedef struct bench_lod_options {
  const uint32_t* threads;
  uint32_t thread_count;
  uint32_t frames;
  const char* const* inputs; /* table1 models */
  uint32_t input_count;
} bench_lod_options;

/* Scheduler time per frame on 10k, 100k and 1M patches for each thread count. */
int bench_scheduler(const bench_lod_options* o, double bandwidth, FILE* csv);
/* Schwarz et al.'s Table 1: base / adaptive / uniform triangles at 1600x1144, 0.5 px, PN. */
int bench_table1(const bench_lod_options* o, FILE* csv);

#endif
