/* tesslod::core -- computed vertex normals, with creases.
 * Owned by the mesh module (mesh.c, mesh_adjacency.c, mesh_attributes.c,
 * mesh_normals.c).
 *
 * A vertex normal is the weighted sum of the unit normals of the faces
 * around its welded position (so UV-seam duplicates get one normal),
 * weighted by the corner angle (Thuermer & Wuethrich; the Phong
 * tessellation paper's choice) or by face area. Sums run in face order, in
 * double, so equal inputs give bitwise equal normals.
 *
 * Curved faces (a given mid-edge node on an edge at the corner) use per
 * corner the tangents of the quadratic edges there, dQ/dt(0) = 4 M - 3 P_i
 * - P_j, for the corner's normal and angle: the true normal of the
 * quadratic face at its corner. Edges without a given node stay flat (a
 * Phong node comes from the normals and must not feed back).
 *
 * Creases (crease_angle_deg > 0): each face corner sums only the faces
 * around its position whose corner normal is within the crease angle of its
 * own. One input vertex can then need several normals; at creation the
 * corners of a vertex are grouped by their (bitwise) normal and each group
 * past the first gets a new vertex, appended after the input ones, with the
 * source's position and alpha. Later recomputations (tlod_mesh_update) keep
 * that split; a vertex whose corners then disagree gets their mean.
 *
 * This work is based on:
 *   T. Boubekeur, M. Alexa. Phong Tessellation. ACM TOG 27(5), 2008
 *   (angle-weighted vertex normals).
 *   G. Thuermer, C. A. Wuethrich. Computing vertex normals from polygonal
 *   facets. Journal of Graphics Tools 3(1), 1998.
 */
#include <math.h>
#include <string.h>

#include "internal.h"

#define PI_D 3.14159265358979323846

/* Everything a computation with creases needs, allocated up front so that a computation
 * that fails has not written a normal yet. */
typedef struct normal_job {
  tlod_mesh* m;
  bool area;             /* face area weights, else corner angles */
  double cos_crease;     /* corners with dot(n_f, n_g) >= this are on the same side */
  double (*corner_n)[3]; /* per corner slot: unit normal, zero when there is none */
  double* weight;        /* per corner slot face * 4 + corner */
  uint32_t* w_first;     /* corner slots of welded position w: w_slots[w_first[w] .. w_first[w+1]) */
  uint32_t* w_slots;     /* in face order */
  uint8_t* state;        /* 0 no corner seen, 1 corners agree, 2 they differ */
  double (*mean)[3];     /* sum of the unit corner normals of a vertex */
} normal_job;

/* Node-only vertices (no corner of any face) never get a computed normal. */
static bool wants_normal(const tlod_mesh* m, uint32_t v) {
  if (_tlod_mesh_is_node_only(m, v)) return false;
  return m->normal_computed[v] || m->desc.normal_mode == TLOD_NORMALS_ANGLE || m->desc.normal_mode == TLOD_NORMALS_AREA;
}

/* ------------------------------------------------------------------------ */
/* Face geometry                                                            */
/* ------------------------------------------------------------------------ */

static void sub3(const float* a, const float* b, double out[3]) {
  for (int i = 0; i < 3; i++)
    out[i] = (double)a[i] - (double)b[i];
}

static void cross3(const double a[3], const double b[3], double out[3]) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static double length3(const double a[3]) { return sqrt(dot3(a, a)); }

static bool node_given(const tlod_mesh* m, uint32_t f, uint32_t slot) {
  return m->node_given && ((uint32_t)m->node_given[f] >> slot & 1u);
}

/* Tangent at corner i of face f towards corner to, along the edge with
 * node slot s: the quadratic edge's dQ/dt(0) when the node is given, else
 * the flat edge. Shared nodes are not used: they are resolved with the
 * adjacency, after the normals, and the result must not depend on that. */
static void edge_tangent(const tlod_mesh* m, uint32_t f, uint32_t i, uint32_t to, uint32_t s, double out[3]) {
  const float* p = m->positions[m->faces[f][i]];
  const float* q = m->positions[m->faces[f][to]];
  if (!node_given(m, f, s)) {
    sub3(q, p, out);
    return;
  }
  const float* n = m->positions[m->face_nodes[f][s]];
  for (int c = 0; c < 3; c++)
    out[c] = 4.0 * (double)n[c] - 3.0 * (double)p[c] - (double)q[c];
}

