/*
 * gl_quadratic_test.c -- TLOD_SURFACE_QUADRATIC on the GPU (owned by the GL
 * tests). White-box for the positions: the vertex-side stages are
 * assembled by the devices' own function (_tlod_shader_vertex_side,
 * backends/shaders/shader_sources.h) from the embedded files, with the
 * PLAIN variant's defines, and linked here with transform feedback of
 * v_world (identity model: exactly the evaluated position). Fed with
 * core's patch records (tlod_surface_patch_records) and the devices' own
 * pattern buffer layout (device_stage.h), on quadratic_cube.h's curved cube
 * (9-node and 8-node quads, 6-node triangles):
 *   pattern path (pattern.vert): every pattern vertex of both shapes at
 *     the max level on every patch, no geomorph: within POS_TOL of the
 *     shape functions evaluated in quadratic_cube.h (double) and of
 *     tlod_surface_eval(); corners bitwise the mesh's positions; the two
 *     patches of every edge give bitwise equal points (closed output);
 *   strip path (strip.vert): every point of a strip on every edge at two
 *     level pairs is bitwise the patches' own edge point;
 *   hardware path (tess.vert/.tesc/.tese, triangles and quads, uniform
 *     level 3): every tessellated vertex within POS_TOL of a level-3 grid
 *     point of the pattern path, bitwise on edges and corners, and every
 *     grid point reached.
 * Device level (public API): the default "gl" device and a
 * hardware-tessellation one accept quadratic surfaces (curved cube, and a
 * linear mesh without nodes) and draw them; the pattern path's image of the
 * cube matches the CPU tessellation drawn by gl_test.h's renderer
 * (coverage off only on its silhouette band); an attribute replaced by
 * tlod_mesh_update_attribute() reaches the image after
 * tlod_device_update_surface() (fragment hook showing attribute 0; the
 * "cpu" device's mesh carries it too).
 */
#include "device_stage.h"
#include "gl_test.h"
#include "quadratic_cube.h"
#include "shader_sources.h"

#define LMAX 4
#define N (1u << LMAX)
#define HW_LEVEL 3
#define POS_TOL 1e-6 /* float evaluation, nodes of size ~1.6: a few ulps of the extent (2.6) */
#define W 128
#define H 128

/* ---- programs of the device's own sources, with transform feedback ---------- */

static GLuint stage(GLenum kind, const char* main_src, int corners) {
  char defines[_TLOD_SHADER_DEFINES_BYTES];
  _tlod_shader_defines(&(_tlod_shader_variant){0}, defines);
  const char* src[_TLOD_SHADER_STAGE_SOURCES];
  bool last = kind == GL_TESS_EVALUATION_SHADER || !corners; /* the stage feeding the fragments */
  int n = _tlod_shader_vertex_side(src, defines, corners ? _tlod_shader_corners(corners) : NULL,
                                   _tlod_shader_surface(TLOD_SURFACE_QUADRATIC), last, main_src);
  GLuint sh = glCreateShader(kind);
  glShaderSource(sh, n, src, NULL);
  glCompileShader(sh);
  if (!gl_status_ok(sh, GL_COMPILE_STATUS, glGetShaderiv, glGetShaderInfoLog, "quadratic stage")) {
    glDeleteShader(sh);
    return 0;
  }
  return sh;
}

/* main_src[0] the vertex stage, [1], [2] the control and evaluation
 * stages (hardware path: corners 3 or 4) or NULL. */
static GLuint capture_program(const char* const main_src[3], int corners) {
  static const GLenum kinds[3] = {GL_VERTEX_SHADER, GL_TESS_CONTROL_SHADER, GL_TESS_EVALUATION_SHADER};
  GLuint prog = glCreateProgram();
  bool ok = true;
  for (int i = 0; i < 3 && main_src[i]; i++) {
    GLuint sh = stage(kinds[i], main_src[i], corners);
    ok = ok && sh;
    if (sh) glAttachShader(prog, sh), glDeleteShader(sh);
  }
  const char* outs[1] = {"v_world"};
  glTransformFeedbackVaryings(prog, 1, outs, GL_INTERLEAVED_ATTRIBS);
  glLinkProgram(prog);
  if (!ok || !gl_status_ok(prog, GL_LINK_STATUS, glGetProgramiv, glGetProgramInfoLog, "quadratic program")) {
    glDeleteProgram(prog);
    return 0;
  }
  static const float id4[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}, id3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  glProgramUniformMatrix4fv(prog, glGetUniformLocation(prog, "u_model"), 1, GL_FALSE, id4);
  glProgramUniformMatrix4fv(prog, glGetUniformLocation(prog, "u_view_proj"), 1, GL_FALSE, id4);
  glProgramUniformMatrix3fv(prog, glGetUniformLocation(prog, "u_normal_matrix"), 1, GL_FALSE, id3);
  glProgramUniform1ui(prog, glGetUniformLocation(prog, "u_grid"), N);
  glProgramUniform1ui(prog, glGetUniformLocation(prog, "u_max_level"), LMAX);
  glProgramUniform1ui(prog, glGetUniformLocation(prog, "u_attribute_count"), 0u);
  glProgramUniform1ui(prog, glGetUniformLocation(prog, "u_corners"), (GLuint)corners);
  return prog;
}

