/* tesslod::core -- surfaces: per-patch precomputation and the evaluation
 * entry point that routes corners, edges and interiors (docs/design.md
 * invariants 1 and 2). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "error_table_lanes.h"
#include "patch_lanes.h"

static tlod_surface_desc surface_desc_defaults(const tlod_surface_desc* in) {
  tlod_surface_desc d = in ? *in : (tlod_surface_desc){0};
  if (d.type == TLOD_SURFACE_DEFAULT) d.type = TLOD_SURFACE_PHONG;
  if (d.alpha_mode == TLOD_ALPHA_DEFAULT) d.alpha_mode = TLOD_ALPHA_GLOBAL, d.alpha = 0.75f;
  if (d.shading_normal == TLOD_SHADING_NORMAL_DEFAULT) d.shading_normal = TLOD_SHADING_NORMAL_INTERPOLATED;
  if (d.error_tables == TLOD_ERROR_TABLES_DEFAULT) d.error_tables = TLOD_ERROR_TABLES_MEASURED;
  if (!d.label) d.label = "surface";
  return d;
}

static void gather(const tlod_surface* s, uint32_t face, _tlod_corners* c) {
  const tlod_mesh* m = s->mesh;
  c->n = m->face_corners[face];
  for (uint32_t i = 0; i < c->n; i++) {
    uint32_t vi = m->faces[face][i];
    c->p[i] = v3_load(m->positions[vi]);
    c->nrm[i] = v3_load(m->normals[vi]);
    c->alpha[i] = s->alpha[vi];
  }
}

void _tlod_sphere_of(const _tlod_corners* c, const v3* extra, uint32_t extra_n, float grow, tlod_patch_info* info) {
  v3 center = c->p[0];
  for (uint32_t i = 1; i < c->n; i++)
    center = v3_add(center, c->p[i]);
  center = v3_scale(center, 1.0f / (float)c->n);
  /* Squared distances, one square root: sqrtf is correctly rounded and
   * monotone, so this is bitwise the largest distance. */
  float r2 = 0.0f;
  for (uint32_t i = 0; i < c->n; i++) {
    v3 d = v3_sub(c->p[i], center);
    r2 = v3_dot(d, d) > r2 ? v3_dot(d, d) : r2;
  }
  for (uint32_t i = 0; i < extra_n; i++) {
    v3 d = v3_sub(extra[i], center);
    r2 = v3_dot(d, d) > r2 ? v3_dot(d, d) : r2;
  }
  float r = sqrtf(r2);
  v3_store(info->center, center);
  /* Relative slack covers the rounding of the evaluation itself. */
  info->radius = (r + grow) * (1.0f + 1e-5f);
}

/* Per-level error tables (error_table.c): the cubic net a triangle needs
 * (PN: the control net; Phong with per-vertex alphas: alpha_net, computed
 * once in build_patch for the bound and the table; NULL otherwise), the quad
 * net computed above for Phong quads. */
static void build_error_table(tlod_surface* s, uint32_t f, const _tlod_corners* c, const double (*alpha_net)[3],
                              const double (*quad_net)[4][3]) {
  tlod_patch_info* info = &s->info[f];
  bool pn = s->desc.type == TLOD_SURFACE_PN;
  double net[10][3];
  for (int i = 0; pn && i < 10; i++)
    for (int k = 0; k < 3; k++)
      net[i][k] = s->pn[f].b[i][k];
  if (s->desc.error_tables == TLOD_ERROR_TABLES_CLOSED_FORM) {
    _tlod_error_table_closed(c, (const double(*)[3])net, pn ? 10 : 0, info);
    return;
  }
  bool phong = s->desc.type == TLOD_SURFACE_PHONG;
  if (c->n == 4) {
    _tlod_error_table(s->desc.type, c, NULL, phong ? quad_net : NULL, info);
    return;
  }
  if (pn) alpha_net = (const double(*)[3])net;
  _tlod_error_table(s->desc.type, c, alpha_net, NULL, info);
}

/* TLOD_ERROR_TABLES_NONE: every bound "unknown" (tlod_patch_error_bound()
 * then returns +INFINITY). */
static void no_tables(tlod_patch_info* info) {
  for (int l = 0; l < TLOD_ERROR_TABLE_LEVELS; l++)
    info->error_table[l] = INFINITY;
  info->error_tail = INFINITY;
  info->error_slack = 0.0f;
}