/* a towards the next corner, b towards the previous one. */
static void corner_tangents(const tlod_mesh* m, uint32_t f, uint32_t i, double a[3], double b[3]) {
  uint32_t k = m->face_corners[f], prev = (i + k - 1) % k;
  edge_tangent(m, f, i, (i + 1) % k, i, a);
  edge_tangent(m, f, i, prev, prev, b);
}

/* A face with a given node on some edge has curved corners. */
static bool curved_face(const tlod_mesh* m, uint32_t f) {
  return m->node_given && (m->node_given[f] & ((1u << m->face_corners[f]) - 1u)) != 0;
}

/* Twice the area vector, and its length. Quads: the cross product of the diagonals (exact
 * for planar quads); when the diagonals are parallel (a folded quad) the
 * two triangles' sum stands in. */
static double face_cross(float (*p)[3], const uint32_t* c, uint32_t k, double out[3]) {
  double a[3], b[3];
  if (k == 4) {
    sub3(p[c[2]], p[c[0]], a);
    sub3(p[c[3]], p[c[1]], b);
    cross3(a, b, out);
    double len = length3(out);
    if (len > 1e-12 * (dot3(a, a) + dot3(b, b))) return len;
    double t[3];
    sub3(p[c[1]], p[c[0]], a);
    sub3(p[c[2]], p[c[0]], b);
    cross3(a, b, out);
    sub3(p[c[3]], p[c[0]], a);
    cross3(b, a, t);
    for (int i = 0; i < 3; i++)
      out[i] += t[i];
    return length3(out);
  }
  sub3(p[c[1]], p[c[0]], a);
  sub3(p[c[2]], p[c[0]], b);
  cross3(a, b, out);
  return length3(out);
}

/* x / len (one division), len = |x|; zero when x is. */
static void unit3_len(const double x[3], double len, double out[3]) {
  double inv = len > 0.0 ? 1.0 / len : 0.0;
  for (int i = 0; i < 3; i++)
    out[i] = x[i] * inv;
}

static void unit3(const double x[3], double out[3]) { unit3_len(x, length3(x), out); }

/* The unit normal of face f (zero when degenerate); returns twice its area. */
static double face_normal(const tlod_mesh* m, uint32_t f, double n[3]) {
  double x[3], len = face_cross(m->positions, m->faces[f], m->face_corners[f], x);
  unit3_len(x, len, n);
  return len;
}

/* Corner i of face f from its tangents: what its angle needs (|a x b|^2
 * and a . b) and, for a curved face, its own unit normal (a x b / |a x b|). */
static void corner_data(const tlod_mesh* m, uint32_t f, uint32_t i, double* y2, double* x, double own[3]) {
  double a[3], b[3], c[3];
  corner_tangents(m, f, i, a, b);
  cross3(a, b, c);
  unit3(c, own);
  *y2 = dot3(c, c);
  *x = dot3(a, b);
}

/* Corner i of face f (unit normal n, twice its area area2): its weight,
 * and its unit normal in out (n, or on a curved face the tangents' own). */
static double corner_weight(const tlod_mesh* m, bool area, uint32_t f, uint32_t i, double area2, bool curved,
                            const double n[3], double out[3]) {
  double y2, x, own[3], w = 0.5 * area2;
  memcpy(out, n, 3 * sizeof(double));
  if (area && !curved) return w;
  corner_data(m, f, i, &y2, &x, own);
  if (curved) memcpy(out, own, sizeof(own));
  if (!area) _tlod_corner_angles(TLOD_SIMD_SCALAR, &y2, &x, &w, 1);
  return w;
}

/* Corner normals and weights of face f. Area weights stay the flat area. */
static void face_geometry(normal_job* j, uint32_t f) {
  const tlod_mesh* m = j->m;
  uint32_t k = m->face_corners[f];
  double n[3], area2 = face_normal(m, f, n);
  for (uint32_t i = 0; i < 4; i++) {
    memcpy(j->corner_n[f * 4 + i], n, sizeof(n));
    j->weight[f * 4 + i] = 0.0;
  }
  for (uint32_t i = 0; i < k; i++)
    j->weight[f * 4 + i] = corner_weight(m, j->area, f, i, area2, curved_face(m, f), n, j->corner_n[f * 4 + i]);
}

