/* tesslod::lod -- the draw list of one view: instances grouped in buckets
 * of one (shape, level) pattern each, connection strips, statistics.
 *
 * Built in parallel and deterministically: the patches are cut into fixed
 * chunks of _TLOD_LIST_CHUNK (never dependent on the thread count); a scan
 * finds each chunk's blocks with a visible patch (culled blocks are not
 * read again; a fused frame's patch pass has marked them, and the scan
 * reads those marks on the caller) and lists the busy chunks; a first
 * pass over those counts each chunk's instances per bucket, strips and
 * statistics, a serial prefix sum in chunk order gives each chunk its
 * offsets, and a second pass writes every chunk at its offsets
 * (docs/design.md 1.4). The result is the serial
 * order (bucket-major, patch order inside a bucket; strips in patch order)
 * whatever the workers and however the engine splits the chunks.
 *
 * This work is based on:
 *   M. Schwarz, M. Staginski, M. Stamminger. GPU-based rendering of PN
 *   triangle meshes with adaptive tessellation. VMV 2006, sec. 4 (patches
 *   drawn by pattern, edges between different levels joined by connection
 *   patterns). */
#include <math.h>
#include <string.h>

#include "scheduler_frame.h"

/* _tlod_list_chunk.blocks holds a bit per block of a chunk. */
_Static_assert(_TLOD_LIST_CHUNK / FAST_BLOCK <= 64, "a chunk has at most 64 blocks");

/* The frame's arrays as locals: the per-patch int8 level stores may alias
 * anything, and read through fr->vs every pointer would be reloaded after
 * each of them. */
typedef struct list_arrays {
  _tlod_list_in in; /* the kernels' arrays */
  _tlod_list_kernels kernels;
  const uint8_t* block_slots; /* _tlod_up_edges */
  const uint8_t* seen;        /* a fused frame's blocks with a visible patch (_tlod_soa.seen), else NULL */
  const tlod_patterns* pat;
  bool strips; /* FLAT draws no strip */
} list_arrays;

static list_arrays arrays_of(const _tlod_frame* fr) {
  _tlod_view_state* vs = fr->vs;
  return (list_arrays){.in = {.slot = fr->s->up.slot,
                              .patch_count = fr->s->patch_count,
                              .levels_n = fr->s->desc.max_level + 1,
                              .visible = vs->visible,
                              .cont = vs->cont,
                              .e_max = vs->e_max,
                              .corners = fr->mesh.face_corners,
                              .levels = vs->levels,
                              .edges = vs->strip_edges,
                              .instances = vs->instances},
                       .kernels = fr->s->list,
                       .block_slots = fr->s->up.block_slots,
                       .seen =
                           fr->fused ? fr->s->soa.seen + (size_t)(vs - fr->s->views) * fr->s->soa.block_count : NULL,
                       .pat = fr->s->patterns,
                       .strips = fr->s->desc.policy != TLOD_POLICY_FLAT};
}

static uint32_t chunk_count(uint32_t patches) { return (patches + _TLOD_LIST_CHUNK - 1) / _TLOD_LIST_CHUNK; }

static void chunk_range(const _tlod_frame* fr, uint32_t c, uint32_t* begin, uint32_t* end) {
  *begin = c * _TLOD_LIST_CHUNK;
  *end = *begin + _TLOD_LIST_CHUNK < fr->s->patch_count ? *begin + _TLOD_LIST_CHUNK : fr->s->patch_count;
}

/* The triangles of strip st (tlod_draw_strip_connection without its checks:
 * the levels are the scheduler's, never above the patterns'). */
static uint32_t strip_triangles(const tlod_patterns* p, const tlod_draw_strip* st) {
  return (st->exact ? p->connect_exact_count : p->connect_count)[st->level_a][st->level_b];
}

