/* Private to the GPU backends (gl, vulkan): what a draw stages on the CPU
 * before it records anything, shared so both devices draw the same lists
 * the same way: every item's instances, strips and strip references into
 * one array each, the draw order (BLEND items last, farthest first), the
 * hardware path's edge levels and its batches under Mesa's 65,536
 * tessellated vertices, the view vectors of the shading. Header-only: the
 * backends link below the dispatch. */
#ifndef TESSLOD_DEVICE_STAGE_H
#define TESSLOD_DEVICE_STAGE_H

#include <math.h>

#include "device_internal.h"
#include "layout.h" /* backends/shaders: tlod_gl_instance, tlod_gl_strip */

/* Item k's start in the staged arrays: its instances, and its strip
 * triangles as index_count indices from index_first (into refs). */
typedef struct _tlod_stage_range {
  uint32_t instance_first, index_first, index_count, ref_count;
} _tlod_stage_range;

/* What the staged arrays were made from, per item (_tlod_stage_unchanged). */
typedef struct _tlod_stage_key {
  const tlod_draw_list* dl;
  uint64_t generation;
  const tlod_surface* surface;
  uint32_t instance_count, strip_count, patch_count;
} _tlod_stage_key;

typedef struct _tlod_stage {
  bool hardware; /* edge levels for the tessellation path */
  bool valid;    /* keys and saved describe the staged arrays */
  _tlod_stage_key* keys;
  uint32_t key_cap, key_count;
  unsigned char* saved; /* every list's instances, strips (and levels, hardware) as staged */
  uint32_t saved_cap;
  tlod_gl_instance* instances;
  uint32_t instance_cap, instance_count;
  tlod_gl_strip* strips;
  uint32_t strip_cap, strip_count;
  uint32_t (*refs)[2]; /* (strip, point): each point of each strip once */
  uint32_t ref_cap, ref_count;
  uint32_t* indices; /* strip triangles, 3 refs each: strips are drawn indexed (one invocation per point) */
  uint32_t index_cap, index_count;
  uint32_t* instance_of; /* patch -> instance of the item being staged */
  uint32_t instance_of_cap;
  _tlod_stage_range* ranges;
  uint32_t range_cap;
  uint32_t* order; /* draw order of the items: non-BLEND in item order, then BLEND farthest first */
  float* order_depth;
  uint32_t order_cap, order_depth_cap;
} _tlod_stage;

static inline void _tlod_stage_free(const tlod_context* ctx, _tlod_stage* s) {
  void* arrays[] = {s->instances, s->strips, s->refs, s->indices, s->instance_of,
                    s->ranges,    s->order,  s->keys, s->saved,   s->order_depth};
  for (size_t i = 0; i < sizeof(arrays) / sizeof(arrays[0]); i++)
    tlod_context_free(ctx, arrays[i]);
}

/* Hardware path: an edge is tessellated at the finer of its two sides'
 * levels, so both sides generate the same points. */
static inline uint32_t _tlod_stage_edge_levels(const tlod_mesh_view* m, const tlod_draw_list* dl,
                                               const tlod_draw_instance* in) {
  uint32_t packed = 0;
  for (uint32_t e = 0; e < m->face_corners[in->patch]; e++) {
    uint32_t l = in->level, g = m->links[in->patch][e].face;
    if (g != UINT32_MAX && dl->levels[g] > (int8_t)l) l = (uint32_t)dl->levels[g];
    packed |= l << (8 * e);
  }
  return packed;
}

/* The points of a strip between levels la and lb: a's edge polyline
 * (2^la + 1 points) then b's (2^lb + 1), strip.vert's numbering. */
static inline uint32_t _tlod_stage_strip_points(uint32_t la, uint32_t lb) { return (1u << la) + (1u << lb) + 2u; }

/* The references (points) and indices of a draw list's strips. */
static inline void _tlod_stage_strip_counts(const tlod_patterns* p, const tlod_draw_list* dl, uint32_t* refs,
                                            uint32_t* indices) {
  for (uint32_t k = 0; k < dl->strip_count; k++) {
    uint32_t count;
    tlod_draw_strip_connection(p, &dl->strips[k], &count);
    *indices += 3 * count;
    *refs += count ? _tlod_stage_strip_points(dl->strips[k].level_a, dl->strips[k].level_b) : 0u;
  }
}