/* ------------------------------------------------------------------------ */
/* The job                                                                  */
/* ------------------------------------------------------------------------ */

static void job_free(normal_job* j) {
  const tlod_context* ctx = j->m->ctx;
  _tlod_free(ctx, j->corner_n);
  _tlod_free(ctx, j->weight);
  _tlod_free(ctx, j->w_first);
  _tlod_free(ctx, j->w_slots);
  _tlod_free(ctx, j->state);
  _tlod_free(ctx, j->mean);
}

static tlod_result job_alloc(normal_job* j) {
  tlod_mesh* m = j->m;
  const tlod_context* ctx = m->ctx;
  size_t nf = m->face_count, nv = m->vertex_count;
  j->corner_n = _tlod_calloc(ctx, nf * 4, sizeof(*j->corner_n));
  j->weight = _tlod_calloc(ctx, nf * 4, sizeof(double));
  j->w_first = _tlod_calloc(ctx, nv + 1, sizeof(uint32_t));
  j->w_slots = _tlod_calloc(ctx, nf * 4, sizeof(uint32_t));
  j->state = _tlod_calloc(ctx, nv, 1);
  j->mean = _tlod_calloc(ctx, nv, sizeof(*j->mean));
  if (j->corner_n && j->weight && j->w_first && j->w_slots && j->state && j->mean) return TLOD_SUCCESS;
  job_free(j);
  /* The constant, not _tlod_fail's return value: static analysis cannot
   * see that it returns its argument, and callers rely on the failure. */
  (void)_tlod_fail(m->ctx, TLOD_ERROR_OUT_OF_MEMORY, "mesh '%s': out of memory (normals)", m->label);
  return TLOD_ERROR_OUT_OF_MEMORY;
}

/* Corner slots grouped by welded position (a counting sort, O(n)). Filling
 * backwards from each group's end leaves every group in face order. */
static void group_corners(normal_job* j) {
  const tlod_mesh* m = j->m;
  for (uint32_t f = 0; f < m->face_count; f++)
    for (uint32_t i = 0; i < m->face_corners[f]; i++)
      j->w_first[m->weld_id[m->faces[f][i]]]++;
  uint32_t total = 0;
  for (uint32_t w = 0; w < m->vertex_count; w++) {
    total += j->w_first[w];
    j->w_first[w] = total;
  }
  j->w_first[m->vertex_count] = total;
  for (uint32_t f = m->face_count; f-- > 0;)
    for (uint32_t i = m->face_corners[f]; i-- > 0;)
      j->w_slots[--j->w_first[m->weld_id[m->faces[f][i]]]] = f * 4 + i;
}

static tlod_result job_start(normal_job* j, tlod_mesh* m) {
  memset(j, 0, sizeof(*j));
  j->m = m;
  j->area = m->desc.normal_mode == TLOD_NORMALS_AREA;
  /* A hair of slack so that faces exactly at the crease angle count as
   * the same side whatever the rounding of their normals. */
  j->cos_crease = cos((double)m->desc.crease_angle_deg * (PI_D / 180.0)) - 1e-9;
  tlod_result r = job_alloc(j);
  if (r != TLOD_SUCCESS) return r;
  for (uint32_t f = 0; f < m->face_count; f++)
    face_geometry(j, f);
  group_corners(j);
  return TLOD_SUCCESS;
}

/* ------------------------------------------------------------------------ */
/* Normals                                                                  */
/* ------------------------------------------------------------------------ */

static bool nonzero(const double n[3]) { return n[0] != 0.0 || n[1] != 0.0 || n[2] != 0.0; }

/* When the faces cancel out (or there are none): the own corner's normal,
 * else the first corner at the position with one, else +z. */
static void fallback_normal(const normal_job* j, uint32_t w, uint32_t own_slot, float out[3]) {
  const double* n = NULL;
  if (own_slot != _TLOD_NONE && nonzero(j->corner_n[own_slot])) n = j->corner_n[own_slot];
  for (uint32_t s = j->w_first[w]; !n && s < j->w_first[w + 1]; s++)
    if (nonzero(j->corner_n[j->w_slots[s]])) n = j->corner_n[j->w_slots[s]];
  out[0] = n ? (float)n[0] : 0.0f;
  out[1] = n ? (float)n[1] : 0.0f;
  out[2] = n ? (float)n[2] : 1.0f;
}

