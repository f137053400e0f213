/*
 * degenerate_test.c -- degenerate and hostile geometry through the whole
 * pipeline (issue #10): tlod_mesh_create -> tlod_surface_create for every
 * surface type (flat, Phong with a global alpha, Phong with per-vertex
 * alphas, PN) -> scheduler frames from three cameras -> CPU tessellation of
 * each view's draw list and of a uniform level.
 *
 * Each case either is refused, with a message naming the element at fault
 * (vertex or face index), or works: every patch bound, evaluated point,
 * scheduler measure and output position and normal is finite, output
 * normals are unit, and a closed input gives a closed output (every edge
 * used once in each direction, positions compared bitwise; where pattern
 * points are closer than the float resolution of their coordinates, as on a
 * unit sphere 3e5 from the origin, they may round to one position: then
 * collapsed triangles are allowed, cracks are not). Which of the
 * two a case gets is part of the contract (tesslod/core.h CONTRACT):
 *   works:   a single triangle, an isolated (unused) vertex, holes, a
 *            non-manifold edge (three faces on it: counted, each face keeps
 *            its own border there), coincident vertices with different
 *            indices (welded; different normals make a crease), slivers,
 *            zero-area faces among good ones (dropped, counted), zero, NaN,
 *            opposite or tangent normals (repaired or used: finite output),
 *            coordinates at +-TLOD_POSITION_LIMIT and tiny ones;
 *   refused: NaN / Inf / beyond-limit positions (naming the vertex),
 *            indices >= vertex_count up to 2^32 - 1 (naming the face), a
 *            mesh of zero-area faces only (naming a face), quads for PN
 *            (naming the face).
 * Public headers only.
 */
#include <float.h>
#include <stdint.h>

#include "shapes.h"
#include "tesslod/cpu.h"
#include "tesslod/lod.h"
#include "test.h"
#include "test_camera.h"
#include "test_context.h"

#define MAX_LEVEL 4
#define CAP_V 1024
#define CAP_I 4096

/* ------------------------------------------------------------------------ */
/* Cases                                                                    */
/* ------------------------------------------------------------------------ */

typedef struct dcase {
  const char* name;
  float positions[CAP_V][3];
  float normals[CAP_V][3];
  bool has_normals;
  uint32_t vertex_count;
  uint32_t indices[CAP_I];
  uint32_t index_count;
  tlod_face_type face_type;
  bool closed;            /* closed input (tlod_mesh_info): the output must be closed too */
  bool coincident_sheets; /* closed, but two faces cover each other: output not checked for closedness */
  bool float_limited;     /* pattern points finer than float resolution: output checked for cracks only */
  const char* refused;    /* NULL: must work; else a substring of the refusal */
  tlod_result expected;   /* the refusal's code */
} dcase;

static dcase g_case; /* one at a time; large arrays off the stack */

static dcase* case_begin(const char* name, tlod_face_type type, bool closed) {
  memset(&g_case, 0, sizeof g_case);
  g_case.name = name;
  g_case.face_type = type;
  g_case.closed = closed;
  return &g_case;
}

static uint32_t add_vertex(dcase* c, double x, double y, double z) {
  uint32_t v = c->vertex_count++;
  c->positions[v][0] = (float)x, c->positions[v][1] = (float)y, c->positions[v][2] = (float)z;
  return v;
}

static void set_normal(dcase* c, uint32_t v, double x, double y, double z) {
  c->has_normals = true;
  c->normals[v][0] = (float)x, c->normals[v][1] = (float)y, c->normals[v][2] = (float)z;
}

static void add_face(dcase* c, uint32_t n, const uint32_t* idx) {
  for (uint32_t i = 0; i < n; i++)
    c->indices[c->index_count++] = idx[i];
}

#define TRI(c, a, b, d) add_face(c, 3, (const uint32_t[3]){a, b, d})

static void refuse(dcase* c, tlod_result code, const char* what) {
  c->expected = code;
  c->refused = what;
}

/* A shapes.h shape scaled about the origin (normals, if any, kept). */
static void add_shape(dcase* c, const shape* s, double scale) {
  uint32_t base = c->vertex_count;
  for (uint32_t v = 0; v < s->vertex_count; v++) {
    const float* p = s->positions + 3 * (size_t)v;
    add_vertex(c, p[0] * scale, p[1] * scale, p[2] * scale);
    if (s->normals) set_normal(c, base + v, s->normals[3 * v], s->normals[3 * v + 1], s->normals[3 * v + 2]);
  }
  for (uint32_t i = 0; i < s->index_count; i++)
    c->indices[c->index_count++] = base + s->indices[i];
}

