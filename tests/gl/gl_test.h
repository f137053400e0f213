/*
 * gl_test.h -- shared fixtures of the GL tests (tests/gl/<name>_test.c): a
 * headless context from platform/, cameras, tesslod fixtures, and a
 * small independent GL mesh renderer for CPU-tessellated reference meshes.
 * Owned by the GL tests; header-only (every function static).
 *
 * The reference renderer draws exactly the shading documented for the GL
 * device (tesslod/backend.h, tlod_draw_desc / tlod_draw_item):
 *   colour = base * (0.15 + 0.85 * max(dot(normalize(n), l), 0)),
 *   l = normalize(0.3, 0.8, 0.5) by default, base = (0.8, 0.8, 0.8, 1),
 *   world-space normals, no culling, no two-sided lighting.
 */
#ifndef TLOD_GL_TEST_H
#define TLOD_GL_TEST_H

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "shapes.h"
#include "tesslod/backend.h"
#include "tesslod/cpu.h"
#include "tesslod/lod.h"
#include "test.h"
#include "test_camera.h"
#include "test_lod.h"
#include "tlod_platform.h"

/* Like TEST_END, but a failed run exits with _Exit: the early returns of a
 * failed check leave objects behind, and LeakSanitizer's report of them
 * would only bury the message that matters. */
#define GL_TEST_END()                                                                                                  \
  do {                                                                                                                 \
    if (_test_failed) {                                                                                                \
      printf("%d passed, %d failed\n", _test_passed, _test_failed);                                                    \
      fflush(stdout);                                                                                                  \
      fflush(stderr);                                                                                                  \
      _Exit(1);                                                                                                        \
    }                                                                                                                  \
    TEST_END();                                                                                                        \
  } while (0)

/* ------------------------------------------------------------------------ */
/* Context                                                                  */
/* ------------------------------------------------------------------------ */

/* Headless platform of w x h, or NULL with the platform's reason printed:
 * GL tests FAIL (never skip) when no context can be made. */
static inline tlod_platform* gl_test_platform(uint32_t w, uint32_t h, char* error, size_t error_size) {
  tlod_platform* p = NULL;
  if (!tlod_platform_create(&(tlod_platform_desc){.width = w, .height = h}, &p, error, error_size)) {
    fprintf(stderr, "no GL context: %s\n", error);
    return NULL;
  }
  static bool described;
  if (!described) {
    char buf[320];
    printf("  %s\n", tlod_platform_describe(p, buf, sizeof buf));
    described = true;
  }
  return p;
}

static inline const char* gl_error_name(GLenum e) { return tlod_platform_gl_error_name(e); }

/* An offscreen FBO of the test's own (RGBA8 + DEPTH24_STENCIL8). */
typedef struct gl_target {
  GLuint fbo, color, depth;
  uint32_t w, h;
} gl_target;

static inline bool gl_target_make(gl_target* t, uint32_t w, uint32_t h) {
  memset(t, 0, sizeof *t);
  t->w = w, t->h = h;
  glGenFramebuffers(1, &t->fbo);
  glGenRenderbuffers(1, &t->color);
  glGenRenderbuffers(1, &t->depth);
  glBindRenderbuffer(GL_RENDERBUFFER, t->color);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, (GLsizei)w, (GLsizei)h);
  glBindRenderbuffer(GL_RENDERBUFFER, t->depth);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, (GLsizei)w, (GLsizei)h);
  glBindRenderbuffer(GL_RENDERBUFFER, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, t->color);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, t->depth);
  return glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
}

static inline void gl_target_free(gl_target* t) {
  glDeleteFramebuffers(1, &t->fbo);
  glDeleteRenderbuffers(1, &t->color);
  glDeleteRenderbuffers(1, &t->depth);
  memset(t, 0, sizeof *t);
}

/* Reads the bound read framebuffer, BOTTOM row first (GL order), RGBA8. */
static inline void gl_read_rgba(uint32_t w, uint32_t h, uint8_t* rgba) {
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, (GLsizei)w, (GLsizei)h, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
}