/* sum[0..2] / |sum|, unless it is negligible against the total weight
 * sum[3] (opposite faces cancelling). */
static void unit_from_sum(const normal_job* j, const double sum[4], uint32_t w, uint32_t own, float out[3]) {
  double len = length3(sum);
  if (!(len > 1e-9 * sum[3]) || !(len > 0.0)) {
    fallback_normal(j, w, own, out);
    return;
  }
  for (int i = 0; i < 3; i++)
    out[i] = (float)(sum[i] / len);
}

/* With creases: the normal of face corner slot, whose vertex sits at welded
 * position w, from the faces there on its side of the crease. */
static void corner_normal(const normal_job* j, uint32_t slot, uint32_t w, float out[3]) {
  const double* own = j->corner_n[slot];
  double sum[4] = {0.0, 0.0, 0.0, 0.0};
  for (uint32_t s = j->w_first[w]; s < j->w_first[w + 1]; s++) {
    const double* n = j->corner_n[j->w_slots[s]];
    if (dot3(own, n) < j->cos_crease) continue;
    double wt = j->weight[j->w_slots[s]];
    for (int i = 0; i < 3; i++)
      sum[i] += wt * n[i];
    sum[3] += wt;
  }
  unit_from_sum(j, sum, w, slot, out);
}

/* A vertex no kept face uses: the normal of all faces at its position. */
static void unused_normal(const normal_job* j, uint32_t v, float out[3]) {
  uint32_t w = j->m->weld_id[v];
  double sum[4] = {0.0, 0.0, 0.0, 0.0};
  for (uint32_t s = j->w_first[w]; s < j->w_first[w + 1]; s++) {
    uint32_t slot = j->w_slots[s];
    for (int i = 0; i < 3; i++)
      sum[i] += j->weight[slot] * j->corner_n[slot][i];
    sum[3] += j->weight[slot];
  }
  unit_from_sum(j, sum, w, _TLOD_NONE, out);
}

static bool same_normal(const float* a, const float* b) { return memcmp(a, b, 3 * sizeof(float)) == 0; }

/* Creases, topology kept: a vertex takes its corners' normal when they
 * agree (so an unchanged mesh reproduces its normals bitwise), else their
 * mean. */
static void assign_creased(normal_job* j) {
  tlod_mesh* m = j->m;
  for (uint32_t f = 0; f < m->face_count; f++)
    for (uint32_t i = 0; i < m->face_corners[f]; i++) {
      uint32_t v = m->faces[f][i];
      if (!wants_normal(j->m, v)) continue;
      float n[3];
      corner_normal(j, f * 4 + i, m->weld_id[v], n);
      if (j->state[v] == 0) {
        memcpy(m->normals[v], n, sizeof(n));
        j->state[v] = 1;
      } else if (j->state[v] == 1 && !same_normal(m->normals[v], n)) {
        j->state[v] = 2;
      }
      for (int c = 0; c < 3; c++)
        j->mean[v][c] += n[c];
    }
  for (uint32_t v = 0; v < m->vertex_count; v++) {
    if (!wants_normal(j->m, v)) continue;
    if (j->state[v] == 0) unused_normal(j, v, m->normals[v]);
    double sum[4] = {j->mean[v][0], j->mean[v][1], j->mean[v][2], 1.0};
    if (j->state[v] == 2) unit_from_sum(j, sum, m->weld_id[v], _TLOD_NONE, m->normals[v]);
  }
}

/* ------------------------------------------------------------------------ */
/* Smooth normals (no creases)                                              */
/* ------------------------------------------------------------------------ */

/* sum[w][3] markers (weights are >= 0): the faces at w cancel out and no
 * corner normal was found yet; or sum[w][0..2] is the first one found. */
#define SUM_PENDING (-1.0)
#define SUM_FOUND (-2.0)

/* Each corner adds weight * normal to its welded position's sum, faces in
 * order: the order the grouped sums of the creased path use, with no
 * per-corner arrays. sum[w][3] is the total weight. */
/* Corners of up to BATCH_FACES faces, gathered so that their angles are
 * computed in lanes (mesh_angles.c), then summed in face order. */