/* Closed tetrahedron, counter-clockwise from outside, with vertex `top` last. */
static void add_tetrahedron(dcase* c, double top) {
  uint32_t a = add_vertex(c, 0, 0, 0), b = add_vertex(c, 1, 0, 0), d = add_vertex(c, 0, 1, 0);
  uint32_t t = add_vertex(c, 0.3, 0.3, top);
  TRI(c, a, d, b);
  TRI(c, a, b, t);
  TRI(c, b, d, t);
  TRI(c, d, a, t);
}

/* ------------------------------------------------------------------------ */
/* Checks of a working case                                                 */
/* ------------------------------------------------------------------------ */

static bool finite3(const float* x) { return isfinite(x[0]) && isfinite(x[1]) && isfinite(x[2]); }

static double length3f(const float* x) { return sqrt((double)x[0] * x[0] + (double)x[1] * x[1] + (double)x[2] * x[2]); }

static void check_patches(const tlod_surface* s, const char* what) {
  tlod_surface_view sv = tlod_surface_query_view(s);
  for (uint32_t p = 0; p < sv.patch_count; p++) {
    const tlod_patch_info* in = &sv.patches[p];
    bool ok = finite3(in->center) && isfinite(in->radius) && isfinite(in->error_bound) && isfinite(in->error_tail) &&
              isfinite(in->error_slack);
    for (int l = 0; l < TLOD_ERROR_TABLE_LEVELS; l++)
      ok = ok && isfinite(in->error_table[l]);
    CHECK_MSG(ok, "%s: patch %u: bound or sphere not finite", what, p);
    static const float uv[6][2] = {{1, 0}, {0.5f, 0.5f}, {1.0f / 3, 1.0f / 3}, {0.1f, 0.8f}, {0.25f, 0}, {0, 0}};
    for (int k = 0; k < 6; k++) {
      tlod_surface_point pt;
      CHECK(tlod_surface_eval(s, p, uv[k][0], uv[k][1], &pt) == TLOD_SUCCESS);
      bool fin = finite3(pt.position) && finite3(pt.normal) && finite3(pt.tangent) && finite3(pt.bitangent);
      CHECK_MSG(fin, "%s: patch %u at (%g, %g): point not finite", what, p, (double)uv[k][0], (double)uv[k][1]);
      CHECK_MSG(fabs(length3f(pt.normal) - 1.0) < 1e-3, "%s: patch %u at (%g, %g): normal length %g", what, p,
                (double)uv[k][0], (double)uv[k][1], length3f(pt.normal));
    }
  }
}

static void check_draw_list(const tlod_draw_list* dl, uint32_t vertex_count, const char* what) {
  for (uint32_t p = 0; p < dl->patch_count; p++)
    CHECK_MSG(!isnan(dl->e_max[p]) && dl->e_max[p] >= 0.0f, "%s: patch %u: e_max %g", what, p, (double)dl->e_max[p]);
  for (uint32_t v = 0; v < vertex_count; v++)
    CHECK_MSG(isfinite(dl->vertex_depth[v]), "%s: vertex %u: depth %g", what, v, (double)dl->vertex_depth[v]);
  for (uint32_t i = 0; i < dl->instance_count; i++) {
    const tlod_draw_instance* in = &dl->instances[i];
    bool ok = isfinite(in->morph);
    CHECK_MSG(ok, "%s: instance %u (patch %u): morph not finite", what, i, in->patch);
  }
  CHECK_MSG(isfinite(dl->effective_epsilon), "%s: effective epsilon %g", what, (double)dl->effective_epsilon);
}

static void check_output(const tlod_cpu_mesh* m, bool closed, const char* what) {
  CHECK_MSG(m->triangle_count > 0 || !closed, "%s: no triangles", what);
  for (uint32_t v = 0; v < m->vertex_count; v++) {
    CHECK_MSG(finite3(m->positions + 3 * (size_t)v), "%s: output vertex %u: position not finite", what, v);
    const float* n = m->normals + 3 * (size_t)v;
    CHECK_MSG(finite3(n) && fabs(length3f(n) - 1.0) < 1e-3, "%s: output vertex %u: normal (%g, %g, %g)", what, v,
              (double)n[0], (double)n[1], (double)n[2]);
  }
  if (!closed || m->triangle_count == 0) return;
  if (g_case.float_limited) {
    /* Neighbouring pattern points a float ulp apart round to one position:
     * collapsed triangles, but no crack (no half-edge without its twin). */
    shape_census cs = shape_half_edge_census(m->positions, m->vertex_count, m->indices, m->triangle_count, NULL, 0);
    CHECK_MSG(cs.open == 0, "%s: closed input, %u open half-edges in the output", what, cs.open);
    return;
  }
  char why[256];
  bool ok = shape_closed_manifold(m->positions, m->vertex_count, m->indices, m->triangle_count, m->triangle_patch, why,
                                  sizeof why);
  CHECK_MSG(ok, "%s: closed input, open output: %s", what, why);
}

