/* tlod bench --suite eval (bench_eval.c), --suite build (bench_build.c) and
 * the other suites of IN. */
#ifndef TLOD_TOOLS_BENCH_EVAL_H
#define TLOD_TOOLS_BENCH_EVAL_H

#include <stdio.h>

#include "bench_options.h"

/* Preprocessing and CPU evaluation rates on o->in against rep's memory
 * rates; csv (may be NULL) gets one row per case, rep's json the cases and
 * eval_bandwidth_fraction (Phong, level 5, 2 threads). */
struct bench_report;
int bench_eval(const bench_options* o, struct bench_report* rep, FILE* csv);
/* Surface build CPU time on one thread, measured error tables against the
 * closed form, per surface type, on o->in; csv (may be NULL) one row per type. */
int bench_build(const bench_options* o, FILE* csv);

/* Skinning, mesh update and surface refresh per frame on the generated
 * skinned cylinder (bench_skin.c); csv one row per size, threads, stage. */
int bench_skin(const bench_options* o, FILE* csv);
/* 50 instances against the same triangles in one object, on cpu and gpu->backend (bench_objects.c). */
struct bench_gpu;
int bench_objects(const bench_options* o, const struct bench_gpu* gpu, FILE* csv);

#endif
