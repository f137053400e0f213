/* tlod bench -- its options. */
#ifndef TLOD_TOOLS_BENCH_OPTIONS_H
#define TLOD_TOOLS_BENCH_OPTIONS_H

#include <stdbool.h>
#include <stdint.h>

/* gl and draw frames per case without --frames: frame times on a software
 * rasteriser vary more than the scheduler's, so the median needs more. */
#define BENCH_GPU_FRAMES 60u

typedef struct bench_options {
  const char* in;
  const char* csv;
  uint32_t levels[8], level_count;
  uint32_t threads[8], thread_count;
  uint32_t repeat, warmup, frames;
  bool frames_given; /* --frames given: gl and draw default to more frames (BENCH_GPU_FRAMES) */
  const char* suite;
  const char* table1[16];
  uint32_t table1_count;
  const char* backend;                       /* the suites that draw: "gl" (default) or "vulkan" */
  const char* shader_cache;                  /* vulkan: --shader-cache DIR or "off"; NULL: the default folder */
  const char* json;                          /* --json FILE: the figures as one JSON document, written atomically */
  const char* scheduler_mesh;                /* --scheduler-mesh IN: the figures suite's scheduler mesh */
  uint32_t bandwidth_mib;                    /* --bandwidth-mib N: memory-rate buffers */
  uint32_t peer_faces;                       /* --peer-faces N: one mesh size; 0: 100k and 1M faces */
  const char* peer_mesh;                     /* --peer-mesh KIND: triangle, quad or mixed; NULL: all three */
  uint32_t peer_levels[8], peer_level_count; /* --peer-levels L,L: levels 1-4; count 0: all four */
} bench_options;

/* CLI_OK, or CLI_USAGE with the error printed; --help prints and exits. */
int bench_parse(int argc, char** argv, bench_options* o);

#endif
