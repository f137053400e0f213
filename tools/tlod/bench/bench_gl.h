/* tlod bench --suite gl (bench_gl.c) and what the suites that draw share
 * (bench_gpu.c): the GPU of --backend gl or vulkan and one timed frame. */
#ifndef TLOD_TOOLS_BENCH_GL_H
#define TLOD_TOOLS_BENCH_GL_H

#include "cli.h"
#include "tesslod/backend.h"

typedef struct tlod_platform tlod_platform;

/* --backend and, for vulkan, the shader cache folder in use (NULL: none). */
typedef struct bench_gpu {
  const char* backend; /* "gl" or "vulkan" */
  const char* shader_cache;
} bench_gpu;

/* Headless platform of w x h for gpu->backend; CLI_FAILED with the error printed. */
int bench_gpu_open(const bench_gpu* gpu, uint32_t w, uint32_t h, tlod_platform** out);
/* One frame: begin (cleared), the draw, end (vulkan: submit) and wait for
 * the GPU. *wall_ms: the device's wall time plus the submit and the wait
 * (gl: around its finish), so both APIs' frames include their GPU work. A
 * platform NULL draws without one (the cpu backend). */
int bench_frame(tlod_platform* p, tlod_context* ctx, tlod_device* dev, tlod_draw_desc* d, double* wall_ms);

/* Frame times of the GPU backend for each model, and Phong against flat on the first. */
int bench_gl(const bench_gpu* gpu, const char* const* models, uint32_t model_count, uint32_t frames, FILE* csv);

/* Backend CPU time per frame for about 100k visible patches (bench_draw.c);
 * rep's json gets the cases. */
struct bench_report;
int bench_draw(const bench_gpu* gpu, uint32_t frames, struct bench_report* rep, FILE* csv);
/* Vulkan device start without, with an empty and with a filled shader cache (bench_vkstart.c). */
int bench_vkstart(uint32_t repeat, FILE* csv);

#endif
