/* tlod play -- the GPU platform (a GL context or a Vulkan device), or the
 * default's fallback to the cpu backend when no GL context can be made.
 * Vulkan never falls back: asked for, it starts or the run fails. */
#include <string.h>

#include "cli.h"
#include "common/gpu_target.h"
#include "play_run.h"

#if TLOD_HAS_GL || TLOD_HAS_VULKAN
#include "tlod_platform.h"
#endif

/* What could not be had, for the error line. */
static const char* failed_what(const play_options* o, bool vulkan) {
  if (vulkan) return o->validate ? "--backend vulkan --validate" : "--backend vulkan";
  if (o->window) return "--window: cannot open a GL window";
  if (o->backend) return "--backend gl: no GL context";
  return "--screenshot-every: screenshots need a GL context, and there is none";
}

tlod_platform* play_platform_open(const play_options* o, int* rc, const char** backend) {
  bool vulkan = o->backend && !strcmp(o->backend, "vulkan");
  bool required = vulkan || (o->backend && !strcmp(o->backend, "gl")) || o->window || o->screenshot_every;
  char err[512] = "";
  tlod_platform* p = NULL;
  gpu_target_desc d = {.backend = vulkan ? "vulkan" : "gl",
                       .width = o->width,
                       .height = o->height,
                       .window = o->window,
                       .validation = o->validate,
                       .title = "tlod play"};
  if (gpu_target_open(&d, &p, err, sizeof(err))) {
    *rc = CLI_OK;
    *backend = d.backend;
    return p;
  }
  if (required) {
    *rc = cli_error(CLI_FAILED, "%s: %s", failed_what(o, vulkan), err);
    return NULL;
  }
  if (!o->quiet) fprintf(stderr, "tlod: note: no GL context (%s); playing on the cpu backend\n", err);
  *rc = CLI_OK;
  *backend = "cpu";
  return NULL;
}

void play_platform_close(tlod_platform* p) { gpu_target_close(p); }

void play_platform_describe(tlod_platform* p, const char* backend, char* out, size_t size) {
  if (!strcmp(backend, "null"))
    snprintf(out, size, "null device (validates and counts every call; draws nothing, no image)");
  else
    snprintf(out, size, "cpu reference tessellator (realises each draw list as a mesh; no image)");
#if TLOD_HAS_GL || TLOD_HAS_VULKAN
  if (p) tlod_platform_describe(p, out, size);
#else
  (void)p;
#endif
}
