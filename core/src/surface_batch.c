/* tesslod::core -- tlod_surface_eval_interior(): a patch's interior points
 * in lanes of BATCH, the kernels of surface_batch.inc compiled per
 * instruction set and chosen by the caller's tlod_simd. Bitwise the scalar
 * evaluation (_tlod_patch_eval_with): same operations, same order, exact
 * IEEE sqrt and division, no contraction (-ffp-contract=off). Surfaces the
 * kernels do not cover (quadratic faces, true shading normals) take the
 * scalar code point by point. */
#include <string.h>

#include "surface_eval.h"

enum { BATCH = 64 };

/* One batch of lanes: inputs (u, v), outputs as structure-of-arrays and
 * the lanes the scalar code must redo. */
typedef struct _tlod_batch {
  float u[BATCH], v[BATCH];
  float px[BATCH], py[BATCH], pz[BATCH];
  float nx[BATCH], ny[BATCH], nz[BATCH];
  int flag[BATCH];
} _tlod_batch;

typedef void (*corner_kernel)(const _tlod_corners* c, _tlod_batch* b, uint32_t n, bool normals);
typedef void (*pn_kernel)(const _tlod_corners* c, const _tlod_pn_patch* pt, _tlod_batch* b, uint32_t n, bool normals);

typedef void (*store_kernel)(const _tlod_batch* b, uint32_t n, float* pos, float* nrm);

typedef struct kernels {
  corner_kernel flat, phong;
  pn_kernel pn;
  store_kernel store;
} kernels;

#define KERNEL_FILE "surface_batch.inc"
#include "simd_instances.inc"
#undef KERNEL_FILE

static const kernels* kernels_for(tlod_simd simd) {
  static const kernels table[] = {
    {flat_scalar, phong_scalar, pn_scalar, store_scalar},
#if defined(__x86_64__)
    {flat_sse2, phong_sse2, pn_sse2, store_sse2},
    {flat_avx2, phong_avx2, pn_avx2, store_avx2},
    {flat_avx512, phong_avx512, pn_avx512, store_avx512},
#endif
  };
  int at = 0;
#if defined(__x86_64__)
  at = simd == TLOD_SIMD_AVX512 ? 3 : simd == TLOD_SIMD_AVX2 ? 2 : simd == TLOD_SIMD_SSE2 ? 1 : 0;
#else
  (void)simd;
#endif
  return &table[at];
}

static void run_kernel(const tlod_surface* s, uint32_t patch, const kernels* k, const _tlod_corners* c, _tlod_batch* b,
                       uint32_t n, bool normals) {
  switch (s->desc.type) {
  case TLOD_SURFACE_PN:
    k->pn(c, &s->pn[patch], b, n, normals);
    break;
  case TLOD_SURFACE_PHONG:
    k->phong(c, b, n, normals);
    break;
  default:
    k->flat(c, b, n, normals);
    break;
  }
}

/* Flagged normals from the scalar code. */
static void redo_flagged(const tlod_surface* s, uint32_t patch, const _tlod_corners* c, const _tlod_batch* b,
                         uint32_t n, float* nrm) {
  for (uint32_t k = 0; k < n; k++) {
    if (!b->flag[k]) continue;
    tlod_surface_point p;
    _tlod_patch_eval_with(s, patch, c, b->u[k], b->v[k], 0, &p);
    memcpy(nrm + 3 * k, p.normal, sizeof(float) * 3);
  }
}

static void eval_scalar(const tlod_surface* s, uint32_t patch, const _tlod_corners* c, uint32_t count, const float* u,
                        const float* v, float* positions, float* normals) {
  for (uint32_t k = 0; k < count; k++) {
    tlod_surface_point p;
    _tlod_patch_eval_with(s, patch, c, u[k], v[k], 0, &p);
    memcpy(positions + 3 * (size_t)k, p.position, sizeof(float) * 3);
    if (normals) memcpy(normals + 3 * (size_t)k, p.normal, sizeof(float) * 3);
  }
}

tlod_result tlod_surface_eval_interior(const tlod_surface* s, uint32_t patch, tlod_simd simd, uint32_t count,
                                       const float* u, const float* v, float* positions, float* normals) {
  if (!s || patch >= s->patch_count) return TLOD_ERROR_INVALID_ARGUMENT;
  if (count == 0) return TLOD_SUCCESS;
  if (!u || !v || !positions) return TLOD_ERROR_INVALID_ARGUMENT;
  _tlod_corners c;
  _tlod_patch_corners(s, patch, &c);
  if (s->desc.type == TLOD_SURFACE_QUADRATIC || s->desc.shading_normal == TLOD_SHADING_NORMAL_TRUE) {
    eval_scalar(s, patch, &c, count, u, v, positions, normals);
    return TLOD_SUCCESS;
  }
  const kernels* k = kernels_for(simd);
  _tlod_batch b;
  for (uint32_t at = 0; at < count; at += BATCH) {
    uint32_t n = count - at < BATCH ? count - at : BATCH;
    memcpy(b.u, u + at, sizeof(float) * n);
    memcpy(b.v, v + at, sizeof(float) * n);
    run_kernel(s, patch, k, &c, &b, n, normals != NULL);
    float* nrm = normals ? normals + 3 * (size_t)at : NULL;
    k->store(&b, n, positions + 3 * (size_t)at, nrm);
    if (nrm) redo_flagged(s, patch, &c, &b, n, nrm);
  }
  return TLOD_SUCCESS;
}