static GLuint ssbo(GLuint binding, const void* data, size_t bytes) {
  GLuint b;
  glCreateBuffers(1, &b);
  glNamedBufferData(b, (GLsizeiptr)bytes, data, GL_STATIC_DRAW);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, b);
  return b;
}

/* Runs draw() with rasterizer discard into a feedback buffer of floats
 * vec3s; returns how many were written (primitive_mode: GL_POINTS or
 * GL_TRIANGLES). */
typedef void (*draw_fn)(const void* user);
static uint32_t capture(GLuint prog, GLenum primitive_mode, draw_fn draw, const void* user, float (*out)[3],
                        uint32_t cap) {
  GLuint tf, q;
  glCreateBuffers(1, &tf);
  glNamedBufferData(tf, (GLsizeiptr)(sizeof(float[3]) * cap), NULL, GL_STATIC_READ);
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, tf);
  glCreateQueries(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN, 1, &q);
  glUseProgram(prog);
  glEnable(GL_RASTERIZER_DISCARD);
  glBeginQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN, q);
  glBeginTransformFeedback(primitive_mode);
  draw(user);
  glEndTransformFeedback();
  glEndQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN);
  glDisable(GL_RASTERIZER_DISCARD);
  glUseProgram(0);
  GLuint prims = 0;
  glGetQueryObjectuiv(q, GL_QUERY_RESULT, &prims);
  uint32_t n = prims * (primitive_mode == GL_POINTS ? 1u : 3u);
  if (n > cap) n = cap;
  glGetNamedBufferSubData(tf, 0, (GLsizeiptr)(sizeof(float[3]) * n), out);
  glDeleteQueries(1, &q);
  glDeleteBuffers(1, &tf);
  GLenum err = glGetError();
  if (err != GL_NO_ERROR) fprintf(stderr, "GL error %s in a capture\n", gl_error_name(err));
  return err == GL_NO_ERROR ? n : 0;
}

/* ---- the scene: the cube's records and patterns in the devices' layout -------- */

typedef struct scene {
  qcube q;
  tlod_context* ctx;
  tlod_patterns* pat;
  tlod_mesh* mesh;
  tlod_surface* surf;
  _tlod_pattern_data pd;
  const tlod_pattern_vertex* pv[2];
  uint32_t pv_count[2];
  GLuint bufs[4]; /* patches, pattern, attributes, instances */
  /* The pattern path's points: edge[p][e][num], num over N from corner e. */
  float edge[QCUBE_FACES][4][N + 1][3];
} scene;

static void scene_close(scene* s) {
  glDeleteBuffers(4, s->bufs);
  _tlod_pattern_data_free(s->ctx, &s->pd);
  tlod_surface_destroy(s->surf);
  tlod_mesh_destroy(s->mesh);
  tlod_patterns_destroy(s->pat);
  tlod_context_destroy(s->ctx);
}

static bool scene_open(scene* s) {
  memset(s, 0, sizeof *s);
  qcube_make(&s->q);
  tlod_patch_record rec[QCUBE_FACES];
  static const float zero[4] = {0};
  bool ok = tlod_context_create(&(tlod_context_desc){.thread_count = 1}, &s->ctx) == TLOD_SUCCESS &&
            (s->pat = new_patterns(s->ctx, LMAX)) && tlod_mesh_create(s->ctx, &s->q.desc, &s->mesh) == TLOD_SUCCESS &&
            tlod_surface_create(s->ctx, s->mesh, &(tlod_surface_desc){.type = TLOD_SURFACE_QUADRATIC}, &s->surf) ==
                TLOD_SUCCESS &&
            tlod_surface_patch_records(s->surf, 0, QCUBE_FACES, rec) == TLOD_SUCCESS &&
            _tlod_pattern_data_make(s->ctx, s->pat, &s->pd);
  if (!ok) {
    fprintf(stderr, "quadratic cube: %s\n", s->ctx ? tlod_context_last_error(s->ctx) : "no context");
    return false;
  }
  for (int sh = 0; sh < 2; sh++)
    s->pv[sh] = tlod_patterns_vertices(s->pat, (tlod_pattern_shape)sh, &s->pv_count[sh]);
  s->bufs[0] = ssbo(TLOD_BINDING_PATCHES, rec, sizeof rec);
  s->bufs[1] = ssbo(TLOD_BINDING_PATTERN, s->pd.vertices, sizeof(tlod_gl_pattern_vertex) * s->pd.vertex_count);
  s->bufs[2] = ssbo(TLOD_BINDING_ATTRIBUTES, zero, sizeof zero);
  return true;
}