/* Three cameras around the mesh's bounding box: near perspective, far
 * perspective from another side, orthographic from below. */
static void cameras_for(const tlod_mesh* mesh, tlod_view_desc views[3]) {
  tlod_mesh_info info = tlod_mesh_query_info(mesh);
  double c[3], r = 0;
  for (int k = 0; k < 3; k++) {
    c[k] = 0.5 * ((double)info.bbox_min[k] + info.bbox_max[k]);
    double h = 0.5 * ((double)info.bbox_max[k] - info.bbox_min[k]);
    r += h * h;
  }
  r = sqrt(r);
  if (!(r > 0)) r = 1;
  static const double dirs[3][3] = {{0.6, -0.7, 0.4}, {-0.3, 0.5, 0.8}, {0.1, 0.2, -1.0}};
  static const double dist[3] = {1.6, 6.0, 4.0};
  for (int k = 0; k < 3; k++) {
    double d[3] = {dirs[k][0], dirs[k][1], dirs[k][2]};
    shape_normalize3(d);
    camera cam = {.fovy = 0.9, .half_h = 1.2 * r, .aspect = 4.0 / 3.0, .ortho = k == 2, .width = 320, .height = 240};
    for (int i = 0; i < 3; i++)
      cam.eye[i] = c[i] + dist[k] * r * d[i], cam.target[i] = c[i];
    cam.up[0] = 0, cam.up[1] = 0, cam.up[2] = 1;
    if (fabs(d[2]) > 0.9) cam.up[1] = 1, cam.up[2] = 0;
    cam.znear = 0.01 * r, cam.zfar = (dist[k] + 2) * r;
    views[k] = make_view(&cam);
  }
}

typedef struct pipeline {
  tlod_context* ctx;
  tlod_mesh* mesh;
  tlod_surface* surf;
  tlod_patterns* pat;
  tlod_scheduler* sched;
  tlod_cpu_mesh* out;
} pipeline;

static void pipeline_free(pipeline* p) {
  tlod_cpu_mesh_destroy(p->ctx, p->out);
  tlod_scheduler_destroy(p->sched);
  tlod_patterns_destroy(p->pat);
  tlod_surface_destroy(p->surf);
  tlod_mesh_destroy(p->mesh);
  memset(p, 0, sizeof *p);
}

/* Frames for three views, each view's draw list realised, then a uniform level. */
static void run_frames(pipeline* p, tlod_scheduler_desc sd, bool closed, const char* what) {
  tlod_result r = tlod_scheduler_create(p->ctx, p->surf, p->pat, &sd, &p->sched);
  CHECK_MSG(r == TLOD_SUCCESS, "%s: scheduler: %s", what, tlod_context_last_error(p->ctx));
  tlod_view_desc views[3];
  cameras_for(p->mesh, views);
  uint32_t nv = tlod_mesh_vertex_count(p->mesh);
  for (int frame = 0; frame < 2; frame++) {
    r = tlod_scheduler_update(p->sched, &(tlod_frame_desc){.views = views, .view_count = 3, .dt_ms = 50});
    CHECK_MSG(r == TLOD_SUCCESS, "%s: update: %s", what, tlod_context_last_error(p->ctx));
    for (uint32_t v = 0; v < 3; v++) {
      const tlod_draw_list* dl = tlod_scheduler_draw_list(p->sched, v);
      char at[160];
      snprintf(at, sizeof at, "%s, frame %d, view %u", what, frame, v);
      CALL(check_draw_list(dl, nv, at));
      tlod_cpu_tessellate_desc td = {.draw_list = dl};
      r = p->out ? tlod_cpu_tessellate_into(p->ctx, p->surf, p->pat, &td, p->out)
                 : tlod_cpu_tessellate(p->ctx, p->surf, p->pat, &td, &p->out);
      CHECK_MSG(r == TLOD_SUCCESS, "%s: tessellate: %s", at, tlod_context_last_error(p->ctx));
      CALL(check_output(p->out, closed && dl->culled == 0, at));
    }
  }
  tlod_cpu_tessellate_desc td = {.level = MAX_LEVEL - 1};
  r = tlod_cpu_tessellate_into(p->ctx, p->surf, p->pat, &td, p->out);
  CHECK_MSG(r == TLOD_SUCCESS, "%s: tessellate uniform: %s", what, tlod_context_last_error(p->ctx));
  CALL(check_output(p->out, closed, what));
}

