/*
 * pattern_refine.c -- nested refinement patterns (tesslod::lod); owned by the
 * refinement-pattern code, see patterns_internal.h for the layout.
 *
 * This work is based on: Schwarz, Staginski, Stamminger 2006; Boubekeur &
 * Schlick 2005 (generic mesh refinement on GPU).
 *
 * Pattern l of a shape is a regular grid of spacing 1/2^l whose diagonals
 * all run the same way (triangle: parallel to the w = const side, quad:
 * (0,0)-(1,1)). Such a grid is exactly what l successive 1-to-4 splits give,
 * so level l's vertices are a subset of level l + 1's and one vertex array
 * serves every level (Schwarz et al., section 3).
 *
 * Generation works on "fine" integer grid coordinates over N = 2^max_level
 * and a direct map fine (A, B) -> vertex index, so nothing is ever searched:
 * level-l point (a, b) is fine point (a * s, b * s) with s = 2^(max_level - l).
 */
#include <assert.h>
#include <string.h>

#include "patterns_internal.h"

/* Corners in unit coordinates (times N gives fine coordinates), in corner
 * order: triangle i (u=1), j (v=1), k (w=1); quad 0..3 counter-clockwise. */
static const uint8_t k_corners[TLOD_PATTERN_SHAPE_NUM][4][2] = {
    {{1, 0}, {0, 1}, {0, 0}, {0, 0}},
    {{0, 0}, {1, 0}, {1, 1}, {0, 1}},
};
static const uint32_t k_corner_count[TLOD_PATTERN_SHAPE_NUM] = {3, 4};

static bool shape_valid(tlod_pattern_shape shape) { return (uint32_t)shape < (uint32_t)TLOD_PATTERN_SHAPE_NUM; }

/* Last grid column of row b on an n-grid: the triangle is the half a + b <= n. */
static uint32_t row_end(tlod_pattern_shape shape, uint32_t n, uint32_t b) {
  return shape == TLOD_PATTERN_TRIANGLE ? n - b : n;
}

/* Levels above TLOD_MAX_LEVEL (or a bad shape) give 0 rather than counts
 * that would overflow uint32 a few levels later. */
uint32_t tlod_pattern_vertex_count(tlod_pattern_shape shape, uint32_t level) {
  if (!shape_valid(shape) || level > TLOD_MAX_LEVEL) return 0;
  uint32_t n = 1u << level;
  return shape == TLOD_PATTERN_TRIANGLE ? (n + 1) * (n + 2) / 2 : (n + 1) * (n + 1);
}

uint32_t tlod_pattern_triangle_count(tlod_pattern_shape shape, uint32_t level) {
  if (!shape_valid(shape) || level > TLOD_MAX_LEVEL) return 0;
  uint32_t quads = 1u << (2 * level);
  return shape == TLOD_PATTERN_TRIANGLE ? quads : 2 * quads;
}

/* ------------------------------------------------------------------------ */
/* Generation                                                               */
/* ------------------------------------------------------------------------ */

typedef struct build_state {
  tlod_context* ctx;
  tlod_pattern_shape shape;
  uint32_t max_level;
  uint32_t fine_n; /* N = 2^max_level */
  uint32_t* map;   /* (N + 1)^2, fine (A, B) -> vertex index, row stride N + 1 */
  _tlod_pattern_set* set;
} build_state;

static uint32_t* map_slot(const build_state* st, uint32_t fa, uint32_t fb) {
  return &st->map[(size_t)fb * (st->fine_n + 1) + fa];
}

static void* alloc_array(tlod_context* ctx, size_t count, size_t size, const char* what, tlod_result* result) {
  /* calloc: vertex structs have padding, zeroing it keeps two builds bytewise equal. */
  void* p = tlod_context_calloc(ctx, count, size);
  if (!p)
    *result =
        tlod_context_fail(ctx, TLOD_ERROR_OUT_OF_MEMORY,
                          "tlod_patterns_create: out of memory allocating %s (%zu x %zu bytes)", what, count, size);
  return p;
}

