/* tesslod::backend -- the "cpu" backend: realises each draw list as a mesh
 * with the reference tessellator (what GPU backends are compared against). */

#include "backend_internal.h"
#include "tesslod/cpu.h"

typedef struct cpu_backend {
  tlod_context* ctx;
  const tlod_surface* surface;
  const tlod_patterns* patterns;
  tlod_cpu_mesh* mesh;
  tlod_backend_timings timings;
} cpu_backend;

static tlod_result cpu_create(tlod_context* ctx, const tlod_backend_desc* desc, void** state) {
  (void)desc;
  cpu_backend* b = _tlod_calloc(ctx, 1, sizeof(*b));
  if (!b) return _tlod_fail(ctx, TLOD_ERROR_OUT_OF_MEMORY, "cpu backend: out of memory");
  b->ctx = ctx;
  b->timings.gpu_ms = -1.0;
  *state = b;
  return TLOD_SUCCESS;
}

static void cpu_destroy(void* state) {
  cpu_backend* b = state;
  tlod_cpu_mesh_destroy(b->ctx, b->mesh);
  _tlod_free(b->ctx, b);
}

static tlod_result cpu_upload(void* state, const tlod_surface* surface, const tlod_patterns* patterns) {
  cpu_backend* b = state;
  b->surface = surface;
  b->patterns = patterns;
  return TLOD_SUCCESS;
}

static tlod_result cpu_draw(void* state, const tlod_backend_frame* frame) {
  cpu_backend* b = state;
  if (!b->surface) return _tlod_fail(b->ctx, TLOD_ERROR_INVALID_ARGUMENT, "cpu backend: draw before upload");
  double t0 = _tlod_now_ms();
  tlod_cpu_tessellate_desc d = {.draw_list = frame->draw_list};
  tlod_result r = b->mesh ? tlod_cpu_tessellate_into(b->ctx, b->surface, b->patterns, &d, b->mesh)
                          : tlod_cpu_tessellate(b->ctx, b->surface, b->patterns, &d, &b->mesh);
  if (r != TLOD_SUCCESS) return r;
  b->timings.cpu_ms = b->timings.wall_ms = _tlod_now_ms() - t0;
  b->timings.triangles = b->mesh->triangle_count;
  b->timings.vertices = b->mesh->vertex_count;
  b->timings.draw_calls = 0;
  return TLOD_SUCCESS;
}

static tlod_result cpu_read_image(void* state, uint32_t width, uint32_t height, uint8_t* rgba) {
  (void)width, (void)height, (void)rgba;
  cpu_backend* b = state;
  return _tlod_fail(b->ctx, TLOD_ERROR_UNSUPPORTED,
                    "cpu backend: it realises meshes and has no image (use tlod_backend_cpu_mesh)");
}

static tlod_backend_timings cpu_timings(const void* state) { return ((const cpu_backend*)state)->timings; }

const tlod_backend_vtbl _tlod_cpu_backend_vtbl = {cpu_create, cpu_destroy,    cpu_upload,
                                                  cpu_draw,   cpu_read_image, cpu_timings};

const tlod_cpu_mesh* _tlod_cpu_backend_mesh(const void* state) { return ((const cpu_backend*)state)->mesh; }