static inline bool _tlod_stage_reserve(const tlod_context* ctx, _tlod_stage* s, const tlod_patterns* p,
                                       const tlod_draw_desc* desc, const _tlod_draw_ref* items) {
  uint32_t instances = 0, strips = 0, refs = 0, indices = 0, patches = 0;
  for (uint32_t k = 0; k < desc->item_count; k++) {
    const tlod_draw_list* dl = items[k].item->draw_list;
    instances += dl->instance_count;
    strips += dl->strip_count;
    _tlod_stage_strip_counts(p, dl, &refs, &indices);
    patches = dl->patch_count > patches ? dl->patch_count : patches;
  }
  return _tlod_device_grow(ctx, (void**)&s->instances, &s->instance_cap, instances + 1, sizeof(tlod_gl_instance)) &&
         _tlod_device_grow(ctx, (void**)&s->strips, &s->strip_cap, strips + 1, sizeof(tlod_gl_strip)) &&
         _tlod_device_grow(ctx, (void**)&s->refs, &s->ref_cap, refs + 1, sizeof(uint32_t[2])) &&
         _tlod_device_grow(ctx, (void**)&s->indices, &s->index_cap, indices + 1, sizeof(uint32_t)) &&
         _tlod_device_grow(ctx, (void**)&s->instance_of, &s->instance_of_cap, patches + 1, sizeof(uint32_t)) &&
         _tlod_device_grow(ctx, (void**)&s->ranges, &s->range_cap, desc->item_count, sizeof(*s->ranges));
}

/* The fourth edge's blend: a quad's edge blends with its patch; a
 * triangle's unused fourth edge is exact. */
static inline float _tlod_stage_fourth_edge_morph(const tlod_mesh_view* m, const tlod_draw_instance* in) {
  return in->patch < m->face_count && m->face_corners[in->patch] == 4 ? in->morph : 1.0f;
}

/* One item's strips and their references, after its instances. */
static inline void _tlod_stage_strips(_tlod_stage* s, const tlod_patterns* p, const tlod_draw_list* dl) {
  for (uint32_t j = 0; j < dl->strip_count; j++) {
    const tlod_draw_strip* st = &dl->strips[j];
    /* Each side blends its edge points as its own patch does. */
    float ma = dl->instances[s->instance_of[st->patch_a]].morph;
    float mb = dl->instances[s->instance_of[st->patch_b]].morph;
    uint32_t id = s->strip_count + j;
    s->strips[id] = (tlod_gl_strip){st->patch_a,
                                    st->patch_b,
                                    st->edge_a | (uint32_t)st->edge_b << 8,
                                    st->level_a | (uint32_t)st->level_b << 8,
                                    {ma, mb, 0.0f, 0.0f}};
    uint32_t count, base = s->ref_count;
    const uint32_t* tris = tlod_draw_strip_connection(p, st, &count);
    uint32_t points = count ? _tlod_stage_strip_points(st->level_a, st->level_b) : 0u;
    for (uint32_t r = 0; r < points; r++)
      s->refs[base + r][0] = id, s->refs[base + r][1] = r;
    s->ref_count += points;
    for (uint32_t t = 0; t < 3 * count; t++)
      s->indices[s->index_count++] = base + tris[t];
  }
  s->strip_count += dl->strip_count;
}

/* The bytes of a list the staged arrays depend on: instances, strips and
 * (hardware: the edge levels) every patch's level. */
static inline size_t _tlod_stage_list_bytes(const _tlod_stage* s, const tlod_draw_list* dl) {
  return sizeof(tlod_draw_instance) * dl->instance_count + sizeof(tlod_draw_strip) * dl->strip_count +
         (s->hardware ? dl->patch_count : 0u);
}

static inline _tlod_stage_key _tlod_stage_key_of(const _tlod_draw_ref* it) {
  const tlod_draw_list* dl = it->item->draw_list;
  return (_tlod_stage_key){dl, dl->generation, it->surface, dl->instance_count, dl->strip_count, dl->patch_count};
}

/* The generation is not compared: a list whose update left it as it was
 * (today every update makes a new generation) is still the same list, and
 * the bytes decide (_tlod_stage_unchanged). */
static inline bool _tlod_stage_key_equal(const _tlod_stage_key* a, const _tlod_stage_key* b) {
  return a->dl == b->dl && a->surface == b->surface && a->instance_count == b->instance_count &&
         a->strip_count == b->strip_count && a->patch_count == b->patch_count;
}

