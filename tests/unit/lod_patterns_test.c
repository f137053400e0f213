/*
 * lod_patterns_test.c -- tests of the nested refinement patterns (tesslod/lod.h);
 * owned by the refinement-pattern code. Reads private state: none (public API only;
 * patterns_internal.h is not needed).
 *
 * This work is based on: Schwarz, Staginski, Stamminger 2006; Boubekeur &
 * Schlick 2005 (generic mesh refinement on GPU).
 *
 * Every geometric check is exact: grid coordinates are integers and the
 * floats involved are dyadic with few bits, so no tolerance is used.
 */
#include <stdint.h>
#include <time.h>

#include "tesslod/lod.h"
#include "test.h"
#include "test_context.h"

static const tlod_pattern_shape k_shapes[2] = {TLOD_PATTERN_TRIANGLE, TLOD_PATTERN_QUAD};
static const char* const k_shape_names[2] = {"triangle", "quad"};
/* Corners in unit coordinates, in the order lod.h names them. */
static const int k_corner_uv[2][4][2] = {
    {{1, 0}, {0, 1}, {0, 0}, {0, 0}}, /* i, j, k */
    {{0, 0}, {1, 0}, {1, 1}, {0, 1}},
};
static const uint32_t k_corner_count[2] = {3, 4};

/* ------------------------------------------------------------------------ */
/* Fixtures                                                                 */
/* ------------------------------------------------------------------------ */

static tlod_patterns* new_patterns(tlod_context* ctx, uint32_t max_level) {
  tlod_patterns* p = NULL;
  tlod_result r = tlod_patterns_create(ctx, &(tlod_patterns_desc){.max_level = max_level}, &p);
  return r == TLOD_SUCCESS ? p : NULL;
}

