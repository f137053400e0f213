/* tesslod::core -- tlod_surface_eval_edges(): the positions of many patch
 * edges' points at once, the lanes being edges (at level 2 an edge has 3
 * points: lanes over one edge's points would stay empty). Each edge's ends
 * are gathered once in canonical direction; then, per point parameter, one
 * kernel call over all lanes (surface_edges.inc, compiled per instruction
 * set). Bitwise tlod_surface_eval_edge() with normals NULL: the same
 * operations per point, in the same order, no contraction
 * (-ffp-contract=off). */
#include "surface_eval.h"

enum { EDGE_LANES = 64 };

/* A block of edges, structure of arrays: end A then end B in canonical
 * direction (the smaller weld id first), and whether that is the patch's
 * own direction. */
typedef struct _tlod_edge_lanes {
  float ax[EDGE_LANES], ay[EDGE_LANES], az[EDGE_LANES], anx[EDGE_LANES], any[EDGE_LANES], anz[EDGE_LANES];
  float bx[EDGE_LANES], by[EDGE_LANES], bz[EDGE_LANES], bnx[EDGE_LANES], bny[EDGE_LANES], bnz[EDGE_LANES];
  float aa[EDGE_LANES], ba[EDGE_LANES];
  int32_t forward[EDGE_LANES];
} _tlod_edge_lanes;

typedef void (*edge_kernel)(const _tlod_edge_lanes* e, uint32_t n, float t_end, float* restrict ox, float* restrict oy,
                            float* restrict oz);

#define KERNEL_FILE "surface_edges.inc"
#include "simd_instances.inc"
#undef KERNEL_FILE

static inline void put_end(_tlod_edge_lanes* e, uint32_t r, bool end_b, const tlod_mesh* m, const float* alpha,
                           uint32_t v) {
  const float *p = m->positions[v], *n = m->normals[v];
  float a = alpha ? alpha[v] : 0.0f;
  if (end_b) {
    e->bx[r] = p[0], e->by[r] = p[1], e->bz[r] = p[2], e->bnx[r] = n[0], e->bny[r] = n[1], e->bnz[r] = n[2];
    e->ba[r] = a;
  } else {
    e->ax[r] = p[0], e->ay[r] = p[1], e->az[r] = p[2], e->anx[r] = n[0], e->any[r] = n[1], e->anz[r] = n[2];
    e->aa[r] = a;
  }
}

/* Lane r: edge `edge` of patch `patch`, in canonical direction. */
static void gather_edge(const tlod_surface* s, _tlod_edge_lanes* e, uint32_t r, uint32_t patch, uint32_t edge) {
  const tlod_mesh* m = s->mesh;
  uint32_t next = edge + 1 == m->face_corners[patch] ? 0 : edge + 1; /* no division per edge */
  uint32_t a = m->faces[patch][edge], b = m->faces[patch][next];
  bool forward = m->weld_id[a] < m->weld_id[b];
  const float* alpha = s->desc.type == TLOD_SURFACE_PHONG ? s->alpha : NULL;
  put_end(e, r, false, m, alpha, forward ? a : b);
  put_end(e, r, true, m, alpha, forward ? b : a);
  e->forward[r] = forward;
}

/* Edges [0, n) of the block, every point: lane r's point k goes to vertex
 * first[r] + k of positions. Up to POINT_GROUP points are evaluated for
 * all lanes before any is stored, then each edge's are written together
 * (the kernel's lane stores have landed by the time they are read back,
 * and an edge's points are consecutive in the output). */
enum { POINT_GROUP = 16 };
static void eval_block(edge_kernel k, const _tlod_edge_lanes* e, uint32_t n, uint32_t count, const uint32_t* param,
                       float nn, const uint32_t* first, float* positions) {
  float ox[POINT_GROUP][EDGE_LANES], oy[POINT_GROUP][EDGE_LANES], oz[POINT_GROUP][EDGE_LANES];
  for (uint32_t j0 = 0; j0 < count; j0 += POINT_GROUP) {
    uint32_t jn = count - j0 < POINT_GROUP ? count - j0 : POINT_GROUP;
    for (uint32_t j = 0; j < jn; j++)
      k(e, n, (float)param[j0 + j] / nn, ox[j], oy[j], oz[j]);
    for (uint32_t r = 0; r < n; r++) {
      float* p = positions + 3 * ((size_t)first[r] + j0);
      for (uint32_t j = 0; j < jn; j++)
        p[3 * j] = ox[j][r], p[3 * j + 1] = oy[j][r], p[3 * j + 2] = oz[j][r];
    }
  }
}

static bool edges_valid(const tlod_surface* s, uint32_t edge_count, const uint32_t* patches, const uint8_t* edges,
                        uint32_t count, const uint32_t* param, uint32_t nn) {
  for (uint32_t j = 0; j < count; j++)
    if (param[j] == 0 || param[j] >= nn) return false;
  for (uint32_t r = 0; r < edge_count; r++)
    if (patches[r] >= s->patch_count || edges[r] >= s->mesh->face_corners[patches[r]]) return false;
  return true;
}

/* Surfaces the lanes do not cover (PN, quadratic faces): edge by edge. */
static void eval_each(const tlod_surface* s, uint32_t grid_log2, uint32_t edge_count, const uint32_t* patches,
                      const uint8_t* edges, uint32_t count, const uint32_t* param, const uint32_t* first,
                      float* positions) {
  for (uint32_t r = 0; r < edge_count; r++)
    tlod_surface_eval_edge(s, patches[r], edges[r], grid_log2, count, param, positions + 3 * (size_t)first[r], NULL);
}

tlod_result tlod_surface_eval_edges(const tlod_surface* s, tlod_simd simd, uint32_t grid_log2, uint32_t edge_count,
                                    const uint32_t* patches, const uint8_t* edges, uint32_t count,
                                    const uint32_t* param, const uint32_t* first, float* positions) {
  if (!s || grid_log2 > TLOD_GRID_MAX_LOG2) return TLOD_ERROR_INVALID_ARGUMENT;
  if (edge_count == 0 || count == 0) return TLOD_SUCCESS;
  if (!patches || !edges || !param || !first || !positions) return TLOD_ERROR_INVALID_ARGUMENT;
  uint32_t nn = 1u << grid_log2;
  if (!edges_valid(s, edge_count, patches, edges, count, param, nn)) return TLOD_ERROR_INVALID_ARGUMENT;
  bool phong = s->desc.type == TLOD_SURFACE_PHONG;
  if ((!phong && s->desc.type != TLOD_SURFACE_FLAT) || s->quad) {
    eval_each(s, grid_log2, edge_count, patches, edges, count, param, first, positions);
    return TLOD_SUCCESS;
  }
  edge_kernel k = phong ? KERNEL_FOR(phong_edges, simd) : KERNEL_FOR(flat_edges, simd);
  _tlod_edge_lanes e;
  for (uint32_t at = 0; at < edge_count; at += EDGE_LANES) {
    uint32_t n = edge_count - at < EDGE_LANES ? edge_count - at : EDGE_LANES;
    for (uint32_t r = 0; r < n; r++)
      gather_edge(s, &e, r, patches[at + r], edges[at + r]);
    eval_block(k, &e, n, count, param, (float)nn, first + at, positions);
  }
  return TLOD_SUCCESS;
}