static inline void gl_read_stencil(uint32_t w, uint32_t h, uint8_t* stencil) {
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, (GLsizei)w, (GLsizei)h, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, stencil);
}

/* Window depth of the bound read framebuffer, bottom row first. */
static inline void gl_read_depth(uint32_t w, uint32_t h, float* depth) {
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, (GLsizei)w, (GLsizei)h, GL_DEPTH_COMPONENT, GL_FLOAT, depth);
}

/* Stencil records the facing of the visible fragment: 1 front, 2 back, 0
 * nothing drawn. Stencil state is not in the backend's save list (it must
 * leave it as the engine set it), so this works around tlod_device_draw
 * too. Needs the stencil cleared to 0 and the depth test on. */
static inline void gl_stencil_facing_begin(void) {
  glEnable(GL_STENCIL_TEST);
  glStencilMask(0xFF);
  glStencilFuncSeparate(GL_FRONT, GL_ALWAYS, 1, 0xFF);
  glStencilFuncSeparate(GL_BACK, GL_ALWAYS, 2, 0xFF);
  glStencilOpSeparate(GL_FRONT_AND_BACK, GL_KEEP, GL_KEEP, GL_REPLACE);
}

static inline void gl_stencil_facing_end(void) { glDisable(GL_STENCIL_TEST); }

/* ------------------------------------------------------------------------ */
/* Cameras (test_camera.h: double precision, stored as float)               */
/* ------------------------------------------------------------------------ */

/* Camera at eye looking at target; near / far hug a unit-radius-ish object
 * (24-bit depth keeps plenty of precision). */
static inline camera camera_look(double ex, double ey, double ez, double tx, double ty, double tz, double fovy_deg,
                                 uint32_t w, uint32_t h) {
  camera c = {.eye = {ex, ey, ez}, .target = {tx, ty, tz}, .up = {0, 0, 1}, .fovy = fovy_deg * SHAPES_PI / 180.0};
  double d[3] = {tx - ex, ty - ey, tz - ez};
  double dist = len3(d);
  shape_normalize3(d);
  if (fabs(d[2]) > 0.95) c.up[0] = 0, c.up[1] = 1, c.up[2] = 0;
  c.znear = dist > 3.0 ? dist - 2.5 : 0.05;
  c.zfar = dist + 3.0;
  c.width = w, c.height = h;
  c.aspect = (double)w / h;
  return c;
}

static inline void camera_print(const camera* c, char* buf, size_t size) {
  snprintf(buf, size, "eye (%.4f, %.4f, %.4f) target (%.4f, %.4f, %.4f) up (%.0f, %.0f, %.0f) fovy %.1f deg", c->eye[0],
           c->eye[1], c->eye[2], c->target[0], c->target[1], c->target[2], c->up[0], c->up[1], c->up[2],
           c->fovy * 180.0 / SHAPES_PI);
}

/* ------------------------------------------------------------------------ */
/* tesslod fixtures                                                         */
/* ------------------------------------------------------------------------ */

/* A shape's mesh and surface on patterns of the test's (a device is made
 * for one pattern set, so the fixtures of a test share it), and, with a
 * device, the surface's device surface. */
typedef struct fixture {
  tlod_context* ctx;
  tlod_mesh* mesh;
  tlod_surface* surf;
  const tlod_patterns* pat; /* borrowed */
  tlod_device* dev;
  tlod_device_surface* ds;
} fixture;

static inline void fixture_free(fixture* fx) {
  tlod_device_destroy_surface(fx->dev, fx->ds);
  tlod_surface_destroy(fx->surf);
  tlod_mesh_destroy(fx->mesh);
  fx->surf = NULL, fx->mesh = NULL, fx->pat = NULL, fx->ds = NULL, fx->dev = NULL;
}

