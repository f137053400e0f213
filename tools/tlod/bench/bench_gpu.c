/* tlod bench -- the GPU of the suites that draw (bench_gl.h). */
#include <stdio.h>

#include "bench_gl.h"
#include "common/gpu_target.h"

int bench_gpu_open(const bench_gpu* gpu, uint32_t w, uint32_t h, tlod_platform** out) {
  char err[512];
  gpu_target_desc d = {.backend = gpu->backend, .width = w, .height = h, .title = "tlod bench"};
  if (!gpu_target_open(&d, out, err, sizeof(err))) return cli_error(CLI_FAILED, "bench %s: %s", gpu->backend, err);
  return CLI_OK;
}

int bench_frame(tlod_platform* p, tlod_context* ctx, tlod_device* dev, tlod_draw_desc* d, double* wall_ms) {
  static const float clear[4] = {0.1f, 0.1f, 0.12f, 1.0f};
  char err[512];
  double submit_ms = 0.0;
  *wall_ms = 0.0;
  if (p && !gpu_frame_begin(p, clear, d, err, sizeof(err))) return cli_error(CLI_FAILED, "%s", err);
  if (tlod_device_draw(dev, d) != TLOD_SUCCESS) {
    if (p) gpu_frame_end(p, false, &submit_ms, err, sizeof(err)); /* the frame begun is ended either way */
    return cli_error(CLI_FAILED, "%s", tlod_context_last_error(ctx));
  }
  if (p && !gpu_frame_end(p, true, &submit_ms, err, sizeof(err))) return cli_error(CLI_FAILED, "%s", err);
  *wall_ms = tlod_device_query_stats(dev).wall_ms + submit_ms;
  return CLI_OK;
}
