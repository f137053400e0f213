/* tlod bench --suite eval (bench_eval.c) and the memcpy bandwidth (bench_bandwidth.c). */
#ifndef TLOD_TOOLS_BENCH_EVAL_H
#define TLOD_TOOLS_BENCH_EVAL_H

#include <stdio.h>

#include "bench_options.h"

/* Best memcpy rate of a 256 MiB buffer, bytes copied per second. */
double bench_memcpy_bandwidth(void);
/* Preprocessing and CPU evaluation rates on o->in; csv (may be NULL) gets one row per case. */
int bench_eval(const bench_options* o, FILE* csv);

#endif
