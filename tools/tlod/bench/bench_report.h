/* tlod bench -- what one run reports beside its cases: the processor, the
 * SIMD level the library chose, the memory rates measured in the run, and
 * the headline figures of issue 15 (bench_report.c), on stdout and into the
 * --json document. */
#ifndef TLOD_TOOLS_BENCH_REPORT_H
#define TLOD_TOOLS_BENCH_REPORT_H

#include <stdbool.h>

#include "bench_bandwidth.h"
#include "common/json_writer.h"

typedef struct bench_report {
  json_writer* json; /* NULL without --json; suites add their cases to it */
  bench_bandwidth bw;
  /* NAN until a suite measures them (written as null). */
  double scheduler_1m_ms;         /* refine-moving, 2 threads: median process CPU per frame / 2 */
  double scheduler_1m_cpu_ms;     /* the same, process CPU per frame (both threads) */
  double scheduler_1m_wall_ms;    /* the same, median wall clock per frame */
  double eval_bandwidth_fraction; /* Phong L5 T2: output bytes over memcpy's bytes copied, per CPU-second */
  double strip_triangle_overhead; /* Table 1 scenes, HYBRID: worst scene's strip / pattern triangles */
  const char* scheduler_mesh;     /* the mesh scheduler_1m_ms was measured on */
  uint32_t scheduler_patches;
} bench_report;

/* Prints the processor and SIMD level and measures the memory rates (buffers
 * of bandwidth_mib MiB; 0: not measured, for the suites that do not read
 * them), writing them all to json. false: error printed. */
bool bench_report_begin(bench_report* r, json_writer* json, uint32_t bandwidth_mib);
/* Prints the headline figures and writes them to json (null: not measured). */
void bench_report_end(const bench_report* r);
/* The processor's model name (/proc/cpuinfo), with family/model, e.g.
 * "Intel(R) Xeon(R) Processor (family 6 model 207)"; "unknown" elsewhere. */
void bench_processor(char* buf, size_t size);

#endif