enum { BATCH_FACES = _TLOD_FACE_LANES, BATCH_CORNERS = 4 * BATCH_FACES };
typedef struct corner_batch {
  double y2[BATCH_CORNERS]; /* |a x b|^2 of the corner's tangents */
  double x[BATCH_CORNERS];  /* a . b */
  double w[BATCH_CORNERS];  /* the weight */
  double n[BATCH_CORNERS][3];
  uint32_t v[BATCH_CORNERS];
  uint32_t count;
} corner_batch;

/* Face f as lane l of the face kernel. */
static void face_lane(const tlod_mesh* m, uint32_t f, uint32_t l, _tlod_face_lanes* lanes) {
  uint32_t k = m->face_corners[f];
  for (uint32_t c = 0; c < 4; c++) {
    const float* p = m->positions[m->faces[f][c < k ? c : 0]];
    for (uint32_t d = 0; d < 3; d++)
      lanes->p[3 * c + d][l] = (double)p[d];
  }
  lanes->quad[l] = k == 4 ? 1.0 : 0.0;
}

/* The normal of face f from lane l (face_normal where the lane defers). */
static double lane_normal(const tlod_mesh* m, uint32_t f, uint32_t l, const _tlod_face_lanes* lanes, double n[3]) {
  if (lanes->redo[l] != 0.0) return face_normal(m, f, n);
  for (int d = 0; d < 3; d++)
    n[d] = lanes->n[d][l];
  return lanes->len[l];
}

/* Face f (lane l of the face kernel) into the batch: its corners' vertex,
 * normal, and the weight (area) or what its angle needs (the lanes' flat
 * corners, else the curved tangents). */
static void batch_face(const tlod_mesh* m, bool area, uint32_t f, const _tlod_face_lanes* lanes, uint32_t l,
                       corner_batch* b) {
  uint32_t k = m->face_corners[f], at = b->count;
  bool curved = curved_face(m, f);
  double n[3], area2 = lane_normal(m, f, l, lanes, n);
  for (uint32_t i = 0; i < k; i++) {
    b->v[at + i] = m->faces[f][i];
    memcpy(b->n[at + i], n, 3 * sizeof(double));
    b->w[at + i] = 0.5 * area2;
  }
  for (uint32_t i = 0; !curved && !area && i < k; i++)
    b->y2[at + i] = lanes->y2[i][l], b->x[at + i] = lanes->x[i][l];
  for (uint32_t i = 0; curved && i < k; i++)
    corner_data(m, f, i, &b->y2[at + i], &b->x[at + i], b->n[at + i]);
  b->count += k;
}

static void batch_sum(const corner_batch* b, const tlod_mesh* m, double (*sum)[4]) {
  for (uint32_t i = 0; i < b->count; i++) {
    double* s = sum[m->weld_id[b->v[i]]];
    for (int d = 0; d < 3; d++)
      s[d] += b->w[i] * b->n[i][d];
    s[3] += b->w[i];
  }
}

/* Each corner adds weight * normal to its welded position's sum, faces in
 * order: the order the grouped sums of the creased path use, with no
 * per-corner arrays. sum[w][3] is the total weight. */
static void sum_faces(const tlod_mesh* m, bool area, double (*sum)[4]) {
  tlod_simd simd = tlod_context_simd(m->ctx);
  corner_batch b;
  _tlod_face_lanes lanes;
  for (uint32_t f0 = 0; f0 < m->face_count; f0 += BATCH_FACES) {
    uint32_t f1 = m->face_count - f0 < BATCH_FACES ? m->face_count : f0 + BATCH_FACES;
    /* Curved faces' corners take their own normal, flat ones the face's. */
    for (uint32_t f = f0; f < f1; f++)
      face_lane(m, f, f - f0, &lanes);
    _tlod_face_normals(simd, &lanes, f1 - f0);
    b.count = 0;
    for (uint32_t f = f0; f < f1; f++)
      batch_face(m, area, f, &lanes, f - f0, &b);
    if (!area) _tlod_corner_angles(simd, b.y2, b.x, b.w, b.count);
    batch_sum(&b, m, sum);
  }
}

/* The normal of v from its position's sum, as unit_from_sum; false (w
 * marked pending) where the faces cancel out. */
static bool from_sum(tlod_mesh* m, double (*sum)[4], uint32_t v) {
  double* s = sum[m->weld_id[v]];
  if (s[3] < 0.0) return false;
  double len = length3(s);
  if (!(len > 1e-9 * s[3]) || !(len > 0.0)) {
    s[3] = SUM_PENDING;
    return false;
  }
  double inv = 1.0 / len;
  for (int i = 0; i < 3; i++)
    m->normals[v][i] = (float)(s[i] * inv);
  return true;
}