/* A fixture of any mesh desc (attributes, say); dev may be NULL (no device surface). */
static inline bool fixture_make_desc(fixture* fx, tlod_context* ctx, const tlod_mesh_desc* md, tlod_surface_type type,
                                     const tlod_patterns* patterns, tlod_device* dev) {
  memset(fx, 0, sizeof *fx);
  fx->ctx = ctx;
  fx->pat = patterns;
  fx->dev = dev;
  tlod_result r = tlod_mesh_create(ctx, md, &fx->mesh);
  if (r == TLOD_SUCCESS)
    r = tlod_surface_create(ctx, fx->mesh, &(tlod_surface_desc){.type = type, .label = md->label}, &fx->surf);
  if (r == TLOD_SUCCESS && dev) r = tlod_device_create_surface(dev, fx->surf, &fx->ds);
  if (r != TLOD_SUCCESS) {
    fprintf(stderr, "fixture %s: %s: %s\n", md->label, tlod_result_string(r), tlod_context_last_error(ctx));
    fixture_free(fx);
    return false;
  }
  return true;
}

/* A shape's fixture; dev may be NULL (no device surface). */
static inline bool fixture_make(fixture* fx, tlod_context* ctx, const shape* s, tlod_surface_type type,
                                const tlod_patterns* patterns, tlod_device* dev) {
  tlod_mesh_desc md = shape_mesh_desc(s);
  return fixture_make_desc(fx, ctx, &md, type, patterns, dev);
}

/* shape_seam_sphere(nlat, nlon) with TEXCOORD_0 = lat-long UVs: vertex
 * (i, j) has (j / nlon, i / nlat) (v = 0 at the +z pole, glTF's top), so
 * the copied column and the pole copies are UV seams. desc points into the
 * struct: keep it where it is (do not copy it). */
typedef struct uv_sphere {
  shape sph;
  float* uv;
  tlod_attribute_desc attr;
  tlod_mesh_desc desc;
} uv_sphere;

static inline void uv_sphere_free(uv_sphere* u) {
  free(u->uv);
  shape_free(&u->sph);
  memset(u, 0, sizeof *u);
}

static inline bool uv_sphere_make(uv_sphere* u, uint32_t nlat, uint32_t nlon) {
  memset(u, 0, sizeof *u);
  u->sph = shape_seam_sphere(nlat, nlon);
  u->uv = malloc(sizeof(float) * 2 * (nlat + 1) * (nlon + 1));
  for (uint32_t i = 0; u->uv && i <= nlat; ++i)
    for (uint32_t j = 0; j <= nlon; ++j) {
      u->uv[2 * (i * (nlon + 1) + j)] = (float)j / (float)nlon;
      u->uv[2 * (i * (nlon + 1) + j) + 1] = (float)i / (float)nlat;
    }
  u->attr = (tlod_attribute_desc){.data = u->uv, .components = 2, .name = "TEXCOORD_0"};
  u->desc = shape_mesh_desc(&u->sph);
  u->desc.attributes = &u->attr;
  u->desc.attribute_count = 1;
  return u->uv != NULL;
}

/* The scheduler plans in an object's own space: its view is view * model
 * (column-major). */
static inline tlod_view_desc object_view(const tlod_view_desc* v, const float model[16]) {
  tlod_view_desc o = *v;
  for (int c = 0; c < 4; c++)
    for (int r = 0; r < 4; r++) {
      float s = 0.0f;
      for (int k = 0; k < 4; k++)
        s += v->view[k * 4 + r] * model[c * 4 + k];
      o.view[c * 4 + r] = s;
    }
  return o;
}

static inline tlod_scheduler* new_scheduler(const fixture* fx, tlod_scheduler_desc d) {
  return scheduler_create(fx->ctx, fx->surf, fx->pat, d);
}

/* One frame for one view; NULL on failure (reported). */
static inline const tlod_draw_list* plan(const fixture* fx, tlod_scheduler* s, const tlod_view_desc* v, float dt_ms) {
  tlod_frame_desc f = {.views = v, .view_count = 1, .dt_ms = dt_ms};
  return scheduler_plan(fx->ctx, s, &f);
}