static void build_patch(tlod_surface* s, uint32_t f) {
  _tlod_corners c;
  gather(s, f, &c);
  tlod_patch_info* info = &s->info[f];
  info->corner_count = c.n;
  /* Phong without tables never comes here: build_range's untabled_patch. */
  bool none = s->desc.error_tables == TLOD_ERROR_TABLES_NONE;
  double quad_net[4][4][3], alpha_net[10][3];
  bool per_vertex = false;
  switch (s->desc.type) {
  case TLOD_SURFACE_QUADRATIC:
    /* Nodes, bounds, sphere and tables of its own (quadratic.c). */
    _tlod_quadratic_build(s, f, &c, &s->quad[f], info);
    if (none) no_tables(info);
    return;
  case TLOD_SURFACE_PN: {
    _tlod_pn_build(&c, &s->pn[f]);
    info->error_bound = _tlod_pn_bound(&s->pn[f], &c, &info->d_max);
    v3 ctrl[10];
    for (int i = 0; i < 10; i++)
      ctrl[i] = v3_load(s->pn[f].b[i]);
    /* Bernstein convex hull: the control points enclose the patch. */
    _tlod_sphere_of(&c, ctrl, 10, 0.0f, info);
    break;
  }
  case TLOD_SURFACE_PHONG:
    if (c.n == 3) {
      per_vertex = !(c.alpha[0] == c.alpha[1] && c.alpha[1] == c.alpha[2]);
      if (per_vertex) _tlod_phong_alpha_net(&c, alpha_net);
      info->error_bound = _tlod_phong_tri_bound(&c, per_vertex ? (const double(*)[3])alpha_net : NULL, &info->d_max);
    } else {
      _tlod_quad_net(&c, quad_net);
      info->error_bound = _tlod_quad_net_bound(quad_net, &c, &info->d_max);
    }
    _tlod_sphere_of(&c, NULL, 0, info->error_bound, info);
    break;
  default:
    /* gather() gave flat surfaces zero alphas: the quad bound is the bilinear one. */
    info->error_bound = c.n == 4 ? _tlod_quad_bound(&c, &info->d_max) : 0.0f;
    if (c.n == 3) info->d_max = 0.0f;
    _tlod_sphere_of(&c, NULL, 0, info->error_bound, info);
    break;
  }
  if (none)
    no_tables(info);
  else
    build_error_table(s, f, &c, per_vertex ? (const double(*)[3])alpha_net : NULL, quad_net);
}

/* Phong quads with tables are built in lanes of patches
 * (error_table_lanes.c): bitwise build_patch's bound, sphere and table. */
typedef struct quad_lanes {
  uint32_t n, face[_TLOD_QUAD_LANES];
  _tlod_corners c[_TLOD_QUAD_LANES];
} quad_lanes;

static void flush_quads(tlod_surface* s, quad_lanes* q) {
  if (!q->n) return;
  tlod_patch_info* info[_TLOD_QUAD_LANES];
  for (uint32_t i = 0; i < q->n; i++)
    info[i] = &s->info[q->face[i]], info[i]->corner_count = 4;
  _tlod_phong_quads(s->ctx->desc.simd, q->c, q->n, s->desc.error_tables, info);
  q->n = 0;
}

static bool in_lanes(const tlod_surface* s, uint32_t f) {
  return s->desc.type == TLOD_SURFACE_PHONG && s->desc.error_tables != TLOD_ERROR_TABLES_NONE &&
         s->mesh->face_corners[f] == 4;
}

/* Builds patch f now, or queues it for the next lanes (flush_quads). */
static void build_or_queue(tlod_surface* s, uint32_t f, quad_lanes* q) {
  if (!in_lanes(s, f)) {
    build_patch(s, f);
    return;
  }
  gather(s, f, &q->c[q->n]);
  q->face[q->n++] = f;
  if (q->n == _TLOD_QUAD_LANES) flush_quads(s, q);
}

/* Phong without tables: a patch's sphere is all it computes (at creation,
 * and all that moves on a refresh), made in lanes of patches of one corner
 * count (surface_spheres.c; the rule: docs/design.md 3.5b, "Two modes"). */
typedef struct sphere_queue {
  uint32_t n[2], face[2][PATCH_LANES];
} sphere_queue;

