/* tesslod::core -- meshes: validation, repairs, queries and updates.
 * Owned by the mesh module (mesh.c, mesh_adjacency.c, mesh_attributes.c,
 * mesh_normals.c).
 *
 * Input is checked in full before anything is allocated, so a rejected mesh
 * costs no allocation; what can be repaired (degenerate faces, bad normals,
 * alphas out of range) is repaired, counted in tlod_mesh_info and recorded
 * as a finding.
 *
 * This work is based on:
 *   T. Boubekeur, M. Alexa. Phong Tessellation. ACM TOG 27(5), 2008
 *   (angle-weighted vertex normals).
 *   G. Thuermer, C. A. Wuethrich. Computing vertex normals from polygonal
 *   facets. Journal of Graphics Tools 3(1), 1998.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "internal.h"

/* ------------------------------------------------------------------------ */
/* Strided input                                                            */
/* ------------------------------------------------------------------------ */

/* memcpy, because a stride need not keep floats aligned. */
static void load3(const float* base, uint32_t stride, uint32_t i, float out[3]) {
  memcpy(out, (const unsigned char*)base + (size_t)stride * i, 3 * sizeof(float));
}

static float load1(const float* base, uint32_t stride, uint32_t i) {
  float x;
  memcpy(&x, (const unsigned char*)base + (size_t)stride * i, sizeof(float));
  return x;
}

static const char component_name[3] = {'x', 'y', 'z'};

/* ------------------------------------------------------------------------ */
/* Validation (nothing allocated yet)                                       */
/* ------------------------------------------------------------------------ */

/* What validation worked out about the desc. */
typedef struct mesh_plan {
  tlod_mesh_desc d; /* defaults resolved, input pointers kept */
  char label[64];
  uint32_t face_size; /* 3 or 4; 0 for MIXED */
  uint32_t input_faces;
} mesh_plan;

static uint32_t plan_face_size(const mesh_plan* p, uint32_t f) {
  return p->face_size ? p->face_size : p->d.face_sizes[f];
}

static tlod_result check_stride(tlod_context* ctx, const mesh_plan* p, const char* name, uint32_t stride,
                                uint32_t element) {
  if (stride >= element) return TLOD_SUCCESS;
  return _tlod_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "mesh '%s': %s %u bytes is smaller than an element (%u bytes)",
                    p->label, name, stride, element);
}

static tlod_result check_enums(tlod_context* ctx, const mesh_plan* p) {
  const tlod_mesh_desc* d = &p->d;
  if ((uint32_t)d->face_type >= TLOD_FACE_NUM)
    return _tlod_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "mesh '%s': face_type %u is not a tlod_face_type", p->label,
                      (uint32_t)d->face_type);
  if ((uint32_t)d->normal_mode >= TLOD_NORMALS_NUM)
    return _tlod_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "mesh '%s': normal_mode %u is not a tlod_normal_mode", p->label,
                      (uint32_t)d->normal_mode);
  if (!isfinite(d->crease_angle_deg) || d->crease_angle_deg < 0.0f)
    return _tlod_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "mesh '%s': crease_angle_deg %g must be finite and >= 0",
                      p->label, (double)d->crease_angle_deg);
  if (!isfinite(d->weld_epsilon) || d->weld_epsilon < 0.0f)
    return _tlod_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "mesh '%s': weld_epsilon %g must be finite and >= 0", p->label,
                      (double)d->weld_epsilon);
  return TLOD_SUCCESS;
}

static tlod_result check_pointers(tlod_context* ctx, const mesh_plan* p) {
  const tlod_mesh_desc* d = &p->d;
  const char* missing = NULL;
  if (!d->positions && d->vertex_count > 0) missing = "positions";
  if (!d->indices && d->index_count > 0) missing = "indices";
  if (d->face_type == TLOD_FACE_MIXED && !d->face_sizes && d->face_count > 0) missing = "face_sizes";
  if (missing) return _tlod_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "mesh '%s': %s is NULL", p->label, missing);
  tlod_result r = check_stride(ctx, p, "position_stride", d->position_stride, 12);
  if (r == TLOD_SUCCESS && d->normals) r = check_stride(ctx, p, "normal_stride", d->normal_stride, 12);
  if (r == TLOD_SUCCESS && d->alphas) r = check_stride(ctx, p, "alpha_stride", d->alpha_stride, 4);
  return r;
}