/* The n visible bytes from f OR-ed, 8 at a time (n a multiple of 8). */
static uint64_t any_visible(const uint8_t* visible, uint32_t f, uint32_t n) {
  uint64_t any = 0;
  for (uint32_t i = f; i < f + n; i += 8) {
    uint64_t w;
    memcpy(&w, visible + i, 8);
    any |= w;
  }
  return any;
}

/* Patches [f0, f1) of a visible block: strip edges (for the second pass,
 * which makes the strips), levels, bucket counts, statistics. */
static uint32_t count_block(const list_arrays* a, uint32_t* counts, _tlod_list_tally* t, uint32_t f0, uint32_t f1) {
  a->kernels.count(&a->in, f0, f1, counts, t);
  return a->strips ? a->kernels.strip_edges(&a->in, f0, f1, a->block_slots[f0 / FAST_BLOCK]) : 0;
}

/* Block k of chunk [f0, f1): its patch range. */
static void block_range(uint32_t f0, uint32_t f1, uint32_t k, uint32_t* b0, uint32_t* b1) {
  *b0 = f0 + k * FAST_BLOCK;
  *b1 = *b0 + FAST_BLOCK < f1 ? *b0 + FAST_BLOCK : f1;
}

/* Whether block [b0, b1) has a visible patch (a short tail byte by byte). */
static bool block_visible(const uint8_t* visible, uint32_t b0, uint32_t b1) {
  uint32_t whole = (b1 - b0) / 8 * 8;
  bool any = any_visible(visible, b0, whole) != 0;
  for (uint32_t f = b0 + whole; f < b1; f++)
    any |= visible[f] != 0;
  return any;
}

/* Chunk c reset: its visible blocks found, its culled ones' levels set
 * to -1 and counted (nothing reads them again this frame). A fused frame's
 * patch pass marked the blocks and set those levels already (a->seen). */
static void scan_chunk(const _tlod_frame* fr, const list_arrays* a, uint32_t c) {
  _tlod_list_chunk* ch = &fr->vs->chunks[c];
  uint32_t f0, f1;
  chunk_range(fr, c, &f0, &f1);
  *ch = (_tlod_list_chunk){.e_max_min = INFINITY};
  for (uint32_t k = 0; f0 + k * FAST_BLOCK < f1; k++) {
    uint32_t b0, b1;
    block_range(f0, f1, k, &b0, &b1);
    if (a->seen ? a->seen[b0 / FAST_BLOCK] != 0 : block_visible(a->in.visible, b0, b1)) {
      ch->blocks |= UINT64_C(1) << k;
    } else {
      if (!a->seen) memset(a->in.levels + b0, -1, b1 - b0);
      ch->culled += b1 - b0;
    }
  }
}

/* Pass 0 over chunks [begin, end): scan_chunk. */
static void scan_task(void* data, uint32_t begin, uint32_t end, uint32_t worker) {
  (void)worker;
  const _tlod_frame* fr = data;
  list_arrays a = arrays_of(fr);
  for (uint32_t c = begin; c < end; c++)
    scan_chunk(fr, &a, c);
}

/* Pass 1 over busy chunks [begin, end): count_block over their visible blocks. */
static void count_task(void* data, uint32_t begin, uint32_t end, uint32_t worker) {
  (void)worker;
  _tlod_frame* fr = data;
  list_arrays a = arrays_of(fr);
  for (uint32_t i = begin; i < end; i++) {
    uint32_t c = fr->vs->busy[i], f0, f1, b0, b1, strips = 0;
    _tlod_list_chunk* ch = &fr->vs->chunks[c];
    _tlod_list_tally t = {.e_min = INFINITY, .culled = ch->culled};
    chunk_range(fr, c, &f0, &f1);
    for (uint32_t k = 0; ch->blocks >> k; k++) {
      block_range(f0, f1, k, &b0, &b1);
      if (ch->blocks & (UINT64_C(1) << k)) strips += count_block(&a, ch->counts, &t, b0, b1);
    }
    ch->e_max_min = t.e_min, ch->e_max_max = t.e_max;
    ch->strips = strips, ch->culled = t.culled;
  }
}

