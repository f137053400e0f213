/* tesslod::lod -- the fast path's clusters: a bounding sphere per block of
 * FAST_BLOCK patches (built with the structure-of-arrays copies), its
 * frustum state per frame with a proven rounding margin, and per chunk of
 * FAST_VCHUNK vertices the blocks that read them, so that a frame touches
 * neither the patches of a culled block nor the vertices only culled
 * blocks use (docs/design.md 3.13). */
#include <math.h>
#include <string.h>

#include "scheduler_fast.h"

#define SLACK _TLOD_BLOCK_SLACK

static bool finite_sphere(const _tlod_soa* a, uint32_t i) {
  return isfinite(a->cx[i]) && isfinite(a->cy[i]) && isfinite(a->cz[i]) && isfinite(a->radius[i]) &&
         a->radius[i] >= 0.0f;
}

/* Centre: the middle of the centres' box; r: the farthest patch sphere
 * from it, both in double, r and l1 raised by SLACK for their rounding. */
static _tlod_block block_sphere(const _tlod_soa* a, uint32_t begin, uint32_t end) {
  const float* c[3] = {a->cx, a->cy, a->cz};
  _tlod_block b = {.valid = true};
  for (int k = 0; k < 3; k++) {
    double lo = c[k][begin], hi = lo, big = 0.0;
    for (uint32_t i = begin; i < end; i++) {
      lo = c[k][i] < lo ? c[k][i] : lo, hi = c[k][i] > hi ? c[k][i] : hi;
      big = fabs((double)c[k][i]) > big ? fabs((double)c[k][i]) : big;
    }
    b.c[k] = 0.5 * (lo + hi);
    b.l1 += big;
  }
  for (uint32_t i = begin; i < end; i++) {
    b.valid = b.valid && finite_sphere(a, i);
    double dx = a->cx[i] - b.c[0], dy = a->cy[i] - b.c[1], dz = a->cz[i] - b.c[2];
    double r = sqrt(dx * dx + dy * dy + dz * dz) + (double)a->radius[i];
    b.r = r > b.r ? r : b.r;
  }
  b.r += SLACK * (b.r + b.l1);
  b.l1 *= 1.0 + SLACK;
  b.valid = b.valid && isfinite(b.r) && isfinite(b.l1);
  return b;
}

/* The (chunk, block) pairs in which the block reads a vertex of the chunk,
 * each once: counted into chunk_first[chunk + 1], or (fill) written at
 * next[chunk]; last: scratch, one entry per chunk. */
static uint32_t chunk_pairs(_tlod_soa* a, uint32_t* last, bool fill, uint32_t* next) {
  uint32_t n = a->patch_count, pairs = 0;
  for (uint32_t j = 0; j < a->chunk_count; j++)
    last[j] = UINT32_MAX;
  for (uint32_t f = 0; f < n; f++) {
    uint32_t b = f / FAST_BLOCK;
    for (uint32_t c = 0; c < 4; c++) {
      uint32_t j = a->corner[c * n + f] / FAST_VCHUNK;
      if (last[j] == b) continue;
      last[j] = b, pairs++;
      if (fill) a->chunk_blocks[next[j]++] = b;
      if (!fill) a->chunk_first[j + 1]++;
    }
  }
  return pairs;
}

/* chunk_first and chunk_blocks (grown only when the mesh needs more). */
static bool build_chunks(tlod_context* ctx, _tlod_soa* a, uint32_t* scratch) {
  uint32_t* last = scratch;
  uint32_t* next = scratch + a->chunk_count;
  memset(a->chunk_first, 0, sizeof(uint32_t) * ((size_t)a->chunk_count + 1));
  uint32_t pairs = chunk_pairs(a, last, false, NULL);
  for (uint32_t j = 0; j < a->chunk_count; j++)
    a->chunk_first[j + 1] += a->chunk_first[j];
  if (pairs > a->chunk_capacity) {
    tlod_context_free(ctx, a->chunk_blocks);
    a->chunk_capacity = 0;
    if (!(a->chunk_blocks = tlod_context_alloc(ctx, sizeof(uint32_t) * ((size_t)pairs + 1)))) return false;
    a->chunk_capacity = pairs;
  }
  memcpy(next, a->chunk_first, sizeof(uint32_t) * a->chunk_count);
  chunk_pairs(a, last, true, next);
  return true;
}

/* Block b's sphere into the structure-of-arrays fields. */
static void store_sphere(_tlod_soa* a, uint32_t b, const _tlod_block* s) {
  a->bx[b] = s->c[0], a->by[b] = s->c[1], a->bz[b] = s->c[2];
  a->br[b] = s->r, a->bl1[b] = s->l1, a->bvalid[b] = s->valid;
}