static void add_vertex(build_state* st, uint32_t fa, uint32_t fb, uint32_t level, uint32_t parent0, uint32_t parent1) {
  _tlod_pattern_set* set = st->set;
  tlod_pattern_vertex* v = &set->vertices[set->vertex_count];
  v->i = (uint16_t)fa;
  v->j = (uint16_t)fb;
  /* N is a power of two <= 1024: both divisions are exact in float. */
  v->u = (float)fa / (float)st->fine_n;
  v->v = (float)fb / (float)st->fine_n;
  v->level = (uint8_t)level;
  v->parent[0] = parent0;
  v->parent[1] = parent1;
  *map_slot(st, fa, fb) = set->vertex_count++;
}

static void insert_corners(build_state* st) {
  for (uint32_t c = 0; c < st->set->corner_count; ++c)
    add_vertex(st, k_corners[st->shape][c][0] * st->fine_n, k_corners[st->shape][c][1] * st->fine_n, 0, UINT32_MAX,
               UINT32_MAX);
}

/* The level-(l-1) edge whose midpoint is level-l point (a, b), not both even:
 * ends[0] = (a, b) - d, ends[1] = (a, b) + d, with d along a row, a column,
 * or the cell diagonal, which is (1, -1) in the triangle (parallel to the
 * w = const side) and (1, 1) in the quad. */
static void split_edge(tlod_pattern_shape shape, uint32_t a, uint32_t b, uint32_t ends[2][2]) {
  int32_t da = 1, db = 0;
  if (b % 2 == 1) {
    da = a % 2 == 1 ? 1 : 0;
    db = a % 2 == 0 || shape == TLOD_PATTERN_QUAD ? 1 : -1;
  }
  ends[0][0] = (uint32_t)((int32_t)a - da), ends[0][1] = (uint32_t)((int32_t)b - db);
  ends[1][0] = (uint32_t)((int32_t)a + da), ends[1][1] = (uint32_t)((int32_t)b + db);
}

/* Appends the vertices level l adds (those not on the level-(l-1) grid), in
 * raster order: rows b ascending, then a ascending. */
static void insert_level(build_state* st, uint32_t level) {
  uint32_t n = 1u << level, s = 1u << (st->max_level - level);
  for (uint32_t b = 0; b <= n; ++b) {
    for (uint32_t a = 0; a <= row_end(st->shape, n, b); ++a) {
      if (((a | b) & 1u) == 0) continue; /* already there from level - 1 */
      uint32_t ends[2][2];
      split_edge(st->shape, a, b, ends);
      add_vertex(st, a * s, b * s, level, *map_slot(st, ends[0][0] * s, ends[0][1] * s),
                 *map_slot(st, ends[1][0] * s, ends[1][1] * s));
    }
  }
}

static uint32_t* emit(const build_state* st, uint32_t* out, uint32_t s, const uint32_t tri[3][2]) {
  for (int c = 0; c < 3; ++c)
    *out++ = *map_slot(st, tri[c][0] * s, tri[c][1] * s);
  return out;
}

/* Cells of level l, counter-clockwise in (u, v). Triangle cell (a, b): lower
 * (a,b) (a+1,b) (a,b+1), upper (a+1,b) (a+1,b+1) (a,b+1) where it fits.
 * Quad cell: split along (a,b)-(a+1,b+1). */
static void build_indices(const build_state* st, uint32_t level) {
  uint32_t n = 1u << level, s = 1u << (st->max_level - level);
  uint32_t* out = st->set->indices[level];
  for (uint32_t b = 0; b < n; ++b) {
    uint32_t cells = st->shape == TLOD_PATTERN_TRIANGLE ? n - b : n;
    for (uint32_t a = 0; a < cells; ++a) {
      if (st->shape == TLOD_PATTERN_TRIANGLE) {
        out = emit(st, out, s, (const uint32_t[3][2]){{a, b}, {a + 1, b}, {a, b + 1}});
        if (a + b + 2 <= n) out = emit(st, out, s, (const uint32_t[3][2]){{a + 1, b}, {a + 1, b + 1}, {a, b + 1}});
      } else {
        out = emit(st, out, s, (const uint32_t[3][2]){{a, b}, {a + 1, b}, {a + 1, b + 1}});
        out = emit(st, out, s, (const uint32_t[3][2]){{a, b}, {a + 1, b + 1}, {a, b + 1}});
      }
    }
  }
  assert(out == st->set->indices[level] + st->set->index_count[level]);
}

