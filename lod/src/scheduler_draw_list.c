/* tesslod::lod -- the draw list of one view: instances grouped in buckets
 * of one (shape, level) pattern each, connection strips, statistics.
 *
 * Built in parallel and deterministically: the patches are cut into fixed
 * chunks of _TLOD_LIST_CHUNK (never dependent on the thread count); a first
 * pass counts each chunk's instances per bucket, strips and statistics, a
 * serial prefix sum in chunk order gives each chunk its offsets, and a
 * second pass writes every chunk at its offsets. The result is the serial
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

static tlod_pattern_shape shape_of(const tlod_mesh_view* m, uint32_t f) {
  return m->face_corners[f] == 4 ? TLOD_PATTERN_QUAD : TLOD_PATTERN_TRIANGLE;
}

/* Buckets are ordered by shape, then level: bucket index shape * (lmax + 1) + level. */
static uint32_t bucket_of(const _tlod_frame* fr, uint32_t f, uint32_t level) {
  return (uint32_t)shape_of(&fr->mesh, f) * (fr->s->desc.max_level + 1) + level;
}

static uint32_t chunk_count(uint32_t patches) { return (patches + _TLOD_LIST_CHUNK - 1) / _TLOD_LIST_CHUNK; }

static void chunk_range(const _tlod_frame* fr, uint32_t c, uint32_t* begin, uint32_t* end) {
  *begin = c * _TLOD_LIST_CHUNK;
  *end = *begin + _TLOD_LIST_CHUNK < fr->s->patch_count ? *begin + _TLOD_LIST_CHUNK : fr->s->patch_count;
}

/* The strip across edge e of visible patch f at level l (a strip is needed). */
static tlod_draw_strip strip_of(const _tlod_frame* fr, uint32_t f, uint32_t e, uint32_t l) {
  tlod_edge_link link = fr->mesh.links[f][e];
  uint32_t lg = _tlod_drawn_level(fr->vs->cont[link.face]);
  /* The coarser side's edge points are exact when its new vertices are at
   * rest: then the finer side has the same points (all of lower level). */
  uint32_t coarse = l < lg ? f : link.face, lc = l < lg ? l : lg;
  bool exact = link.smooth && l != lg && _tlod_morph_of(fr->vs->cont[coarse], lc) == 1.0f;
  return (tlod_draw_strip){f, link.face, (uint8_t)e, link.edge, (uint8_t)l, (uint8_t)lg, !link.smooth, exact};
}

/* Running statistics of a chunk's count pass, kept in locals rather
 * than in the chunk (whose counts[] stores would otherwise alias them). */
typedef struct chunk_tally {
  float e_min, e_max;
  uint32_t strips, culled;
  uint64_t strip_triangles;
} chunk_tally;

/* Whether edge e of visible patch f (drawn level l, blend m) needs a strip:
 * _tlod_strip_needed with f's level and blend computed once per patch. */
static bool strip_needed_at(const _tlod_frame* fr, uint32_t f, uint32_t e, uint32_t l, float m) {
  tlod_edge_link link = fr->mesh.links[f][e];
  uint32_t g = link.face;
  if (g == _TLOD_NO_FACE || g < f || !fr->vs->visible[g]) return false;
  float cg = fr->vs->cont[g];
  uint32_t lg = _tlod_drawn_level(cg);
  return !link.smooth || l != lg || m != _tlod_morph_of(cg, lg);
}

/* Strips of visible patch f at level l into the tally; the edges that
 * have one into strip_edges[f] (bit e), for the second pass. */
static void count_strips(const _tlod_frame* fr, chunk_tally* t, uint32_t f, uint32_t l) {
  uint8_t mask = 0;
  float m = _tlod_morph_of(fr->vs->cont[f], l);
  bool flat = fr->s->desc.policy == TLOD_POLICY_FLAT; /* FLAT draws no strip */
  for (uint32_t e = 0; !flat && e < fr->mesh.face_corners[f]; e++) {
    if (!strip_needed_at(fr, f, e, l, m)) continue;
    mask |= (uint8_t)(1u << e);
    tlod_draw_strip st = strip_of(fr, f, e, l);
    uint32_t n = 0;
    tlod_draw_strip_connection(fr->s->patterns, &st, &n);
    t->strips++;
    t->strip_triangles += n;
  }
  fr->vs->strip_edges[f] = mask;
}

/* Visible patch f at level l: its bucket count, statistics and strips. */
static void count_visible(const _tlod_frame* fr, _tlod_list_chunk* ch, chunk_tally* t, uint32_t f, uint32_t l) {
  float e = fr->vs->e_max[f];
  ch->counts[bucket_of(fr, f, l)]++;
  t->e_min = e < t->e_min ? e : t->e_min;
  t->e_max = e > t->e_max ? e : t->e_max;
  count_strips(fr, t, f, l);
}

/* Whether the n visible bytes from f are all 0 (culled). */
static bool all_culled(const uint8_t* visible, uint32_t f, uint32_t n) {
  uint8_t any = 0;
  for (uint32_t i = f; i < f + n; i++)
    any |= visible[i];
  return !any;
}

/* The culled patches from f skipped at once, else 0: a whole block when f
 * starts one (chunks are whole blocks), else 8 when f is a multiple of 8
 * (a visible border patch's block is mostly culled too). One scan of the
 * visible bytes instead of a test per patch. */