static void flush_spheres(const tlod_surface* s, sphere_queue* q, uint32_t k) {
  _tlod_phong_spheres(s, s->ctx->desc.simd, q->face[k], q->n[k]);
  q->n[k] = 0;
}

static void queue_sphere(const tlod_surface* s, sphere_queue* q, uint32_t f) {
  uint32_t k = s->mesh->face_corners[f] == 4;
  q->face[k][q->n[k]++] = f;
  if (q->n[k] == PATCH_LANES) flush_spheres(s, q, k);
}

static bool spheres_only(const tlod_surface* s) {
  return s->desc.type == TLOD_SURFACE_PHONG && s->desc.error_tables == TLOD_ERROR_TABLES_NONE;
}

static void flush_all_spheres(const tlod_surface* s, sphere_queue* q) {
  for (uint32_t k = 0; k < 2; k++)
    if (q->n[k]) flush_spheres(s, q, k);
}

/* Patch f without tables: what does not move, its sphere queued. */
static void untabled_patch(tlod_surface* s, uint32_t f, sphere_queue* q) {
  tlod_patch_info* info = &s->info[f];
  info->corner_count = s->mesh->face_corners[f];
  info->error_bound = INFINITY;
  info->d_max = INFINITY;
  no_tables(info);
  queue_sphere(s, q, f);
}

static void build_range(void* data, uint32_t begin, uint32_t end, uint32_t worker) {
  (void)worker;
  tlod_surface* s = data;
  if (spheres_only(s)) {
    sphere_queue sq = {.n = {0}};
    for (uint32_t f = begin; f < end; f++)
      untabled_patch(s, f, &sq);
    flush_all_spheres(s, &sq);
    return;
  }
  quad_lanes q = {0};
  for (uint32_t f = begin; f < end; f++)
    build_or_queue(s, f, &q);
  flush_quads(s, &q);
}

static tlod_result validate_surface_desc(tlod_context* ctx, const tlod_mesh* mesh, const tlod_surface_desc* d) {
  if ((unsigned)d->type >= TLOD_SURFACE_NUM)
    return _tlod_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "surface '%s': unknown type %d", d->label, (int)d->type);
  if ((unsigned)d->shading_normal >= TLOD_SHADING_NORMAL_NUM)
    return _tlod_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "surface '%s': unknown shading normal %d", d->label,
                      (int)d->shading_normal);
  if ((unsigned)d->alpha_mode >= TLOD_ALPHA_NUM)
    return _tlod_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "surface '%s': unknown alpha mode %d", d->label,
                      (int)d->alpha_mode);
  if ((unsigned)d->error_tables >= TLOD_ERROR_TABLES_NUM)
    return _tlod_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "surface '%s': unknown error_tables mode %d", d->label,
                      (int)d->error_tables);
  if (d->alpha_mode == TLOD_ALPHA_GLOBAL && !(d->alpha >= 0.0f && d->alpha <= 1.0f))
    return _tlod_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "surface '%s': alpha %g outside [0, 1]", d->label,
                      (double)d->alpha);
  if (d->alpha_mode == TLOD_ALPHA_PER_VERTEX && !mesh->alphas)
    return _tlod_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT,
                      "surface '%s': alpha mode PER_VERTEX but mesh '%s' has no alphas", d->label, mesh->label);
  if (d->type == TLOD_SURFACE_PN) {
    for (uint32_t f = 0; f < mesh->face_count; f++) {
      if (mesh->face_corners[f] != 3)
        return _tlod_fail(ctx, TLOD_ERROR_UNSUPPORTED,
                          "surface '%s': PN triangles need triangles, but face %u of mesh '%s' is a quad "
                          "(use Phong, or triangulate)",
                          d->label, mesh->face_input[f], mesh->label);
    }
  }
  return TLOD_SUCCESS;
}

void tlod_surface_destroy(tlod_surface* s) {
  if (!s) return;
  tlod_context* ctx = s->ctx;
  _tlod_free(ctx, s->info);
  _tlod_free(ctx, s->pn);
  _tlod_free(ctx, s->quad);
  _tlod_free(ctx, s->alpha);
  _tlod_free(ctx, s->snapshot);
  _tlod_free(ctx, s->changed);
  _tlod_free(ctx, s);
}