/* Finest-level edge rows; coarser levels subsample them, which is why the
 * patterns object keeps no fine map after creation. */
static void build_edges(const build_state* st) {
  uint32_t N = st->fine_n, cc = st->set->corner_count;
  for (uint32_t e = 0; e < cc; ++e) {
    const uint8_t* c0 = k_corners[st->shape][e];
    const uint8_t* c1 = k_corners[st->shape][(e + 1) % cc];
    uint32_t* row = st->set->edges + (size_t)e * (N + 1);
    for (uint32_t t = 0; t <= N; ++t) {
      /* c1 - c0 is -1, 0 or 1 per axis, so this walks the edge one fine step at a time. */
      uint32_t fa = c0[0] * N + t * c1[0] - t * c0[0];
      uint32_t fb = c0[1] * N + t * c1[1] - t * c0[1];
      row[t] = *map_slot(st, fa, fb);
    }
  }
}

static tlod_result alloc_set(build_state* st) {
  tlod_result r = TLOD_SUCCESS;
  _tlod_pattern_set* set = st->set;
  set->vertices = alloc_array(st->ctx, tlod_pattern_vertex_count(st->shape, st->max_level), sizeof(tlod_pattern_vertex),
                              "pattern vertices", &r);
  if (!set->vertices) return r;
  set->edges =
      alloc_array(st->ctx, (size_t)set->corner_count * (st->fine_n + 1), sizeof(uint32_t), "pattern edges", &r);
  if (!set->edges) return r;
  for (uint32_t l = 0; l <= st->max_level; ++l) {
    set->index_count[l] = 3 * tlod_pattern_triangle_count(st->shape, l);
    set->indices[l] = alloc_array(st->ctx, set->index_count[l], sizeof(uint32_t), "pattern indices", &r);
    if (!set->indices[l]) return r;
  }
  return r;
}

static tlod_result build_set(tlod_patterns* p, tlod_pattern_shape shape, uint32_t* map) {
  build_state st = {p->ctx, shape, p->max_level, 1u << p->max_level, map, &p->sets[shape]};
  st.set->corner_count = k_corner_count[shape];
  tlod_result r = alloc_set(&st);
  if (r != TLOD_SUCCESS) return r;
  insert_corners(&st);
  for (uint32_t l = 1; l <= p->max_level; ++l) {
    insert_level(&st, l);
    assert(st.set->vertex_count == tlod_pattern_vertex_count(shape, l));
  }
  for (uint32_t l = 0; l <= p->max_level; ++l)
    build_indices(&st, l);
  build_edges(&st);
  return TLOD_SUCCESS;
}

tlod_result tlod_patterns_create(tlod_context* ctx, const tlod_patterns_desc* desc, tlod_patterns** out) {
  if (out) *out = NULL;
  if (!ctx) return TLOD_ERROR_INVALID_ARGUMENT;
  if (!out) return tlod_context_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "tlod_patterns_create: out is NULL");
  uint32_t max_level = desc && desc->max_level ? desc->max_level : TLOD_DEFAULT_MAX_LEVEL;
  if (max_level > TLOD_MAX_LEVEL)
    return tlod_context_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT,
                             "tlod_patterns_create: max_level %u is above TLOD_MAX_LEVEL (%d)", max_level,
                             TLOD_MAX_LEVEL);

  tlod_result r = TLOD_SUCCESS;
  tlod_patterns* p = alloc_array(ctx, 1, sizeof *p, "patterns", &r);
  if (!p) return r;
  p->ctx = ctx;
  p->max_level = max_level;
  /* Scratch map shared by both shapes (the triangle uses the half a + b <= N). */
  size_t side = ((size_t)1 << max_level) + 1;
  uint32_t* map = alloc_array(ctx, side * side, sizeof *map, "pattern index map", &r);
  for (uint32_t s = 0; map && r == TLOD_SUCCESS && s < TLOD_PATTERN_SHAPE_NUM; ++s)
    r = build_set(p, (tlod_pattern_shape)s, map);
  tlod_context_free(ctx, map);
  if (r == TLOD_SUCCESS) r = _tlod_patterns_build_connections(p);
  if (r != TLOD_SUCCESS) {
    tlod_patterns_destroy(p);
    return r;
  }
  *out = p;
  return TLOD_SUCCESS;
}