/* One instance per patch at `level`, edge levels all `level`, no geomorph. */
static void upload_instances(scene* s, uint32_t level) {
  tlod_gl_instance ins[QCUBE_FACES];
  for (uint32_t p = 0; p < QCUBE_FACES; p++)
    ins[p] = (tlod_gl_instance){.patch = p,
                                .level = level,
                                .edge_levels = level | level << 8 | level << 16 | level << 24,
                                .morph = {1, 1, 1, 1},
                                .morph_e3 = {1, 1, 1, 1}};
  glDeleteBuffers(1, &s->bufs[3]);
  s->bufs[3] = ssbo(TLOD_BINDING_INSTANCES, ins, sizeof ins);
}

/* Patches 0-3 are quads, 4-7 triangles. */
static uint32_t first_patch(int sh) { return sh == TLOD_PATTERN_QUAD ? 0u : 4u; }

/* ---- pattern path ----------------------------------------------------------- */

typedef struct pattern_draw {
  GLuint prog;
  const scene* s;
  int sh;
} pattern_draw;

static void draw_pattern(const void* user) {
  const pattern_draw* d = user;
  GLuint vao;
  glCreateVertexArrays(1, &vao);
  glBindVertexArray(vao);
  glUniform1ui(glGetUniformLocation(d->prog, "u_shape_base"), d->s->pd.shape_base[d->sh]);
  glUniform1ui(glGetUniformLocation(d->prog, "u_first_instance"), first_patch(d->sh));
  glDrawArraysInstanced(GL_POINTS, 0, (GLsizei)d->s->pv_count[d->sh], 4);
  glBindVertexArray(0);
  glDeleteVertexArrays(1, &vao);
}

/* The worst distance of the pattern path's points from the shape
 * functions and from tlod_surface_eval; corners bitwise; edge points kept. */
static void check_pattern_points(scene* s, int sh, float (*got)[3], double* shape_err, double* core_err) {
  uint32_t n = s->pv_count[sh], corners = sh == TLOD_PATTERN_QUAD ? 4u : 3u;
  for (uint32_t k = 0; k < 4; k++)
    for (uint32_t x = 0; x < n; x++) {
      uint32_t p = first_patch(sh) + k;
      const float* g = got[k * n + x];
      const tlod_pattern_vertex* v = &s->pv[sh][x];
      double u = (double)v->i / N, w = (double)v->j / N, want[3];
      qcube_eval(&s->q, (int)p, u, w, want);
      tlod_surface_point sp;
      CHECK(tlod_surface_eval(s->surf, p, v->u, v->v, &sp) == TLOD_SUCCESS);
      for (int c = 0; c < 3; c++) {
        *shape_err = fmax(*shape_err, fabs(g[c] - want[c]));
        *core_err = fmax(*core_err, fabs(g[c] - sp.position[c]));
      }
      uint32_t param = 0, kind = tlod_grid_point_kind(corners, LMAX, v->i, v->j, &param);
      if (kind < 4) {
        CHECK_MSG(!memcmp(g, s->q.pos[s->q.corners[p][kind]], sizeof(float[3])), "patch %u corner %u not exact", p,
                  kind);
        memcpy(s->edge[p][kind][0], g, sizeof(float[3]));
        memcpy(s->edge[p][(kind + corners - 1) % corners][N], g, sizeof(float[3]));
      } else if (kind < 8) {
        memcpy(s->edge[p][kind - 4][param], g, sizeof(float[3]));
      }
    }
}