static tlod_result resolve_desc(tlod_context* ctx, const tlod_mesh_desc* in, mesh_plan* p) {
  memset(p, 0, sizeof(*p));
  p->d = *in;
  snprintf(p->label, sizeof(p->label), "%s", in->label ? in->label : "mesh");
  tlod_mesh_desc* d = &p->d;
  d->label = p->label;
  if (d->position_stride == 0) d->position_stride = 12;
  if (d->normal_stride == 0) d->normal_stride = 12;
  if (d->alpha_stride == 0) d->alpha_stride = 4;
  tlod_result r = check_enums(ctx, p);
  if (r != TLOD_SUCCESS) return r;
  if (d->face_type == TLOD_FACE_DEFAULT) d->face_type = TLOD_FACE_TRIANGLES;
  if (d->normal_mode == TLOD_NORMALS_DEFAULT) d->normal_mode = TLOD_NORMALS_KEEP;
  /* KEEP without normals computes them; say so in the resolved desc. */
  if (d->normal_mode == TLOD_NORMALS_KEEP && !d->normals) d->normal_mode = TLOD_NORMALS_ANGLE;
  return check_pointers(ctx, p);
}

static tlod_result count_mixed_faces(tlod_context* ctx, mesh_plan* p) {
  const tlod_mesh_desc* d = &p->d;
  if (d->face_count == 0)
    return _tlod_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "mesh '%s': no faces (face_count 0)", p->label);
  uint64_t sum = 0;
  for (uint32_t f = 0; f < d->face_count; f++) {
    if (d->face_sizes[f] != 3 && d->face_sizes[f] != 4)
      return _tlod_fail(ctx, TLOD_ERROR_INVALID_MESH,
                        "mesh '%s': face %u: face_sizes %u (MIXED faces have 3 or 4 corners)", p->label, f,
                        d->face_sizes[f]);
    sum += d->face_sizes[f];
  }
  if (sum != d->index_count)
    return _tlod_fail(ctx, TLOD_ERROR_INVALID_MESH, "mesh '%s': face_sizes sum to %llu but index_count is %u", p->label,
                      (unsigned long long)sum, d->index_count);
  p->face_size = 0;
  p->input_faces = d->face_count;
  return TLOD_SUCCESS;
}

static tlod_result count_faces(tlod_context* ctx, mesh_plan* p) {
  const tlod_mesh_desc* d = &p->d;
  tlod_result r = TLOD_SUCCESS;
  if (d->face_type == TLOD_FACE_MIXED) {
    r = count_mixed_faces(ctx, p);
  } else {
    p->face_size = d->face_type == TLOD_FACE_QUADS ? 4 : 3;
    if (d->index_count == 0)
      return _tlod_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "mesh '%s': no faces (index_count 0)", p->label);
    if (d->index_count % p->face_size != 0)
      return _tlod_fail(ctx, TLOD_ERROR_INVALID_MESH, "mesh '%s': index_count %u is not a multiple of %u (%s)",
                        p->label, d->index_count, p->face_size, p->face_size == 4 ? "quads" : "triangles");
    p->input_faces = d->index_count / p->face_size;
  }
  /* Face edge slots are face * 4 + edge in 32 bits. */
  if (r == TLOD_SUCCESS && p->input_faces > UINT32_MAX / 4 - 1)
    r = _tlod_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "mesh '%s': %u faces is too many", p->label, p->input_faces);
  return r;
}

static tlod_result check_indices(tlod_context* ctx, const mesh_plan* p) {
  const tlod_mesh_desc* d = &p->d;
  uint32_t first = 0;
  for (uint32_t f = 0; f < p->input_faces; f++) {
    uint32_t k = plan_face_size(p, f);
    for (uint32_t i = 0; i < k; i++) {
      uint32_t v = d->indices[first + i];
      if (v >= d->vertex_count)
        return _tlod_fail(ctx, TLOD_ERROR_INVALID_MESH,
                          "mesh '%s': face %u (indices %u..%u): index %u out of range (%u vertices)", p->label, f,
                          first, first + k - 1, v, d->vertex_count);
    }
    first += k;
  }
  return TLOD_SUCCESS;
}

/* Positions are finite and within TLOD_POSITION_LIMIT, so that the float
 * maths downstream (PN control points, squared lengths, projections) cannot
 * overflow (docs/design.md "Coordinate range"). what: "" or "update: ". */
static tlod_result check_position(tlod_context* ctx, const char* label, const char* what, uint32_t v,
                                  const float x[3]) {
  for (int c = 0; c < 3; c++) {
    if (!isfinite(x[c]))
      return _tlod_fail(ctx, TLOD_ERROR_INVALID_MESH, "mesh '%s': %svertex %u: position.%c is %g (not finite)", label,
                        what, v, component_name[c], (double)x[c]);
    if (fabsf(x[c]) > TLOD_POSITION_LIMIT)
      return _tlod_fail(ctx, TLOD_ERROR_INVALID_MESH,
                        "mesh '%s': %svertex %u: position.%c is %g (outside +-%g, TLOD_POSITION_LIMIT)", label, what, v,
                        component_name[c], (double)x[c], (double)TLOD_POSITION_LIMIT);
  }
  return TLOD_SUCCESS;
}