/* Pass 2 over busy chunks [begin, end): instances and strips at the
 * chunk's offsets (counts[] now holds each bucket's first slot of the chunk). */
static void write_task(void* data, uint32_t begin, uint32_t end, uint32_t worker) {
  (void)worker;
  _tlod_frame* fr = data;
  list_arrays a = arrays_of(fr);
  for (uint32_t i = begin; i < end; i++) {
    uint32_t c = fr->vs->busy[i], f0, f1, b0, b1;
    _tlod_list_chunk* ch = &fr->vs->chunks[c];
    tlod_draw_strip *first = ch->strips ? fr->vs->strips + ch->strip_first : NULL, *next = first;
    chunk_range(fr, c, &f0, &f1);
    for (uint32_t k = 0; ch->blocks >> k; k++) {
      block_range(f0, f1, k, &b0, &b1);
      if (!(ch->blocks & (UINT64_C(1) << k))) continue;
      a.kernels.write(&a.in, b0, b1, ch->counts);
      if (next) next += a.kernels.strips(&a.in, b0, b1, next);
    }
    for (const tlod_draw_strip* st = first; st < next; st++)
      ch->strip_triangles += strip_triangles(a.pat, st);
  }
}

/* The chunks with a visible block, in chunk order: the only ones passes 1
 * and 2 visit, so the workers share the visible patches, not the culled. */
static void list_busy(_tlod_view_state* vs, uint32_t chunks) {
  vs->busy_count = 0;
  for (uint32_t c = 0; c < chunks; c++)
    if (vs->chunks[c].blocks) vs->busy[vs->busy_count++] = c;
}

/* Bucket b's count into the level histogram and the pattern triangles. */
static void count_bucket(tlod_draw_list* dl, uint32_t levels, uint32_t b, uint32_t count) {
  dl->level_histogram[b % levels] += count;
  dl->pattern_triangles += (uint64_t)count * tlod_pattern_triangle_count((tlod_pattern_shape)(b / levels), b % levels);
}

/* Non-empty buckets into the list (with the histogram and pattern
 * triangles); every chunk's counts become its first slot per bucket, in
 * chunk order. Returns the instance count. */
static uint32_t lay_out_buckets(_tlod_frame* fr, uint32_t chunks) {
  _tlod_view_state* vs = fr->vs;
  uint32_t levels = fr->s->desc.max_level + 1, first = 0, nb = 0;
  for (uint32_t b = 0; b < TLOD_PATTERN_SHAPE_NUM * levels; b++) {
    uint32_t start = first;
    for (uint32_t c = 0; c < chunks; c++) {
      uint32_t n = vs->chunks[c].counts[b];
      vs->chunks[c].counts[b] = first;
      first += n;
    }
    count_bucket(&vs->list, levels, b, first - start);
    if (first > start)
      vs->buckets[nb++] = (tlod_draw_bucket){(tlod_pattern_shape)(b / levels), b % levels, start, first - start};
  }
  vs->list.bucket_count = nb;
  return first;
}

/* Chunk statistics summed in chunk order (independent of the workers). */
static void sum_chunks(_tlod_frame* fr, uint32_t chunks) {
  _tlod_view_state* vs = fr->vs;
  tlod_draw_list* dl = &vs->list;
  dl->culled = dl->strip_count = 0;
  dl->e_max_min = INFINITY;
  dl->e_max_max = 0.0f;
  for (uint32_t c = 0; c < chunks; c++) {
    _tlod_list_chunk* ch = &vs->chunks[c];
    ch->strip_first = dl->strip_count;
    dl->strip_count += ch->strips;
    dl->culled += ch->culled;
    dl->e_max_min = ch->e_max_min < dl->e_max_min ? ch->e_max_min : dl->e_max_min;
    dl->e_max_max = ch->e_max_max > dl->e_max_max ? ch->e_max_max : dl->e_max_max;
  }
  if (dl->culled == fr->s->patch_count) dl->e_max_min = 0.0f;
}

