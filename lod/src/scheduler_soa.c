/* tesslod::lod -- the fast path's structure-of-arrays inputs: patch
 * spheres, error bounds per level and corner ids, vertex positions and
 * normals, copied from the mesh and surface views and copied again when
 * their generations move (tlod_mesh_update, tlod_surface_refresh). */
#include <string.h>

#include "scheduler_frame.h"

void _tlod_soa_free(tlod_context* ctx, _tlod_soa* a) {
  void* arrays[] = {a->cx, a->cy, a->cz, a->radius, a->bound, a->corner, a->px,
                    a->py, a->pz, a->nx, a->ny,     a->nz,    a->packed};
  for (size_t i = 0; i < sizeof(arrays) / sizeof(arrays[0]); i++)
    tlod_context_free(ctx, arrays[i]);
  _tlod_blocks_free(ctx, a);
  memset(a, 0, sizeof(*a));
}

/* One spare entry each, as the view arrays (a mesh of no faces). */
static bool soa_alloc(tlod_context* ctx, _tlod_soa* a, uint32_t np, uint32_t nv, uint32_t levels) {
  size_t p = (size_t)np + 1, v = (size_t)nv + 1;
  float** pf[] = {&a->cx, &a->cy, &a->cz, &a->radius};
  float** vf[] = {&a->px, &a->py, &a->pz, &a->nx, &a->ny, &a->nz};
  bool ok = true;
  for (size_t i = 0; i < 4; i++)
    ok = (*pf[i] = tlod_context_alloc(ctx, sizeof(float) * p)) && ok;
  for (size_t i = 0; i < 6; i++)
    ok = (*vf[i] = tlod_context_alloc(ctx, sizeof(float) * v)) && ok;
  ok = (a->bound = tlod_context_alloc(ctx, sizeof(float) * p * levels)) && ok;
  ok = (a->corner = tlod_context_alloc(ctx, sizeof(uint32_t) * p * 4)) && ok;
  ok = (a->packed = tlod_context_alloc(ctx, sizeof(uint32_t) * v)) && ok;
  return ok;
}

/* Frees every array (the next update starts again) and fails. */
static tlod_result soa_out_of_memory(tlod_scheduler* s) {
  _tlod_soa_free(s->ctx, &s->soa);
  return tlod_context_fail(s->ctx, TLOD_ERROR_OUT_OF_MEMORY, "scheduler '%s': out of memory", s->label);
}

static void copy_patches(_tlod_soa* a, const tlod_surface_view* sv, const tlod_mesh_view* mv) {
  uint32_t n = a->patch_count;
  for (uint32_t f = 0; f < n; f++) {
    const tlod_patch_info* info = &sv->patches[f];
    a->cx[f] = info->center[0], a->cy[f] = info->center[1], a->cz[f] = info->center[2];
    a->radius[f] = info->radius;
    for (uint32_t l = 0; l < a->levels; l++)
      a->bound[(size_t)l * n + f] = tlod_patch_error_bound(info, l);
    for (uint32_t c = 0; c < 4; c++)
      a->corner[c * n + f] = mv->faces[f][c < mv->face_corners[f] ? c : 0];
  }
}

static void copy_vertices(_tlod_soa* a, const tlod_mesh_view* mv) {
  for (uint32_t i = 0; i < a->vertex_count; i++) {
    a->px[i] = mv->positions[i][0], a->py[i] = mv->positions[i][1], a->pz[i] = mv->positions[i][2];
    a->nx[i] = mv->normals[i][0], a->ny[i] = mv->normals[i][1], a->nz[i] = mv->normals[i][2];
  }
}

static tlod_result soa_copy(tlod_scheduler* s, const tlod_mesh_view* mv, const tlod_surface_view* sv) {
  _tlod_soa* a = &s->soa;
  if (!a->cx) {
    a->patch_count = s->patch_count, a->vertex_count = s->vertex_count, a->levels = s->desc.max_level + 1;
    if (!soa_alloc(s->ctx, a, a->patch_count, a->vertex_count, a->levels)) return soa_out_of_memory(s);
  }
  copy_patches(a, sv, mv);
  copy_vertices(a, mv);
  if (!_tlod_blocks_build(s->ctx, a)) return soa_out_of_memory(s);
  a->mesh_generation = mv->generation, a->surface_generation = sv->generation;
  return TLOD_SUCCESS;
}

tlod_result _tlod_soa_update(tlod_scheduler* s, const tlod_mesh_view* mv, const tlod_surface_view* sv) {
  _tlod_soa* a = &s->soa;
  bool fresh = a->mesh_generation == mv->generation && a->surface_generation == sv->generation;
  tlod_result r = fresh ? TLOD_SUCCESS : soa_copy(s, mv, sv);
  if (r == TLOD_SUCCESS && !_tlod_blocks_hold(s->ctx, a, s->view_count)) r = soa_out_of_memory(s);
  return r;
}