static tlod_result check_vertices(tlod_context* ctx, const mesh_plan* p) {
  const tlod_mesh_desc* d = &p->d;
  for (uint32_t v = 0; v < d->vertex_count; v++) {
    float x[3];
    load3(d->positions, d->position_stride, v, x);
    tlod_result r = check_position(ctx, p->label, "", v, x);
    if (r != TLOD_SUCCESS) return r;
    if (d->alphas && !isfinite(load1(d->alphas, d->alpha_stride, v)))
      return _tlod_fail(ctx, TLOD_ERROR_INVALID_MESH, "mesh '%s': vertex %u: alpha is %g (not finite)", p->label, v,
                        (double)load1(d->alphas, d->alpha_stride, v));
  }
  return TLOD_SUCCESS;
}

static tlod_result validate(tlod_context* ctx, const tlod_mesh_desc* in, mesh_plan* p) {
  tlod_result r = resolve_desc(ctx, in, p);
  if (r == TLOD_SUCCESS) r = count_faces(ctx, p);
  if (r == TLOD_SUCCESS) r = check_indices(ctx, p);
  if (r == TLOD_SUCCESS) r = check_vertices(ctx, p);
  if (r == TLOD_SUCCESS) r = _tlod_mesh_check_attributes(ctx, p->label, &p->d);
  if (r == TLOD_SUCCESS) r = _tlod_mesh_check_nodes(ctx, p->label, &p->d, p->face_size, p->input_faces);
  return r;
}

/* ------------------------------------------------------------------------ */
/* Building                                                                 */
/* ------------------------------------------------------------------------ */

static tlod_result fail_oom(tlod_mesh* m, const char* what) {
  return _tlod_fail(m->ctx, TLOD_ERROR_OUT_OF_MEMORY, "mesh '%s': out of memory (%s)", m->label, what);
}

/* Normalised in double so that a float normal of any magnitude survives.
 * Returns false for a zero-length or non-finite normal. */
static bool unit_normal(const float in[3], float out[3]) {
  double x = in[0], y = in[1], z = in[2];
  double len = sqrt(x * x + y * y + z * z);
  if (!(len > 0.0) || !isfinite(len)) return false;
  out[0] = (float)(x / len);
  out[1] = (float)(y / len);
  out[2] = (float)(z / len);
  return true;
}

/* A node-only vertex is no corner: its normal is never read, so it is not
 * computed or repaired; a valid given one is kept, else (0, 0, 1). */
static void node_normal(tlod_mesh* m, const tlod_mesh_desc* d, uint32_t v) {
  float n[3];
  if (d->normal_mode == TLOD_NORMALS_KEEP) load3(d->normals, d->normal_stride, v, n);
  if (d->normal_mode != TLOD_NORMALS_KEEP || !unit_normal(n, m->normals[v]))
    memcpy(m->normals[v], (const float[3]){0.0f, 0.0f, 1.0f}, sizeof(m->normals[v]));
}

/* After the faces and their nodes: node-only vertices are left out. */
static void copy_normals(tlod_mesh* m, const tlod_mesh_desc* d) {
  for (uint32_t v = 0; v < m->vertex_count; v++) {
    float n[3];
    if (_tlod_mesh_is_node_only(m, v)) {
      node_normal(m, d, v);
      continue;
    }
    if (d->normal_mode != TLOD_NORMALS_KEEP) {
      /* No normals given, or a recomputing mode: the normal is computed. */
      m->normal_computed[v] = 1;
      m->info.normals_computed++;
      continue;
    }
    load3(d->normals, d->normal_stride, v, n);
    if (unit_normal(n, m->normals[v])) continue;
    m->normal_computed[v] = 1;
    m->info.normals_repaired++;
    _tlod_mesh_add_finding(m, TLOD_FINDING_NORMAL_REPAIRED, v, _TLOD_NONE, "vertex %u: normal (%g, %g, %g) recomputed",
                           v, (double)n[0], (double)n[1], (double)n[2]);
  }
}

static void copy_alphas(tlod_mesh* m, const tlod_mesh_desc* d) {
  for (uint32_t v = 0; v < m->vertex_count; v++) {
    float a = load1(d->alphas, d->alpha_stride, v);
    float c = a < 0.0f ? 0.0f : (a > 1.0f ? 1.0f : a);
    if (c != a)
      _tlod_mesh_add_finding(m, TLOD_FINDING_ALPHA_CLAMPED, v, _TLOD_NONE, "vertex %u: alpha %g clamped to %g", v,
                             (double)a, (double)c);
    m->alphas[v] = c;
  }
}

static tlod_result copy_vertices(tlod_mesh* m, const tlod_mesh_desc* d) {
  const tlod_context* ctx = m->ctx;
  uint32_t n = d->vertex_count;
  m->vertex_count = n;
  m->positions = _tlod_calloc(ctx, n, sizeof(*m->positions));
  m->normals = _tlod_calloc(ctx, n, sizeof(*m->normals));
  m->normal_computed = _tlod_calloc(ctx, n, 1);
  if (d->alphas) m->alphas = _tlod_calloc(ctx, n, sizeof(float));
  if (!m->positions || !m->normals || !m->normal_computed || (d->alphas && !m->alphas)) return fail_oom(m, "vertices");
  for (uint32_t v = 0; v < n; v++)
    load3(d->positions, d->position_stride, v, m->positions[v]);
  if (d->alphas) copy_alphas(m, d);
  return TLOD_SUCCESS;
}

