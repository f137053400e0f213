/* tesslod::core -- mesh welding and edge adjacency.
 * Owned by the mesh module (mesh.c, mesh_adjacency.c, mesh_attributes.c,
 * mesh_normals.c).
 *
 * Exact welding radix-sorts position hashes: O(n), and O(n log n) at worst
 * (positions sorted within a hash). Epsilon welding hashes grid cells of
 * the weld epsilon: expected O(n). Edges are bucketed by their smaller
 * welded end (a counting sort): O(n log n) at worst. Both give the same
 * result for the same input whatever the hash layout.
 *
 * This work is based on:
 *   T. Boubekeur, M. Alexa. Phong Tessellation. ACM TOG 27(5), 2008
 *   (patches agree along an edge when both sides share positions, normals
 *   and alphas: the smooth flag).
 *   G. Thuermer, C. A. Wuethrich. Computing vertex normals from polygonal
 *   facets. Journal of Graphics Tools 3(1), 1998.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

static uint64_t mix64(uint64_t x) {
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ULL;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebULL;
  x ^= x >> 31;
  return x;
}

/* Load factor at most 1/2 keeps linear probing short. */
static size_t table_capacity(size_t n) {
  size_t c = 16;
  while (c < 2 * n)
    c <<= 1;
  return c;
}

static tlod_result fail_oom(tlod_mesh* m, const char* what) {
  return _tlod_fail(m->ctx, TLOD_ERROR_OUT_OF_MEMORY, "mesh '%s': out of memory (%s)", m->label, what);
}

/* ------------------------------------------------------------------------ */
/* Welding                                                                  */
/* ------------------------------------------------------------------------ */

/* One representative vertex per welded position (the first seen, so the
 * smallest index). vertex_plus1 == 0 marks an empty slot. */
typedef struct weld_slot {
  uint32_t tag; /* high half of the hash: most mismatches end here */
  uint32_t vertex_plus1;
} weld_slot;

typedef struct weld_table {
  weld_slot* slots;
  size_t mask;
  double inv_cell; /* epsilon welding: 1 / cell size; 0 for exact welding */
  double eps;
} weld_table;

/* -0.0 and +0.0 must weld, so zero is hashed as +0.0. */
static uint64_t float_key(float x) {
  if (x == 0.0f) x = 0.0f;
  uint32_t u;
  memcpy(&u, &x, sizeof(u));
  return u;
}

static uint64_t exact_hash(const float p[3]) {
  return mix64(mix64(float_key(p[0]) | float_key(p[1]) << 32) ^ float_key(p[2]));
}

static uint64_t double_key(double x) {
  if (x == 0.0) x = 0.0;
  uint64_t u;
  memcpy(&u, &x, sizeof(u));
  return u;
}

static uint64_t cell_hash(const double c[3]) {
  return mix64(mix64(mix64(double_key(c[0])) ^ double_key(c[1])) ^ double_key(c[2]));
}

static void cell_of(const weld_table* t, const float p[3], double c[3]) {
  for (int i = 0; i < 3; i++)
    c[i] = floor((double)p[i] * t->inv_cell);
}

static void table_insert(weld_table* t, uint64_t hash, uint32_t v) {
  size_t i = (size_t)hash & t->mask;
  while (t->slots[i].vertex_plus1)
    i = (i + 1) & t->mask;
  t->slots[i] = (weld_slot){(uint32_t)(hash >> 32), v + 1};
}

static bool within_eps(const weld_table* t, const float* a, const float* b) {
  for (int i = 0; i < 3; i++)
    if (fabs((double)a[i] - (double)b[i]) > t->eps) return false;
  return true;
}

/* The smallest representative within eps of v (per coordinate), or NONE.
 * Cells are a little over 2 eps wide, so on each axis a match lies in v's
 * cell or the neighbour on the side of the cell half v is in: 8 cells to
 * look at. Several representatives may share a cell. */