/* The blocks' arrays: five doubles and a flag a block in one allocation. */
static bool alloc_blocks(tlod_context* ctx, _tlod_soa* a) {
  size_t n = (size_t)a->block_count + 1;
  a->bx = tlod_context_alloc(ctx, n * (5 * sizeof(double) + 1));
  if (!a->bx) return false;
  a->by = a->bx + n, a->bz = a->by + n, a->br = a->bz + n, a->bl1 = a->br + n;
  a->bvalid = (uint8_t*)(a->bl1 + n);
  return true;
}

bool _tlod_blocks_build(tlod_context* ctx, _tlod_soa* a) {
  if (!a->bx) {
    a->block_count = (a->patch_count + FAST_BLOCK - 1) / FAST_BLOCK;
    a->chunk_count = (a->vertex_count + FAST_VCHUNK - 1) / FAST_VCHUNK;
    a->block_state = tlod_context_alloc(ctx, (size_t)a->block_count + 1);
    a->chunk_first = tlod_context_alloc(ctx, sizeof(uint32_t) * ((size_t)a->chunk_count + 1));
    if (!alloc_blocks(ctx, a) || !a->block_state || !a->chunk_first) return false;
  }
  for (uint32_t b = 0; b < a->block_count; b++) {
    uint32_t begin = b * FAST_BLOCK, end = a->patch_count - begin < FAST_BLOCK ? a->patch_count : begin + FAST_BLOCK;
    _tlod_block s = block_sphere(a, begin, end);
    store_sphere(a, b, &s);
  }
  uint32_t* scratch = tlod_context_alloc(ctx, sizeof(uint32_t) * 2 * ((size_t)a->chunk_count + 1));
  bool ok = scratch && build_chunks(ctx, a, scratch);
  tlod_context_free(ctx, scratch);
  return ok;
}

bool _tlod_blocks_hold(tlod_context* ctx, _tlod_soa* a, uint32_t views) {
  if (views <= a->held_views) return true;
  size_t bytes = (size_t)views * a->block_count + 1;
  uint8_t *grown = tlod_context_calloc(ctx, bytes, 1), *seen = tlod_context_calloc(ctx, bytes, 1);
  if (!grown || !seen) {
    tlod_context_free(ctx, grown);
    tlod_context_free(ctx, seen);
    return false;
  }
  if (a->held) memcpy(grown, a->held, (size_t)a->held_views * a->block_count);
  tlod_context_free(ctx, a->held);
  tlod_context_free(ctx, a->seen);
  a->held = grown, a->seen = seen, a->held_views = views;
  return true;
}

/* A patch's test evaluates d_i = ((p0 cx + p1 cy) + p2 cz) + p3 in float:
 * at most 4 roundings per term, |fl(d_i) - d_i| <= gamma_4 (|p0 cx| +
 * |p1 cy| + |p2 cz| + |p3|) <= gamma_4 (max|p_k| l1 + |p3|), gamma_4 =
 * 4u / (1 - 4u) < 2.385e-7 (u = 2^-24), plus 2^-149 per underflowing
 * product. 3e-7 leaves room for the double rounding of the block's own sum.
 * With the exact d = p . c + p3 of the block centre, |n| the plane normal's
 * length and |c_i - c| <= r - r_i:
 *   d_i >= d - |n| (r - r_i), so d - |n| r - margin >= 0 gives
 *     fl(d_i) >= -r_i: no patch is outside the plane;
 *   d_i <= d + |n| (r - r_i), so d + max(|n|, 1) r + margin < 0 gives
 *     fl(d_i) < -r_i: every patch is outside it.
 * margin = 3e-7 (max|p_k| l1 + |p3|) + SLACK |n| r + 1e-40; the kernels'
 * classify (scheduler_fast.inc) tests every block against these terms. */
static void plane_terms(const float planes[6][4], _tlod_plane_terms* t) {
  for (int p = 0; p < 6; p++) {
    for (int k = 0; k < 4; k++)
      t->p[p][k] = planes[p][k];
    const double* q = t->p[p];
    t->n[p] = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]) * (1.0 + SLACK);
    t->n1[p] = fmax(t->n[p], 1.0);
    t->base[p] = fmax(fabs(q[0]), fmax(fabs(q[1]), fabs(q[2])));
    t->d_abs[p] = fabs(q[3]);
  }
}

void _tlod_blocks_classify(_tlod_soa* a, const _tlod_fast_kernels* kernels, const float planes[6][4], bool cull) {
  if (!cull) {
    memset(a->block_state, _TLOD_BLOCK_IN, a->block_count);
    return;
  }
  _tlod_plane_terms terms;
  plane_terms(planes, &terms);
  kernels->classify(a, &terms, 0, a->block_count);
}

void _tlod_blocks_free(tlod_context* ctx, _tlod_soa* a) {
  void* arrays[] = {a->bx, a->block_state, a->chunk_first, a->chunk_blocks, a->held, a->seen};
  for (size_t i = 0; i < sizeof(arrays) / sizeof(arrays[0]); i++)
    tlod_context_free(ctx, arrays[i]);
}