/* A per-vertex alpha that depends on the position only, so coincident
 * vertices agree (their edge stays smooth). */
static float alpha_of(const float* x) {
  uint32_t b[3];
  memcpy(b, x, sizeof b);
  return 0.1f + 0.1f * (float)((b[0] ^ (b[1] >> 3) ^ (b[2] >> 7)) % 9u);
}

typedef struct variant {
  const char* name;
  tlod_surface_desc desc;
} variant;

static const variant k_variants[] = {
    {"flat", {.type = TLOD_SURFACE_FLAT}},
    {"phong", {.type = TLOD_SURFACE_PHONG, .alpha_mode = TLOD_ALPHA_GLOBAL, .alpha = 0.75f}},
    {"phong-vertex", {.type = TLOD_SURFACE_PHONG, .alpha_mode = TLOD_ALPHA_PER_VERTEX}},
    {"pn", {.type = TLOD_SURFACE_PN}},
    {"pn-true", {.type = TLOD_SURFACE_PN, .shading_normal = TLOD_SHADING_NORMAL_TRUE}},
};

static tlod_mesh_desc case_desc(const dcase* c, const float* alphas) {
  return (tlod_mesh_desc){.positions = &c->positions[0][0],
                          .normals = c->has_normals ? &c->normals[0][0] : NULL,
                          .alphas = alphas,
                          .vertex_count = c->vertex_count,
                          .indices = c->indices,
                          .index_count = c->index_count,
                          .face_type = c->face_type,
                          .label = c->name};
}

/* A refusal: the right code, no object, the element named. */
static void check_refused(tlod_result r, const void* out, tlod_result code, const char* want, const char* error,
                          const char* what) {
  CHECK_MSG(r == code, "%s: %s, expected %s (%s)", what, tlod_result_string(r), tlod_result_string(code), error);
  CHECK_MSG(out == NULL, "%s: refused but an object came back", what);
  CHECK_MSG(strstr(error, want) != NULL, "%s: message '%s' does not name '%s'", what, error, want);
}

/* One variant of the current case. */
static void run_variant(tlod_context* ctx, const dcase* c, const variant* va) {
  static float alphas[CAP_V];
  for (uint32_t v = 0; v < c->vertex_count; v++)
    alphas[v] = alpha_of(c->positions[v]);
  char what[160];
  snprintf(what, sizeof what, "%s / %s", c->name, va->name);
  pipeline p = {.ctx = ctx};
  tlod_mesh_desc md = case_desc(c, alphas);
  tlod_result r = tlod_mesh_create(ctx, &md, &p.mesh);
  if (c->refused) {
    CALL(check_refused(r, p.mesh, c->expected, c->refused, tlod_context_last_error(ctx), what));
    return;
  }
  CHECK_MSG(r == TLOD_SUCCESS, "%s: mesh: %s", what, tlod_context_last_error(ctx));
  tlod_mesh_info info = tlod_mesh_query_info(p.mesh);
  CHECK_MSG(info.closed == c->closed, "%s: mesh closed %d, the case says %d", what, info.closed, c->closed);
  r = tlod_surface_create(ctx, p.mesh, &va->desc, &p.surf);
  if (va->desc.type == TLOD_SURFACE_PN && info.quad_count > 0) {
    check_refused(r, p.surf, TLOD_ERROR_UNSUPPORTED, "is a quad", tlod_context_last_error(ctx), what);
    CHECK_MSG(strstr(tlod_context_last_error(ctx), "face "), "%s: '%s'", what, tlod_context_last_error(ctx));
    pipeline_free(&p);
    return;
  }
  if (r == TLOD_SUCCESS) r = tlod_patterns_create(ctx, &(tlod_patterns_desc){.max_level = MAX_LEVEL}, &p.pat);
  if (r != TLOD_SUCCESS) {
    CHECK_MSG(false, "%s: surface: %s", what, tlod_context_last_error(ctx));
    pipeline_free(&p);
    return;
  }
  int failed = _test_checks_failed;
  check_patches(p.surf, what);
  bool closed = c->closed && !c->coincident_sheets;
  if (_test_checks_failed == failed) run_frames(&p, (tlod_scheduler_desc){.epsilon_px = 0.5f}, closed, what);
  if (_test_checks_failed == failed) {
    tlod_scheduler_destroy(p.sched);
    p.sched = NULL;
    tlod_scheduler_desc sd = {.policy = TLOD_POLICY_ERROR, .morph = TLOD_MORPH_CONTINUOUS, .epsilon_px = 0.2f};
    run_frames(&p, sd, closed, what);
  }
  pipeline_free(&p);
}