static uint32_t eps_find(const weld_table* t, float (*pos)[3], uint32_t v) {
  double c[3], lo[3], n[3];
  for (int i = 0; i < 3; i++) {
    double x = (double)pos[v][i] * t->inv_cell;
    c[i] = floor(x);
    lo[i] = x - c[i] < 0.5 ? c[i] - 1.0 : c[i];
  }
  uint32_t best = _TLOD_NONE;
  for (int d = 0; d < 8; d++) {
    for (int i = 0; i < 3; i++)
      n[i] = lo[i] + ((d >> i) & 1);
    uint64_t h = cell_hash(n);
    uint32_t tag = (uint32_t)(h >> 32);
    for (size_t i = (size_t)h & t->mask; t->slots[i].vertex_plus1; i = (i + 1) & t->mask) {
      uint32_t r = t->slots[i].vertex_plus1 - 1;
      if (t->slots[i].tag == tag && r < best && within_eps(t, pos[r], pos[v])) best = r;
    }
  }
  return best;
}

static void weld_eps(weld_table* t, tlod_mesh* m) {
  for (uint32_t v = 0; v < m->vertex_count; v++) {
    double c[3];
    cell_of(t, m->positions[v], c);
    uint32_t rep = eps_find(t, m->positions, v);
    if (rep == _TLOD_NONE) {
      table_insert(t, cell_hash(c), v);
      rep = v;
    }
    m->weld_id[v] = rep;
  }
}

static tlod_result weld_by_cells(tlod_mesh* m) {
  size_t cap = table_capacity(m->vertex_count);
  /* A hair over 2 eps: two points within eps are then less than half a
   * cell apart despite rounding in the product (see eps_find). */
  weld_table t = {.mask = cap - 1, .eps = m->desc.weld_epsilon};
  t.inv_cell = 1.0 / (2.0 * t.eps * (1.0 + 1e-6));
  t.slots = _tlod_calloc(m->ctx, cap, sizeof(weld_slot));
  if (!t.slots) return fail_oom(m, "weld table");
  weld_eps(&t, m);
  _tlod_free(m->ctx, t.slots);
  return TLOD_SUCCESS;
}

/* Exact welding sorts (hash, vertex) keys instead of probing a table: the
 * table's probes were random loads in a table past the caches, the sort's
 * passes stream. A stable radix sort keeps each hash's vertices ascending,
 * so the first of a run with a position is its smallest index, as the
 * table's first-seen representative was: the same weld ids. */
typedef struct weld_key {
  uint32_t hash;
  uint32_t vertex;
} weld_key;

enum { RADIX_BITS = 11, RADIX = 1 << RADIX_BITS, RADIX_PASSES = 3 };

static void radix_pass(const weld_key* in, weld_key* out, uint32_t n, int shift) {
  uint32_t start[RADIX] = {0};
  for (uint32_t i = 0; i < n; i++)
    start[(in[i].hash >> shift) & (RADIX - 1)]++;
  for (uint32_t d = 0, total = 0; d < RADIX; d++) {
    uint32_t c = start[d];
    start[d] = total;
    total += c;
  }
  for (uint32_t i = 0; i < n; i++)
    out[start[(in[i].hash >> shift) & (RADIX - 1)]++] = in[i];
}

/* Sorted by hash, vertices ascending within a hash; *keys swaps with *tmp. */
static void sort_keys(weld_key** keys, weld_key** tmp, uint32_t n) {
  for (int p = 0; p < RADIX_PASSES; p++) {
    radix_pass(*keys, *tmp, n, p * RADIX_BITS);
    weld_key* x = *keys;
    *keys = *tmp, *tmp = x;
  }
}

/* Positions in lexicographic order; -0.0 and +0.0 tie (positions are
 * finite, so < is a total preorder). */
static int position_cmp(const tlod_mesh* m, weld_key a, weld_key b) {
  const float *p = m->positions[a.vertex], *q = m->positions[b.vertex];
  for (int c = 0; c < 3; c++)
    if (p[c] != q[c]) return p[c] < q[c] ? -1 : 1;
  return 0;
}