static double now_seconds(void) {
  struct timespec ts;
  timespec_get(&ts, TIME_UTC);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int compare_u64(const void* a, const void* b) {
  uint64_t x = *(const uint64_t*)a, y = *(const uint64_t*)b;
  return x < y ? -1 : x > y;
}

/* LSD radix sort, 16 bits a pass: qsort made the level-10 checks take
 * seconds under the sanitizers. */
static void sort_u64(uint64_t* keys, size_t count) {
  uint64_t* tmp = malloc(sizeof *tmp * (count ? count : 1));
  size_t* start = malloc(sizeof *start * 65536);
  for (int shift = 0; shift < 64; shift += 16) {
    memset(start, 0, sizeof *start * 65536);
    for (size_t k = 0; k < count; ++k)
      start[(keys[k] >> shift) & 0xFFFF]++;
    size_t sum = 0;
    for (size_t d = 0; d < 65536; ++d) {
      size_t c = start[d];
      start[d] = sum;
      sum += c;
    }
    for (size_t k = 0; k < count; ++k)
      tmp[start[(keys[k] >> shift) & 0xFFFF]++] = keys[k];
    memcpy(keys, tmp, sizeof *keys * count);
  }
  free(tmp);
  free(start);
}

static bool contains_u64(const uint64_t* sorted, size_t count, uint64_t key) {
  return bsearch(&key, sorted, count, sizeof key, compare_u64) != NULL;
}

static uint64_t undirected_key(uint32_t a, uint32_t b) { return a < b ? (uint64_t)a << 32 | b : (uint64_t)b << 32 | a; }

static uint64_t directed_key(uint32_t from, uint32_t to) { return (uint64_t)from << 32 | to; }

/* Vertex indices are < 1025^2 < 2^21, so a sorted triple packs in 63 bits. */
static uint64_t triangle_key(uint32_t a, uint32_t b, uint32_t c) {
  uint32_t t;
  if (a > b) t = a, a = b, b = t;
  if (b > c) t = b, b = c, c = t;
  if (a > b) t = a, a = b, b = t;
  return (uint64_t)a << 42 | (uint64_t)b << 21 | c;
}

/* Edges of one level's triangles, sorted: directed (from, to) or undirected. */
static uint64_t* sorted_edges(const uint32_t* idx, uint32_t index_count, bool directed) {
  uint64_t* keys = malloc(sizeof *keys * (index_count ? index_count : 1));
  for (uint32_t t = 0; t < index_count; t += 3)
    for (uint32_t c = 0; c < 3; ++c) {
      uint32_t a = idx[t + c], b = idx[t + (c + 1) % 3];
      keys[t + c] = directed ? directed_key(a, b) : undirected_key(a, b);
    }
  sort_u64(keys, index_count);
  return keys;
}

/* One level's edges, sorted both ways; shared by the checks of that level
 * and, as the coarser level, by the parent check of the next. */
typedef struct level_edges {
  uint64_t* directed;
  uint64_t* undirected;
  uint32_t count; /* = index count: 3 edges a triangle */
} level_edges;

static level_edges edges_of(const tlod_patterns* p, tlod_pattern_shape shape, uint32_t level) {
  level_edges e = {0};
  const uint32_t* idx = tlod_patterns_indices(p, shape, level, &e.count);
  e.directed = sorted_edges(idx, e.count, true);
  e.undirected = sorted_edges(idx, e.count, false);
  return e;
}

static void free_edges(level_edges* e) {
  free(e->directed);
  free(e->undirected);
  *e = (level_edges){0};
}

/* Twice the signed area in exact integer (fine) grid coordinates. */
static int64_t area2_grid(const tlod_pattern_vertex* a, const tlod_pattern_vertex* b, const tlod_pattern_vertex* c) {
  int64_t ux = (int64_t)b->i - a->i, uy = (int64_t)b->j - a->j;
  int64_t vx = (int64_t)c->i - a->i, vy = (int64_t)c->j - a->j;
  return ux * vy - uy * vx;
}

/* Twice the signed area in (u, v), from the float fields. */
static double area2_uv(const tlod_pattern_vertex* a, const tlod_pattern_vertex* b, const tlod_pattern_vertex* c) {
  double ux = (double)b->u - a->u, uy = (double)b->v - a->v;
  double vx = (double)c->u - a->u, vy = (double)c->v - a->v;
  return ux * vy - uy * vx;
}

/* ------------------------------------------------------------------------ */
/* Checks on one built patterns object                                      */
/* ------------------------------------------------------------------------ */

static void check_counts(const tlod_patterns* p, int s) {
  uint32_t max = tlod_patterns_max_level(p), vcount = 0;
  const tlod_pattern_vertex* v = tlod_patterns_vertices(p, k_shapes[s], &vcount);
  CHECK(v != NULL);
  CHECK_MSG(vcount == tlod_pattern_vertex_count(k_shapes[s], max), "%s: %u vertices", k_shape_names[s], vcount);
  for (uint32_t l = 0; l <= max; ++l) {
    uint32_t index_count = 0;
    const uint32_t* idx = tlod_patterns_indices(p, k_shapes[s], l, &index_count);
    CHECK(idx != NULL);
    CHECK_MSG(index_count == 3 * tlod_pattern_triangle_count(k_shapes[s], l), "%s level %u: %u indices",
              k_shape_names[s], l, index_count);
  }
}

/* Sorted by first level with exact prefix boundaries, corners first in
 * corner order, raster order inside a level, each grid point exactly once,
 * u and v exactly i / N and j / N, and every level-l index < count(l). */
static void check_vertex_order(const tlod_patterns* p, int s) {
  uint32_t max = tlod_patterns_max_level(p), N = 1u << max, count = 0;
  const tlod_pattern_vertex* v = tlod_patterns_vertices(p, k_shapes[s], &count);
  uint8_t* seen = calloc((size_t)(N + 1) * (N + 1), 1);
  for (uint32_t k = 0; k < count; ++k) {
    uint32_t l = v[k].level, step = N >> l;
    CHECK_MSG(l <= max && k < tlod_pattern_vertex_count(k_shapes[s], l) &&
                  (l == 0 || k >= tlod_pattern_vertex_count(k_shapes[s], l - 1)),
              "%s vertex %u: level %u outside its prefix", k_shape_names[s], k, l);
    CHECK_MSG(v[k].i % step == 0 && v[k].j % step == 0, "%s vertex %u not on the level-%u grid", k_shape_names[s], k,
              l);
    CHECK_MSG(l == 0 || v[k].i % (2 * step) != 0 || v[k].j % (2 * step) != 0,
              "%s vertex %u already on the level-%u grid", k_shape_names[s], k, l - 1);
    CHECK_MSG(s == 0 ? v[k].i + v[k].j <= N : v[k].i <= N && v[k].j <= N, "%s vertex %u outside", k_shape_names[s], k);
    CHECK_MSG(v[k].u == (float)v[k].i / (float)N && v[k].v == (float)v[k].j / (float)N,
              "%s vertex %u: (u, v) = (%.9g, %.9g)", k_shape_names[s], k, v[k].u, v[k].v);
    uint8_t* slot = &seen[(size_t)v[k].j * (N + 1) + v[k].i];
    CHECK_MSG(!*slot, "%s vertex %u: grid point (%u, %u) twice", k_shape_names[s], k, v[k].i, v[k].j);
    *slot = 1;
    if (k < k_corner_count[s]) {
      CHECK_MSG(l == 0 && v[k].i == k_corner_uv[s][k][0] * N && v[k].j == k_corner_uv[s][k][1] * N,
                "%s vertex %u is not corner %u", k_shape_names[s], k, k);
    } else if (k > 0 && v[k - 1].level == l) {
      uint64_t prev = (uint64_t)v[k - 1].j << 16 | v[k - 1].i, cur = (uint64_t)v[k].j << 16 | v[k].i;
      CHECK_MSG(prev < cur, "%s vertices %u, %u not in raster order", k_shape_names[s], k - 1, k);
    }
  }
  free(seen);
  for (uint32_t l = 0; l <= max; ++l) {
    uint32_t index_count = 0, limit = tlod_pattern_vertex_count(k_shapes[s], l);
    const uint32_t* idx = tlod_patterns_indices(p, k_shapes[s], l, &index_count);
    for (uint32_t t = 0; t < index_count; ++t)
      CHECK_MSG(idx[t] < limit, "%s level %u: index %u = %u >= %u", k_shape_names[s], l, t, idx[t], limit);
  }
}

/* Each vertex inserted at level l splits an edge of pattern l - 1: its
 * parents are level-(l-1) vertices joined by an edge of that pattern, in
 * (i, j) order, and its fine grid point is exactly their midpoint. Corners
 * (l == 0) have no parents. */
static void check_parents(const tlod_patterns* p, int s, uint32_t l, const level_edges* coarse_edges) {
  uint32_t count = 0;
  const tlod_pattern_vertex* v = tlod_patterns_vertices(p, k_shapes[s], &count);
  if (l == 0) {
    for (uint32_t k = 0; k < k_corner_count[s]; ++k)
      CHECK_MSG(v[k].parent[0] == UINT32_MAX && v[k].parent[1] == UINT32_MAX, "%s corner %u has parents",
                k_shape_names[s], k);
    return;
  }
  uint32_t coarse = tlod_pattern_vertex_count(k_shapes[s], l - 1);
  uint32_t bad = UINT32_MAX;
  for (uint32_t k = coarse; k < tlod_pattern_vertex_count(k_shapes[s], l) && bad == UINT32_MAX; ++k) {
    uint32_t p0 = v[k].parent[0], p1 = v[k].parent[1];
    bool ok = p0 < coarse && p1 < coarse &&
              contains_u64(coarse_edges->undirected, coarse_edges->count, undirected_key(p0, p1));
    ok = ok && v[p0].i + v[p1].i == 2u * v[k].i && v[p0].j + v[p1].j == 2u * v[k].j;
    ok = ok && (v[p0].i < v[p1].i || (v[p0].i == v[p1].i && v[p0].j < v[p1].j));
    if (!ok) bad = k;
  }
  CHECK_MSG(bad == UINT32_MAX, "%s level %u: vertex %u parents (%u, %u) wrong", k_shape_names[s], l, bad,
            v[bad].parent[0], v[bad].parent[1]);
}

static bool on_domain_boundary(int s, const tlod_pattern_vertex* a, uint32_t N) {
  if (s == 0) return a->i == 0 || a->j == 0 || a->i + a->j == N;
  return a->i == 0 || a->j == 0 || a->i == N || a->j == N;
}

/* Both ends on one side of the domain (not just each on some side). */
static bool boundary_edge_on_side(int s, const tlod_pattern_vertex* a, const tlod_pattern_vertex* b, uint32_t N) {
  if ((a->i == 0 && b->i == 0) || (a->j == 0 && b->j == 0)) return true;
  if (s == 0) return a->i + a->j == N && b->i + b->j == N;
  return (a->i == N && b->i == N) || (a->j == N && b->j == N);
}

static void check_edge_use(const tlod_patterns* p, int s, uint32_t l, const level_edges* level) {
  uint32_t N = 1u << tlod_patterns_max_level(p), count = 0, boundary = 0;
  const tlod_pattern_vertex* v = tlod_patterns_vertices(p, k_shapes[s], &count);
  const uint64_t *directed = level->directed, *edges = level->undirected;
  uint32_t index_count = level->count;
  bool twice_directed = false, over_used = false, off_side = false;
  for (uint32_t e = 1; e < index_count; ++e)
    twice_directed |= directed[e] == directed[e - 1];
  for (uint32_t e = 0; e < index_count;) {
    uint32_t run = 1;
    while (e + run < index_count && edges[e + run] == edges[e])
      ++run;
    over_used |= run > 2;
    if (run == 1) {
      const tlod_pattern_vertex *a = &v[edges[e] >> 32], *b = &v[edges[e] & 0xFFFFFFFFu];
      off_side |= !on_domain_boundary(s, a, N) || !boundary_edge_on_side(s, a, b, N);
      ++boundary;
    }
    e += run;
  }
  CHECK_MSG(!over_used, "%s level %u: an edge is used by more than 2 triangles", k_shape_names[s], l);
  CHECK_MSG(!twice_directed, "%s level %u: a directed edge is used twice (inconsistent winding)", k_shape_names[s], l);
  CHECK_MSG(!off_side, "%s level %u: a boundary edge is not on the domain boundary", k_shape_names[s], l);
  CHECK_MSG(boundary == k_corner_count[s] << l, "%s level %u: %u boundary edges", k_shape_names[s], l, boundary);
}

/* CCW with positive area, each triangle half a level-l cell, areas summing
 * to the domain, each edge used at most twice, boundary on the domain's. */
static void check_tiling(const tlod_patterns* p, int s, uint32_t l, const level_edges* edges) {
  uint32_t max = tlod_patterns_max_level(p), step = 1u << (max - l), count = 0, index_count = 0;
  const tlod_pattern_vertex* v = tlod_patterns_vertices(p, k_shapes[s], &count);
  const uint32_t* idx = tlod_patterns_indices(p, k_shapes[s], l, &index_count);
  double area = 0.0;
  for (uint32_t t = 0; t < index_count; t += 3) {
    const tlod_pattern_vertex *a = &v[idx[t]], *b = &v[idx[t + 1]], *c = &v[idx[t + 2]];
    double a2 = area2_uv(a, b, c);
    CHECK_MSG(a2 > 0.0, "%s level %u triangle %u: signed area %.9g", k_shape_names[s], l, t / 3, a2 / 2);
    CHECK_MSG(area2_grid(a, b, c) == (int64_t)step * step, "%s level %u triangle %u: not half a cell", k_shape_names[s],
              l, t / 3);
    area += a2 / 2;
  }
  CHECK_MSG(area == (s == 0 ? 0.5 : 1.0), "%s level %u: total area %.17g", k_shape_names[s], l, area);
  CALL(check_edge_use(p, s, l, edges));
}

static bool inside_closed(const tlod_pattern_vertex* a, const tlod_pattern_vertex* b, const tlod_pattern_vertex* c,
                          const tlod_pattern_vertex* x) {
  return area2_grid(a, b, x) >= 0 && area2_grid(b, c, x) >= 0 && area2_grid(c, a, x) >= 0;
}

/* Fine grid point -> vertex index, built from the vertex array alone. */
static uint32_t* grid_lookup(const tlod_pattern_vertex* v, uint32_t count, uint32_t N) {
  uint32_t* map = malloc(sizeof *map * (size_t)(N + 1) * (N + 1));
  for (size_t k = 0; k < (size_t)(N + 1) * (N + 1); ++k)
    map[k] = UINT32_MAX;
  for (uint32_t k = 0; k < count; ++k)
    map[(size_t)v[k].j * (N + 1) + v[k].i] = k;
  return map;
}

typedef struct nesting_level {
  const tlod_pattern_vertex* v;
  const uint32_t* map; /* grid_lookup */
  uint32_t N;
  uint64_t* child_keys; /* sorted triangle keys of level l + 1 */
  uint32_t child_count;
  uint8_t* claimed; /* per child key */
} nesting_level;

static uint32_t midpoint(const nesting_level* n, uint32_t a, uint32_t b) {
  const tlod_pattern_vertex *x = &n->v[a], *y = &n->v[b];
  if ((x->i + y->i) % 2 || (x->j + y->j) % 2) return UINT32_MAX;
  return n->map[(size_t)((x->j + y->j) / 2) * (n->N + 1) + (x->i + y->i) / 2];
}

/* Claims the level-(l+1) triangle (a, b, c); false if it is missing or
 * already claimed by another parent. */
static bool claim_child(nesting_level* n, uint32_t a, uint32_t b, uint32_t c) {
  uint64_t key = triangle_key(a, b, c);
  uint64_t* hit = bsearch(&key, n->child_keys, n->child_count, sizeof key, compare_u64);
  if (!hit || n->claimed[hit - n->child_keys]) return false;
  n->claimed[hit - n->child_keys] = 1;
  return true;
}

/* Level-l triangle t is exactly the union of its 4 level-(l+1) children:
 * all 4 split triangles exist at level l + 1 (claimed once each), their
 * vertices lie in the closed parent, and their areas add up to the parent's. */
static void check_one_parent(nesting_level* n, const uint32_t* tri, uint32_t l, uint32_t t) {
  uint32_t m01 = midpoint(n, tri[0], tri[1]), m12 = midpoint(n, tri[1], tri[2]), m20 = midpoint(n, tri[2], tri[0]);
  CHECK_MSG(m01 != UINT32_MAX && m12 != UINT32_MAX && m20 != UINT32_MAX, "level %u triangle %u: midpoint missing", l,
            t);
  const uint32_t kids[4][3] = {{tri[0], m01, m20}, {m01, tri[1], m12}, {m20, m12, tri[2]}, {m01, m12, m20}};
  const tlod_pattern_vertex *a = &n->v[tri[0]], *b = &n->v[tri[1]], *c = &n->v[tri[2]];
  int64_t area = 0;
  for (int k = 0; k < 4; ++k) {
    CHECK_MSG(claim_child(n, kids[k][0], kids[k][1], kids[k][2]), "level %u triangle %u: child %d missing or shared", l,
              t, k);
    for (int q = 0; q < 3; ++q)
      CHECK_MSG(inside_closed(a, b, c, &n->v[kids[k][q]]), "level %u triangle %u: child %d outside", l, t, k);
    area += area2_grid(&n->v[kids[k][0]], &n->v[kids[k][1]], &n->v[kids[k][2]]);
  }
  CHECK_MSG(area == area2_grid(a, b, c), "level %u triangle %u: children area %lld", l, t, (long long)area);
}

static void check_nesting(const tlod_patterns* p, int s, uint32_t l) {
  uint32_t count = 0, coarse_count = 0, fine_count = 0, N = 1u << tlod_patterns_max_level(p);
  nesting_level n = {.v = tlod_patterns_vertices(p, k_shapes[s], &count), .N = N};
  const uint32_t* coarse = tlod_patterns_indices(p, k_shapes[s], l, &coarse_count);
  const uint32_t* fine = tlod_patterns_indices(p, k_shapes[s], l + 1, &fine_count);
  CHECK_MSG(fine_count == 4 * coarse_count, "%s level %u -> %u: %u vs %u indices", k_shape_names[s], l, l + 1,
            coarse_count, fine_count);
  uint32_t* map = grid_lookup(n.v, count, N);
  n.map = map;
  n.child_count = fine_count / 3;
  n.child_keys = malloc(sizeof *n.child_keys * n.child_count);
  n.claimed = calloc(n.child_count, 1);
  for (uint32_t t = 0; t < n.child_count; ++t)
    n.child_keys[t] = triangle_key(fine[3 * t], fine[3 * t + 1], fine[3 * t + 2]);
  sort_u64(n.child_keys, n.child_count);
  int before = _test_checks_failed;
  for (uint32_t t = 0; t < coarse_count / 3 && _test_checks_failed == before; ++t)
    check_one_parent(&n, coarse + 3 * t, l, t);
  free(map);
  free(n.child_keys);
  free(n.claimed);
}

/* Parameter of a point along edge e, in units of 1/N (0 at corner e). */
static uint32_t edge_parameter(int s, uint32_t e, const tlod_pattern_vertex* x, uint32_t N) {
  if (s == 0) return e == 0 ? x->j : e == 1 ? N - x->j : x->i;
  return e == 0 ? x->i : e == 1 ? x->j : e == 2 ? N - x->i : N - x->j;
}

/* Exactly on the edge in float: barycentric 0 (u, v or u + v == 1), quad coordinate 0 or 1. */
static bool on_edge_float(int s, uint32_t e, const tlod_pattern_vertex* x) {
  if (s == 0) return e == 0 ? x->u + x->v == 1.0f : e == 1 ? x->u == 0.0f : x->v == 0.0f;
  return e == 0 ? x->v == 0.0f : e == 1 ? x->u == 1.0f : e == 2 ? x->v == 1.0f : x->u == 0.0f;
}

/* Problem with one edge polyline: 0 none, 1 count, 2 ends, 3 a point. */
static int edge_problem(const tlod_patterns* p, int s, uint32_t l, uint32_t e, const uint64_t* directed,
                        uint32_t index_count, uint32_t* buf, uint32_t* bad) {
  uint32_t N = 1u << tlod_patterns_max_level(p), n = 1u << l, count = 0;
  const tlod_pattern_vertex* v = tlod_patterns_vertices(p, k_shapes[s], &count);
  const int* c0 = k_corner_uv[s][e];
  const int* c1 = k_corner_uv[s][(e + 1) % k_corner_count[s]];
  if (tlod_patterns_edge(p, k_shapes[s], l, e, buf) != n + 1) return 1;
  if (v[buf[0]].i != c0[0] * N || v[buf[0]].j != c0[1] * N || v[buf[n]].i != c1[0] * N || v[buf[n]].j != c1[1] * N)
    return 2;
  for (uint32_t t = 0; t <= n; ++t) {
    const tlod_pattern_vertex* x = &v[buf[t]];
    bool ok = buf[t] < tlod_pattern_vertex_count(k_shapes[s], l) && on_edge_float(s, e, x) &&
              edge_parameter(s, e, x, N) == t * (N >> l);
    if (t < n) ok = ok && contains_u64(directed, index_count, directed_key(buf[t], buf[t + 1]));
    if (!ok) return *bad = t, 3;
  }
  return 0;
}

/* Corner e to corner e + 1, 2^l + 1 points exactly on the edge at parameters
 * t / 2^l (so strictly monotone), every segment a directed edge of the
 * level-l triangles (the pattern lies to its left). */
static void check_edges(const tlod_patterns* p, int s, uint32_t l, const level_edges* edges, uint32_t* buf) {
  uint32_t bad = 0, e = 0;
  int problem = 0;
  for (; e < k_corner_count[s] && !problem; ++e)
    problem = edge_problem(p, s, l, e, edges->directed, edges->count, buf, &bad);
  CHECK_MSG(problem != 1, "%s level %u edge %u: wrong point count", k_shape_names[s], l, e - 1);
  CHECK_MSG(problem != 2, "%s level %u edge %u: does not run corner to corner", k_shape_names[s], l, e - 1);
  CHECK_MSG(problem != 3, "%s level %u edge %u: point %u wrong", k_shape_names[s], l, e - 1, bad);
  CHECK(tlod_patterns_edge(p, k_shapes[s], l, k_corner_count[s], buf) == 0);
}

/* Per-level checks of one shape for levels first..max (nesting from first
 * to first + 1 up). */
static void check_levels(const tlod_patterns* p, int s, uint32_t first, uint32_t* buf) {
  uint32_t max = tlod_patterns_max_level(p);
  level_edges coarse = first > 0 ? edges_of(p, k_shapes[s], first - 1) : (level_edges){0};
  int before = _test_checks_failed;
  for (uint32_t l = first; l <= max && _test_checks_failed == before; ++l) {
    level_edges edges = edges_of(p, k_shapes[s], l);
    check_parents(p, s, l, &coarse);
    if (_test_checks_failed == before) check_tiling(p, s, l, &edges);
    if (_test_checks_failed == before) check_edges(p, s, l, &edges, buf);
    if (_test_checks_failed == before && l < max) check_nesting(p, s, l);
    free_edges(&coarse);
    coarse = edges;
  }
  free_edges(&coarse);
}

/* All checks on both shapes: the whole-array ones, then the per-level ones. */
static void check_all(const tlod_patterns* p, uint32_t first) {
  uint32_t* buf = malloc(sizeof *buf * ((1u << tlod_patterns_max_level(p)) + 1));
  int before = _test_checks_failed;
  for (int s = 0; s < 2 && _test_checks_failed == before; ++s) {
    check_counts(p, s);
    if (_test_checks_failed == before) check_vertex_order(p, s);
    if (_test_checks_failed == before) check_levels(p, s, first, buf);
  }
  free(buf);
}

/* ------------------------------------------------------------------------ */
/* Tests                                                                    */
/* ------------------------------------------------------------------------ */

TEST(test_closed_formulas) {
  for (uint32_t l = 0; l <= TLOD_MAX_LEVEL; ++l) {
    uint64_t n = (uint64_t)1 << l;
    CHECK_MSG(tlod_pattern_vertex_count(TLOD_PATTERN_TRIANGLE, l) == (n + 1) * (n + 2) / 2, "level %u", l);
    CHECK_MSG(tlod_pattern_triangle_count(TLOD_PATTERN_TRIANGLE, l) == n * n, "level %u", l);
    CHECK_MSG(tlod_pattern_vertex_count(TLOD_PATTERN_QUAD, l) == (n + 1) * (n + 1), "level %u", l);
    CHECK_MSG(tlod_pattern_triangle_count(TLOD_PATTERN_QUAD, l) == 2 * n * n, "level %u", l);
  }
  /* Past the supported range the counts would overflow soon: 0. */
  CHECK(tlod_pattern_vertex_count(TLOD_PATTERN_QUAD, TLOD_MAX_LEVEL + 1) == 0);
  CHECK(tlod_pattern_triangle_count(TLOD_PATTERN_TRIANGLE, 32) == 0);
  CHECK(tlod_pattern_vertex_count(TLOD_PATTERN_SHAPE_NUM, 1) == 0);
}

TEST(test_default_level) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx != NULL);
  tlod_patterns* p = NULL;
  tlod_result r = tlod_patterns_create(ctx, NULL, &p);
  uint32_t max = tlod_patterns_max_level(p);
  tlod_patterns* q = new_patterns(ctx, 0);
  uint32_t max_q = tlod_patterns_max_level(q);
  tlod_patterns_destroy(p);
  tlod_patterns_destroy(q);
  tlod_context_destroy(ctx);
  CHECK(r == TLOD_SUCCESS && q != NULL);
  CHECK_MSG(max == TLOD_DEFAULT_MAX_LEVEL && max_q == TLOD_DEFAULT_MAX_LEVEL, "%u, %u", max, max_q);
}