static void run_case(const dcase* c) {
  tlod_context* ctx = new_context(2, NULL, NULL);
  CHECK(ctx);
  for (size_t k = 0; k < sizeof k_variants / sizeof k_variants[0]; k++)
    run_variant(ctx, c, &k_variants[k]);
  tlod_context_destroy(ctx);
}

/* The closed tetrahedron plus vertex 4 at (x, y, z) and a face that must be
 * dropped (it has no area). */
static void run_tetrahedron_plus(const char* name, double x, double y, double z, const uint32_t face[3]) {
  dcase* c = case_begin(name, TLOD_FACE_TRIANGLES, true);
  add_tetrahedron(c, 1.0);
  add_vertex(c, x, y, z);
  add_face(c, 3, face);
  run_case(c);
}

/* ------------------------------------------------------------------------ */
/* Topology                                                                 */
/* ------------------------------------------------------------------------ */

TEST(single_triangle) {
  dcase* c = case_begin("single triangle", TLOD_FACE_TRIANGLES, false);
  add_vertex(c, 0, 0, 0), add_vertex(c, 1, 0, 0), add_vertex(c, 0, 1, 0.2);
  TRI(c, 0, 1, 2);
  run_case(c);
  c = case_begin("single quad", TLOD_FACE_QUADS, false);
  add_vertex(c, 0, 0, 0), add_vertex(c, 1, 0, 0), add_vertex(c, 1, 1, 0.3), add_vertex(c, 0, 1, 0);
  add_face(c, 4, (const uint32_t[4]){0, 1, 2, 3});
  run_case(c);
}

TEST(isolated_vertex) {
  dcase* c = case_begin("isolated vertex", TLOD_FACE_TRIANGLES, true);
  add_tetrahedron(c, 1.0);
  add_vertex(c, 5, 5, 5); /* referenced by no face */
  run_case(c);
  shape q = shape_quad_cube();
  c = case_begin("isolated vertex, quads", TLOD_FACE_QUADS, true);
  add_shape(c, &q, 1.0);
  add_vertex(c, -3, 0, 0);
  shape_free(&q);
  run_case(c);
}

TEST(holes) {
  shape s = shape_icosphere(1);
  dcase* c = case_begin("icosphere with two holes", TLOD_FACE_TRIANGLES, false);
  add_shape(c, &s, 1.0);
  /* Remove faces 0 and 40 (not adjacent): two triangular holes. */
  memmove(&c->indices[120], &c->indices[123], sizeof(uint32_t) * (c->index_count - 123));
  memmove(&c->indices[0], &c->indices[3], sizeof(uint32_t) * (c->index_count - 3));
  c->index_count -= 6;
  shape_free(&s);
  run_case(c);
  shape g = shape_open_grid(4);
  c = case_begin("open grid", TLOD_FACE_TRIANGLES, false);
  add_shape(c, &g, 1.0);
  shape_free(&g);
  run_case(c);
}

TEST(non_manifold_edge) {
  /* Three triangles on the edge (0, 1), plus a fourth: works (tesslod/core.h
   * counts the edge as non-manifold and links none of its faces there). */
  dcase* c = case_begin("three faces on one edge", TLOD_FACE_TRIANGLES, false);
  add_vertex(c, 0, 0, 0), add_vertex(c, 1, 0, 0);
  add_vertex(c, 0.5, 1, 0), add_vertex(c, 0.5, -0.5, 0.8), add_vertex(c, 0.5, -0.5, -0.8);
  TRI(c, 0, 1, 2);
  TRI(c, 1, 0, 3);
  TRI(c, 1, 0, 4);
  TRI(c, 2, 1, 3);
  run_case(c);
  tlod_context* ctx = new_context(1, NULL, NULL);
  tlod_mesh_desc md = case_desc(c, NULL);
  tlod_mesh* m = NULL;
  CHECK(tlod_mesh_create(ctx, &md, &m) == TLOD_SUCCESS);
  CHECK(tlod_mesh_query_info(m).non_manifold_edges == 1);
  CHECK(tlod_mesh_edge_link(m, 0, 0).face == UINT32_MAX); /* edge 0 -> 1 of face 0 */
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
}