/* Pending positions take the first corner normal there in face order (as
 * fallback_normal), else +z: one pass over the faces, rare. */
static void resolve_pending(tlod_mesh* m, bool area, double (*sum)[4]) {
  for (uint32_t f = 0; f < m->face_count; f++) {
    double n[3], area2 = face_normal(m, f, n);
    for (uint32_t i = 0; i < m->face_corners[f]; i++) {
      double *s = sum[m->weld_id[m->faces[f][i]]], c[3];
      if (s[3] != SUM_PENDING) continue;
      corner_weight(m, area, f, i, area2, curved_face(m, f), n, c);
      if (nonzero(c)) memcpy(s, c, sizeof(c)), s[3] = SUM_FOUND;
    }
  }
  for (uint32_t v = 0; v < m->vertex_count; v++) {
    const double* s = sum[m->weld_id[v]];
    if (!wants_normal(m, v) || s[3] >= 0.0) continue;
    bool found = s[3] == SUM_FOUND;
    m->normals[v][0] = found ? (float)s[0] : 0.0f;
    m->normals[v][1] = found ? (float)s[1] : 0.0f;
    m->normals[v][2] = found ? (float)s[2] : 1.0f;
  }
}

static void smooth_normals(tlod_mesh* m, double (*sum)[4]) {
  bool area = m->desc.normal_mode == TLOD_NORMALS_AREA, pending = false;
  memset(sum, 0, (size_t)m->vertex_count * sizeof(*sum));
  sum_faces(m, area, sum);
  for (uint32_t v = 0; v < m->vertex_count; v++)
    if (wants_normal(m, v) && !from_sum(m, sum, v)) pending = true;
  if (pending) resolve_pending(m, area, sum);
}

/* ------------------------------------------------------------------------ */
/* Crease splits (creation only)                                            */
/* ------------------------------------------------------------------------ */

/* Vertices appended by a split: new vertex input_count + k has source
 * src[k] and normal nrm[k]; next[k] chains the splits of one source. */
typedef struct split_list {
  uint32_t* first; /* per input vertex: its first split, NONE if none */
  uint32_t* next;
  uint32_t* src;
  float (*nrm)[3];
  uint32_t count, capacity;
} split_list;

static void split_free_lists(const tlod_context* ctx, split_list* s) {
  _tlod_free(ctx, s->next);
  _tlod_free(ctx, s->src);
  _tlod_free(ctx, s->nrm);
}

static void split_free(const tlod_context* ctx, split_list* s) {
  _tlod_free(ctx, s->first);
  split_free_lists(ctx, s);
}

/* A copy of the used elements of p with room for cap; p is left alone. */
static void* regrown(const tlod_context* ctx, const void* p, size_t used, size_t cap, size_t size) {
  void* q = _tlod_calloc(ctx, cap, size);
  if (q && used) memcpy(q, p, used * size);
  return q;
}

static bool split_grow(const tlod_context* ctx, split_list* s) {
  size_t cap = s->capacity ? (size_t)s->capacity * 2 : 64;
  uint32_t* next = regrown(ctx, s->next, s->count, cap, sizeof(uint32_t));
  uint32_t* src = regrown(ctx, s->src, s->count, cap, sizeof(uint32_t));
  float(*nrm)[3] = regrown(ctx, s->nrm, s->count, cap, sizeof(*s->nrm));
  if (!next || !src || !nrm) {
    _tlod_free(ctx, next);
    _tlod_free(ctx, src);
    _tlod_free(ctx, nrm);
    return false;
  }
  split_free_lists(ctx, s);
  s->next = next;
  s->src = src;
  s->nrm = nrm;
  s->capacity = (uint32_t)cap;
  return true;
}

/* The vertex carrying normal n for a corner of v: v itself or a split of
 * it, made when no existing one matches. NONE when out of memory. */