/* Both patches of every edge: bitwise equal points (the edge runs the other way on the neighbour). */
static void check_shared_edges(const scene* s, uint32_t* edges) {
  tlod_mesh_view mv = tlod_mesh_query_view(s->mesh);
  *edges = 0;
  for (uint32_t p = 0; p < QCUBE_FACES; p++)
    for (uint32_t e = 0; e < mv.face_corners[p]; e++) {
      tlod_edge_link l = mv.links[p][e];
      CHECK_MSG(l.face != UINT32_MAX, "patch %u edge %u has no neighbour: the cube is closed", p, e);
      for (uint32_t k = 0; k <= N; k++)
        CHECK_MSG(!memcmp(s->edge[p][e][k], s->edge[l.face][l.edge][N - k], sizeof(float[3])),
                  "patch %u edge %u point %u/%u differs from patch %u edge %u's", p, e, k, N, l.face, l.edge);
      (*edges)++;
    }
}

/* ---- strip path ------------------------------------------------------------- */

typedef struct strip_draw {
  GLuint refs;
  uint32_t count;
} strip_draw;

static void draw_strips(const void* user) {
  const strip_draw* d = user;
  GLuint vao;
  glCreateVertexArrays(1, &vao);
  glEnableVertexArrayAttrib(vao, TLOD_ATTRIB_STRIP_REF);
  glVertexArrayAttribIFormat(vao, TLOD_ATTRIB_STRIP_REF, 2, GL_UNSIGNED_INT, 0);
  glVertexArrayAttribBinding(vao, TLOD_ATTRIB_STRIP_REF, 0);
  glVertexArrayVertexBuffer(vao, 0, d->refs, 0, sizeof(uint32_t[2]));
  glBindVertexArray(vao);
  glDrawArrays(GL_POINTS, 0, (GLsizei)d->count);
  glBindVertexArray(0);
  glDeleteVertexArrays(1, &vao);
}

/* A strip on every patch edge (a = the patch, b = its neighbour) at levels
 * (la, lb); refs name every point of each strip's pattern in order. */
static uint32_t make_strips(const scene* s, uint32_t la, uint32_t lb, tlod_gl_strip* strips, uint32_t (*refs)[2]) {
  tlod_mesh_view mv = tlod_mesh_query_view(s->mesh);
  uint32_t n = 0, r = 0;
  for (uint32_t p = 0; p < QCUBE_FACES; p++)
    for (uint32_t e = 0; e < mv.face_corners[p]; e++, n++) {
      tlod_edge_link l = mv.links[p][e];
      strips[n] = (tlod_gl_strip){p, l.face, e | (uint32_t)l.edge << 8, la | lb << 8, {1, 1, 0, 0}};
      for (uint32_t k = 0; k <= (1u << la) + 1u + (1u << lb); k++)
        refs[r][0] = n, refs[r++][1] = k;
    }
  return r;
}

/* Point k of strip (p, e) -> (b, eb) is the pattern path's edge point. */
static void check_strip_points(const scene* s, uint32_t la, uint32_t lb, const uint32_t (*refs)[2],
                               const tlod_gl_strip* strips, const float (*got)[3], uint32_t count) {
  uint32_t na = 1u << la, nb = 1u << lb;
  for (uint32_t i = 0; i < count; i++) {
    const tlod_gl_strip* st = &strips[refs[i][0]];
    uint32_t k = refs[i][1], a_side = k <= na;
    uint32_t patch = a_side ? st->patch_a : st->patch_b, e = a_side ? st->edges & 255u : st->edges >> 8;
    uint32_t num = a_side ? k << (LMAX - la) : (nb - (k - na - 1u)) << (LMAX - lb);
    CHECK_MSG(!memcmp(got[i], s->edge[patch][e][num], sizeof(float[3])),
              "strip of patch %u edge %u, levels %u/%u, point %u: not the patch's edge point %u/%u", st->patch_a,
              st->edges & 255u, la, lb, k, num, N);
  }
}

static void strip_path(const scene* s, GLuint prog, uint32_t la, uint32_t lb, uint32_t* points) {
  tlod_gl_strip strips[4 * QCUBE_FACES];
  uint32_t(*refs)[2] = calloc(4 * QCUBE_FACES * (2u * N + 2u), sizeof *refs);
  float(*got)[3] = calloc(4 * QCUBE_FACES * (2u * N + 2u), sizeof *got);
  CHECK(refs && got);
  uint32_t count = make_strips(s, la, lb, strips, refs);
  GLuint bufs[2];
  glCreateBuffers(2, bufs);
  glNamedBufferData(bufs[0], (GLsizeiptr)sizeof strips, strips, GL_STATIC_DRAW);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TLOD_BINDING_STRIPS, bufs[0]);
  glNamedBufferData(bufs[1], (GLsizeiptr)(sizeof *refs * count), refs, GL_STATIC_DRAW);
  strip_draw d = {bufs[1], count};
  CHECK_MSG(capture(prog, GL_POINTS, draw_strips, &d, got, count) == count, "strip points missing");
  CALL(check_strip_points(s, la, lb, (const uint32_t(*)[2])refs, strips, (const float(*)[3])got, count));
  *points += count;
  glDeleteBuffers(2, bufs);
  free(refs);
  free(got);
}