/* Zero area relative to the triangle's size: |cross| <= 1e-12 * longest^2. */
static bool triangle_degenerate(const float* a, const float* b, const float* c) {
  double e0[3], e1[3], e2[3];
  for (int i = 0; i < 3; i++) {
    e0[i] = (double)b[i] - a[i];
    e1[i] = (double)c[i] - a[i];
    e2[i] = (double)c[i] - b[i];
  }
  double cx = e0[1] * e1[2] - e0[2] * e1[1];
  double cy = e0[2] * e1[0] - e0[0] * e1[2];
  double cz = e0[0] * e1[1] - e0[1] * e1[0];
  double l0 = e0[0] * e0[0] + e0[1] * e0[1] + e0[2] * e0[2];
  double l1 = e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2];
  double l2 = e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2];
  /* Sums of squares of finite differences (positions are checked): never
   * NaN, so plain compares give fmax's result without its library call. */
  double l01 = l0 > l1 ? l0 : l1, longest = l01 > l2 ? l01 : l2, bound = 1e-12 * longest;
  /* Squared, without the square root (the profile's largest part of this
   * test); the two differ only within an ulp of the threshold. */
  return cx * cx + cy * cy + cz * cz <= bound * bound;
}

/* True (and a finding) when input face f must be dropped. */
static bool face_degenerate(tlod_mesh* m, uint32_t f, const uint32_t* idx, uint32_t k) {
  for (uint32_t i = 0; i < k; i++)
    for (uint32_t j = i + 1; j < k; j++) {
      if (idx[i] == idx[j]) {
        _tlod_mesh_add_finding(m, TLOD_FINDING_DEGENERATE_FACE, f, _TLOD_NONE, "face %u: repeated vertex %u", f,
                               idx[i]);
        return true;
      }
      if (m->weld_id[idx[i]] == m->weld_id[idx[j]]) {
        _tlod_mesh_add_finding(m, TLOD_FINDING_DEGENERATE_FACE, f, _TLOD_NONE,
                               "face %u: vertices %u and %u share a position", f, idx[i], idx[j]);
        return true;
      }
    }
  float(*p)[3] = m->positions;
  bool zero = triangle_degenerate(p[idx[0]], p[idx[1]], p[idx[2]]);
  /* A quad is dropped only when both of its halves are flat: a quad with
   * one flat half is a valid triangle-shaped patch. */
  if (k == 4) zero = zero && triangle_degenerate(p[idx[0]], p[idx[2]], p[idx[3]]);
  if (zero) _tlod_mesh_add_finding(m, TLOD_FINDING_DEGENERATE_FACE, f, _TLOD_NONE, "face %u: zero area", f);
  return zero;
}

/* The mesh is freed on failure: its refusal names a face from the findings. */
static const char* first_degenerate(const tlod_mesh* m) {
  for (uint32_t i = 0; i < m->info.finding_count; i++)
    if (m->findings[i].kind == TLOD_FINDING_DEGENERATE_FACE) return m->findings[i].message;
  return "face 0 first; findings full";
}

static tlod_result copy_faces(tlod_mesh* m, const mesh_plan* p) {
  const tlod_context* ctx = m->ctx;
  uint32_t nf = p->input_faces;
  m->faces = _tlod_calloc(ctx, nf, sizeof(*m->faces));
  m->face_corners = _tlod_calloc(ctx, nf, 1);
  m->face_input = _tlod_calloc(ctx, nf, sizeof(uint32_t));
  if (!m->faces || !m->face_corners || !m->face_input) return fail_oom(m, "faces");
  uint32_t kept = 0, first = 0;
  for (uint32_t f = 0; f < nf; f++) {
    uint32_t k = plan_face_size(p, f);
    const uint32_t* idx = p->d.indices + first;
    first += k;
    if (face_degenerate(m, f, idx, k)) {
      m->info.degenerate_faces_dropped++;
      continue;
    }
    for (uint32_t i = 0; i < 4; i++)
      m->faces[kept][i] = i < k ? idx[i] : _TLOD_NONE;
    m->face_corners[kept] = (uint8_t)k;
    m->face_input[kept] = f;
    if (k == 3)
      m->info.triangle_count++;
    else
      m->info.quad_count++;
    kept++;
  }
  m->face_count = kept;
  m->info.face_count = kept;
  if (kept == 0)
    return _tlod_fail(m->ctx, TLOD_ERROR_INVALID_MESH, "mesh '%s': all %u faces are degenerate (%s)", m->label, nf,
                      first_degenerate(m));
  return TLOD_SUCCESS;
}