/* The default max level (6), every check on every level. */
TEST(test_structure_level6) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  tlod_patterns* p = new_patterns(ctx, 6);
  CHECK(p != NULL);
  check_all(p, 0);
  tlod_patterns_destroy(p);
  tlod_context_destroy(ctx);
}

/* Levels 8 and 10 build fast. Every check runs on every level of 8; on 10
 * (1M quad vertices) the sort-based checks run on levels 9 and 10 only, to
 * keep the sanitizer build quick, and the linear ones on the whole array. */
static void build_and_check(uint32_t max_level, uint32_t first_checked) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  double t0 = now_seconds();
  tlod_patterns* p = new_patterns(ctx, max_level);
  double t1 = now_seconds();
  if (p) check_all(p, first_checked);
  double t2 = now_seconds();
  uint32_t count = 0;
  tlod_patterns_vertices(p, TLOD_PATTERN_QUAD, &count);
  printf("     max level %2u: built in %.3f s (quad: %u vertices), checked in %.3f s\n", max_level, t1 - t0, count,
         t2 - t1);
  tlod_patterns_destroy(p);
  tlod_context_destroy(ctx);
  CHECK_MSG(p != NULL, "max level %u did not build", max_level);
  CHECK(count == tlod_pattern_vertex_count(TLOD_PATTERN_QUAD, max_level));
}