static tlod_result alloc_surface(tlod_context* ctx, const tlod_mesh* mesh, tlod_surface* s) {
  s->info = _tlod_calloc(ctx, mesh->face_count, sizeof(*s->info));
  s->alpha = _tlod_calloc(ctx, mesh->vertex_count, sizeof(float));
  s->snapshot = _tlod_calloc(ctx, mesh->vertex_count, sizeof(*s->snapshot));
  if (s->desc.type == TLOD_SURFACE_PN) s->pn = _tlod_calloc(ctx, mesh->face_count, sizeof(*s->pn));
  if (s->desc.type == TLOD_SURFACE_QUADRATIC) s->quad = _tlod_calloc(ctx, mesh->face_count, sizeof(*s->quad));
  if (!s->info || !s->alpha || !s->snapshot || (s->desc.type == TLOD_SURFACE_PN && !s->pn) ||
      (s->desc.type == TLOD_SURFACE_QUADRATIC && !s->quad))
    return _tlod_fail(ctx, TLOD_ERROR_OUT_OF_MEMORY, "surface '%s': out of memory for %u patches", s->desc.label,
                      mesh->face_count);
  return TLOD_SUCCESS;
}

static void take_snapshot(tlod_surface* s) {
  const tlod_mesh* m = s->mesh;
  for (uint32_t v = 0; v < m->vertex_count; v++) {
    memcpy(s->snapshot[v], m->positions[v], sizeof(float) * 3);
    memcpy(s->snapshot[v] + 3, m->normals[v], sizeof(float) * 3);
  }
}

tlod_result tlod_surface_create(tlod_context* ctx, const tlod_mesh* mesh, const tlod_surface_desc* desc,
                                tlod_surface** out) {
  if (!out)
    return ctx ? _tlod_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "tlod_surface_create: out is NULL")
               : TLOD_ERROR_INVALID_ARGUMENT;
  *out = NULL;
  if (!ctx) return TLOD_ERROR_INVALID_ARGUMENT;
  if (!mesh) return _tlod_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "tlod_surface_create: mesh is NULL");
  tlod_surface_desc d = surface_desc_defaults(desc);
  tlod_result r = validate_surface_desc(ctx, mesh, &d);
  if (r != TLOD_SUCCESS) return r;
  tlod_surface* s = _tlod_calloc(ctx, 1, sizeof(*s));
  if (!s) return _tlod_fail(ctx, TLOD_ERROR_OUT_OF_MEMORY, "surface '%s': out of memory", d.label);
  s->ctx = ctx;
  s->generation = 1;
  s->mesh = mesh;
  s->desc = d;
  snprintf(s->label, sizeof(s->label), "%s", d.label);
  s->desc.label = s->label;
  s->patch_count = mesh->face_count;
  r = alloc_surface(ctx, mesh, s);
  if (r != TLOD_SUCCESS) {
    tlod_surface_destroy(s);
    return r;
  }
  for (uint32_t v = 0; v < mesh->vertex_count; v++)
    s->alpha[v] =
        d.type == TLOD_SURFACE_FLAT ? 0.0f : (d.alpha_mode == TLOD_ALPHA_PER_VERTEX ? mesh->alphas[v] : d.alpha);
  take_snapshot(s);
  _tlod_parallel_for(ctx, build_range, s, s->patch_count);
  *out = s;
  return TLOD_SUCCESS;
}

/* Flags the vertices whose position or normal differs (bitwise) from the
 * snapshot, and takes their new values into it (the patches are rebuilt
 * from the mesh, not from the snapshot). */
static void mark_vertices(void* data, uint32_t begin, uint32_t end, uint32_t worker) {
  (void)worker;
  tlod_surface* s = data;
  const tlod_mesh* m = s->mesh;
  for (uint32_t v = begin; v < end; v++) {
    float* snap = s->snapshot[v];
    bool changed = memcmp(snap, m->positions[v], sizeof(float) * 3) != 0 ||
                   memcmp(snap + 3, m->normals[v], sizeof(float) * 3) != 0;
    s->changed[v] = changed;
    if (!changed) continue;
    memcpy(snap, m->positions[v], sizeof(float) * 3);
    memcpy(snap + 3, m->normals[v], sizeof(float) * 3);
  }
}