/* Appends (copy) or compares (!copy) list dl's instances, strips and
 * (levels) its levels at saved + *at. */
static inline bool _tlod_list_bytes(unsigned char* saved, bool levels, const tlod_draw_list* dl, size_t* at,
                                    bool copy) {
  const void* parts[3] = {dl->instances, dl->strips, dl->levels};
  size_t sizes[3] = {sizeof(tlod_draw_instance) * dl->instance_count, sizeof(tlod_draw_strip) * dl->strip_count,
                     levels ? dl->patch_count : 0u};
  bool same = true;
  for (int k = 0; k < 3; k++) {
    if (!sizes[k]) continue;
    if (copy)
      memcpy(saved + *at, parts[k], sizes[k]);
    else
      same = same && !memcmp(saved + *at, parts[k], sizes[k]);
    *at += sizes[k];
  }
  return same;
}

static inline bool _tlod_stage_list_saved(_tlod_stage* s, const tlod_draw_list* dl, size_t* at, bool copy) {
  return _tlod_list_bytes(s->saved, s->hardware, dl, at, copy);
}

/* One item's list as last evaluated (the CPU-mesh mode's cache): its key,
 * the surface's and mesh's generations, its bytes. */
typedef struct _tlod_list_snapshot {
  bool valid;
  _tlod_stage_key key;
  uint64_t surface_generation, mesh_generation;
  unsigned char* bytes;
  uint32_t cap;
} _tlod_list_snapshot;

static inline void _tlod_snapshot_generations(const tlod_surface* s, uint64_t* surface, uint64_t* mesh) {
  *surface = tlod_surface_query_view(s).generation;
  *mesh = tlod_mesh_query_view(tlod_surface_mesh(s)).generation;
}

/* True when the item's list, surface and mesh are those of the snapshot. */
static inline bool _tlod_snapshot_same(const _tlod_list_snapshot* sn, const _tlod_draw_ref* it) {
  _tlod_stage_key key = _tlod_stage_key_of(it);
  uint64_t sg, mg;
  _tlod_snapshot_generations(it->surface, &sg, &mg);
  size_t at = 0;
  return sn->valid && _tlod_stage_key_equal(&key, &sn->key) && sg == sn->surface_generation &&
         mg == sn->mesh_generation && _tlod_list_bytes(sn->bytes, true, it->item->draw_list, &at, false);
}

/* Out of memory only loses the next skip. */
static inline void _tlod_snapshot_take(const tlod_context* ctx, _tlod_list_snapshot* sn, const _tlod_draw_ref* it) {
  const tlod_draw_list* dl = it->item->draw_list;
  size_t bytes = sizeof(tlod_draw_instance) * dl->instance_count + sizeof(tlod_draw_strip) * dl->strip_count +
                 dl->patch_count + 1u;
  sn->valid = bytes <= UINT32_MAX && _tlod_device_grow(ctx, (void**)&sn->bytes, &sn->cap, (uint32_t)bytes, 1);
  if (!sn->valid) return;
  sn->key = _tlod_stage_key_of(it);
  _tlod_snapshot_generations(it->surface, &sn->surface_generation, &sn->mesh_generation);
  size_t at = 0;
  _tlod_list_bytes(sn->bytes, true, dl, &at, true);
}

/* True when the staged arrays are those of this draw's items: the same
 * lists over the same surfaces with the same instances, strips and levels
 * byte for byte. Not the generation alone: an address and a generation can
 * come back after a scheduler is destroyed and another made; and a new
 * generation may hold the same list (a still camera, all at one level). */
static inline bool _tlod_stage_unchanged(_tlod_stage* s, const tlod_draw_desc* desc, const _tlod_draw_ref* items) {
  if (!s->valid || s->key_count != desc->item_count) return false;
  for (uint32_t k = 0; k < desc->item_count; k++) {
    _tlod_stage_key key = _tlod_stage_key_of(&items[k]);
    if (!_tlod_stage_key_equal(&key, &s->keys[k])) return false;
  }
  size_t at = 0;
  for (uint32_t k = 0; k < desc->item_count; k++) {
    if (!_tlod_stage_list_saved(s, items[k].item->draw_list, &at, false)) return false;
  }
  return true;
}