static tlod_result count_unused(tlod_mesh* m) {
  uint8_t* used = _tlod_calloc(m->ctx, m->vertex_count, 1);
  if (!used) return fail_oom(m, "vertex marks");
  for (uint32_t f = 0; f < m->face_count; f++)
    for (uint32_t i = 0; i < m->face_corners[f]; i++)
      used[m->faces[f][i]] = 1;
  for (uint32_t v = 0; v < m->vertex_count; v++) {
    if (used[v] || _tlod_mesh_is_node_only(m, v)) continue;
    m->info.unused_vertices++;
    _tlod_mesh_add_finding(m, TLOD_FINDING_UNUSED_VERTEX, v, _TLOD_NONE, "vertex %u: referenced by no face", v);
  }
  _tlod_free(m->ctx, used);
  return TLOD_SUCCESS;
}

static void bbox_add(const float* x, float lo[3], float hi[3]) {
  for (int c = 0; c < 3; c++) { /* finite: plain compares, no libm calls */
    lo[c] = x[c] < lo[c] ? x[c] : lo[c];
    hi[c] = x[c] > hi[c] ? x[c] : hi[c];
  }
}

static void store_bbox(tlod_mesh* m, const float lo[3], const float hi[3]) {
  memcpy(m->info.bbox_min, lo, 3 * sizeof(float));
  memcpy(m->info.bbox_max, hi, 3 * sizeof(float));
}

/* Over the corners and nodes of kept faces, so unused vertices do not count. */
static void compute_bbox(tlod_mesh* m) {
  float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (uint32_t f = 0; f < m->face_count; f++) {
    for (uint32_t i = 0; i < m->face_corners[f]; i++)
      bbox_add(m->positions[m->faces[f][i]], lo, hi);
    for (uint32_t s = 0; m->face_nodes && s < TLOD_FACE_NODES; s++)
      if (m->face_nodes[f][s] != _TLOD_NONE) bbox_add(m->positions[m->face_nodes[f][s]], lo, hi);
  }
  store_bbox(m, lo, hi);
}

/* The box of all vertices, when that is the box of the face corners (every
 * vertex is one: no unused vertices, no nodes; else false), in four
 * independent chains. The same values as compute_bbox; the bits too,
 * except for the sign of a zero bound (-0 and +0 compare equal, and the
 * first one seen stays). */
static bool vertex_bbox(const tlod_mesh* m, float lo[3], float hi[3]) {
  if (m->face_nodes || m->info.unused_vertices || m->vertex_count == 0) return false;
  float l[4][3], h[4][3];
  for (int k = 0; k < 4; k++)
    memcpy(l[k], m->positions[0], sizeof(l[k])), memcpy(h[k], m->positions[0], sizeof(h[k]));
  uint32_t n = m->vertex_count;
  for (uint32_t v = 0; v < n; v++)
    bbox_add(m->positions[v], l[v & 3], h[v & 3]);
  for (int k = 1; k < 4; k++)
    bbox_add(l[k], l[0], h[0]), bbox_add(h[k], l[0], h[0]);
  memcpy(lo, l[0], sizeof(l[0]));
  memcpy(hi, h[0], sizeof(h[0]));
  return true;
}

/* At creation, compute_bbox's bits: the vertices' box unless a bound is
 * zero (whose sign depends on the order), at a third of the cost. */
static void create_bbox(tlod_mesh* m) {
  float lo[3], hi[3];
  bool ok = vertex_bbox(m, lo, hi);
  for (int c = 0; ok && c < 3; c++)
    ok = lo[c] != 0.0f && hi[c] != 0.0f;
  if (ok)
    store_bbox(m, lo, hi);
  else
    compute_bbox(m);
}

static void log_summary(const tlod_mesh* m) {
  const tlod_mesh_info* i = &m->info;
  _tlod_log(m->ctx, TLOD_LOG_INFO,
            "mesh '%s': %u faces (%u triangles, %u quads), %u vertices, %u positions, %u edges "
            "(%u boundary, %u non-manifold, %u crease)",
            m->label, i->face_count, i->triangle_count, i->quad_count, m->vertex_count, i->welded_vertex_count,
            i->edge_count, i->boundary_edges, i->non_manifold_edges, i->crease_edges);
  if (m->vertex_count > i->input_vertex_count)
    _tlod_log(m->ctx, TLOD_LOG_INFO, "mesh '%s': crease angle %g: %u vertices appended to split normals at creases",
              m->label, (double)m->desc.crease_angle_deg, m->vertex_count - i->input_vertex_count);
  if (i->degenerate_faces_dropped || i->normals_repaired || i->unused_vertices || i->findings_dropped)
    _tlod_log(m->ctx, TLOD_LOG_WARNING,
              "mesh '%s': %u degenerate faces dropped, %u normals repaired, %u unused vertices, "
              "%u findings (%u more not stored)",
              m->label, i->degenerate_faces_dropped, i->normals_repaired, i->unused_vertices, i->finding_count,
              i->findings_dropped);
}

