/*
 * gl_test.h -- shared fixtures of the GL tests (tests/gl/<name>_test.c): a
 * headless context from platform/, "gl" devices and sessions, and a small
 * independent GL mesh renderer for CPU-tessellated reference meshes (also
 * the reference of the Vulkan tests). The API-independent fixtures
 * (cameras, tesslod fixtures, one-item draws) are tests/unit/test_device.h.
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
#include "test_device.h"
#include "test_lod.h"
#include "tlod_platform.h"

#define GL_TEST_END() DEVICE_TEST_END()

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

/* A "gl" device on the current context, or NULL with the reason printed. */
static inline tlod_device* new_gl_device(tlod_context* ctx, const tlod_patterns* patterns, const char* label,
                                         tlod_device_gl_desc gl) {
  /* The GL tests are of the vertex-shader path: AUTO (the CPU mesh on
   * llvmpipe) is ON unless a test asks for OFF. */
  if (gl.gpu_eval == TLOD_GPU_EVAL_DEFAULT) gl.gpu_eval = TLOD_GPU_EVAL_ON;
  return new_device(ctx, &(tlod_device_desc){.backend = "gl", .patterns = patterns, .gl = gl, .label = label});
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

/* Realises dl (tlod_cpu_tessellate) and draws the mesh with the reference
 * renderer into the bound framebuffer, cleared first (clear_frame); with
 * facing, the stencil records the facing of the visible fragment
 * (gl_stencil_facing_begin). Returns the mesh, for the caller to read and
 * destroy (tlod_cpu_mesh_destroy), or NULL (reported). */
static inline tlod_cpu_mesh* ref_draw_list(ref_renderer* r, const fixture* fx, const tlod_draw_list* dl,
                                           const tlod_view_desc* v, uint32_t w, uint32_t h, bool facing) {
  tlod_cpu_mesh* m = realise(fx, dl);
  if (!m) return NULL;
  clear_frame(w, h);
  if (facing) gl_stencil_facing_begin();
  ref_upload(r, m);
  ref_draw(r, v);
  if (facing) gl_stencil_facing_end();
  return m;
}

#endif