/* Records what was staged; out of memory only loses the next skip. */
static inline void _tlod_stage_remember(const tlod_context* ctx, _tlod_stage* s, const tlod_draw_desc* desc,
                                        const _tlod_draw_ref* items) {
  size_t bytes = 1;
  for (uint32_t k = 0; k < desc->item_count; k++)
    bytes += _tlod_stage_list_bytes(s, items[k].item->draw_list);
  s->valid = bytes <= UINT32_MAX &&
             _tlod_device_grow(ctx, (void**)&s->keys, &s->key_cap, desc->item_count, sizeof(_tlod_stage_key)) &&
             _tlod_device_grow(ctx, (void**)&s->saved, &s->saved_cap, (uint32_t)bytes, 1);
  if (!s->valid) return;
  size_t at = 0;
  for (uint32_t k = 0; k < desc->item_count; k++) {
    s->keys[k] = _tlod_stage_key_of(&items[k]);
    _tlod_stage_list_saved(s, items[k].item->draw_list, &at, true);
  }
  s->key_count = desc->item_count;
}

/* Every item's instances, strips and strip references into one array each
 * (one upload per array per draw); item k's start in ranges[k], its staging
 * time in item_stats[k].cpu_ms. When the items' lists are those staged
 * last (_tlod_stage_unchanged) the arrays are kept and *restaged is false:
 * the device need not send them again. */
static inline tlod_result _tlod_stage_items(tlod_context* ctx, _tlod_stage* s, const tlod_patterns* p, const char* who,
                                            const tlod_draw_desc* desc, const _tlod_draw_ref* items,
                                            tlod_draw_item_stats* item_stats, bool* restaged) {
  *restaged = !_tlod_stage_unchanged(s, desc, items);
  if (!*restaged) return TLOD_SUCCESS;
  s->valid = false;
  if (!_tlod_stage_reserve(ctx, s, p, desc, items))
    return tlod_context_fail(ctx, TLOD_ERROR_OUT_OF_MEMORY, "%s: out of memory staging a draw", who);
  s->instance_count = s->strip_count = s->ref_count = s->index_count = 0;
  for (uint32_t k = 0; k < desc->item_count; k++) {
    double t0 = tlod_now_ms();
    const tlod_draw_list* dl = items[k].item->draw_list;
    tlod_mesh_view m = tlod_mesh_query_view(tlod_surface_mesh(items[k].surface));
    s->ranges[k].instance_first = s->instance_count;
    s->ranges[k].index_first = s->index_count;
    uint32_t ref_first = s->ref_count;
    for (uint32_t j = 0; j < dl->instance_count; j++) {
      const tlod_draw_instance* in = &dl->instances[j];
      s->instances[s->instance_count + j] =
          (tlod_gl_instance){.patch = in->patch,
                             .level = in->level,
                             .edge_levels = s->hardware ? _tlod_stage_edge_levels(&m, dl, in) : 0u,
                             .morph = {in->morph, in->morph, in->morph, in->morph},
                             .morph_e3 = {_tlod_stage_fourth_edge_morph(&m, in), 0, 0, 0}};
      if (in->patch < dl->patch_count) s->instance_of[in->patch] = j;
    }
    _tlod_stage_strips(s, p, dl);
    s->ranges[k].index_count = s->index_count - s->ranges[k].index_first;
    s->ranges[k].ref_count = s->ref_count - ref_first;
    s->instance_count += dl->instance_count;
    item_stats[k].cpu_ms = tlod_now_ms() - t0;
  }
  _tlod_stage_remember(ctx, s, desc, items);
  return TLOD_SUCCESS;
}

/* Eye-space depth (negative in front of the camera) of the item's centre
 * (the model-transformed centre of its surface, `center`). */
static inline float _tlod_stage_depth(const tlod_draw_desc* fr, const tlod_draw_item* item, const float c[3]) {
  static const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  const float* m = item->has_model ? item->model : identity;
  float w[3];
  for (int r = 0; r < 3; r++)
    w[r] = m[r] * c[0] + m[4 + r] * c[1] + m[8 + r] * c[2] + m[12 + r];
  const float* v = fr->view;
  return v[2] * w[0] + v[6] * w[1] + v[10] * w[2] + v[14];
}

