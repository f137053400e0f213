/* tesslod::core -- a patch evaluated on the integer grid its refinement
 * patterns live on: each point classified exactly (corner, edge with its
 * exact edge parameter, interior) and routed to the mesh vertex, the one
 * canonical edge function, or the patch formula (docs/design.md invariants 1
 * and 2). The same classification routes pattern vertices in the shaders. */
#include <string.h>

#include "surface_eval.h"

static uint32_t triangle_kind(uint32_t nn, uint32_t i, uint32_t j, uint32_t* param) {
  uint32_t w = nn - i - j;
  if (i == nn || j == nn || w == nn) return i == nn ? 0u : (j == nn ? 1u : 2u);
  if (w == 0) return *param = j, TLOD_GRID_EDGE + 0; /* i -> j: weight of j */
  if (i == 0) return *param = w, TLOD_GRID_EDGE + 1; /* j -> k: weight of k */
  if (j == 0) return *param = i, TLOD_GRID_EDGE + 2; /* k -> i: weight of i */
  return TLOD_GRID_INTERIOR;
}

static uint32_t quad_kind(uint32_t nn, uint32_t i, uint32_t j, uint32_t* param) {
  bool ei = i == 0 || i == nn, ej = j == 0 || j == nn;
  if (ei && ej) return i == 0 ? (j == 0 ? 0u : 3u) : (j == 0 ? 1u : 2u);
  if (j == 0) return *param = i, TLOD_GRID_EDGE + 0;       /* 0 -> 1 */
  if (i == nn) return *param = j, TLOD_GRID_EDGE + 1;      /* 1 -> 2 */
  if (j == nn) return *param = nn - i, TLOD_GRID_EDGE + 2; /* 2 -> 3 */
  if (i == 0) return *param = nn - j, TLOD_GRID_EDGE + 3;  /* 3 -> 0 */
  return TLOD_GRID_INTERIOR;
}

static bool on_grid(uint32_t corner_count, uint32_t grid_log2, uint32_t i, uint32_t j) {
  if (grid_log2 > TLOD_GRID_MAX_LOG2 || (corner_count != 3 && corner_count != 4)) return false;
  uint32_t nn = 1u << grid_log2; /* i, j < 2^32 and nn <= 2^15: the sum cannot wrap in 64 bits */
  return corner_count == 4 ? i <= nn && j <= nn : (uint64_t)i + j <= nn;
}

uint32_t tlod_grid_point_kind(uint32_t corner_count, uint32_t grid_log2, uint32_t i, uint32_t j, uint32_t* param) {
  if (!on_grid(corner_count, grid_log2, i, j)) return TLOD_GRID_OFF;
  uint32_t nn = 1u << grid_log2;
  return corner_count == 4 ? quad_kind(nn, i, j, param) : triangle_kind(nn, i, j, param);
}

static void eval_point(const tlod_surface* s, uint32_t patch, const _tlod_corners* c, uint32_t grid_log2,
                       const uint16_t ij[2], float pos[3], float nrm[3]) {
  const tlod_mesh* m = s->mesh;
  uint32_t param = 0, kind = tlod_grid_point_kind(c->n, grid_log2, ij[0], ij[1], &param);
  float nn = (float)(1u << grid_log2);
  if (kind < TLOD_GRID_EDGE) {
    memcpy(pos, m->positions[m->faces[patch][kind]], sizeof(float) * 3);
    memcpy(nrm, m->normals[m->faces[patch][kind]], sizeof(float) * 3);
  } else if (kind < TLOD_GRID_INTERIOR) {
    _tlod_patch_edge_point(s, patch, kind - TLOD_GRID_EDGE, (float)param / nn, pos, nrm);
  } else {
    tlod_surface_point p;
    _tlod_patch_eval_with(s, patch, c, (float)ij[0] / nn, (float)ij[1] / nn, 0, &p);
    memcpy(pos, p.position, sizeof(float) * 3);
    memcpy(nrm, p.normal, sizeof(float) * 3);
  }
}

/* Every point on the grid, before anything is written. */
static bool grid_valid(uint32_t corners, uint32_t grid_log2, const uint16_t* ij, size_t ij_stride, uint32_t count) {
  const char* at = (const char*)ij;
  for (uint32_t k = 0; k < count; k++, at += ij_stride) {
    uint16_t point[2];
    memcpy(point, at, sizeof(point));
    if (!on_grid(corners, grid_log2, point[0], point[1])) return false;
  }
  return true;
}

tlod_result tlod_surface_eval_grid(const tlod_surface* s, uint32_t patch, uint32_t grid_log2, const uint16_t* ij,
                                   size_t ij_stride, uint32_t count, float* positions, float* normals) {
  if (!s || patch >= s->patch_count || grid_log2 > TLOD_GRID_MAX_LOG2) return TLOD_ERROR_INVALID_ARGUMENT;
  if (count == 0) return TLOD_SUCCESS;
  if (!ij || !positions || !grid_valid(s->mesh->face_corners[patch], grid_log2, ij, ij_stride, count))
    return TLOD_ERROR_INVALID_ARGUMENT;
  _tlod_corners c;
  _tlod_patch_corners(s, patch, &c);
  const char* at = (const char*)ij;
  float unused[3];
  for (uint32_t k = 0; k < count; k++, at += ij_stride) {
    uint16_t point[2];
    memcpy(point, at, sizeof(point));
    eval_point(s, patch, &c, grid_log2, point, positions + 3 * (size_t)k, normals ? normals + 3 * (size_t)k : unused);
  }
  return TLOD_SUCCESS;
}