/* The CPU reference realisation of a draw list (welded, with normals). */
static inline tlod_cpu_mesh* realise(const fixture* fx, const tlod_draw_list* dl) {
  tlod_cpu_tessellate_desc d = {.draw_list = dl};
  tlod_cpu_mesh* out = NULL;
  tlod_result r = tlod_cpu_tessellate(fx->ctx, fx->surf, fx->pat, &d, &out);
  if (r != TLOD_SUCCESS) {
    fprintf(stderr, "tlod_cpu_tessellate(draw_list): %s: %s\n", tlod_result_string(r),
            tlod_context_last_error(fx->ctx));
    return NULL;
  }
  return out;
}

static inline tlod_patterns* new_patterns(tlod_context* ctx, uint32_t max_level) {
  tlod_patterns* p = NULL;
  tlod_result r = tlod_patterns_create(ctx, &(tlod_patterns_desc){.max_level = max_level}, &p);
  if (r != TLOD_SUCCESS)
    fprintf(stderr, "tlod_patterns_create: %s: %s\n", tlod_result_string(r), tlod_context_last_error(ctx));
  return p;
}

/* A "gl" device on the current context, or NULL with the reason printed. */
static inline tlod_device* new_gl_device(tlod_context* ctx, const tlod_patterns* patterns, const char* label,
                                         tlod_device_gl_desc gl) {
  tlod_device* dev = NULL;
  tlod_result r = tlod_device_create(
      ctx, &(tlod_device_desc){.backend = "gl", .patterns = patterns, .gl = gl, .label = label}, &dev);
  if (r != TLOD_SUCCESS)
    fprintf(stderr, "tlod_device_create(\"gl\"): %s: %s (this build has: %s)\n", tlod_result_string(r),
            tlod_context_last_error(ctx), tlod_backend_names());
  return dev;
}

/* What a device test starts with: a headless platform (its context
 * current), a tesslod context, patterns and a "gl" device on them. */
typedef struct gl_session {
  tlod_platform* platform;
  tlod_context* ctx;
  tlod_patterns* pat;
  tlod_device* dev;
} gl_session;

static inline void gl_session_close(gl_session* s) {
  tlod_device_destroy(s->dev);
  tlod_patterns_destroy(s->pat);
  tlod_context_destroy(s->ctx);
  if (s->platform) tlod_platform_destroy(s->platform);
  memset(s, 0, sizeof *s);
}

/* false with the reason printed (GL tests then FAIL, never skip). */
static inline bool gl_session_open(gl_session* s, uint32_t w, uint32_t h, uint32_t max_level, const char* label,
                                   tlod_device_gl_desc gl) {
  char err[512] = "";
  memset(s, 0, sizeof *s);
  s->platform = gl_test_platform(w, h, err, sizeof err);
  if (!s->platform) return false;
  tlod_platform_bind(s->platform);
  if (tlod_context_create(&(tlod_context_desc){.thread_count = 2}, &s->ctx) != TLOD_SUCCESS ||
      !(s->pat = new_patterns(s->ctx, max_level)) || !(s->dev = new_gl_device(s->ctx, s->pat, label, gl))) {
    gl_session_close(s);
    return false;
  }
  return true;
}

/* What the one-object device tests start with: a session of w x h with
 * patterns to level 5, an icosphere(2) fixture of `type` on its device and
 * a scheduler to level 5. Close with sphere_scene_close, also after a
 * failed check (every member starts out NULL / empty). */
static inline void sphere_scene_open(gl_session* gs, shape* sph, fixture* fx, tlod_scheduler** sch, uint32_t w,
                                     uint32_t h, const char* label, tlod_surface_type type) {
  memset(sph, 0, sizeof *sph);
  memset(fx, 0, sizeof *fx);
  *sch = NULL;
  CHECK_MSG(gl_session_open(gs, w, h, 5, label, (tlod_device_gl_desc){0}), "no GL context or device (see above)");
  *sph = shape_icosphere(2);
  CHECK(fixture_make(fx, gs->ctx, sph, type, gs->pat, gs->dev));
  *sch = new_scheduler(fx, (tlod_scheduler_desc){.max_level = 5});
  CHECK(*sch);
}

