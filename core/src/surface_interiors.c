/* tesslod::core -- tlod_surface_eval_interiors(): the positions of many
 * patches' interior points at once, the lanes being patches (at level 2 a
 * triangle has 3 interior points, a quad 9: lanes over one patch's points
 * stay mostly empty). Each patch's corners are gathered once; then, per
 * point, its corner weights once and one kernel call over all lanes
 * (surface_interiors.inc, compiled per instruction set). Bitwise
 * tlod_surface_eval_interior() with normals NULL (no contraction:
 * -ffp-contract=off). */
#include "patch_lanes.h"

typedef void (*patch_kernel)(const _tlod_patch_lanes* L, uint32_t n, const float w[4], float* restrict ox,
                             float* restrict oy, float* restrict oz);

#define KERNEL_FILE "surface_interiors.inc"
#include "simd_instances.inc"
#undef KERNEL_FILE

/* The corner weights of (u, v) as phong.c's corner_weights forms them. */
static void corner_weights(uint32_t n, float u, float v, float w[4]) {
  if (n == 3) {
    w[0] = u, w[1] = v, w[2] = 1.0f - u - v, w[3] = 0.0f;
    return;
  }
  float su = 1.0f - u, sv = 1.0f - v;
  w[0] = su * sv, w[1] = u * sv, w[2] = u * v, w[3] = su * v;
}

/* Lanes [0, n), every point: lane r's point k goes to vertex first[r] + k.
 * Up to POINT_GROUP points are evaluated for all lanes before any is
 * stored, then each patch's are written together (as surface_edges.c). */
enum { POINT_GROUP = 16 };
static void eval_block(patch_kernel k, const _tlod_patch_lanes* L, uint32_t n, uint32_t count, const float* u,
                       const float* v, const uint32_t* first, float* positions) {
  float ox[POINT_GROUP][PATCH_LANES], oy[POINT_GROUP][PATCH_LANES], oz[POINT_GROUP][PATCH_LANES], w[4];
  for (uint32_t j0 = 0; j0 < count; j0 += POINT_GROUP) {
    uint32_t jn = count - j0 < POINT_GROUP ? count - j0 : POINT_GROUP;
    for (uint32_t j = 0; j < jn; j++) {
      corner_weights(L->corners, u[j0 + j], v[j0 + j], w);
      k(L, n, w, ox[j], oy[j], oz[j]);
    }
    for (uint32_t r = 0; r < n; r++) {
      float* p = positions + 3 * ((size_t)first[r] + j0);
      for (uint32_t j = 0; j < jn; j++)
        p[3 * j] = ox[j][r], p[3 * j + 1] = oy[j][r], p[3 * j + 2] = oz[j][r];
    }
  }
}

/* Surfaces the lanes do not cover (PN, quadratic): patch by patch. */
static void eval_each(const tlod_surface* s, tlod_simd simd, uint32_t patch_count, const uint32_t* patches,
                      uint32_t count, const float* u, const float* v, const uint32_t* first, float* positions) {
  for (uint32_t r = 0; r < patch_count; r++)
    tlod_surface_eval_interior(s, patches[r], simd, count, u, v, positions + 3 * (size_t)first[r], NULL);
}

tlod_result tlod_surface_eval_interiors(const tlod_surface* s, tlod_simd simd, uint32_t patch_count,
                                        const uint32_t* patches, uint32_t count, const float* u, const float* v,
                                        const uint32_t* first, float* positions) {
  if (!s) return TLOD_ERROR_INVALID_ARGUMENT;
  if (patch_count == 0 || count == 0) return TLOD_SUCCESS;
  if (!patches || !u || !v || !first || !positions) return TLOD_ERROR_INVALID_ARGUMENT;
  for (uint32_t r = 0; r < patch_count; r++)
    if (patches[r] >= s->patch_count) return TLOD_ERROR_INVALID_ARGUMENT;
  bool phong = s->desc.type == TLOD_SURFACE_PHONG;
  if (!phong && s->desc.type != TLOD_SURFACE_FLAT) {
    eval_each(s, simd, patch_count, patches, count, u, v, first, positions);
    return TLOD_SUCCESS;
  }
  patch_kernel k = phong ? KERNEL_FOR(phong_patches, simd) : KERNEL_FOR(flat_patches, simd);
  const uint8_t* corners = s->mesh->face_corners;
  _tlod_patch_lanes L;
  for (uint32_t at = 0, n; at < patch_count; at += n) {
    /* A block: up to PATCH_LANES patches with the first one's corner count. */
    L.corners = corners[patches[at]];
    for (n = 0; at + n < patch_count && n < PATCH_LANES && corners[patches[at + n]] == L.corners; n++)
      _tlod_lanes_gather(s, &L, n, patches[at + n]);
    eval_block(k, &L, n, count, u, v, first + at, positions);
  }
  return TLOD_SUCCESS;
}
