/* tesslod::core -- a surface's read-only view and its packed per-patch
 * records, the layout GPU shaders read (std430 Patch). */
#include <string.h>

#include "internal.h"

tlod_surface_view tlod_surface_query_view(const tlod_surface* s) {
  if (!s) return (tlod_surface_view){0};
  return (tlod_surface_view){.type = s->desc.type,
                             .patch_count = s->patch_count,
                             .patches = s->info,
                             .vertex_alpha = s->alpha,
                             .generation = s->generation};
}

static void copy3(float dst[4], const float src[3]) { memcpy(dst, src, sizeof(float) * 3); }

static void fill_record(const tlod_surface* s, uint32_t f, tlod_patch_record* out) {
  const tlod_mesh* m = s->mesh;
  memset(out, 0, sizeof(*out));
  out->info[0] = m->face_corners[f];
  for (uint32_t c = 0; c < m->face_corners[f]; c++) {
    uint32_t v = m->faces[f][c];
    copy3(out->corner[c], m->positions[v]);
    out->corner[c][3] = s->alpha[v];
    copy3(out->normal[c], m->normals[v]);
    out->weld[c] = m->weld_id[v];
  }
  if (s->quad) {
    /* Lagrange nodes M0..M3 and the centre, w = 0 (core.h tlod_patch_record). */
    for (int i = 0; i < 5; i++)
      copy3(out->pn_control[i], s->quad[f].node[i]);
    out->info[1] = s->quad[f].given;
  }
  if (!s->pn) return;
  for (int i = 0; i < 10; i++)
    copy3(out->pn_control[i], s->pn[f].b[i]);
  for (int i = 0; i < 3; i++)
    copy3(out->pn_normal[i], s->pn[f].n[i]);
}

tlod_result tlod_surface_patch_records(const tlod_surface* s, uint32_t first, uint32_t count, tlod_patch_record* out) {
  if (!s) return TLOD_ERROR_INVALID_ARGUMENT;
  if (!out || first > s->patch_count || count > s->patch_count - first)
    return _tlod_fail(s->ctx, TLOD_ERROR_INVALID_ARGUMENT,
                      "surface '%s': patch records [%u, %u + %u) outside its %u patches (or out is NULL)", s->label,
                      first, first, count, s->patch_count);
  for (uint32_t k = 0; k < count; k++)
    fill_record(s, first + k, &out[k]);
  return TLOD_SUCCESS;
}