void tlod_patterns_destroy(tlod_patterns* patterns) {
  if (!patterns) return;
  tlod_context* ctx = patterns->ctx;
  for (uint32_t s = 0; s < TLOD_PATTERN_SHAPE_NUM; ++s) {
    _tlod_pattern_set* set = &patterns->sets[s];
    tlod_context_free(ctx, set->vertices);
    tlod_context_free(ctx, set->edges);
    for (uint32_t l = 0; l <= TLOD_MAX_LEVEL; ++l)
      tlod_context_free(ctx, set->indices[l]);
  }
  _tlod_patterns_free_connections(patterns);
  tlod_context_free(ctx, patterns);
}

/* ------------------------------------------------------------------------ */
/* Queries                                                                  */
/* ------------------------------------------------------------------------ */

uint32_t tlod_patterns_max_level(const tlod_patterns* patterns) { return patterns ? patterns->max_level : 0; }

/* Core classifies grid points for tlod_surface_eval_grid(); pattern vertices
 * are such grid points, so there is one classification, core's. */
uint32_t tlod_pattern_vertex_kind(tlod_pattern_shape shape, uint32_t max_level, uint32_t i, uint32_t j,
                                  uint32_t* param) {
  if (!shape_valid(shape)) return TLOD_PATTERN_KIND_OFF;
  return tlod_grid_point_kind(shape == TLOD_PATTERN_TRIANGLE ? 3u : 4u, max_level, i, j, param);
}

const tlod_pattern_vertex* tlod_patterns_vertices(const tlod_patterns* patterns, tlod_pattern_shape shape,
                                                  uint32_t* count) {
  bool ok = patterns && shape_valid(shape);
  if (count) *count = ok ? patterns->sets[shape].vertex_count : 0;
  return ok ? patterns->sets[shape].vertices : NULL;
}

const uint32_t* tlod_patterns_indices(const tlod_patterns* patterns, tlod_pattern_shape shape, uint32_t level,
                                      uint32_t* index_count) {
  bool ok = patterns && shape_valid(shape) && level <= patterns->max_level;
  if (index_count) *index_count = ok ? patterns->sets[shape].index_count[level] : 0;
  return ok ? patterns->sets[shape].indices[level] : NULL;
}

/* Returns 0 (and writes nothing) for a bad shape, level or edge. */
uint32_t tlod_patterns_edge(const tlod_patterns* patterns, tlod_pattern_shape shape, uint32_t level, uint32_t edge,
                            uint32_t* out) {
  if (!patterns || !out || !shape_valid(shape) || level > patterns->max_level) return 0;
  const _tlod_pattern_set* set = &patterns->sets[shape];
  if (edge >= set->corner_count) return 0;
  uint32_t fine_n = 1u << patterns->max_level, n = 1u << level;
  uint32_t step = 1u << (patterns->max_level - level);
  const uint32_t* row = set->edges + (size_t)edge * (fine_n + 1);
  for (uint32_t t = 0; t <= n; ++t)
    out[t] = row[t * step];
  return n + 1;
}

/* Counts what the paper's argument is about: the vertex array(s) and the
 * index arrays. The small edge rows and the object itself are left out of
 * both figures. */
size_t tlod_patterns_memory(const tlod_patterns* patterns, size_t* separate_bytes) {
  size_t nested = 0, separate = 0;
  for (uint32_t s = 0; patterns && s < TLOD_PATTERN_SHAPE_NUM; ++s) {
    const _tlod_pattern_set* set = &patterns->sets[s];
    nested += (size_t)set->vertex_count * sizeof(tlod_pattern_vertex);
    for (uint32_t l = 0; l <= patterns->max_level; ++l) {
      size_t index_bytes = (size_t)set->index_count[l] * sizeof(uint32_t);
      nested += index_bytes;
      separate +=
          index_bytes + (size_t)tlod_pattern_vertex_count((tlod_pattern_shape)s, l) * sizeof(tlod_pattern_vertex);
    }
  }
  if (separate_bytes) *separate_bytes = separate;
  return nested;
}