/* Stable: a's key first on a tie. */
static void merge_runs(const tlod_mesh* m, const weld_key* a, uint32_t na, const weld_key* b, uint32_t nb,
                       weld_key* out) {
  uint32_t i = 0, j = 0, k = 0;
  while (i < na && j < nb)
    out[k++] = position_cmp(m, b[j], a[i]) < 0 ? b[j++] : a[i++];
  while (i < na)
    out[k++] = a[i++];
  while (j < nb)
    out[k++] = b[j++];
}

/* A run of equal hashes (vertices ascending) sorted by position, stably, so
 * each position's vertices stay ascending: bottom-up merge sort through
 * scratch, O(n log n) however many distinct positions collide in a hash
 * (a crafted file gains nothing). */
static void sort_run(const tlod_mesh* m, weld_key* run, weld_key* scratch, uint32_t n) {
  weld_key *from = run, *to = scratch;
  for (size_t w = 1; w < n; w *= 2) { /* size_t: 2 w stays below SIZE_MAX (n keys fit in memory) */
    for (size_t lo = 0; lo < n; lo += 2 * w) {
      size_t mid = n - lo < w ? n : lo + w, hi = n - mid < w ? n : mid + w;
      merge_runs(m, from + lo, (uint32_t)(mid - lo), from + mid, (uint32_t)(hi - mid), to + lo);
    }
    weld_key* x = from;
    from = to, to = x;
  }
  if (from != run) memcpy(run, from, n * sizeof(*run));
}

/* Each vertex of a run takes the first vertex at its position: its
 * smallest index. */
static void weld_run(tlod_mesh* m, weld_key* run, weld_key* scratch, uint32_t n) {
  if (n > 1) sort_run(m, run, scratch, n);
  for (uint32_t i = 0, rep = 0; i < n; i++) {
    if (i == 0 || position_cmp(m, run[i - 1], run[i]) != 0) rep = run[i].vertex;
    m->weld_id[run[i].vertex] = rep;
  }
}

static tlod_result weld_by_sort(tlod_mesh* m) {
  uint32_t n = m->vertex_count;
  if (n == 0) return TLOD_SUCCESS;
  weld_key* keys = _tlod_alloc_array(m->ctx, n, sizeof(weld_key));
  weld_key* tmp = _tlod_alloc_array(m->ctx, n, sizeof(weld_key));
  if (!keys || !tmp) {
    _tlod_free(m->ctx, keys);
    _tlod_free(m->ctx, tmp);
    return fail_oom(m, "weld keys");
  }
  for (uint32_t v = 0; v < n; v++)
    keys[v] = (weld_key){(uint32_t)(exact_hash(m->positions[v]) >> 32), v};
  sort_keys(&keys, &tmp, n);
  for (uint32_t i = 0, j; i < n; i = j) {
    for (j = i + 1; j < n && keys[j].hash == keys[i].hash; j++) {
    }
    weld_run(m, keys + i, tmp + i, j - i);
  }
  _tlod_free(m->ctx, keys);
  _tlod_free(m->ctx, tmp);
  return TLOD_SUCCESS;
}

tlod_result _tlod_mesh_weld(tlod_mesh* m) {
  if (!m->weld_id) m->weld_id = _tlod_calloc(m->ctx, m->vertex_count, sizeof(uint32_t));
  if (!m->weld_id) return fail_oom(m, "weld ids");
  return m->desc.weld_epsilon > 0.0f ? weld_by_cells(m) : weld_by_sort(m);
}

/* ------------------------------------------------------------------------ */
/* Smooth flags                                                             */
/* ------------------------------------------------------------------------ */

static bool same_vertex_data(const tlod_mesh* m, uint32_t a, uint32_t b) {
  if (a == b) return true;
  if (memcmp(m->positions[a], m->positions[b], sizeof(m->positions[a])) != 0) return false;
  if (memcmp(m->normals[a], m->normals[b], sizeof(m->normals[a])) != 0) return false;
  return !m->alphas || memcmp(&m->alphas[a], &m->alphas[b], sizeof(float)) == 0;
}