TEST(coincident_vertices) {
  /* Vertex 0 of the tetrahedron duplicated as vertex 4 (same floats); two
   * faces use each. Computed normals: one smooth vertex after welding. */
  dcase* c = case_begin("coincident vertices", TLOD_FACE_TRIANGLES, true);
  add_tetrahedron(c, 1.0);
  add_vertex(c, 0, 0, 0);
  c->indices[3 * 3 + 1] = 4; /* face 3 (2, 0, 3) -> (2, 4, 3) */
  run_case(c);
  /* The same with given normals that differ: a crease, closed by strips. */
  c = case_begin("coincident vertices, split normals", TLOD_FACE_TRIANGLES, true);
  add_tetrahedron(c, 1.0);
  add_vertex(c, 0, 0, 0);
  c->indices[3 * 3 + 1] = 4;
  for (uint32_t v = 0; v < 5; v++)
    set_normal(c, v, c->positions[v][0] - 0.3, c->positions[v][1] - 0.3, c->positions[v][2] - 0.3);
  set_normal(c, 4, -1, 0.2, 0.1);
  run_case(c);
  /* Two corners of one face at one position: that face is dropped. */
  run_tetrahedron_plus("face with coincident corners", 1, 0, 0, (const uint32_t[3]){1, 4, 3});
}

/* ------------------------------------------------------------------------ */
/* Degenerate faces                                                         */
/* ------------------------------------------------------------------------ */

TEST(slivers_and_zero_area) {
  /* A tetrahedron nearly flat (apex 1e-6 over the base): four slivers. */
  dcase* c = case_begin("flat tetrahedron", TLOD_FACE_TRIANGLES, true);
  add_tetrahedron(c, 1e-6);
  run_case(c);
  /* A needle: two vertices 1e-6 apart (not welded) on a closed bipyramid. */
  c = case_begin("needle", TLOD_FACE_TRIANGLES, true);
  add_vertex(c, 0, 0, 0), add_vertex(c, 1, 0, 0), add_vertex(c, 1, 1e-6, 0);
  add_vertex(c, 0.5, 0.3, 0.5), add_vertex(c, 0.5, 0.3, -0.5);
  TRI(c, 0, 1, 3), TRI(c, 1, 2, 3), TRI(c, 2, 0, 3);
  TRI(c, 1, 0, 4), TRI(c, 2, 1, 4), TRI(c, 0, 2, 4);
  run_case(c);
  /* A zero-area face among good ones: dropped and counted; the rest is closed. */
  run_tetrahedron_plus("one zero-area face", 0.5, 0, 0, (const uint32_t[3]){0, 1, 4});
  /* Two back-to-back copies of a sliver (a closed pillow): the computed
   * normals cancel, the fallback keeps them finite. The two sheets
   * coincide, so output points of both may weld: no closedness check. */
  c = case_begin("sliver pillow", TLOD_FACE_TRIANGLES, true);
  add_vertex(c, 0, 0, 0), add_vertex(c, 1, 0, 0), add_vertex(c, 0.5, 1e-5, 0);
  TRI(c, 0, 1, 2), TRI(c, 0, 2, 1);
  c->coincident_sheets = true;
  run_case(c);
  /* Only zero-area faces: refused naming a face. */
  c = case_begin("zero-area faces only", TLOD_FACE_TRIANGLES, false);
  add_vertex(c, 0, 0, 0), add_vertex(c, 1, 0, 0), add_vertex(c, 2, 0, 0);
  TRI(c, 0, 1, 2), TRI(c, 2, 1, 0);
  refuse(c, TLOD_ERROR_INVALID_MESH, "face 0: zero area");
  run_case(c);
  /* A quad with a repeated index (triangle-shaped) and a flat one. */
  shape q = shape_quad_cube();
  c = case_begin("quads with degenerate faces", TLOD_FACE_QUADS, true);
  add_shape(c, &q, 1.0);
  uint32_t a = add_vertex(c, 3, 0, 0), b = add_vertex(c, 4, 0, 0), d = add_vertex(c, 4, 1, 0);
  add_face(c, 4, (const uint32_t[4]){a, b, d, d});
  uint32_t e = add_vertex(c, 5, 0, 0), f = add_vertex(c, 6, 0, 0), g = add_vertex(c, 7, 0, 0);
  add_face(c, 4, (const uint32_t[4]){e, f, g, add_vertex(c, 8, 0, 0)});
  shape_free(&q);
  run_case(c);
}

/* ------------------------------------------------------------------------ */
/* Normals                                                                  */
/* ------------------------------------------------------------------------ */