static uint32_t split_vertex(const tlod_context* ctx, split_list* s, uint32_t base, uint32_t v, const float n[3]) {
  uint32_t prev = _TLOD_NONE;
  for (uint32_t k = s->first[v]; k != _TLOD_NONE; prev = k, k = s->next[k])
    if (same_normal(s->nrm[k], n)) return base + k;
  if (s->count == s->capacity && !split_grow(ctx, s)) return _TLOD_NONE;
  uint32_t k = s->count++;
  s->next[k] = _TLOD_NONE;
  s->src[k] = v;
  memcpy(s->nrm[k], n, 3 * sizeof(float));
  /* Appended, so the splits of v stay in creation order. */
  if (prev == _TLOD_NONE)
    s->first[v] = k;
  else
    s->next[prev] = k;
  return base + k;
}

/* Groups each vertex's corners by normal; corners past the first group move
 * to split vertices (faces are rewritten here, vertex arrays later). */
static tlod_result split_corners(normal_job* j, split_list* s) {
  tlod_mesh* m = j->m;
  uint32_t n = m->vertex_count;
  for (uint32_t f = 0; f < m->face_count; f++)
    for (uint32_t i = 0; i < m->face_corners[f]; i++) {
      uint32_t v = m->faces[f][i];
      if (!wants_normal(j->m, v)) continue;
      float c[3];
      /* v < n here: a corner is rewritten only after its own normal. */
      corner_normal(j, f * 4 + i, m->weld_id[v], c);
      if (j->state[v] == 0) {
        memcpy(m->normals[v], c, sizeof(c));
        j->state[v] = 1;
      } else if (!same_normal(m->normals[v], c)) {
        uint32_t d = split_vertex(m->ctx, s, n, v, c);
        if (d == _TLOD_NONE)
          return _tlod_fail(m->ctx, TLOD_ERROR_OUT_OF_MEMORY, "mesh '%s': out of memory (crease splits)", m->label);
        m->faces[f][i] = d;
      }
    }
  for (uint32_t v = 0; v < n; v++)
    if (wants_normal(j->m, v) && j->state[v] == 0) unused_normal(j, v, m->normals[v]);
  return TLOD_SUCCESS;
}

/* The per-vertex arrays of a mesh, grown for the split vertices. */
typedef struct vertex_arrays {
  float (*positions)[3];
  float (*normals)[3];
  uint32_t* weld_id;
  uint8_t* normal_computed;
  float* alphas;
  uint32_t* source;
} vertex_arrays;

static void arrays_free(const tlod_context* ctx, vertex_arrays* a) {
  _tlod_free(ctx, a->positions);
  _tlod_free(ctx, a->normals);
  _tlod_free(ctx, a->weld_id);
  _tlod_free(ctx, a->normal_computed);
  _tlod_free(ctx, a->alphas);
  _tlod_free(ctx, a->source);
}

/* All or nothing, so the mesh stays consistent when memory runs out. */
static bool arrays_grow(const tlod_mesh* m, size_t total, uint32_t splits, vertex_arrays* a) {
  const tlod_context* ctx = m->ctx;
  uint32_t n = m->vertex_count;
  a->positions = regrown(ctx, m->positions, n, total, sizeof(*m->positions));
  a->normals = regrown(ctx, m->normals, n, total, sizeof(*m->normals));
  a->weld_id = regrown(ctx, m->weld_id, n, total, sizeof(uint32_t));
  a->normal_computed = regrown(ctx, m->normal_computed, n, total, 1);
  a->alphas = m->alphas ? regrown(ctx, m->alphas, n, total, sizeof(float)) : NULL;
  a->source = _tlod_calloc(ctx, splits, sizeof(uint32_t));
  if (a->positions && a->normals && a->weld_id && a->normal_computed && (a->alphas || !m->alphas) && a->source)
    return true;
  arrays_free(ctx, a);
  return false;
}

/* Swaps the grown arrays in and frees the old ones. */
static void arrays_swap(tlod_mesh* m, vertex_arrays* a) {
  vertex_arrays old = {m->positions, m->normals, m->weld_id, m->normal_computed, m->alphas, NULL};
  m->positions = a->positions;
  m->normals = a->normals;
  m->weld_id = a->weld_id;
  m->normal_computed = a->normal_computed;
  m->alphas = a->alphas;
  arrays_free(m->ctx, &old);
}