/* s->order: the non-BLEND items in item order, then the BLEND items
 * farthest first (most negative eye z; a stable insertion sort: equal
 * depths keep item order, and blended items are few). center(state) is the
 * centre of a surface state's bounding box (_tlod_surface_center). */
static inline tlod_result _tlod_stage_order(tlod_context* ctx, _tlod_stage* s, const char* who,
                                            const tlod_draw_desc* fr, const _tlod_draw_ref* items,
                                            const float* (*center)(const void* surface_state)) {
  uint32_t n = fr->item_count, opaque = 0, blended = 0;
  if (!_tlod_device_grow(ctx, (void**)&s->order, &s->order_cap, n, sizeof(uint32_t)) ||
      !_tlod_device_grow(ctx, (void**)&s->order_depth, &s->order_depth_cap, n, sizeof(float)))
    return tlod_context_fail(ctx, TLOD_ERROR_OUT_OF_MEMORY, "%s: out of memory ordering %u items", who, n);
  for (uint32_t k = 0; k < n; k++)
    opaque += items[k].item->blend != TLOD_BLEND_BLEND;
  for (uint32_t k = 0, o = 0; k < n; k++) {
    if (items[k].item->blend != TLOD_BLEND_BLEND) {
      s->order[o++] = k;
      continue;
    }
    float z = _tlod_stage_depth(fr, items[k].item, center(items[k].surface_state));
    uint32_t j = blended++;
    while (j > 0 && s->order_depth[j - 1] > z) {
      s->order_depth[j] = s->order_depth[j - 1];
      s->order[opaque + j] = s->order[opaque + j - 1];
      j--;
    }
    s->order_depth[j] = z;
    s->order[opaque + j] = k;
  }
  return TLOD_SUCCESS;
}

/* The centre of the box around the patches' bounding spheres: where a
 * BLEND item is, for the back-to-front order. */
static inline void _tlod_surface_center(const tlod_surface* s, float out[3]) {
  tlod_surface_view v = tlod_surface_query_view(s);
  float lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  for (uint32_t p = 0; p < v.patch_count; p++) {
    for (int k = 0; k < 3; k++) {
      float a = v.patches[p].center[k] - v.patches[p].radius, b = v.patches[p].center[k] + v.patches[p].radius;
      lo[k] = p == 0 || a < lo[k] ? a : lo[k];
      hi[k] = p == 0 || b > hi[k] ? b : hi[k];
    }
  }
  for (int k = 0; k < 3; k++)
    out[k] = 0.5f * (lo[k] + hi[k]);
}

/* Tessellated vertices of a patch whose largest level is l (docs/platform.md section 1.2). */
static inline uint32_t _tlod_tess_vertices(uint32_t corners, uint32_t l) {
  uint32_t n = 1u << l;
  if (corners == 4) return (n + 1) * (n + 1);
  return n == 1 ? 3u : 3u * n * n / 4u + 3u * n / 2u + 1u;
}

/* Hardware path: the end of the batch of whole patches starting at staged
 * instance `start` (< end) that stays under 65,536 tessellated vertices
 * (Mesa drops what lies past that, silently; a patch past it alone is one
 * batch); its vertices added to *vertices. */
static inline uint32_t _tlod_tess_batch(const tlod_gl_instance* ins, uint32_t start, uint32_t end, uint32_t corners,
                                        uint64_t* vertices) {
  uint32_t i = start, sum = 0;
  for (; i < end; i++) {
    uint32_t l = ins[i].level;
    for (uint32_t e = 0; e < corners; e++) {
      uint32_t le = (ins[i].edge_levels >> (8 * e)) & 255u;
      l = le > l ? le : l;
    }
    uint32_t v = _tlod_tess_vertices(corners, l);
    if (i > start && sum + v > 65535u) break;
    sum += v;
    *vertices += v;
  }
  return i;
}

/* The program variant an item draws with (gl's VARIANT_*, vulkan's
 * VK_VARIANT_*: 0 PLAIN, 1 FULL, 2 MASK): PLAIN unless its fragments read a
 * texture or (with a fragment hook) its mesh's attributes; MASK items
 * their own (discard loses the early depth test). */
static inline int _tlod_stage_variant(bool hook, uint32_t attribute_count, const tlod_draw_item* item) {
  if (item->blend == TLOD_BLEND_MASK) return 2;
  return item->base_color_texture || (hook && attribute_count > 0) ? 1 : 0;
}