TEST(bad_normals) {
  shape s = shape_icosphere(1);
  static const char* const names[4] = {"normals opposite to the faces", "zero normals", "NaN and Inf normals",
                                       "normals tangent to the surface"};
  for (int kind = 0; kind < 4; kind++) {
    dcase* c = case_begin(names[kind], TLOD_FACE_TRIANGLES, true);
    add_shape(c, &s, 1.0);
    for (uint32_t v = 0; v < c->vertex_count; v++) {
      const float* p = c->positions[v];
      if (kind == 0) set_normal(c, v, -p[0], -p[1], -p[2]);
      if (kind == 1) set_normal(c, v, 0, 0, v % 2 ? 0 : 1);
      if (kind == 2) set_normal(c, v, v % 3 ? NAN : INFINITY, 0, 1);
      if (kind == 3) set_normal(c, v, -p[1], p[0], 0.0); /* zero at the poles: repaired */
    }
    run_case(c);
  }
  shape q = shape_quad_sphere(2);
  dcase* c = case_begin("quads, normals opposite", TLOD_FACE_QUADS, true);
  add_shape(c, &q, 1.0);
  for (uint32_t v = 0; v < c->vertex_count; v++)
    set_normal(c, v, -c->positions[v][0], -c->positions[v][1], -c->positions[v][2]);
  run_case(c);
  shape_free(&q);
  shape_free(&s);
}

/* ------------------------------------------------------------------------ */
/* Coordinates and indices                                                  */
/* ------------------------------------------------------------------------ */

TEST(huge_and_tiny_coordinates) {
  shape s = shape_icosphere(1);
  /* Every coordinate within the limit, the extreme ones on it. */
  dcase* c = case_begin("sphere at the position limit", TLOD_FACE_TRIANGLES, true);
  add_shape(c, &s, (double)TLOD_POSITION_LIMIT);
  run_case(c);
  c = case_begin("tetrahedron at the position limit", TLOD_FACE_TRIANGLES, true);
  add_tetrahedron(c, 1.0);
  for (uint32_t v = 0; v < c->vertex_count; v++)
    for (int k = 0; k < 3; k++)
      c->positions[v][k] = (c->positions[v][k] * 2.0f - 1.0f) * TLOD_POSITION_LIMIT;
  run_case(c);
  c = case_begin("tiny sphere", TLOD_FACE_TRIANGLES, true);
  add_shape(c, &s, 1e-15);
  run_case(c);
  c = case_begin("sphere 1e4 from the origin", TLOD_FACE_TRIANGLES, true);
  add_shape(c, &s, 1.0);
  for (uint32_t v = 0; v < c->vertex_count; v++)
    c->positions[v][0] += 1e4f; /* level-4 pattern steps of about 30 float ulps */
  run_case(c);
  c = case_begin("sphere 3e5 from the origin", TLOD_FACE_TRIANGLES, true);
  add_shape(c, &s, 1.0);
  for (uint32_t v = 0; v < c->vertex_count; v++)
    c->positions[v][0] += 3e5f; /* pattern steps of about one float ulp */
  c->float_limited = true;
  run_case(c);
  shape_free(&s);
}

TEST(bad_coordinates_refused) {
  static const struct {
    float value;
    const char* want;
  } bad[] = {
      {NAN, "vertex 3: position.y is nan"},        {INFINITY, "vertex 3: position.y is inf"},
      {-INFINITY, "vertex 3: position.y is -inf"}, {3e38f, "vertex 3: position.y is 3e+38 (outside"},
      {-1.0000001e18f, "vertex 3: position.y"},    {FLT_MAX, "vertex 3: position.y"},
  };
  for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
    dcase* c = case_begin("bad coordinate", TLOD_FACE_TRIANGLES, true);
    add_tetrahedron(c, 1.0);
    c->positions[3][1] = bad[k].value;
    refuse(c, TLOD_ERROR_INVALID_MESH, bad[k].want);
    CALL(run_case(c));
  }
  /* The same through tlod_mesh_update: refused, the mesh unchanged. */
  tlod_context* ctx = new_context(1, NULL, NULL);
  dcase* c = case_begin("update", TLOD_FACE_TRIANGLES, true);
  add_tetrahedron(c, 1.0);
  tlod_mesh_desc md = case_desc(c, NULL);
  tlod_mesh* m = NULL;
  CHECK(tlod_mesh_create(ctx, &md, &m) == TLOD_SUCCESS);
  c->positions[2][0] = 3e38f;
  CHECK(tlod_mesh_update(m, &c->positions[0][0], 0, NULL, 0) == TLOD_ERROR_INVALID_MESH);
  CHECK_MSG(strstr(tlod_context_last_error(ctx), "update: vertex 2: position.x"), "%s", tlod_context_last_error(ctx));
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
}

