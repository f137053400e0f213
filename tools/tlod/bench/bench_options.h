/* tlod bench -- its options. */
#ifndef TLOD_TOOLS_BENCH_OPTIONS_H
#define TLOD_TOOLS_BENCH_OPTIONS_H

#include <stdbool.h>
#include <stdint.h>

typedef struct bench_options {
  const char* in;
  const char* csv;
  uint32_t levels[8], level_count;
  uint32_t threads[8], thread_count;
  uint32_t repeat, warmup, frames;
  const char* suite;
  const char* table1[16];
  uint32_t table1_count;
  const char* backend;      /* the suites that draw: "gl" (default) or "vulkan" */
  const char* shader_cache; /* vulkan: --shader-cache DIR or "off"; NULL: the default folder */
  bool peers;               /* --peers: side by side with OpenSubdiv (bench_peers.h) instead of a suite */
  uint32_t peer_faces;      /* --peer-faces N: one mesh size; 0: 100k and 1M faces */
  const char* json;         /* --json FILE: the figures as JSON (written atomically) */
} bench_options;

/* CLI_OK, or CLI_USAGE with the error printed; --help prints and exits. */
int bench_parse(int argc, char** argv, bench_options* o);

#endif