static uint32_t edge_start(const tlod_mesh* m, uint32_t f, uint32_t e) { return m->faces[f][e]; }

/* A compare, not a modulo: a division per edge showed in the profile. */
static uint32_t edge_end(const tlod_mesh* m, uint32_t f, uint32_t e) {
  return m->faces[f][e + 1 < m->face_corners[f] ? e + 1 : 0];
}

/* Edge e of f meets edge ge of g in the opposite direction: smooth when
 * both sides evaluate the shared edge from bitwise equal data (corners, and
 * the edge's nodes after sharing). */
static bool edge_smooth(const tlod_mesh* m, uint32_t f, uint32_t e, uint32_t g, uint32_t ge) {
  return same_vertex_data(m, edge_start(m, f, e), edge_end(m, g, ge)) &&
         same_vertex_data(m, edge_end(m, f, e), edge_start(m, g, ge)) && _tlod_mesh_same_nodes(m, f, e, g, ge);
}

/* A smooth edge whose two sides carry different attribute values at a
 * corner: the geometry is shared, the attributes are not (a UV seam). */
static bool edge_seam(const tlod_mesh* m, uint32_t f, uint32_t e, uint32_t g, uint32_t ge) {
  return !_tlod_mesh_same_attributes(m, edge_start(m, f, e), edge_end(m, g, ge)) ||
         !_tlod_mesh_same_attributes(m, edge_end(m, f, e), edge_start(m, g, ge));
}

void _tlod_mesh_refresh_smooth(tlod_mesh* m) {
  uint32_t creases = 0, seams = 0;
  bool moved = false;
  for (uint32_t f = 0; f < m->face_count; f++)
    for (uint32_t e = 0; e < m->face_corners[f]; e++) {
      tlod_edge_link* l = &m->links[f][e];
      if (l->face == _TLOD_NONE) continue;
      bool smooth = edge_smooth(m, f, e, l->face, l->edge);
      moved |= smooth != l->smooth;
      l->smooth = smooth;
      l->seam = l->smooth && edge_seam(m, f, e, l->face, l->edge);
      creases += !l->smooth && f < l->face; /* each edge once */
      seams += l->seam && f < l->face;
    }
  m->info.crease_edges = creases;
  m->info.attribute_seam_edges = seams;
  m->smooth_generation += moved;
}

/* ------------------------------------------------------------------------ */
/* Edges                                                                    */
/* ------------------------------------------------------------------------ */

/* A half-edge in the bucket of its smaller welded end: the larger end and
 * its slot face * 4 + edge. */
typedef struct half_edge {
  uint32_t hi;
  uint32_t slot;
} half_edge;

/* Half-edges grouped by smaller welded end (a counting sort), each bucket
 * then sorted by (hi, slot): runs of equal hi are the welded edges, with
 * their half-edges in face order. O(n) plus O(b log b) per bucket, so even
 * a fan around one vertex stays O(n log n); memory is 8 bytes a half-edge. */
typedef struct edge_buckets {
  uint32_t* first; /* bucket w: half[first[w] .. first[w + 1]) */
  half_edge* half;
} edge_buckets;

/* The smaller and larger welded ends of face f's edges; returns their
 * count. Each corner's weld id is loaded once, not twice per edge. */
static uint32_t face_edge_ends(const tlod_mesh* m, uint32_t f, uint32_t lo[4], uint32_t hi[4]) {
  uint32_t k = m->face_corners[f], w[4];
  for (uint32_t i = 0; i < k; i++)
    w[i] = m->weld_id[m->faces[f][i]];
  for (uint32_t e = 0; e < k; e++) {
    uint32_t a = w[e], b = w[e + 1 < k ? e + 1 : 0];
    lo[e] = a < b ? a : b;
    hi[e] = a < b ? b : a;
  }
  return k;
}

static uint64_t half_edge_key(half_edge h) { return (uint64_t)h.hi << 32 | h.slot; }