/* A patch depends on its corners and, on a quadratic surface, its nodes. */
static bool face_changed(const tlod_surface* s, uint32_t f) {
  const tlod_mesh* m = s->mesh;
  const uint8_t* changed = s->changed;
  for (uint32_t i = 0; i < m->face_corners[f]; i++)
    if (changed[m->faces[f][i]]) return true;
  for (uint32_t i = 0; s->quad && m->face_nodes && i < TLOD_FACE_NODES; i++)
    if (m->face_nodes[f][i] != _TLOD_NONE && changed[m->face_nodes[f][i]]) return true;
  return false;
}

/* Rebuilds the patches some vertex of which changed; flags them. */
static void rebuild_range(void* data, uint32_t begin, uint32_t end, uint32_t worker) {
  (void)worker;
  tlod_surface* s = data;
  uint8_t* dirty = s->changed + s->mesh->vertex_count;
  bool spheres = spheres_only(s);
  quad_lanes q = {0};
  sphere_queue sq = {.n = {0}};
  for (uint32_t f = begin; f < end; f++) {
    dirty[f] = face_changed(s, f);
    if (!dirty[f]) continue;
    if (spheres)
      queue_sphere(s, &sq, f);
    else
      build_or_queue(s, f, &q);
  }
  flush_quads(s, &q);
  flush_all_spheres(s, &sq);
}

/* Flags are kept between calls: a refresh allocates only the first time. */
tlod_result tlod_surface_refresh(tlod_surface* s, uint32_t* updated) {
  if (updated) *updated = 0;
  if (!s) return TLOD_ERROR_INVALID_ARGUMENT;
  const tlod_mesh* m = s->mesh;
  if (!s->changed) s->changed = _tlod_calloc(s->ctx, (size_t)m->vertex_count + m->face_count + 1, 1);
  if (!s->changed) return _tlod_fail(s->ctx, TLOD_ERROR_OUT_OF_MEMORY, "surface '%s': out of memory", s->label);
  _tlod_parallel_for(s->ctx, mark_vertices, s, m->vertex_count);
  _tlod_parallel_for(s->ctx, rebuild_range, s, m->face_count);
  const uint8_t* dirty = s->changed + m->vertex_count;
  uint32_t count = 0;
  for (uint32_t f = 0; f < m->face_count; f++)
    count += dirty[f];
  s->generation += count > 0;
  if (updated) *updated = count;
  return TLOD_SUCCESS;
}

tlod_surface_desc tlod_surface_query_desc(const tlod_surface* s) { return s ? s->desc : (tlod_surface_desc){0}; }
const tlod_mesh* tlod_surface_mesh(const tlod_surface* s) { return s ? s->mesh : NULL; }
uint32_t tlod_surface_patch_count(const tlod_surface* s) { return s ? s->patch_count : 0; }

tlod_patch_info tlod_surface_patch(const tlod_surface* s, uint32_t patch) {
  if (!s || patch >= s->patch_count) return (tlod_patch_info){0};
  return s->info[patch];
}

void _tlod_edge_eval(const tlod_surface* s, uint32_t a, uint32_t b, float t, float pos[3], float nrm[3]) {
  const tlod_mesh* m = s->mesh;
  v3 pa = v3_load(m->positions[a]), pb = v3_load(m->positions[b]);
  v3 na = v3_load(m->normals[a]), nb = v3_load(m->normals[b]);
  v3 p, n;
  switch (s->desc.type) {
  case TLOD_SURFACE_PN:
    _tlod_pn_edge(pa, na, pb, nb, t, &p, &n);
    break;
  case TLOD_SURFACE_PHONG:
    _tlod_phong_edge(pa, na, s->alpha[a], pb, nb, s->alpha[b], t, &p, &n);
    break;
  default:
    _tlod_flat_edge(pa, na, pb, nb, t, &p, &n);
    break;
  }
  v3_store(pos, p);
  v3_store(nrm, n);
}

void _tlod_patch_corners(const tlod_surface* s, uint32_t patch, _tlod_corners* c) { gather(s, patch, c); }

