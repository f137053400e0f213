/* tesslod::backend -- the "cpu" device: realises each item's draw list as a
 * mesh with the reference tessellator (what GPU backends are compared
 * against); one mesh per item slot, reused from draw to draw. */
#include "device_internal.h"
#include "tesslod/cpu.h"

typedef struct cpu_device {
  tlod_context* ctx;
  const tlod_patterns* patterns;
  tlod_cpu_mesh** meshes; /* per item slot */
  uint32_t mesh_count;
} cpu_device;

static tlod_result cpu_create(tlod_context* ctx, const tlod_device_desc* desc, tlod_device_stats* stats, void** state) {
  cpu_device* d = tlod_context_calloc(ctx, 1, sizeof(*d));
  if (!d) return tlod_context_fail(ctx, TLOD_ERROR_OUT_OF_MEMORY, "cpu device: out of memory");
  (void)stats;
  d->ctx = ctx;
  d->patterns = desc->patterns;
  *state = d;
  return TLOD_SUCCESS;
}

static void cpu_destroy(void* state) {
  cpu_device* d = state;
  for (uint32_t k = 0; k < d->mesh_count; k++)
    tlod_cpu_mesh_destroy(d->ctx, d->meshes[k]);
  tlod_context_free(d->ctx, d->meshes);
  tlod_context_free(d->ctx, d);
}

static tlod_result grow_meshes(cpu_device* d, uint32_t n) {
  if (n <= d->mesh_count) return TLOD_SUCCESS;
  tlod_cpu_mesh** m = tlod_context_calloc(d->ctx, n, sizeof(*m));
  if (!m) return tlod_context_fail(d->ctx, TLOD_ERROR_OUT_OF_MEMORY, "cpu device: out of memory for %u items", n);
  for (uint32_t k = 0; k < d->mesh_count; k++)
    m[k] = d->meshes[k];
  tlod_context_free(d->ctx, d->meshes);
  d->meshes = m;
  d->mesh_count = n;
  return TLOD_SUCCESS;
}

static tlod_result cpu_draw(void* state, const tlod_draw_desc* desc, const _tlod_draw_ref* refs,
                            tlod_draw_item_stats* item_stats) {
  cpu_device* d = state;
  tlod_result r = grow_meshes(d, desc->item_count);
  if (r != TLOD_SUCCESS) return r;
  for (uint32_t k = 0; k < desc->item_count; k++) {
    double ti = tlod_now_ms();
    tlod_cpu_tessellate_desc td = {.draw_list = refs[k].item->draw_list};
    r = d->meshes[k] ? tlod_cpu_tessellate_into(d->ctx, refs[k].surface, d->patterns, &td, d->meshes[k])
                     : tlod_cpu_tessellate(d->ctx, refs[k].surface, d->patterns, &td, &d->meshes[k]);
    if (r != TLOD_SUCCESS) return r;
    item_stats[k] = (tlod_draw_item_stats){.triangles = d->meshes[k]->triangle_count,
                                           .vertices = d->meshes[k]->vertex_count,
                                           .cpu_ms = tlod_now_ms() - ti};
  }
  return TLOD_SUCCESS;
}

/* No state per surface: the surface itself is all the cpu device needs. */
const _tlod_device_vtbl _tlod_cpu_device_vtbl = {
    .create = cpu_create, .destroy = cpu_destroy, .draw = cpu_draw, .times_draws = false};

const tlod_cpu_mesh* _tlod_cpu_device_mesh(const void* state, uint32_t item) {
  const cpu_device* d = state;
  return item < d->mesh_count ? d->meshes[item] : NULL;
}