static int half_edge_cmp(const void* pa, const void* pb) {
  uint64_t a = half_edge_key(*(const half_edge*)pa), b = half_edge_key(*(const half_edge*)pb);
  return a < b ? -1 : (a > b);
}

/* Buckets are a few half-edges on ordinary meshes: insertion sort on the
 * (hi, slot) key; qsort only for large ones. Either way: deterministic. */
static void sort_bucket(half_edge* h, uint32_t n) {
  if (n > 32) {
    qsort(h, n, sizeof(*h), half_edge_cmp);
    return;
  }
  for (uint32_t i = 1; i < n; i++) {
    half_edge x = h[i];
    uint64_t kx = half_edge_key(x);
    uint32_t j = i;
    for (; j > 0 && half_edge_key(h[j - 1]) > kx; j--)
      h[j] = h[j - 1];
    h[j] = x;
  }
}

/* Each half-edge's welded ends, in face order, are kept between the count
 * and fill passes in the links' memory (8 bytes a slot, 3-4 slots a face:
 * room for every half-edge), which is filled with links afterwards: the
 * fill pass reads them in order instead of the weld ids again. */
_Static_assert(sizeof(tlod_edge_link) >= 2 * sizeof(uint32_t), "a link slot holds a half-edge's two ends");

static uint32_t count_ends(tlod_mesh* m, edge_buckets* b) {
  uint32_t(*ends)[2] = (uint32_t(*)[2])(void*)m->links, h = 0, lo[4], hi[4];
  for (uint32_t f = 0; f < m->face_count; f++)
    for (uint32_t e = 0, k = face_edge_ends(m, f, lo, hi); e < k; e++, h++) {
      ends[h][0] = lo[e], ends[h][1] = hi[e];
      b->first[lo[e]]++;
    }
  return h;
}

static void fill_buckets(tlod_mesh* m, edge_buckets* b, uint32_t h) {
  const uint32_t(*ends)[2] = (const uint32_t(*)[2])(void*)m->links;
  for (uint32_t f = m->face_count; f-- > 0;)
    for (uint32_t e = m->face_corners[f]; e-- > 0;) {
      h--;
      b->half[--b->first[ends[h][0]]] = (half_edge){ends[h][1], f * 4 + e};
    }
}

static tlod_result buckets_build(tlod_mesh* m, edge_buckets* b) {
  const tlod_context* ctx = m->ctx;
  size_t half = (size_t)m->info.triangle_count * 3 + (size_t)m->info.quad_count * 4;
  b->first = _tlod_calloc(ctx, (size_t)m->vertex_count + 1, sizeof(uint32_t));
  b->half = _tlod_alloc_array(ctx, half, sizeof(half_edge)); /* every slot is filled below */
  if (!b->first || !b->half) {
    _tlod_free(ctx, b->first);
    _tlod_free(ctx, b->half);
    return fail_oom(m, "edge buckets");
  }
  uint32_t h = count_ends(m, b), total = 0;
  for (uint32_t w = 0; w < m->vertex_count; w++) {
    total += b->first[w];
    b->first[w] = total; /* end of bucket w; filled backwards to its start */
  }
  b->first[m->vertex_count] = total;
  fill_buckets(m, b, h);
  for (uint32_t w = 0; w < m->vertex_count; w++)
    sort_bucket(b->half + b->first[w], b->first[w + 1] - b->first[w]);
  return TLOD_SUCCESS;
}

static void note_boundary(tlod_mesh* m, uint32_t slot) {
  uint32_t f = slot / 4, e = slot % 4;
  m->info.boundary_edges++;
  _tlod_mesh_add_finding(m, TLOD_FINDING_BOUNDARY_EDGE, m->face_input[f], e,
                         "face %u edge %u (vertices %u, %u): boundary", m->face_input[f], e, edge_start(m, f, e),
                         edge_end(m, f, e));
}