/* ---- hardware path ------------------------------------------------------------ */

typedef struct tess_draw {
  GLuint prog;
  int corners;
} tess_draw;

static void draw_tess(const void* user) {
  const tess_draw* d = user;
  GLuint vao;
  glCreateVertexArrays(1, &vao);
  glBindVertexArray(vao);
  glPatchParameteri(GL_PATCH_VERTICES, d->corners);
  glUniform1ui(glGetUniformLocation(d->prog, "u_first_instance"), first_patch(d->corners == 4));
  glDrawArrays(GL_PATCHES, 0, 4 * d->corners);
  glBindVertexArray(0);
  glDeleteVertexArrays(1, &vao);
}

/* Distance from x to face f's surface near (u, v): Gauss-Newton on the
 * shape functions (the tessellator's inner points are not on the pattern
 * grid, so their parameters are found, not known). */
static double surface_distance(const qcube* q, int f, double u, double v, const float x[3]) {
  double s[3], r[3];
  for (int it = 0; it < 8; it++) {
    double su[3], sv[3], h = 1e-6, a[3], b[3];
    qcube_eval(q, f, u, v, s);
    qcube_eval(q, f, u + h, v, a), qcube_eval(q, f, u - h, v, b);
    for (int c = 0; c < 3; c++)
      su[c] = (a[c] - b[c]) / (2 * h), r[c] = x[c] - s[c];
    qcube_eval(q, f, u, v + h, a), qcube_eval(q, f, u, v - h, b);
    for (int c = 0; c < 3; c++)
      sv[c] = (a[c] - b[c]) / (2 * h);
    double uu = 0, uv = 0, vv = 0, ur = 0, vr = 0;
    for (int c = 0; c < 3; c++)
      uu += su[c] * su[c], uv += su[c] * sv[c], vv += sv[c] * sv[c], ur += su[c] * r[c], vr += sv[c] * r[c];
    double det = uu * vv - uv * uv;
    if (det <= 0.0) break;
    u += (vv * ur - uv * vr) / det, v += (uu * vr - uv * ur) / det;
  }
  qcube_eval(q, f, u, v, s);
  double d = 0.0;
  for (int c = 0; c < 3; c++)
    d = fmax(d, fabs(x[c] - s[c]));
  return d;
}

/* The pattern path's points of the patches with `corners` corners at the
 * max level: positions, patch and grid coordinates. */
typedef struct fine_point {
  float pos[3];
  uint32_t patch, i, j, kind;
} fine_point;

static uint32_t fine_points(scene* s, GLuint pattern_prog, int corners, fine_point* out) {
  int sh = corners == 4 ? TLOD_PATTERN_QUAD : TLOD_PATTERN_TRIANGLE;
  uint32_t n = s->pv_count[sh];
  float(*all)[3] = calloc(4 * n, sizeof *all);
  pattern_draw d = {pattern_prog, s, sh};
  if (!all || capture(pattern_prog, GL_POINTS, draw_pattern, &d, all, 4 * n) != 4 * n) return free(all), 0;
  for (uint32_t k = 0; k < 4 * n; k++) {
    const tlod_pattern_vertex* v = &s->pv[sh][k % n];
    uint32_t param;
    out[k] = (fine_point){{all[k][0], all[k][1], all[k][2]},
                          first_patch(sh) + k / n,
                          v->i,
                          v->j,
                          tlod_grid_point_kind((uint32_t)corners, LMAX, v->i, v->j, &param)};
  }
  free(all);
  return 4 * n;
}

/* Every tessellated vertex on the surface (within POS_TOL of the nearest
 * patch's shape functions); every level-HW_LEVEL edge and corner point of
 * the pattern path tessellated bitwise (so both sides of an edge meet). */