static void finish_info(tlod_mesh* m) {
  uint32_t welded = 0;
  for (uint32_t v = 0; v < m->info.input_vertex_count; v++)
    welded += m->weld_id[v] == v;
  m->info.welded_vertex_count = welded;
  create_bbox(m);
}

/* The desc as the mesh keeps it: defaults resolved, caller arrays dropped. */
static void store_desc(tlod_mesh* m, const mesh_plan* p) {
  m->desc = p->d;
  m->desc.positions = NULL;
  m->desc.normals = NULL;
  m->desc.alphas = NULL;
  m->desc.indices = NULL;
  m->desc.face_sizes = NULL;
  m->desc.attributes = NULL;
  m->desc.face_nodes = NULL;
  m->desc.face_count = p->input_faces;
  m->desc.label = m->label;
}

static tlod_result build(tlod_mesh* m, const mesh_plan* p) {
  store_desc(m, p);
  m->info.input_vertex_count = p->d.vertex_count;
  m->info.input_face_count = p->input_faces;
  tlod_result r = copy_vertices(m, &p->d);
  /* Welding comes before face checks: faces with two corners at one
   * welded position are degenerate. */
  if (r == TLOD_SUCCESS) r = _tlod_mesh_weld(m);
  if (r == TLOD_SUCCESS) r = copy_faces(m, p);
  /* Nodes before the normals and the unused count: node-only vertices get
   * neither a computed normal nor an unused finding. */
  if (r == TLOD_SUCCESS) r = _tlod_mesh_copy_nodes(m, p->d.face_nodes);
  if (r == TLOD_SUCCESS) copy_normals(m, &p->d);
  if (r == TLOD_SUCCESS) r = count_unused(m);
  if (r == TLOD_SUCCESS) r = _tlod_mesh_compute_normals_split(m, &m->split_source);
  /* After the splits, so split vertices get their source's values. */
  if (r == TLOD_SUCCESS) r = _tlod_mesh_copy_attributes(m, &p->d);
  /* Adjacency last: its smooth and seam flags compare the final normals
   * and the attributes. */
  if (r == TLOD_SUCCESS) r = _tlod_mesh_build_adjacency(m);
  if (r == TLOD_SUCCESS) finish_info(m);
  return r;
}

/* ------------------------------------------------------------------------ */
/* Public                                                                   */
/* ------------------------------------------------------------------------ */

tlod_result tlod_mesh_create(tlod_context* ctx, const tlod_mesh_desc* desc, tlod_mesh** out) {
  if (out) *out = NULL;
  if (!ctx) return TLOD_ERROR_INVALID_ARGUMENT;
  if (!desc || !out)
    return _tlod_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "tlod_mesh_create: %s is NULL", desc ? "out" : "desc");
  mesh_plan plan;
  tlod_result r = validate(ctx, desc, &plan);
  if (r != TLOD_SUCCESS) return r;

  tlod_mesh* m = _tlod_calloc(ctx, 1, sizeof(*m));
  if (!m) return _tlod_fail(ctx, TLOD_ERROR_OUT_OF_MEMORY, "mesh '%s': out of memory (mesh)", plan.label);
  m->ctx = ctx;
  m->generation = 1;
  m->smooth_generation = 1;
  memcpy(m->label, plan.label, sizeof(plan.label));
  r = build(m, &plan);
  if (r != TLOD_SUCCESS) {
    tlod_mesh_destroy(m);
    return r;
  }
  log_summary(m);
  *out = m;
  return TLOD_SUCCESS;
}

void tlod_mesh_destroy(tlod_mesh* mesh) {
  if (!mesh) return;
  const tlod_context* ctx = mesh->ctx;
  _tlod_free(ctx, mesh->positions);
  _tlod_free(ctx, mesh->normals);
  _tlod_free(ctx, mesh->alphas);
  _tlod_free(ctx, mesh->weld_id);
  _tlod_free(ctx, mesh->normal_computed);
  _tlod_free(ctx, mesh->faces);
  _tlod_free(ctx, mesh->face_corners);
  _tlod_free(ctx, mesh->face_input);
  _tlod_free(ctx, mesh->links);
  _tlod_free(ctx, mesh->split_source);
  _tlod_free(ctx, mesh->attributes);
  _tlod_free(ctx, mesh->face_nodes);
  _tlod_free(ctx, mesh->node_given);
  _tlod_free(ctx, mesh->node_only);
  _tlod_free(ctx, mesh->normal_sum);
  _tlod_free(ctx, mesh);
}

tlod_mesh_info tlod_mesh_query_info(const tlod_mesh* mesh) { return mesh ? mesh->info : (tlod_mesh_info){0}; }

tlod_finding tlod_mesh_query_finding(const tlod_mesh* mesh, uint32_t i) {
  if (!mesh || i >= mesh->info.finding_count)
    return (tlod_finding){.kind = TLOD_FINDING_NUM, .element = _TLOD_NONE, .element2 = _TLOD_NONE};
  return mesh->findings[i];
}