static void note_non_manifold(tlod_mesh* m, uint32_t slot, uint32_t faces, uint32_t other) {
  uint32_t f = slot / 4, e = slot % 4;
  m->info.non_manifold_edges++;
  if (faces > 2)
    _tlod_mesh_add_finding(m, TLOD_FINDING_NON_MANIFOLD_EDGE, m->face_input[f], e,
                           "face %u edge %u (vertices %u, %u): shared by %u faces", m->face_input[f], e,
                           edge_start(m, f, e), edge_end(m, f, e), faces);
  else
    _tlod_mesh_add_finding(m, TLOD_FINDING_NON_MANIFOLD_EDGE, m->face_input[f], e,
                           "face %u edge %u: same direction in face %u (orientation flips)", m->face_input[f], e,
                           m->face_input[other / 4]);
}

/* Two half-edges: manifold when they run in opposite directions. */
static void link_pair(tlod_mesh* m, uint32_t s, uint32_t t) {
  uint32_t f = s / 4, e = s % 4, g = t / 4, ge = t % 4;
  if (m->weld_id[edge_start(m, f, e)] == m->weld_id[edge_start(m, g, ge)]) {
    note_non_manifold(m, s, 2, t);
    return;
  }
  bool smooth = edge_smooth(m, f, e, g, ge);
  bool seam = smooth && edge_seam(m, f, e, g, ge);
  m->links[f][e] = (tlod_edge_link){.face = g, .edge = (uint8_t)ge, .smooth = smooth, .seam = seam};
  m->links[g][ge] = (tlod_edge_link){.face = f, .edge = (uint8_t)e, .smooth = smooth, .seam = seam};
  m->info.crease_edges += !smooth;
  m->info.attribute_seam_edges += seam;
}

/* Edges in (smaller, larger welded end) order, so findings are too. */
static void classify_edges(tlod_mesh* m, const edge_buckets* b) {
  uint32_t edges = 0;
  for (uint32_t w = 0; w < m->vertex_count; w++) {
    const half_edge* h = b->half + b->first[w];
    uint32_t n = b->first[w + 1] - b->first[w];
    for (uint32_t i = 0, j; i < n; i = j) {
      for (j = i + 1; j < n && h[j].hi == h[i].hi; j++) {
      }
      if (j - i == 1)
        note_boundary(m, h[i].slot);
      else if (j - i == 2)
        link_pair(m, h[i].slot, h[i + 1].slot);
      else
        note_non_manifold(m, h[i].slot, j - i, _TLOD_NONE);
      edges++;
    }
  }
  m->info.edge_count = edges;
  m->info.closed = m->info.boundary_edges == 0 && m->info.non_manifold_edges == 0;
}

tlod_result _tlod_mesh_build_adjacency(tlod_mesh* m) {
  tlod_result r = m->weld_id ? TLOD_SUCCESS : _tlod_mesh_weld(m);
  if (r != TLOD_SUCCESS) return r;
  if (!m->links) m->links = _tlod_calloc(m->ctx, m->face_count, sizeof(*m->links));
  if (!m->links) return fail_oom(m, "edge links");
  edge_buckets b;
  r = buckets_build(m, &b); /* uses the links' memory as scratch */
  if (r != TLOD_SUCCESS) return r;
  /* Boundary, non-manifold and a triangle's unused fourth slot: no link. */
  for (uint32_t f = 0; f < m->face_count; f++)
    for (uint32_t e = 0; e < 4; e++)
      m->links[f][e] = (tlod_edge_link){.face = _TLOD_NONE, .edge = UINT8_MAX, .smooth = false, .seam = false};
  m->info.boundary_edges = m->info.non_manifold_edges = m->info.crease_edges = 0;
  m->info.attribute_seam_edges = 0;
  classify_edges(m, &b);
  _tlod_free(m->ctx, b.first);
  _tlod_free(m->ctx, b.half);
  /* The links give each node-less edge its neighbour's node; the smooth
   * flags then compare the shared nodes. */
  if (m->face_nodes) {
    _tlod_mesh_share_nodes(m);
    _tlod_mesh_refresh_smooth(m);
  }
  return TLOD_SUCCESS;
}