static void check_tess_points(const scene* s, int corners, const float (*got)[3], uint32_t count,
                              const fine_point* fine, uint32_t fine_count, double* err, uint32_t* edge_points) {
  uint32_t step = 1u << (LMAX - HW_LEVEL), missed = 0;
  for (uint32_t i = 0; i < count; i++) {
    double best = 1e30;
    uint32_t bi = 0;
    for (uint32_t g = 0; g < fine_count; g++) {
      double d = 0.0;
      for (int c = 0; c < 3; c++)
        d = fmax(d, fabs((double)got[i][c] - fine[g].pos[c]));
      if (d < best) best = d, bi = g;
    }
    const fine_point* f = &fine[bi];
    *err = fmax(*err, surface_distance(&s->q, (int)f->patch, (double)f->i / N, (double)f->j / N, got[i]));
  }
  for (uint32_t g = 0; g < fine_count; g++) {
    if (fine[g].kind >= 8 || fine[g].i % step || fine[g].j % step) continue;
    bool hit = false;
    for (uint32_t i = 0; i < count && !hit; i++)
      hit = !memcmp(got[i], fine[g].pos, sizeof(float[3]));
    missed += !hit;
    (*edge_points)++;
  }
  CHECK_MSG(missed == 0, "%d-corner patches: %u edge points of level %d not tessellated bitwise", corners, missed,
            HW_LEVEL);
}

static void hardware_path(scene* s, GLuint pattern_prog, int corners, double* err, uint32_t* vertices,
                          uint32_t* edge_points) {
  GLuint prog = capture_program(
      (const char* [3]){_tlod_shader_tess_vert, _tlod_shader_tess_tesc, _tlod_shader_tess_tese}, corners);
  CHECK_MSG(prog, "the tess.* stages under quadratic.glsl (%d corners) did not build (see above)", corners);
  uint32_t cells = 1u << HW_LEVEL, cap = 4u * 2u * cells * cells * 3u + 3u;
  fine_point* fine = calloc(4u * (N + 1u) * (N + 1u), sizeof *fine);
  float(*got)[3] = calloc(cap, sizeof *got);
  CHECK(fine && got);
  upload_instances(s, LMAX);
  uint32_t fine_count = fine_points(s, pattern_prog, corners, fine);
  CHECK(fine_count > 0);
  upload_instances(s, HW_LEVEL);
  tess_draw d = {prog, corners};
  uint32_t count = capture(prog, GL_TRIANGLES, draw_tess, &d, got, cap);
  CHECK_MSG(count > 0 && count < cap, "%d corners: %u tessellated vertices captured", corners, count);
  CALL(check_tess_points(s, corners, (const float(*)[3])got, count, fine, fine_count, err, edge_points));
  *vertices += count;
  free(fine), free(got);
  glDeleteProgram(prog);
}

TEST(test_pattern_path_positions) {
  gl_session gs;
  CHECK_MSG(gl_session_open(&gs, 16, 16, LMAX, "gl_quadratic", (tlod_device_gl_desc){0}), "no GL context");
  scene s;
  CHECK(scene_open(&s));
  upload_instances(&s, LMAX);
  GLuint prog = capture_program((const char* [3]){_tlod_shader_pattern_vert, NULL, NULL}, 0);
  CHECK_MSG(prog, "pattern.vert under quadratic.glsl did not build (see above)");
  double shape_err = 0.0, core_err = 0.0;
  uint32_t points = 0;
  for (int sh = 0; sh < 2; sh++) {
    uint32_t n = 4 * s.pv_count[sh];
    float(*got)[3] = calloc(n, sizeof *got);
    CHECK(got);
    pattern_draw d = {prog, &s, sh};
    CHECK_MSG(capture(prog, GL_POINTS, draw_pattern, &d, got, n) == n, "shape %d: points missing", sh);
    CALL(check_pattern_points(&s, sh, got, &shape_err, &core_err));
    points += n;
    free(got);
  }
  uint32_t edges;
  CALL(check_shared_edges(&s, &edges));
  printf("  pattern path: %u points on %d patches at level %d: %.2e from the shape functions, %.2e from "
         "tlod_surface_eval; corners exact, %u patch edges bitwise their neighbour's\n",
         points, QCUBE_FACES, LMAX, shape_err, core_err, edges);
  CHECK_MSG(shape_err < POS_TOL && core_err < POS_TOL, "pattern path off the quadratic surface");

  GLuint strip_prog = capture_program((const char* [3]){_tlod_shader_strip_vert, NULL, NULL}, 0);
  CHECK_MSG(strip_prog, "strip.vert under quadratic.glsl did not build (see above)");
  uint32_t strip_points = 0;
  CALL(strip_path(&s, strip_prog, LMAX, LMAX - 2, &strip_points));
  CALL(strip_path(&s, strip_prog, 1, LMAX, &strip_points));
  printf("  strip path: %u strip points at levels %d/%d and 1/%d, each bitwise its patch's edge point\n", strip_points,
         LMAX, LMAX - 2, LMAX);
  glDeleteProgram(strip_prog);

  double tess_err = 0.0;
  uint32_t tess_vertices = 0, edge_points = 0;
  CALL(hardware_path(&s, prog, 3, &tess_err, &tess_vertices, &edge_points));
  CALL(hardware_path(&s, prog, 4, &tess_err, &tess_vertices, &edge_points));
  printf("  hardware path: %u tessellated vertices at level %d, %.2e from the shape functions; the %u edge and corner "
         "points of that level bitwise the pattern path's\n",
         tess_vertices, HW_LEVEL, tess_err, edge_points);
  CHECK_MSG(tess_err < POS_TOL, "hardware path off the quadratic surface");
  glDeleteProgram(prog);
  scene_close(&s);
  gl_session_close(&gs);
}