TEST(test_levels_8_and_10) {
  CALL(build_and_check(8, 0));
  CALL(build_and_check(TLOD_MAX_LEVEL, TLOD_MAX_LEVEL - 1));
}

/* Nested = one max-level vertex array + all index arrays; separate = one
 * vertex array per level. Both shapes, from the closed formulas. */
static void expected_memory(uint32_t max, size_t* nested, size_t* separate) {
  *nested = *separate = 0;
  for (int s = 0; s < 2; ++s) {
    uint64_t vmax = (uint64_t)1 << max;
    *nested += (size_t)(s == 0 ? (vmax + 1) * (vmax + 2) / 2 : (vmax + 1) * (vmax + 1)) * sizeof(tlod_pattern_vertex);
    for (uint32_t l = 0; l <= max; ++l) {
      uint64_t n = (uint64_t)1 << l;
      size_t index_bytes = (size_t)(3 * (s == 0 ? n * n : 2 * n * n)) * sizeof(uint32_t);
      *nested += index_bytes;
      *separate +=
          index_bytes + (size_t)(s == 0 ? (n + 1) * (n + 2) / 2 : (n + 1) * (n + 1)) * sizeof(tlod_pattern_vertex);
    }
  }
}

TEST(test_memory) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  const uint32_t levels[2] = {6, 8};
  for (int k = 0; k < 2; ++k) {
    tlod_patterns* p = new_patterns(ctx, levels[k]);
    size_t separate = 0, nested = tlod_patterns_memory(p, &separate), want_nested, want_separate;
    tlod_patterns_destroy(p);
    expected_memory(levels[k], &want_nested, &want_separate);
    printf("     max level %u: nested %zu bytes, separate %zu bytes (%.1f%%; vertex %zu bytes)\n", levels[k], nested,
           separate, 100.0 * (double)nested / (double)separate, sizeof(tlod_pattern_vertex));
    CHECK_MSG(p != NULL, "max level %u", levels[k]);
    CHECK_MSG(nested == want_nested && separate == want_separate, "want %zu, %zu", want_nested, want_separate);
    CHECK(nested < separate);
  }
  tlod_context_destroy(ctx);
}

