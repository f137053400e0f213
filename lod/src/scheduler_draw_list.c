/* tesslod::lod -- the draw list of one view: instances grouped in buckets
 * of one (shape, level) pattern each, connection strips, statistics.
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

/* Drawn levels (-1 when culled) and the instance count of every bucket. */
static void count_levels(_tlod_frame* fr, uint32_t counts[_TLOD_BUCKETS]) {
  _tlod_view_state* vs = fr->vs;
  for (uint32_t f = 0; f < fr->s->patch_count; f++) {
    uint32_t l = _tlod_drawn_level(vs->cont[f]);
    vs->levels[f] = vs->visible[f] ? (int8_t)l : -1;
    if (vs->visible[f]) counts[bucket_of(fr, f, l)]++;
  }
}

/* Non-empty buckets into the list, and each bucket's first instance. */
static uint32_t lay_out_buckets(_tlod_frame* fr, const uint32_t counts[_TLOD_BUCKETS], uint32_t start[_TLOD_BUCKETS]) {
  uint32_t levels = fr->s->desc.max_level + 1, first = 0, nb = 0;
  for (uint32_t b = 0; b < TLOD_PATTERN_SHAPE_NUM * levels; b++) {
    start[b] = first;
    if (counts[b])
      fr->vs->buckets[nb++] = (tlod_draw_bucket){(tlod_pattern_shape)(b / levels), b % levels, first, counts[b]};
    first += counts[b];
  }
  fr->vs->list.bucket_count = nb;
  return first;
}

static void fill_instances(_tlod_frame* fr) {
  _tlod_view_state* vs = fr->vs;
  uint32_t counts[_TLOD_BUCKETS] = {0}, start[_TLOD_BUCKETS];
  count_levels(fr, counts);
  vs->list.instance_count = lay_out_buckets(fr, counts, start);
  for (uint32_t f = 0; f < fr->s->patch_count; f++) {
    if (!vs->visible[f]) continue;
    uint32_t l = (uint32_t)vs->levels[f];
    tlod_draw_instance* in = &vs->instances[start[bucket_of(fr, f, l)]++];
    /* Edges blend with their patch (see _tlod_strip_needed). */
    *in = (tlod_draw_instance){.patch = f, .level = l, .morph = _tlod_morph_of(vs->cont[f], l)};
  }
  vs->list.instances = vs->instances;
  vs->list.buckets = vs->buckets;
}

/* Doubles the strip array when full: strips are only known once counted. */
static tlod_result push_strip(tlod_scheduler* s, _tlod_view_state* vs, const tlod_draw_strip* st) {
  if (vs->list.strip_count == vs->strip_cap) {
    uint32_t cap = vs->strip_cap ? vs->strip_cap * 2 : 256;
    tlod_draw_strip* grown = tlod_context_alloc(s->ctx, sizeof(*grown) * cap);
    if (!grown) return tlod_context_fail(s->ctx, TLOD_ERROR_OUT_OF_MEMORY, "scheduler '%s': out of memory", s->label);
    if (vs->list.strip_count) memcpy(grown, vs->strips, sizeof(*grown) * vs->list.strip_count);
    tlod_context_free(s->ctx, vs->strips);
    vs->strips = grown;
    vs->strip_cap = cap;
  }
  vs->strips[vs->list.strip_count++] = *st;
  return TLOD_SUCCESS;
}

static tlod_result fill_strips(_tlod_frame* fr) {
  _tlod_view_state* vs = fr->vs;
  tlod_draw_list* dl = &vs->list;
  dl->strip_count = 0;
  dl->strip_triangles = 0;
  for (uint32_t f = 0; f < fr->s->patch_count; f++) {
    if (!vs->visible[f]) continue;
    for (uint32_t e = 0; e < fr->mesh.face_corners[f]; e++) {
      if (!_tlod_strip_needed(fr, vs->cont, f, e)) continue;
      tlod_edge_link link = fr->mesh.links[f][e];
      uint8_t la = (uint8_t)vs->levels[f], lb = (uint8_t)vs->levels[link.face];
      tlod_draw_strip st = {f, link.face, (uint8_t)e, link.edge, la, lb, !link.smooth};
      if (push_strip(fr->s, vs, &st) != TLOD_SUCCESS) return TLOD_ERROR_OUT_OF_MEMORY;
      dl->strip_triangles += fr->s->patterns->connect_count[la][lb];
    }
  }
  dl->strips = vs->strips;
  return TLOD_SUCCESS;
}

/* Pattern triangles, culled count, level histogram and e_max range of the
 * visible patches, summed in patch order (independent of the workers). */
static void fill_stats(_tlod_frame* fr) {
  _tlod_view_state* vs = fr->vs;
  tlod_draw_list* dl = &vs->list;
  dl->pattern_triangles = 0;
  dl->culled = 0;
  memset(dl->level_histogram, 0, sizeof(dl->level_histogram));
  dl->e_max_min = INFINITY;
  dl->e_max_max = 0.0f;
  for (uint32_t f = 0; f < fr->s->patch_count; f++) {
    if (vs->levels[f] < 0) {
      dl->culled++;
      continue;
    }
    dl->level_histogram[vs->levels[f]]++;
    dl->pattern_triangles += tlod_pattern_triangle_count(shape_of(&fr->mesh, f), (uint32_t)vs->levels[f]);
    dl->e_max_min = vs->e_max[f] < dl->e_max_min ? vs->e_max[f] : dl->e_max_min;
    dl->e_max_max = vs->e_max[f] > dl->e_max_max ? vs->e_max[f] : dl->e_max_max;
  }
  if (dl->culled == fr->s->patch_count) dl->e_max_min = 0.0f;
}

tlod_result _tlod_fill_draw_list(_tlod_frame* fr) {
  _tlod_view_state* vs = fr->vs;
  vs->list.patch_count = fr->s->patch_count;
  vs->list.levels = vs->levels;
  vs->list.e_max = vs->e_max;
  vs->list.vertex_depth = vs->depth;
  vs->list.effective_epsilon = fr->eps;
  vs->list.generation++;
  fill_instances(fr);
  tlod_result r = fill_strips(fr);
  fill_stats(fr);
  return r;
}