/* ---- device level (public API) ------------------------------------------------- */

/* Shows attribute 0 (a colour) unlit. */
static const char* const k_attribute_hook =
    "vec4 tlod_shade(tlod_fragment f) { return vec4(f.attributes[0].rgb, 1.0); }\n";

/* Draws fx with the device into a cleared frame; the centre pixel and the covered count. */
static void draw_centre(gl_session* gs, const fixture* fx, tlod_scheduler* sch, uint8_t px[4], uint32_t* covered) {
  camera cam = camera_look(2.6, -3.4, 1.9, 0, 0, 0, 45, W, H);
  tlod_view_desc v = make_view(&cam);
  const tlod_draw_list* dl = plan(fx, sch, &v, 0.0f);
  CHECK(dl);
  clear_frame(W, H);
  one_draw d;
  one_draw_make(&d, fx->ds, dl, &v);
  tlod_result r = tlod_device_draw(gs->dev, &d.desc);
  CHECK_MSG(r == TLOD_SUCCESS, "tlod_device_draw: %s: %s", tlod_result_string(r), tlod_context_last_error(gs->ctx));
  uint8_t* img = malloc(4 * W * H);
  CHECK(img);
  gl_read_rgba(W, H, img);
  memcpy(px, img + 4 * (W * (H / 2) + W / 2), 4);
  *covered = 0;
  for (uint32_t k = 0; k < W * H; k++)
    *covered += !is_background(img + 4 * k);
  free(img);
}

static bool colour_is(const uint8_t px[4], const float rgb[3]) {
  for (int c = 0; c < 3; c++)
    if (abs((int)px[c] - (int)lroundf(rgb[c] * 255.0f)) > 2) return false;
  return true;
}

/* The "cpu" device keeps no copy (it tessellates from the mesh at every
 * draw): its mesh carries rgb in attribute 0 after the device update too. */
static void check_cpu_device(gl_session* gs, const fixture* fx, tlod_scheduler* sch, const float rgb[3]) {
  tlod_device* cpu = new_device(gs->ctx, &(tlod_device_desc){.backend = "cpu", .patterns = gs->pat});
  CHECK(cpu);
  tlod_device_surface* ds = NULL;
  CHECK(tlod_device_create_surface(cpu, fx->surf, &ds) == TLOD_SUCCESS);
  CHECK(tlod_device_update_surface(cpu, ds) == TLOD_SUCCESS);
  camera cam = camera_look(2.6, -3.4, 1.9, 0, 0, 0, 45, W, H);
  tlod_view_desc v = make_view(&cam);
  const tlod_draw_list* dl = plan(fx, sch, &v, 0.0f);
  CHECK(dl);
  one_draw d;
  one_draw_make(&d, ds, dl, &v);
  CHECK(tlod_device_draw(cpu, &d.desc) == TLOD_SUCCESS);
  const tlod_cpu_mesh* m = tlod_cpu_device_mesh(cpu, 0);
  CHECK(m && m->attribute_count == 1 && m->vertex_count > 0);
  double err = 0.0;
  for (uint32_t k = 0; k < m->vertex_count; k++)
    for (int c = 0; c < 3; c++)
      err = fmax(err, fabs(m->attributes[k][c] - rgb[c]));
  CHECK_MSG(err < 1e-6, "cpu device: attribute 0 %.2e from the updated values", err);
  tlod_device_destroy(cpu);
}

/* A field's next time step (tlod_mesh_update_attribute) reaches the image
 * at tlod_device_update_surface(), with no surface refresh. */