TEST(test_invalid_arguments) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  tlod_patterns* p = (tlod_patterns*)&p; /* must be reset to NULL */
  tlod_result r = tlod_patterns_create(ctx, &(tlod_patterns_desc){.max_level = TLOD_MAX_LEVEL + 1}, &p);
  char message[512];
  snprintf(message, sizeof message, "%s", tlod_context_last_error(ctx));
  tlod_result r_null_out = tlod_patterns_create(ctx, NULL, NULL);
  tlod_patterns* q = NULL;
  tlod_result r_null_ctx = tlod_patterns_create(NULL, NULL, &q);
  tlod_context_destroy(ctx);
  CHECK_MSG(r == TLOD_ERROR_INVALID_ARGUMENT, "%d", (int)r);
  CHECK(p == NULL);
  CHECK_MSG(strstr(message, "11") != NULL, "message \"%s\" should name the level", message);
  CHECK(r_null_out == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(r_null_ctx == TLOD_ERROR_INVALID_ARGUMENT && q == NULL);
}

TEST(test_queries_reject_bad_input) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  tlod_patterns* p = new_patterns(ctx, 2);
  uint32_t count = 99, buf[8];
  const void* bad_shape = tlod_patterns_vertices(p, TLOD_PATTERN_SHAPE_NUM, &count);
  uint32_t bad_shape_count = count;
  const void* bad_level = tlod_patterns_indices(p, TLOD_PATTERN_QUAD, 3, &count);
  uint32_t bad_level_count = count;
  uint32_t edge_bad_level = tlod_patterns_edge(p, TLOD_PATTERN_QUAD, 3, 0, buf);
  uint32_t edge_bad_edge = tlod_patterns_edge(p, TLOD_PATTERN_TRIANGLE, 1, 3, buf);
  uint32_t edge_null_out = tlod_patterns_edge(p, TLOD_PATTERN_TRIANGLE, 1, 0, NULL);
  tlod_patterns_destroy(p);
  tlod_patterns_destroy(NULL);
  tlod_context_destroy(ctx);
  CHECK(p != NULL);
  CHECK(bad_shape == NULL && bad_shape_count == 0);
  CHECK(bad_level == NULL && bad_level_count == 0);
  CHECK(edge_bad_level == 0 && edge_bad_edge == 0 && edge_null_out == 0);
  CHECK(tlod_patterns_max_level(NULL) == 0 && tlod_patterns_vertices(NULL, TLOD_PATTERN_TRIANGLE, NULL) == NULL);
}