static inline void sphere_scene_close(gl_session* gs, shape* sph, fixture* fx, tlod_scheduler* sch) {
  tlod_scheduler_destroy(sch);
  fixture_free(fx);
  shape_free(sph);
  gl_session_close(gs);
}

/* One item (identity model, default colour) for one view: desc.items points
 * at item, so keep the struct where it is (do not copy it). */
typedef struct one_draw {
  tlod_draw_item item;
  tlod_draw_desc desc;
} one_draw;

static inline void one_draw_make(one_draw* o, const tlod_device_surface* ds, const tlod_draw_list* dl,
                                 const tlod_view_desc* v) {
  memset(o, 0, sizeof *o);
  o->item.surface = ds;
  o->item.draw_list = dl;
  o->desc.items = &o->item;
  o->desc.item_count = 1;
  memcpy(o->desc.view, v->view, sizeof o->desc.view);
  memcpy(o->desc.proj, v->proj, sizeof o->desc.proj);
  o->desc.viewport[2] = v->viewport_width;
  o->desc.viewport[3] = v->viewport_height;
  o->desc.debug = TLOD_DEBUG_NONE;
}

/* ------------------------------------------------------------------------ */
/* Reference mesh renderer (independent of the GL backend)                  */
/* ------------------------------------------------------------------------ */

typedef struct ref_renderer {
  GLuint program, vao, vbo[2], ebo;
  GLint u_view, u_proj, u_light, u_base;
  GLsizei index_count;
} ref_renderer;

static const char* const ref_vs = "#version 450 core\n"
                                  "layout(location = 0) in vec3 a_position;\n"
                                  "layout(location = 1) in vec3 a_normal;\n"
                                  "uniform mat4 u_view, u_proj;\n"
                                  "out vec3 v_normal;\n"
                                  "void main() {\n"
                                  "  v_normal = a_normal;\n"
                                  "  gl_Position = u_proj * (u_view * vec4(a_position, 1.0));\n"
                                  "}\n";
static const char* const ref_fs =
    "#version 450 core\n"
    "in vec3 v_normal;\n"
    "uniform vec3 u_light;\n"
    "uniform vec4 u_base;\n"
    "out vec4 o_color;\n"
    "void main() {\n"
    "  vec3 n = normalize(v_normal);\n"
    "  o_color = vec4(u_base.rgb * (0.15 + 0.85 * max(dot(n, u_light), 0.0)), u_base.a);\n"
    "}\n";

/* Whether a shader's (program's) status is GL_TRUE; if not, prints its
 * info log after `what`. */
static inline bool gl_status_ok(GLuint object, GLenum status, void (*get_iv)(GLuint, GLenum, GLint*),
                                void (*get_log)(GLuint, GLsizei, GLsizei*, GLchar*), const char* what) {
  GLint ok = 0;
  get_iv(object, status, &ok);
  if (ok) return true;
  char log[1024] = "";
  get_log(object, sizeof log, NULL, log);
  fprintf(stderr, "%s: %s\n", what, log);
  return false;
}

static inline GLuint gl_compile(GLenum stage, const char* src) {
  GLuint s = glCreateShader(stage);
  glShaderSource(s, 1, &src, NULL);
  glCompileShader(s);
  if (!gl_status_ok(s, GL_COMPILE_STATUS, glGetShaderiv, glGetShaderInfoLog, "shader compile failed")) {
    glDeleteShader(s);
    return 0;
  }
  return s;
}

static inline GLuint gl_program(const char* vs, const char* fs) {
  GLuint v = gl_compile(GL_VERTEX_SHADER, vs), f = gl_compile(GL_FRAGMENT_SHADER, fs);
  if (!v || !f) {
    glDeleteShader(v);
    glDeleteShader(f);
    return 0;
  }
  GLuint p = glCreateProgram();
  glAttachShader(p, v);
  glAttachShader(p, f);
  glLinkProgram(p);
  glDeleteShader(v);
  glDeleteShader(f);
  if (!gl_status_ok(p, GL_LINK_STATUS, glGetProgramiv, glGetProgramInfoLog, "program link failed")) {
    glDeleteProgram(p);
    return 0;
  }
  return p;
}