/* Appends the split vertices to every per-vertex array. */
static tlod_result append_splits(tlod_mesh* m, const split_list* s, uint32_t** split_source) {
  uint32_t n = m->vertex_count;
  size_t total = (size_t)n + s->count;
  if (total > UINT32_MAX)
    return _tlod_fail(m->ctx, TLOD_ERROR_INVALID_MESH, "mesh '%s': crease splits need more than 2^32 vertices",
                      m->label);
  vertex_arrays a;
  if (!arrays_grow(m, total, s->count, &a))
    return _tlod_fail(m->ctx, TLOD_ERROR_OUT_OF_MEMORY, "mesh '%s': out of memory (crease splits)", m->label);
  for (uint32_t k = 0; k < s->count; k++) {
    uint32_t d = n + k, v = s->src[k];
    memcpy(a.positions[d], a.positions[v], sizeof(a.positions[d]));
    memcpy(a.normals[d], s->nrm[k], sizeof(a.normals[d]));
    a.weld_id[d] = a.weld_id[v];
    a.normal_computed[d] = 1;
    if (a.alphas) a.alphas[d] = a.alphas[v];
    a.source[k] = v;
  }
  *split_source = a.source;
  arrays_swap(m, &a);
  m->vertex_count = (uint32_t)total;
  return TLOD_SUCCESS;
}

static tlod_result split_creases(normal_job* j, uint32_t** split_source) {
  tlod_mesh* m = j->m;
  split_list s = {0};
  s.first = _tlod_calloc(m->ctx, m->vertex_count, sizeof(uint32_t));
  if (!s.first)
    return _tlod_fail(m->ctx, TLOD_ERROR_OUT_OF_MEMORY, "mesh '%s': out of memory (crease splits)", m->label);
  memset(s.first, 0xFF, (size_t)m->vertex_count * sizeof(uint32_t)); /* all NONE */
  tlod_result r = split_corners(j, &s);
  if (r == TLOD_SUCCESS && s.count > 0) r = append_splits(m, &s, split_source);
  split_free(m->ctx, &s);
  return r;
}

/* ------------------------------------------------------------------------ */
/* Entry points                                                             */
/* ------------------------------------------------------------------------ */

static bool any_wanted(const tlod_mesh* m) {
  for (uint32_t v = 0; v < m->vertex_count; v++)
    if (wants_normal(m, v)) return true;
  return false;
}

static bool has_creases(const tlod_mesh* m) { return m->desc.crease_angle_deg > 0.0f; }

static tlod_result compute_creased(tlod_mesh* m, uint32_t** split_source) {
  normal_job j;
  tlod_result r = job_start(&j, m);
  if (r != TLOD_SUCCESS) return r;
  if (split_source)
    r = split_creases(&j, split_source);
  else
    assign_creased(&j);
  job_free(&j);
  return r;
}

/* Smooth normals need only the per-position sums: the mesh's scratch when
 * tlod_mesh_update made it, else a temporary one. */
static tlod_result compute(tlod_mesh* m, uint32_t** split_source) {
  if (!any_wanted(m)) return TLOD_SUCCESS; /* every normal given and valid */
  if (has_creases(m)) return compute_creased(m, split_source);
  double(*sum)[4] = m->normal_sum ? m->normal_sum : _tlod_calloc(m->ctx, m->vertex_count + 1, sizeof(*sum));
  if (!sum) return _tlod_fail(m->ctx, TLOD_ERROR_OUT_OF_MEMORY, "mesh '%s': out of memory (normals)", m->label);
  smooth_normals(m, sum);
  if (sum != m->normal_sum) _tlod_free(m->ctx, sum);
  return TLOD_SUCCESS;
}

tlod_result _tlod_mesh_normals_prepare(tlod_mesh* m) {
  if (has_creases(m) || m->normal_sum) return TLOD_SUCCESS;
  m->normal_sum = _tlod_calloc(m->ctx, m->vertex_count + 1, sizeof(*m->normal_sum));
  return m->normal_sum ? TLOD_SUCCESS
                       : _tlod_fail(m->ctx, TLOD_ERROR_OUT_OF_MEMORY, "mesh '%s': out of memory (normals)", m->label);
}

tlod_result _tlod_mesh_compute_normals(tlod_mesh* mesh) { return compute(mesh, NULL); }

/* Creation: like _tlod_mesh_compute_normals, but corners that need another
 * normal than their vertex's get a split vertex. *split_source receives the
 * source of each appended vertex (NULL when none was needed). */
tlod_result _tlod_mesh_compute_normals_split(tlod_mesh* mesh, uint32_t** split_source) {
  *split_source = NULL;
  return compute(mesh, split_source);
}