TEST(test_attribute_update_reaches_image) {
  gl_session gs;
  CHECK_MSG(gl_session_open(&gs, W, H, LMAX, "gl_quadratic", (tlod_device_gl_desc){.fragment_hook = k_attribute_hook}),
            "no GL context or device (see above)");
  const float a[3] = {0.2f, 0.6f, 0.9f}, b[3] = {0.9f, 0.3f, 0.1f};
  qcube_coloured c;
  qcube_coloured_make(&c, a);
  fixture fx;
  CHECK(fixture_make_desc(&fx, gs.ctx, &c.q.desc, TLOD_SURFACE_QUADRATIC, gs.pat, gs.dev));
  tlod_scheduler* sch = new_scheduler(&fx, (tlod_scheduler_desc){.max_level = LMAX});
  CHECK(sch);
  uint8_t px[4];
  uint32_t covered;
  CALL(draw_centre(&gs, &fx, sch, px, &covered));
  CHECK_MSG(covered > 0 && colour_is(px, a), "first draw: centre (%u %u %u), %u pixels covered", px[0], px[1], px[2],
            covered);
  float next[QCUBE_VERTICES][3];
  for (int v = 0; v < QCUBE_VERTICES; v++)
    memcpy(next[v], b, sizeof b);
  CHECK(tlod_mesh_update_attribute(fx.mesh, 0, &next[0][0], 0) == TLOD_SUCCESS);
  CALL(draw_centre(&gs, &fx, sch, px, &covered));
  CHECK_MSG(colour_is(px, a), "before the device update the device draws its own copy: (%u %u %u)", px[0], px[1],
            px[2]);
  uint64_t bytes = tlod_device_query_stats(gs.dev).gl.attribute_bytes;
  CHECK(tlod_device_update_surface(gs.dev, fx.ds) == TLOD_SUCCESS);
  CHECK(tlod_device_query_stats(gs.dev).gl.attribute_bytes > bytes);
  CALL(draw_centre(&gs, &fx, sch, px, &covered));
  printf("  attribute update: centre pixel (%u %u %u) after tlod_device_update_surface, want (%ld %ld %ld)\n", px[0],
         px[1], px[2], lroundf(b[0] * 255.0f), lroundf(b[1] * 255.0f), lroundf(b[2] * 255.0f));
  CHECK_MSG(colour_is(px, b), "the updated attribute did not reach the image");
  CALL(check_cpu_device(&gs, &fx, sch, b));
  tlod_scheduler_destroy(sch);
  fixture_free(&fx);
  gl_session_close(&gs);
}

/* The default device (0 == every type) and a hardware-tessellation one link
 * the quadratic programs and take quadratic surfaces: the curved cube and a
 * linear mesh (no nodes: its Phong surface), drawn. */
TEST(test_devices_take_quadratic_surfaces) {
  for (int hw = 0; hw < 2; hw++) {
    gl_session gs;
    CHECK_MSG(gl_session_open(&gs, W, H, LMAX, "gl_quadratic", (tlod_device_gl_desc){.hardware_tessellation = hw}),
              "no GL context or device (see above)");
    uint32_t links = tlod_device_query_stats(gs.dev).gl.program_links;
    CHECK_MSG(links == (hw ? 16u : 8u), "%s device: %u program links (4 types)", hw ? "hardware" : "default", links);
    qcube q;
    qcube_make(&q);
    shape sph = shape_icosphere(1);
    tlod_mesh_desc descs[2] = {q.desc, shape_mesh_desc(&sph)};
    for (int k = 0; k < 2; k++) {
      fixture fx;
      CHECK_MSG(fixture_make_desc(&fx, gs.ctx, &descs[k], TLOD_SURFACE_QUADRATIC, gs.pat, gs.dev), "%s refused",
                descs[k].label);
      tlod_scheduler* sch = new_scheduler(
          &fx, (tlod_scheduler_desc){.max_level = LMAX, .morph = hw ? TLOD_MORPH_NONE : TLOD_MORPH_DEFAULT});
      CHECK(sch);
      uint8_t px[4];
      uint32_t covered;
      CALL(draw_centre(&gs, &fx, sch, px, &covered));
      CHECK_MSG(covered > 500 && glGetError() == GL_NO_ERROR, "%s %s: %u pixels covered", hw ? "hardware" : "pattern",
                descs[k].label, covered);
      tlod_scheduler_destroy(sch);
      fixture_free(&fx);
    }
    shape_free(&sph);
    gl_session_close(&gs);
  }
}

int main(void) {
  RUN(test_pattern_path_positions);
  RUN(test_attribute_update_reaches_image);
  RUN(test_devices_take_quadratic_surfaces);
  GL_TEST_END();
}
