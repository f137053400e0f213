/* tlod bench --suite gl (bench_gl.c). */
#ifndef TLOD_TOOLS_BENCH_GL_H
#define TLOD_TOOLS_BENCH_GL_H

#include "cli.h"

/* Frame times of the GL backend for each model, and Phong against flat on the first. */
int bench_gl(const char* const* models, uint32_t model_count, uint32_t frames, FILE* csv);

#endif