/* The strips' triangles (counted by pass 2), summed in chunk order. */
static void sum_strip_triangles(_tlod_view_state* vs, uint32_t chunks) {
  vs->list.strip_triangles = 0;
  for (uint32_t c = 0; c < chunks; c++)
    vs->list.strip_triangles += vs->chunks[c].strip_triangles;
}

/* The strip array grown once to the counted size: it only grows, so a
 * frame with no more strips than any before allocates nothing. */
static tlod_result reserve_strips(tlod_scheduler* s, _tlod_view_state* vs, uint32_t count) {
  if (count <= vs->strip_cap) return TLOD_SUCCESS;
  uint32_t cap = vs->strip_cap * 2 > count ? vs->strip_cap * 2 : count;
  tlod_draw_strip* grown = tlod_context_alloc(s->ctx, sizeof(*grown) * cap);
  if (!grown) return tlod_context_fail(s->ctx, TLOD_ERROR_OUT_OF_MEMORY, "scheduler '%s': out of memory", s->label);
  tlod_context_free(s->ctx, vs->strips);
  vs->strips = grown;
  vs->strip_cap = cap;
  return TLOD_SUCCESS;
}

/* Out of memory for the strips: the instances are still written, the
 * list has no strips (the error says so). */
static void drop_strips(_tlod_view_state* vs, uint32_t chunks) {
  for (uint32_t c = 0; c < chunks; c++)
    vs->chunks[c].strips = 0;
  vs->list.strip_count = 0;
  vs->list.strip_triangles = 0;
}

/* The busy list lives after the chunks, in their block (freed with them). */
tlod_result _tlod_list_alloc(tlod_scheduler* s, _tlod_view_state* vs) {
  size_t chunks = chunk_count(s->patch_count) + 1;
  vs->chunks = tlod_context_calloc(s->ctx, 1, chunks * (sizeof(_tlod_list_chunk) + sizeof(uint32_t)));
  vs->busy = vs->chunks ? (uint32_t*)(vs->chunks + chunks) : NULL;
  vs->strip_edges = tlod_context_calloc(s->ctx, (size_t)s->patch_count + 1, 1);
  return vs->chunks && vs->strip_edges ? TLOD_SUCCESS : TLOD_ERROR_OUT_OF_MEMORY;
}

tlod_result _tlod_fill_draw_list(_tlod_frame* fr) {
  _tlod_view_state* vs = fr->vs;
  uint32_t chunks = chunk_count(fr->s->patch_count);
  vs->list.patch_count = fr->s->patch_count;
  vs->list.levels = vs->levels;
  vs->list.e_max = vs->e_max;
  vs->list.vertex_depth = vs->depth;
  vs->list.effective_epsilon = fr->eps;
  vs->list.generation++;
  vs->list.instances = vs->instances;
  vs->list.buckets = vs->buckets;
  vs->key_valid = vs->settled_known = false;
  _tlod_up_edges_refresh(fr->s, &fr->mesh);
  if (fr->fused) { /* a byte per block: on the caller */
    scan_task(fr, 0, chunks, 0);
  } else {
    tlod_context_parallel_for(fr->s->ctx, scan_task, fr, chunks);
  }
  list_busy(vs, chunks);
  tlod_context_parallel_for(fr->s->ctx, count_task, fr, vs->busy_count);
  vs->list.pattern_triangles = 0;
  memset(vs->list.level_histogram, 0, sizeof(vs->list.level_histogram));
  vs->list.instance_count = lay_out_buckets(fr, chunks);
  sum_chunks(fr, chunks);
  tlod_result r = reserve_strips(fr->s, vs, vs->list.strip_count);
  if (r != TLOD_SUCCESS) drop_strips(vs, chunks);
  tlod_context_parallel_for(fr->s->ctx, write_task, fr, vs->busy_count);
  sum_strip_triangles(vs, chunks);
  vs->list.strips = vs->strips;
  return r;
}