/* Two builds are bytewise identical (deterministic order, zeroed padding). */
TEST(test_deterministic) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  tlod_patterns* a = new_patterns(ctx, 5);
  tlod_patterns* b = new_patterns(ctx, 5);
  bool same = a && b;
  for (int s = 0; s < 2 && same; ++s) {
    uint32_t na = 0, nb = 0;
    const tlod_pattern_vertex* va = tlod_patterns_vertices(a, k_shapes[s], &na);
    const tlod_pattern_vertex* vb = tlod_patterns_vertices(b, k_shapes[s], &nb);
    same = na == nb && memcmp(va, vb, sizeof *va * na) == 0;
    for (uint32_t l = 0; l <= 5 && same; ++l) {
      const uint32_t* ia = tlod_patterns_indices(a, k_shapes[s], l, &na);
      const uint32_t* ib = tlod_patterns_indices(b, k_shapes[s], l, &nb);
      same = na == nb && memcmp(ia, ib, sizeof *ia * na) == 0;
    }
  }
  tlod_patterns_destroy(a);
  tlod_patterns_destroy(b);
  tlod_context_destroy(ctx);
  CHECK(same);
}

/* Fails the k-th allocation of tlod_patterns_create for every k until it
 * succeeds: each failure reports OUT_OF_MEMORY, returns NULL and frees all. */