static uint32_t culled_run(const uint8_t* visible, uint32_t f, uint32_t end) {
  if (f % FAST_BLOCK == 0 && end - f >= FAST_BLOCK && all_culled(visible, f, FAST_BLOCK)) return FAST_BLOCK;
  if (f % 8 == 0 && end - f >= 8 && all_culled(visible, f, 8)) return 8;
  return 0;
}

/* Patches [f0, f1) of a chunk: drawn levels (-1 when culled; a culled
 * patch needs no level), bucket and strip counts, statistics. */
static void count_patches(const _tlod_frame* fr, _tlod_list_chunk* ch, chunk_tally* t, uint32_t f0, uint32_t f1) {
  _tlod_view_state* vs = fr->vs;
  for (uint32_t f = f0; f < f1; f++) {
    uint32_t run = culled_run(vs->visible, f, f1);
    if (run) { /* culled: no level to read */
      memset(vs->levels + f, -1, run);
      t->culled += run;
      f += run - 1;
      continue;
    }
    if (!vs->visible[f]) {
      vs->levels[f] = -1;
      t->culled++;
      continue;
    }
    uint32_t l = _tlod_drawn_level(vs->cont[f]);
    vs->levels[f] = (int8_t)l;
    count_visible(fr, ch, t, f, l);
  }
}

/* Pass 1 over chunks [begin, end): count_patches. */
static void count_task(void* data, uint32_t begin, uint32_t end, uint32_t worker) {
  (void)worker;
  _tlod_frame* fr = data;
  for (uint32_t c = begin; c < end; c++) {
    _tlod_list_chunk* ch = &fr->vs->chunks[c];
    *ch = (_tlod_list_chunk){0};
    chunk_tally t = {.e_min = INFINITY};
    uint32_t f0, f1;
    chunk_range(fr, c, &f0, &f1);
    count_patches(fr, ch, &t, f0, f1);
    ch->e_max_min = t.e_min, ch->e_max_max = t.e_max;
    ch->strips = t.strips, ch->culled = t.culled;
    ch->strip_triangles = t.strip_triangles;
  }
}

/* Pass 2 over chunks [begin, end): instances and strips at the chunk's
 * offsets (counts[] now holds each bucket's first slot of the chunk). */
static void write_task(void* data, uint32_t begin, uint32_t end, uint32_t worker) {
  (void)worker;
  _tlod_frame* fr = data;
  _tlod_view_state* vs = fr->vs;
  for (uint32_t c = begin; c < end; c++) {
    _tlod_list_chunk* ch = &vs->chunks[c];
    uint32_t f0, f1, st = ch->strip_first;
    chunk_range(fr, c, &f0, &f1);
    if (ch->culled == f1 - f0) continue;
    for (uint32_t f = f0; f < f1; f++) {
      uint32_t run = culled_run(vs->visible, f, f1);
      if (run) f += run - 1; /* culled: nothing to write */
      if (run || !vs->visible[f]) continue;
      uint32_t l = (uint32_t)vs->levels[f];
      /* Edges blend with their patch (see _tlod_strip_needed). */
      vs->instances[ch->counts[bucket_of(fr, f, l)]++] =
          (tlod_draw_instance){.patch = f, .level = l, .morph = _tlod_morph_of(vs->cont[f], l)};
      for (uint32_t e = 0; ch->strips && e < fr->mesh.face_corners[f]; e++)
        if (vs->strip_edges[f] & (1u << e)) vs->strips[st++] = strip_of(fr, f, e, l);
    }
  }
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
  dl->strip_triangles = 0;
  dl->culled = dl->strip_count = 0;
  dl->e_max_min = INFINITY;
  dl->e_max_max = 0.0f;
  for (uint32_t c = 0; c < chunks; c++) {
    _tlod_list_chunk* ch = &vs->chunks[c];
    ch->strip_first = dl->strip_count;
    dl->strip_count += ch->strips;
    dl->strip_triangles += ch->strip_triangles;
    dl->culled += ch->culled;
    dl->e_max_min = ch->e_max_min < dl->e_max_min ? ch->e_max_min : dl->e_max_min;
    dl->e_max_max = ch->e_max_max > dl->e_max_max ? ch->e_max_max : dl->e_max_max;
  }
  if (dl->culled == fr->s->patch_count) dl->e_max_min = 0.0f;
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

tlod_result _tlod_list_alloc(tlod_scheduler* s, _tlod_view_state* vs) {
  vs->chunks = tlod_context_calloc(s->ctx, chunk_count(s->patch_count) + 1, sizeof(_tlod_list_chunk));
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
  tlod_context_parallel_for(fr->s->ctx, count_task, fr, chunks);
  vs->list.pattern_triangles = 0;
  memset(vs->list.level_histogram, 0, sizeof(vs->list.level_histogram));
  vs->list.instance_count = lay_out_buckets(fr, chunks);
  sum_chunks(fr, chunks);
  tlod_result r = reserve_strips(fr->s, vs, vs->list.strip_count);
  if (r != TLOD_SUCCESS) drop_strips(vs, chunks);
  tlod_context_parallel_for(fr->s->ctx, write_task, fr, chunks);
  vs->list.strips = vs->strips;
  return r;
}
