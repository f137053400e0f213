/* tlod play -- the GL context, or the fallback to the cpu backend. */
#include <string.h>

#include "cli.h"
#include "play_run.h"

#if TLOD_HAS_GL
#include "tlod_platform.h"
#endif

tlod_platform* play_platform_open(const play_options* o, int* rc, const char** backend) {
  bool required = (o->backend && !strcmp(o->backend, "gl")) || o->window || o->screenshot_every;
  char err[512] = "";
#if TLOD_HAS_GL
  tlod_platform* p = NULL;
  tlod_platform_desc d = {
      .width = o->width, .height = o->height, .window = o->window, .visible = o->window, .title = "tlod play"};
  if (tlod_platform_create(&d, &p, err, sizeof(err))) {
    *rc = CLI_OK;
    *backend = "gl";
    return p;
  }
#else
  snprintf(err, sizeof(err), "this build has no GL backend (TLOD_BACKEND_GL=OFF)");
#endif
  if (required) {
    const char* what = o->window
                           ? "--window: cannot open a GL window"
                           : (o->backend ? "--backend gl: no GL context"
                                         : "--screenshot-every: screenshots need a GL context, and there is none");
    *rc = cli_error(CLI_FAILED, "%s: %s", what, err);
    return NULL;
  }
  if (!o->quiet) fprintf(stderr, "tlod: note: no GL context (%s); playing on the cpu backend\n", err);
  *rc = CLI_OK;
  *backend = "cpu";
  return NULL;
}

void play_platform_close(tlod_platform* p) {
#if TLOD_HAS_GL
  tlod_platform_destroy(p);
#else
  (void)p;
#endif
}

void play_platform_describe(tlod_platform* p, const char* backend, char* out, size_t size) {
  if (!strcmp(backend, "null"))
    snprintf(out, size, "null device (validates and counts every call; draws nothing, no image)");
  else
    snprintf(out, size, "cpu reference tessellator (realises each draw list as a mesh; no image)");
#if TLOD_HAS_GL
  if (p) tlod_platform_describe(p, out, size);
#else
  (void)p;
#endif
}