/* PN: the edge's control points once, then each point as _tlod_pn_edge. */
static void pn_edge_points(const tlod_surface* s, uint32_t a, uint32_t b, bool forward, uint32_t count,
                           const uint32_t* param, float nn, float* positions, float* normals) {
  const tlod_mesh* m = s->mesh;
  _tlod_pn_edge_ctl e;
  _tlod_pn_edge_build(v3_load(m->positions[a]), v3_load(m->normals[a]), v3_load(m->positions[b]),
                      v3_load(m->normals[b]), &e);
  for (uint32_t k = 0; k < count; k++) {
    float t_end = (float)param[k] / nn;
    v3 p, n;
    _tlod_pn_edge_at(&e, forward ? t_end : 1.0f - t_end, &p, &n);
    v3_store(positions + 3 * (size_t)k, p);
    if (normals) v3_store(normals + 3 * (size_t)k, n);
  }
}

/* Positions only, Phong or flat: the edge's ends loaded once, each point
 * as _tlod_phong_edge / _tlod_flat_edge place it (no normal). */
static void edge_positions(const tlod_surface* s, uint32_t a, uint32_t b, bool forward, uint32_t count,
                           const uint32_t* param, float nn, float* positions) {
  const tlod_mesh* m = s->mesh;
  v3 pa = v3_load(m->positions[a]), na = v3_load(m->normals[a]);
  v3 pb = v3_load(m->positions[b]), nb = v3_load(m->normals[b]);
  bool phong = s->desc.type == TLOD_SURFACE_PHONG;
  float aa = phong ? s->alpha[a] : 0.0f, ab = phong ? s->alpha[b] : 0.0f;
  for (uint32_t k = 0; k < count; k++) {
    float t_end = (float)param[k] / nn, t = forward ? t_end : 1.0f - t_end;
    v3 p = phong ? _tlod_phong_edge_position(pa, na, aa, pb, nb, ab, t) : v3_mix2(pa, 1.0f - t, pb, t);
    v3_store(positions + 3 * (size_t)k, p);
  }
}

tlod_result tlod_surface_eval_edge(const tlod_surface* s, uint32_t patch, uint32_t edge, uint32_t grid_log2,
                                   uint32_t count, const uint32_t* param, float* positions, float* normals) {
  if (!s || patch >= s->patch_count || grid_log2 > TLOD_GRID_MAX_LOG2) return TLOD_ERROR_INVALID_ARGUMENT;
  const tlod_mesh* m = s->mesh;
  uint32_t n = m->face_corners[patch], nn = 1u << grid_log2;
  if (edge >= n) return TLOD_ERROR_INVALID_ARGUMENT;
  if (count == 0) return TLOD_SUCCESS;
  if (!param || !positions) return TLOD_ERROR_INVALID_ARGUMENT;
  for (uint32_t k = 0; k < count; k++)
    if (param[k] == 0 || param[k] >= nn) return TLOD_ERROR_INVALID_ARGUMENT;
  uint32_t a = m->faces[patch][edge], b = m->faces[patch][(edge + 1) % n];
  bool forward = m->weld_id[a] < m->weld_id[b];
  if (s->desc.type == TLOD_SURFACE_PN && !s->quad) {
    pn_edge_points(s, forward ? a : b, forward ? b : a, forward, count, param, (float)nn, positions, normals);
    return TLOD_SUCCESS;
  }
  bool plain = s->desc.type == TLOD_SURFACE_PHONG || s->desc.type == TLOD_SURFACE_FLAT;
  if (!normals && plain && !s->quad) {
    edge_positions(s, forward ? a : b, forward ? b : a, forward, count, param, (float)nn, positions);
    return TLOD_SUCCESS;
  }
  float unused[3];
  for (uint32_t k = 0; k < count; k++)
    _tlod_patch_edge_point(s, patch, edge, (float)param[k] / (float)nn, positions + 3 * (size_t)k,
                           normals ? normals + 3 * (size_t)k : unused);
  return TLOD_SUCCESS;
}