uint32_t tlod_mesh_face_count(const tlod_mesh* mesh) { return mesh ? mesh->face_count : 0; }

uint32_t tlod_mesh_face_input_index(const tlod_mesh* mesh, uint32_t face) {
  return mesh && face < mesh->face_count ? mesh->face_input[face] : _TLOD_NONE;
}

uint32_t tlod_mesh_face_corners(const tlod_mesh* mesh, uint32_t face, uint32_t out[4]) {
  if (!mesh || face >= mesh->face_count) return 0;
  uint32_t k = mesh->face_corners[face];
  if (out)
    for (uint32_t i = 0; i < k; i++)
      out[i] = mesh->faces[face][i];
  return k;
}

uint32_t tlod_mesh_vertex_count(const tlod_mesh* mesh) { return mesh ? mesh->vertex_count : 0; }

void tlod_mesh_vertex(const tlod_mesh* mesh, uint32_t vertex, float position[3], float normal[3]) {
  bool ok = mesh && vertex < mesh->vertex_count;
  static const float zero[3] = {0.0f, 0.0f, 0.0f};
  if (position) memcpy(position, ok ? mesh->positions[vertex] : zero, sizeof(zero));
  if (normal) memcpy(normal, ok ? mesh->normals[vertex] : zero, sizeof(zero));
}

uint32_t tlod_mesh_vertex_weld_id(const tlod_mesh* mesh, uint32_t vertex) {
  return mesh && vertex < mesh->vertex_count ? mesh->weld_id[vertex] : _TLOD_NONE;
}

tlod_edge_link tlod_mesh_edge_link(const tlod_mesh* mesh, uint32_t face, uint32_t edge) {
  if (!mesh || face >= mesh->face_count || edge >= mesh->face_corners[face])
    return (tlod_edge_link){.face = _TLOD_NONE, .edge = UINT8_MAX, .smooth = false, .seam = false};
  return mesh->links[face][edge];
}

void _tlod_mesh_add_finding(tlod_mesh* mesh, tlod_finding_kind kind, uint32_t element, uint32_t element2,
                            const char* fmt, ...) {
  if (mesh->info.finding_count >= TLOD_MAX_FINDINGS) {
    mesh->info.findings_dropped++;
    return;
  }
  tlod_finding* f = &mesh->findings[mesh->info.finding_count++];
  f->kind = kind;
  f->element = element;
  f->element2 = element2;
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(f->message, sizeof(f->message), fmt, ap);
  va_end(ap);
}

/* ------------------------------------------------------------------------ */
/* Update                                                                   */
/* ------------------------------------------------------------------------ */

/* The common case in one pass without early exits (NaN and infinities fail
 * the compare too); check_position names the first bad one otherwise. */
static bool positions_in_range(const float* positions, uint32_t ps, uint32_t n) {
  bool ok = true;
  for (uint32_t v = 0; v < n; v++) {
    float x[3];
    load3(positions, ps, v, x);
    ok &= (fabsf(x[0]) <= TLOD_POSITION_LIMIT) & (fabsf(x[1]) <= TLOD_POSITION_LIMIT) &
          (fabsf(x[2]) <= TLOD_POSITION_LIMIT);
  }
  return ok;
}

static tlod_result check_update(tlod_mesh* m, const float* positions, uint32_t ps, const float* normals, uint32_t ns) {
  uint32_t n = m->info.input_vertex_count;
  if ((positions && ps < 12) || (normals && ns < 12))
    return _tlod_fail(m->ctx, TLOD_ERROR_INVALID_ARGUMENT,
                      "mesh '%s': update: stride %u bytes is smaller than an element (12 bytes)", m->label,
                      positions && ps < 12 ? ps : ns);
  if (positions && positions_in_range(positions, ps, n)) positions = NULL; /* checked */
  for (uint32_t v = 0; positions && v < n; v++) {
    float x[3];
    load3(positions, ps, v, x);
    tlod_result r = check_position(m->ctx, m->label, "update: ", v, x);
    if (r != TLOD_SUCCESS) return r;
  }
  for (uint32_t v = 0; normals && v < n; v++) {
    float x[3], u[3];
    load3(normals, ns, v, x);
    if (!unit_normal(x, u))
      return _tlod_fail(m->ctx, TLOD_ERROR_INVALID_MESH,
                        "mesh '%s': update: vertex %u: normal (%g, %g, %g) is zero-length or not "
                        "finite",
                        m->label, v, (double)x[0], (double)x[1], (double)x[2]);
  }
  return TLOD_SUCCESS;
}

static bool any_computed(const tlod_mesh* m) {
  for (uint32_t v = 0; v < m->vertex_count; v++)
    if (m->normal_computed[v]) return true;
  return false;
}