/* The view's shading vectors: the unit light direction (the default when
 * the desc's is zero), the eye's world position, the view's world forward. */
static inline void _tlod_view_vectors(const tlod_draw_desc* fr, float light[3], float eye[3], float fwd[3]) {
  float l[3] = {fr->light_dir[0], fr->light_dir[1], fr->light_dir[2]};
  if (l[0] == 0.0f && l[1] == 0.0f && l[2] == 0.0f) l[0] = 0.3f, l[1] = 0.8f, l[2] = 0.5f;
  float len = sqrtf(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
  const float* v = fr->view;
  for (int i = 0; i < 3; i++) {
    light[i] = l[i] / len;
    eye[i] = -(v[i * 4 + 0] * v[12] + v[i * 4 + 1] * v[13] + v[i * 4 + 2] * v[14]);
    fwd[i] = -v[i * 4 + 2];
  }
}

/* The pattern vertices of both shapes (the layout of TLOD_BINDING_PATTERN)
 * and the indices of every level, with where each shape and level starts. */
typedef struct _tlod_pattern_data {
  tlod_gl_pattern_vertex* vertices;
  uint32_t* indices;
  uint32_t vertex_count, index_total;
  uint32_t index_first[2][TLOD_MAX_LEVEL + 1], index_count[2][TLOD_MAX_LEVEL + 1], shape_base[2];
} _tlod_pattern_data;

static inline void _tlod_pattern_data_fill(const tlod_patterns* p, uint32_t lmax, _tlod_pattern_data* o,
                                           const tlod_pattern_vertex* const pv[2], const uint32_t counts[2]) {
  for (int sh = 0; sh < 2; sh++) {
    uint32_t corners = sh == TLOD_PATTERN_QUAD ? 4u : 3u;
    for (uint32_t x = 0; x < counts[sh]; x++) {
      const tlod_pattern_vertex* v = &pv[sh][x];
      tlod_gl_pattern_vertex* out = &o->vertices[o->shape_base[sh] + x];
      out->uv[0] = v->u, out->uv[1] = v->v;
      out->parent0 = v->parent[0], out->parent1 = v->parent[1];
      uint32_t param = 0, kind = tlod_grid_point_kind(corners, lmax, v->i, v->j, &param);
      out->code = kind | (uint32_t)v->level << TLOD_CODE_LEVEL_SHIFT;
      out->param = param;
    }
    for (uint32_t l = 0; l <= lmax; l++) {
      uint32_t count;
      const uint32_t* src = tlod_patterns_indices(p, (tlod_pattern_shape)sh, l, &count);
      memcpy(o->indices + o->index_first[sh][l], src, sizeof(uint32_t) * count);
    }
  }
}

/* Fills *o (arrays through ctx; _tlod_pattern_data_free). */
static inline bool _tlod_pattern_data_make(const tlod_context* ctx, const tlod_patterns* p, _tlod_pattern_data* o) {
  uint32_t lmax = tlod_patterns_max_level(p), counts[2];
  const tlod_pattern_vertex* pv[2];
  memset(o, 0, sizeof(*o));
  for (int sh = 0; sh < 2; sh++) {
    pv[sh] = tlod_patterns_vertices(p, (tlod_pattern_shape)sh, &counts[sh]);
    o->shape_base[sh] = o->vertex_count;
    o->vertex_count += counts[sh];
    for (uint32_t l = 0; l <= lmax; l++) {
      tlod_patterns_indices(p, (tlod_pattern_shape)sh, l, &o->index_count[sh][l]);
      o->index_first[sh][l] = o->index_total;
      o->index_total += o->index_count[sh][l];
    }
  }
  o->vertices = tlod_context_calloc(ctx, o->vertex_count, sizeof(tlod_gl_pattern_vertex));
  o->indices = tlod_context_alloc(ctx, sizeof(uint32_t) * o->index_total);
  if (o->vertices && o->indices) _tlod_pattern_data_fill(p, lmax, o, pv, counts);
  return o->vertices && o->indices;
}

static inline void _tlod_pattern_data_free(const tlod_context* ctx, _tlod_pattern_data* o) {
  tlod_context_free(ctx, o->vertices);
  tlod_context_free(ctx, o->indices);
  o->vertices = NULL, o->indices = NULL;
}

#endif
