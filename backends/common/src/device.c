/* tesslod::backend -- backend selection by name and the one dispatch point
 * for every call into a backend. */
#include <stdio.h>
#include <string.h>

#include "backend_internal.h"

struct tlod_backend {
  tlod_context* ctx;
  const char* name;
  const tlod_backend_vtbl* vtbl;
  void* state;
};

typedef struct backend_creator {
  const char* name;
  const tlod_backend_vtbl* vtbl; /* NULL: not compiled in */
  const char* missing;           /* why not */
} backend_creator;

static const backend_creator creators[] = {
    {"cpu", &_tlod_cpu_backend_vtbl, NULL},
#if TLOD_HAS_GL
    {"gl", &_tlod_gl_vtbl, NULL},
#else
    {"gl", NULL, "built without TLOD_BACKEND_GL"},
#endif
    {"vulkan", NULL, "the Vulkan backend is not written yet"},
};

const char* tlod_backend_names(void) { return TLOD_HAS_GL ? "cpu,gl" : "cpu"; }

tlod_result tlod_backend_create(tlod_context* ctx, const tlod_backend_desc* desc, tlod_backend** out) {
  if (out) *out = NULL;
  if (!ctx) return TLOD_ERROR_INVALID_ARGUMENT;
  if (!out) return _tlod_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "tlod_backend_create: out is NULL");
  const char* name = desc && desc->name ? desc->name : "cpu";
  const backend_creator* c = NULL;
  for (size_t i = 0; i < sizeof(creators) / sizeof(creators[0]); i++)
    if (!strcmp(creators[i].name, name)) c = &creators[i];
  if (!c)
    return _tlod_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "unknown backend '%s' (this build has: %s)", name,
                      tlod_backend_names());
  if (!c->vtbl) return _tlod_fail(ctx, TLOD_ERROR_UNSUPPORTED, "backend '%s' is not available: %s", name, c->missing);
  tlod_backend* b = _tlod_calloc(ctx, 1, sizeof(*b));
  if (!b) return _tlod_fail(ctx, TLOD_ERROR_OUT_OF_MEMORY, "tlod_backend_create: out of memory");
  b->ctx = ctx;
  b->name = c->name;
  b->vtbl = c->vtbl;
  tlod_result r = c->vtbl->create(ctx, desc, &b->state);
  if (r != TLOD_SUCCESS) {
    _tlod_free(ctx, b);
    return r;
  }
  *out = b;
  return TLOD_SUCCESS;
}

void tlod_backend_destroy(tlod_backend* b) {
  if (!b) return;
  b->vtbl->destroy(b->state);
  _tlod_free(b->ctx, b);
}

const char* tlod_backend_name(const tlod_backend* b) { return b ? b->name : ""; }

tlod_result tlod_backend_upload(tlod_backend* b, const tlod_surface* surface, const tlod_patterns* patterns) {
  if (!b) return TLOD_ERROR_INVALID_ARGUMENT;
  if (!surface || !patterns)
    return _tlod_fail(b->ctx, TLOD_ERROR_INVALID_ARGUMENT, "tlod_backend_upload: NULL argument");
  return b->vtbl->upload(b->state, surface, patterns);
}

tlod_result tlod_backend_draw(tlod_backend* b, const tlod_backend_frame* frame) {
  if (!b) return TLOD_ERROR_INVALID_ARGUMENT;
  if (!frame || !frame->draw_list)
    return _tlod_fail(b->ctx, TLOD_ERROR_INVALID_ARGUMENT, "tlod_backend_draw: no frame or draw list");
  if ((unsigned)frame->debug >= TLOD_DEBUG_NUM)
    return _tlod_fail(b->ctx, TLOD_ERROR_INVALID_ARGUMENT, "tlod_backend_draw: unknown debug view %d",
                      (int)frame->debug);
  return b->vtbl->draw(b->state, frame);
}

tlod_result tlod_backend_read_image(tlod_backend* b, uint32_t width, uint32_t height, uint8_t* rgba) {
  if (!b) return TLOD_ERROR_INVALID_ARGUMENT;
  if (!rgba || !width || !height)
    return _tlod_fail(b->ctx, TLOD_ERROR_INVALID_ARGUMENT, "tlod_backend_read_image: empty image");
  return b->vtbl->read_image(b->state, width, height, rgba);
}

tlod_backend_timings tlod_backend_query_timings(const tlod_backend* b) {
  return b ? b->vtbl->timings(b->state) : (tlod_backend_timings){0};
}

const struct tlod_cpu_mesh* tlod_backend_cpu_mesh(const tlod_backend* b) {
  return b && b->vtbl == &_tlod_cpu_backend_vtbl ? _tlod_cpu_backend_mesh(b->state) : NULL;
}