/* Split vertices (appended after the input ones) follow their source. */
static void copy_split(tlod_mesh* m, float (*dst)[3]) {
  const uint32_t* src = m->split_source;
  uint32_t n = m->info.input_vertex_count;
  for (uint32_t v = n; v < m->vertex_count; v++)
    memcpy(dst[v], dst[src[v - n]], sizeof(dst[v]));
}

static void write_positions(tlod_mesh* m, const float* positions, uint32_t ps) {
  for (uint32_t v = 0; v < m->info.input_vertex_count; v++)
    load3(positions, ps, v, m->positions[v]);
  copy_split(m, m->positions);
}

static void write_normals(tlod_mesh* m, const float* normals, uint32_t ns) {
  for (uint32_t v = 0; v < m->info.input_vertex_count; v++) {
    float x[3];
    load3(normals, ns, v, x);
    unit_normal(x, m->normals[v]); /* checked by check_update */
  }
  copy_split(m, m->normals);
}

/* Positions without normals: computed normals follow the new positions. A
 * failed update leaves the mesh as it was: smooth normals allocate their
 * scratch once, before anything is written (then nothing can fail); with
 * creases, if computing runs out of memory the old positions come back. */
static tlod_result update_positions_only(tlod_mesh* m, const float* positions, uint32_t ps) {
  if (!any_computed(m)) {
    write_positions(m, positions, ps);
    return TLOD_SUCCESS;
  }
  tlod_result r = _tlod_mesh_normals_prepare(m);
  if (r != TLOD_SUCCESS) return r;
  if (m->normal_sum) {
    write_positions(m, positions, ps);
    return _tlod_mesh_compute_normals(m);
  }
  float(*saved)[3] = _tlod_calloc(m->ctx, m->vertex_count, sizeof(*saved));
  if (!saved) return fail_oom(m, "update");
  memcpy(saved, m->positions, (size_t)m->vertex_count * sizeof(*saved));
  write_positions(m, positions, ps);
  r = _tlod_mesh_compute_normals(m);
  if (r != TLOD_SUCCESS) memcpy(m->positions, saved, (size_t)m->vertex_count * sizeof(*saved));
  _tlod_free(m->ctx, saved);
  return r;
}

/* The smooth flags compare the data of distinct vertices at one position,
 * and nodes: with neither, every linked edge is smooth whatever the data. */
static bool smooth_flags_can_change(const tlod_mesh* m) {
  if (m->face_nodes) return true;
  for (uint32_t v = 0; v < m->vertex_count; v++)
    if (m->weld_id[v] != v) return true;
  return false;
}

/* compute_bbox when every vertex is a face corner (no unused vertices, no
 * nodes): the same minima and maxima over the vertices, without the faces'
 * indirection, in independent chains (a float per lane). */
static void update_bbox(tlod_mesh* m) {
  float lo[3], hi[3];
  if (!vertex_bbox(m, lo, hi)) {
    compute_bbox(m);
    return;
  }
  store_bbox(m, lo, hi);
}

tlod_result tlod_mesh_update(tlod_mesh* mesh, const float* positions, uint32_t position_stride, const float* normals,
                             uint32_t normal_stride) {
  if (!mesh) return TLOD_ERROR_INVALID_ARGUMENT;
  uint32_t ps = position_stride ? position_stride : 12;
  uint32_t ns = normal_stride ? normal_stride : 12;
  tlod_result r = check_update(mesh, positions, ps, normals, ns);
  if (r != TLOD_SUCCESS || (!positions && !normals)) return r;
  if (positions && !normals) {
    r = update_positions_only(mesh, positions, ps);
  } else {
    if (positions) write_positions(mesh, positions, ps);
    write_normals(mesh, normals, ns);
  }
  if (r != TLOD_SUCCESS) return r;
  /* Smooth flags compare positions and normals bitwise; both may change. */
  if (smooth_flags_can_change(mesh)) _tlod_mesh_refresh_smooth(mesh);
  update_bbox(mesh);
  mesh->generation++;
  return TLOD_SUCCESS;
}

tlod_mesh_view tlod_mesh_query_view(const tlod_mesh* m) {
  if (!m) return (tlod_mesh_view){0};
  /* Explicit casts: C does not convert T (*)[3] to const T (*)[3] implicitly. */
  return (tlod_mesh_view){
      .vertex_count = m->vertex_count,
      .positions = (const float(*)[3])m->positions,
      .normals = (const float(*)[3])m->normals,
      .weld_id = m->weld_id,
      .face_count = m->face_count,
      .faces = (const uint32_t(*)[4])m->faces,
      .face_corners = m->face_corners,
      .links = (const tlod_edge_link(*)[4])m->links,
      .face_input_index = m->face_input,
      .attribute_count = m->attribute_count,
      .attributes = (const float(*)[4])m->attributes,
      .face_nodes = (const uint32_t(*)[TLOD_FACE_NODES])m->face_nodes,
      .generation = m->generation,
      .smooth_generation = m->smooth_generation,
  };
}