static void check_failing_allocator(uint32_t max_level) {
  counting_allocator counter = {.fail_at = -1};
  tlod_context* ctx = new_context(1, &counter, NULL);
  CHECK(ctx != NULL);
  long live = counter.allocs - counter.frees, k = 0;
  tlod_patterns* p = NULL;
  for (; k < 1000; ++k) {
    counter.fail_at = counter.calls + k;
    tlod_result r = tlod_patterns_create(ctx, &(tlod_patterns_desc){.max_level = max_level}, &p);
    if (r == TLOD_SUCCESS) break;
    bool ok = r == TLOD_ERROR_OUT_OF_MEMORY && p == NULL && counter.allocs - counter.frees == live &&
              tlod_context_last_error(ctx)[0] != '\0';
    if (!ok) tlod_context_destroy(ctx);
    CHECK_MSG(ok, "max level %u, allocation %ld: result %d, %ld blocks leaked", max_level, k, (int)r,
              counter.allocs - counter.frees - live);
  }
  counter.fail_at = -1;
  tlod_patterns_destroy(p);
  tlod_context_destroy(ctx);
  printf("     max level %u: %ld allocation failure points, all clean\n", max_level, k);
  CHECK_MSG(p != NULL && k > 0, "never succeeded (k = %ld)", k);
  CHECK_MSG(counter.allocs == counter.frees, "%ld allocs, %ld frees", counter.allocs, counter.frees);
}

TEST(test_failing_allocator) {
  CALL(check_failing_allocator(0));
  CALL(check_failing_allocator(3));
}

/* Everything goes through the context's allocator. */
TEST(test_uses_context_allocator) {
  counting_allocator counter = {.fail_at = -1};
  tlod_context* ctx = new_context(1, &counter, NULL);
  long before = counter.allocs;
  tlod_patterns* p = new_patterns(ctx, 4);
  long during = counter.allocs - before;
  tlod_patterns_destroy(p);
  tlod_context_destroy(ctx);
  CHECK(p != NULL);
  CHECK_MSG(during > 0, "no allocation went through the context allocator");
  CHECK_MSG(counter.allocs == counter.frees, "%ld allocs, %ld frees", counter.allocs, counter.frees);
}

int main(void) {
  RUN(test_closed_formulas);
  RUN(test_default_level);
  RUN(test_structure_level6);
  RUN(test_levels_8_and_10);
  RUN(test_memory);
  RUN(test_invalid_arguments);
  RUN(test_queries_reject_bad_input);
  RUN(test_deterministic);
  RUN(test_failing_allocator);
  RUN(test_uses_context_allocator);
  TEST_END();
}