void _tlod_patch_eval_with(const tlod_surface* s, uint32_t patch, const _tlod_corners* c, float u, float v,
                           uint32_t flags, tlod_surface_point* out) {
  if (s->desc.shading_normal == TLOD_SHADING_NORMAL_TRUE) flags |= _TLOD_EVAL_TRUE_NORMAL;
  switch (s->desc.type) {
  case TLOD_SURFACE_PN:
    _tlod_pn_eval(&s->pn[patch], c, u, v, flags, out);
    break;
  case TLOD_SURFACE_PHONG:
    _tlod_phong_eval(c, u, v, flags, out);
    return;
  case TLOD_SURFACE_QUADRATIC:
    _tlod_quadratic_eval(&s->quad[patch], c, u, v, out);
    break;
  default:
    _tlod_flat_eval(c, u, v, out);
    break;
  }
  if (flags & _TLOD_EVAL_TRUE_NORMAL) {
    v3 n = v3_normalize(v3_cross(v3_load(out->tangent), v3_load(out->bitangent)));
    if (n.x != 0.0f || n.y != 0.0f || n.z != 0.0f) v3_store(out->normal, n);
  }
}

void _tlod_patch_eval(const tlod_surface* s, uint32_t patch, float u, float v, tlod_surface_point* out) {
  _tlod_corners c;
  gather(s, patch, &c);
  _tlod_patch_eval_with(s, patch, &c, u, v, _TLOD_EVAL_DERIVS, out);
}

/* Where (u, v) lies on edge e of the patch, the weight of its end corner. */
static bool on_edge(uint32_t n, float u, float v, uint32_t* edge, float* t_end) {
  if (n == 3) {
    float w = 1.0f - u - v;
    if (w == 0.0f) return *edge = 0, *t_end = v, true; /* i -> j */
    if (u == 0.0f) return *edge = 1, *t_end = w, true; /* j -> k */
    if (v == 0.0f) return *edge = 2, *t_end = u, true; /* k -> i */
    return false;
  }
  if (v == 0.0f) return *edge = 0, *t_end = u, true;        /* 0 -> 1 */
  if (u == 1.0f) return *edge = 1, *t_end = v, true;        /* 1 -> 2 */
  if (v == 1.0f) return *edge = 2, *t_end = 1.0f - u, true; /* 2 -> 3 */
  if (u == 0.0f) return *edge = 3, *t_end = 1.0f - v, true; /* 3 -> 0 */
  return false;
}

void _tlod_patch_edge_point(const tlod_surface* s, uint32_t patch, uint32_t edge, float t_end, float pos[3],
                            float nrm[3]) {
  const tlod_mesh* m = s->mesh;
  uint32_t n = m->face_corners[patch];
  uint32_t a = m->faces[patch][edge], b = m->faces[patch][(edge + 1) % n];
  if (t_end == 0.0f || t_end == 1.0f) {
    uint32_t corner = t_end == 0.0f ? a : b;
    memcpy(pos, m->positions[corner], sizeof(float) * 3);
    memcpy(nrm, m->normals[corner], sizeof(float) * 3);
    return;
  }
  /* Canonical direction: from the smaller welded id, so both sides agree. */
  bool forward = m->weld_id[a] < m->weld_id[b];
  if (s->quad)
    _tlod_quadratic_edge_point(s, patch, edge, forward ? a : b, forward ? b : a, forward ? t_end : 1.0f - t_end, pos,
                               nrm);
  else if (forward)
    _tlod_edge_eval(s, a, b, t_end, pos, nrm);
  else
    _tlod_edge_eval(s, b, a, 1.0f - t_end, pos, nrm);
}

tlod_result tlod_surface_eval(const tlod_surface* s, uint32_t patch, float u, float v, tlod_surface_point* out) {
  /* No last error: this runs on many threads at once (tesslod/core.h). */
  if (!s || !out || patch >= s->patch_count || !isfinite(u) || !isfinite(v)) {
    if (out) memset(out, 0, sizeof(*out));
    return TLOD_ERROR_INVALID_ARGUMENT;
  }
  _tlod_patch_eval(s, patch, u, v, out);
  uint32_t edge;
  float t_end, normal[3];
  if (on_edge(s->mesh->face_corners[patch], u, v, &edge, &t_end)) {
    /* True normals depend on the patch's own derivatives: keep them. */
    float* nrm = s->desc.shading_normal == TLOD_SHADING_NORMAL_TRUE ? normal : out->normal;
    _tlod_patch_edge_point(s, patch, edge, t_end, out->position, nrm);
  }
  return TLOD_SUCCESS;
}