static inline bool ref_init(ref_renderer* r) {
  memset(r, 0, sizeof *r);
  r->program = gl_program(ref_vs, ref_fs);
  if (!r->program) return false;
  r->u_view = glGetUniformLocation(r->program, "u_view");
  r->u_proj = glGetUniformLocation(r->program, "u_proj");
  r->u_light = glGetUniformLocation(r->program, "u_light");
  r->u_base = glGetUniformLocation(r->program, "u_base");
  glGenVertexArrays(1, &r->vao);
  glGenBuffers(2, r->vbo);
  glGenBuffers(1, &r->ebo);
  glBindVertexArray(r->vao);
  for (GLuint a = 0; a < 2; ++a) {
    glBindBuffer(GL_ARRAY_BUFFER, r->vbo[a]);
    glVertexAttribPointer(a, 3, GL_FLOAT, GL_FALSE, 12, NULL);
    glEnableVertexAttribArray(a);
  }
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, r->ebo);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  return glGetError() == GL_NO_ERROR;
}

static inline void ref_free(ref_renderer* r) {
  glDeleteProgram(r->program);
  glDeleteVertexArrays(1, &r->vao);
  glDeleteBuffers(2, r->vbo);
  glDeleteBuffers(1, &r->ebo);
  memset(r, 0, sizeof *r);
}

static inline void ref_upload(ref_renderer* r, const tlod_cpu_mesh* m) {
  glBindVertexArray(r->vao);
  glBindBuffer(GL_ARRAY_BUFFER, r->vbo[0]);
  glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)m->vertex_count * 12, m->positions, GL_STREAM_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, r->vbo[1]);
  glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)m->vertex_count * 12, m->normals, GL_STREAM_DRAW);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)m->triangle_count * 12, m->indices, GL_STREAM_DRAW);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  r->index_count = (GLsizei)(3 * m->triangle_count);
}

/* Draws the uploaded mesh into the bound framebuffer with the backend's
 * default light and colour. The caller sets viewport, depth and clears. */
static inline void ref_draw(const ref_renderer* r, const tlod_view_desc* v) {
  double l[3] = {0.3, 0.8, 0.5};
  shape_normalize3(l);
  glUseProgram(r->program);
  glUniformMatrix4fv(r->u_view, 1, GL_FALSE, v->view);
  glUniformMatrix4fv(r->u_proj, 1, GL_FALSE, v->proj);
  glUniform3f(r->u_light, (float)l[0], (float)l[1], (float)l[2]);
  glUniform4f(r->u_base, 0.8f, 0.8f, 0.8f, 1.0f);
  glBindVertexArray(r->vao);
  glDrawElements(GL_TRIANGLES, r->index_count, GL_UNSIGNED_INT, NULL);
  glBindVertexArray(0);
  glUseProgram(0);
}

/* ------------------------------------------------------------------------ */
/* Images                                                                   */
/* ------------------------------------------------------------------------ */

/* The clear colour of the GL tests: pure blue. Shaded pixels are grey
 * (r == g == b), so coverage is exact: not-background == covered. */
#define BG_R 0
#define BG_G 0
#define BG_B 255

static inline void clear_frame(uint32_t w, uint32_t h) {
  glViewport(0, 0, (GLsizei)w, (GLsizei)h);
  glDisable(GL_SCISSOR_TEST);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthMask(GL_TRUE);
  glStencilMask(0xFF);
  glClearColor(BG_R / 255.0f, BG_G / 255.0f, BG_B / 255.0f, 1.0f);
  glClearDepth(1.0);
  glClearStencil(0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
}

static inline bool is_background(const uint8_t* px) { return px[0] == BG_R && px[1] == BG_G && px[2] == BG_B; }

#endif