TEST(indices_near_2_32) {
  static const uint32_t bad[] = {4, 0x7FFFFFFFu, 0xFFFFFFFEu, 0xFFFFFFFFu};
  for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
    dcase* c = case_begin("index out of range", TLOD_FACE_TRIANGLES, true);
    add_tetrahedron(c, 1.0);
    c->indices[3 * 2 + 1] = bad[k];
    char want[96];
    snprintf(want, sizeof want, "face 2 (indices 6..8): index %u out of range (4 vertices)", bad[k]);
    refuse(c, TLOD_ERROR_INVALID_MESH, want);
    CALL(run_case(c));
  }
  /* Quads and mixed faces name the face too. */
  shape q = shape_quad_cube();
  dcase* c = case_begin("quad index out of range", TLOD_FACE_QUADS, true);
  add_shape(c, &q, 1.0);
  c->indices[4 * 5 + 3] = UINT32_MAX;
  refuse(c, TLOD_ERROR_INVALID_MESH, "face 5 (indices 20..23): index 4294967295 out of range (8 vertices)");
  shape_free(&q);
  run_case(c);
}

/* ------------------------------------------------------------------------ */
/* Allocation failures on a degenerate mesh                                 */
/* ------------------------------------------------------------------------ */

/* The whole pipeline on the split-normal case with an allocator failing at
 * the k-th call: each run fails cleanly (OUT_OF_MEMORY) or succeeds, and
 * frees everything it took. */
TEST(allocation_failures) {
  dcase* c = case_begin("split normals", TLOD_FACE_TRIANGLES, true);
  add_tetrahedron(c, 1.0);
  add_vertex(c, 0, 0, 0);
  c->indices[3 * 3 + 1] = 4;
  for (uint32_t v = 0; v < 5; v++)
    set_normal(c, v, v == 4 ? -1 : 0, 0, v == 4 ? 0 : 1);
  c->normals[1][0] = NAN; /* repaired */
  long succeeded = 0;
  for (long k = 0; k < 400 && succeeded < 3; k++) {
    counting_allocator counter = {.fail_at = k};
    tlod_context* ctx = new_context(1, &counter, NULL);
    if (!ctx) continue;
    pipeline p = {.ctx = ctx};
    tlod_mesh_desc md = case_desc(c, NULL);
    tlod_result r = tlod_mesh_create(ctx, &md, &p.mesh);
    if (r == TLOD_SUCCESS) r = tlod_surface_create(ctx, p.mesh, &(tlod_surface_desc){.type = TLOD_SURFACE_PN}, &p.surf);
    if (r == TLOD_SUCCESS) r = tlod_patterns_create(ctx, &(tlod_patterns_desc){.max_level = 2}, &p.pat);
    if (r == TLOD_SUCCESS) r = tlod_scheduler_create(ctx, p.surf, p.pat, NULL, &p.sched);
    tlod_view_desc views[3];
    if (r == TLOD_SUCCESS) cameras_for(p.mesh, views);
    if (r == TLOD_SUCCESS)
      r = tlod_scheduler_update(p.sched, &(tlod_frame_desc){.views = views, .view_count = 3, .dt_ms = 20});
    if (r == TLOD_SUCCESS)
      r = tlod_cpu_tessellate(ctx, p.surf, p.pat,
                              &(tlod_cpu_tessellate_desc){.draw_list = tlod_scheduler_draw_list(p.sched, 0)}, &p.out);
    CHECK_MSG(r == TLOD_SUCCESS || r == TLOD_ERROR_OUT_OF_MEMORY, "fail at %ld: %s: %s", k, tlod_result_string(r),
              tlod_context_last_error(ctx));
    succeeded += r == TLOD_SUCCESS;
    pipeline_free(&p);
    tlod_context_destroy(ctx);
    CHECK_MSG(counter.allocs == counter.frees, "fail at %ld: %ld allocations, %ld frees", k, counter.allocs,
              counter.frees);
  }
  CHECK(succeeded > 0);
}

int main(void) {
  RUN(single_triangle);
  RUN(isolated_vertex);
  RUN(holes);
  RUN(non_manifold_edge);
  RUN(coincident_vertices);
  RUN(slivers_and_zero_area);
  RUN(bad_normals);
  RUN(huge_and_tiny_coordinates);
  RUN(bad_coordinates_refused);
  RUN(indices_near_2_32);
  RUN(allocation_failures);
  TEST_END();
}
