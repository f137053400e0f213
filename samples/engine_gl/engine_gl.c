/*
 * engine_gl.c -- how an engine with its own OpenGL context embeds tesslod.
 *
 *   engine_gl [-o out.png] [--frames N] [--size PIXELS]
 *
 * The engine owns everything GL: tlod_platform only hands it a headless 4.5
 * core context. Per frame the engine binds its own FBO, clears it, draws its
 * own floor (its own program and vertex array), lets tesslod draw a UV
 * sphere with a fragment hook material (a checker from the mesh's
 * TEXCOORD_0 plus a rim light), then draws its own overlay triangle on top.
 * tlod_device_draw saves and restores the GL state it touches (tesslod/gl.h),
 * so the engine never re-binds anything after it. The last frame is
 * written as a PNG; each frame's triangle count comes from the device stats.
 */
#include <GL/gl.h>
#include <GL/glext.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sample_scene.h"
#include "tlod_platform.h"

/* The engine's own flat-colour program: positions already in clip space. */
static const char* const flat_vs = "#version 450 core\n"
                                   "layout(location = 0) in vec3 a_position;\n"
                                   "void main() { gl_Position = vec4(a_position, 1.0); }\n";
static const char* const flat_fs = "#version 450 core\n"
                                   "uniform vec4 u_color;\n"
                                   "out vec4 o_color;\n"
                                   "void main() { o_color = u_color; }\n";

/* The engine's geometry: a floor band across the bottom (far away) and an
 * overlay triangle top right (in front of everything). docs/samples.md
 * lists where, for the test. */
static const float floor_tris[18] = {-1, -1, 0.99f, 1, -1,    0.99f, 1,  -0.6f, 0.99f,
                                     -1, -1, 0.99f, 1, -0.6f, 0.99f, -1, -0.6f, 0.99f};
static const float overlay_tri[9] = {0.6f, 0.6f, -0.5f, 0.95f, 0.6f, -0.5f, 0.95f, 0.95f, -0.5f};

typedef struct options {
  const char* out;
  int frames;
  int size;
} options;

typedef struct engine {
  GLuint fbo, color_rb, depth_rb; /* the engine's render target */
  GLuint program, vao, vbo;
  GLint u_color;
  int size;
} engine;

static bool parse_options(int argc, char** argv, options* o) {
  *o = (options){.out = "engine_gl.png", .frames = 3, .size = 256};
  for (int i = 1; i < argc; ++i) {
    bool has_value = i + 1 < argc;
    if (!strcmp(argv[i], "-o") && has_value)
      o->out = argv[++i];
    else if (!strcmp(argv[i], "--frames") && has_value) {
      if (!sample_parse_int("engine_gl", argv[i], argv[i + 1], 1, 1000000, &o->frames)) return false;
      ++i;
    } else if (!strcmp(argv[i], "--size") && has_value) {
      if (!sample_parse_int("engine_gl", argv[i], argv[i + 1], 16, 4096, &o->size)) return false;
      ++i;
    } else {
      fprintf(stderr, "usage: engine_gl [-o out.png] [--frames N] [--size PIXELS]\n");
      return false;
    }
  }
  return true;
}

/* ---- the engine's own GL ---------------------------------------------- */

static GLuint compile(GLenum stage, const char* src) {
  GLuint s = glCreateShader(stage);
  glShaderSource(s, 1, &src, NULL);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[512] = "";
    glGetShaderInfoLog(s, sizeof log, NULL, log);
    fprintf(stderr, "engine_gl: engine shader: %s\n", log);
  }
  return s;
}

static bool engine_program(engine* e) {
  GLuint vs = compile(GL_VERTEX_SHADER, flat_vs), fs = compile(GL_FRAGMENT_SHADER, flat_fs);
  e->program = glCreateProgram();
  glAttachShader(e->program, vs);
  glAttachShader(e->program, fs);
  glLinkProgram(e->program);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(e->program, GL_LINK_STATUS, &ok);
  e->u_color = glGetUniformLocation(e->program, "u_color");
  return ok;
}

/* One vertex buffer: the floor's 6 vertices, then the overlay's 3. */
static void engine_geometry(engine* e) {
  glGenVertexArrays(1, &e->vao);
  glGenBuffers(1, &e->vbo);
  glBindVertexArray(e->vao);
  glBindBuffer(GL_ARRAY_BUFFER, e->vbo);
  glBufferData(GL_ARRAY_BUFFER, sizeof floor_tris + sizeof overlay_tri, NULL, GL_STATIC_DRAW);
  glBufferSubData(GL_ARRAY_BUFFER, 0, sizeof floor_tris, floor_tris);
  glBufferSubData(GL_ARRAY_BUFFER, sizeof floor_tris, sizeof overlay_tri, overlay_tri);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 12, NULL);
  glEnableVertexAttribArray(0);
}

static bool engine_target(engine* e) {
  glGenFramebuffers(1, &e->fbo);
  glGenRenderbuffers(1, &e->color_rb);
  glGenRenderbuffers(1, &e->depth_rb);
  glBindRenderbuffer(GL_RENDERBUFFER, e->color_rb);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, e->size, e->size);
  glBindRenderbuffer(GL_RENDERBUFFER, e->depth_rb);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, e->size, e->size);
  glBindFramebuffer(GL_FRAMEBUFFER, e->fbo);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, e->color_rb);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, e->depth_rb);
  return glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
}

static bool engine_init(engine* e, int size) {
  memset(e, 0, sizeof *e);
  e->size = size;
  if (!engine_target(e) || !engine_program(e)) return false;
  engine_geometry(e);
  return glGetError() == GL_NO_ERROR;
}

static void engine_free(engine* e) {
  glDeleteVertexArrays(1, &e->vao);
  glDeleteBuffers(1, &e->vbo);
  glDeleteProgram(e->program);
  glDeleteFramebuffers(1, &e->fbo);
  glDeleteRenderbuffers(1, &e->color_rb);
  glDeleteRenderbuffers(1, &e->depth_rb);
}

static void engine_draw(const engine* e, GLint first, GLsizei count, const float rgba[4]) {
  glUseProgram(e->program);
  glBindVertexArray(e->vao);
  glUniform4fv(e->u_color, 1, rgba);
  glDrawArrays(GL_TRIANGLES, first, count);
}

/* ---- the frame -------------------------------------------------------- */

static const float floor_green[4] = {0.1f, 0.8f, 0.2f, 1}, overlay_red[4] = {0.9f, 0.1f, 0.1f, 1};

/* The camera circles the sphere, a little above it, 0.4 radians a frame. */
static bool frame(const engine* e, sample_scene* s, int index, uint64_t* triangles) {
  tlod_view_desc v = sample_orbit_camera(0.4f * (float)index, 3.4f, 0.8f, (uint32_t)e->size, (uint32_t)e->size);
  tlod_draw_item item;
  tlod_draw_desc dd;
  if (!sample_scene_plan(s, &v, 16.7f, &item, &dd, "engine_gl")) return false;

  glBindFramebuffer(GL_FRAMEBUFFER, e->fbo); /* the engine's pass */
  glViewport(0, 0, e->size, e->size);
  glEnable(GL_DEPTH_TEST);
  glClearColor(0.08f, 0.08f, 0.1f, 1);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  engine_draw(e, 0, 6, floor_green);
  if (!sample_check(tlod_device_draw(s->dev, &dd), s, "tlod_device_draw", "engine_gl")) return false;
  engine_draw(e, 6, 3, overlay_red); /* the engine's program and VAO are still bound: tesslod restored them */
  *triangles = tlod_device_query_stats(s->dev).triangles;
  return glGetError() == GL_NO_ERROR;
}

/* Reads the engine's FBO (bottom row first) into a top-first PNG. */
static bool write_png(const engine* e, const char* path) {
  size_t row = 4 * (size_t)e->size;
  uint8_t* px = malloc(row * (size_t)e->size);
  uint8_t* flipped = malloc(row * (size_t)e->size);
  char err[256] = "";
  bool ok = px && flipped;
  if (ok) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, e->fbo);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, e->size, e->size, GL_RGBA, GL_UNSIGNED_BYTE, px);
    for (int y = 0; y < e->size; ++y)
      memcpy(flipped + row * (size_t)y, px + row * (size_t)(e->size - 1 - y), row);
    ok = tlod_png_write(path, (uint32_t)e->size, (uint32_t)e->size, flipped, err, sizeof err);
    if (!ok) fprintf(stderr, "engine_gl: %s\n", err);
  }
  free(px);
  free(flipped);
  return ok;
}

static bool run(const options* o, const sample_mesh* m) {
  engine e;
  sample_scene s = {0};
  tlod_device_desc dd = {.backend = "gl",
                         .gl = {.surface_types = 1u << TLOD_SURFACE_PN, .fragment_hook = sample_checker_hook},
                         .label = "engine_gl"};
  tlod_attribute_desc uv;
  tlod_mesh_desc md = sample_mesh_desc(m, &uv);
  bool ok = engine_init(&e, o->size);
  if (!ok) fprintf(stderr, "engine_gl: the engine's own GL setup failed\n");
  ok = ok && sample_scene_init(&s, &md, dd, "engine_gl");
  for (int f = 0; ok && f < o->frames; ++f) {
    uint64_t triangles = 0;
    ok = frame(&e, &s, f, &triangles);
    if (ok) printf("frame %d: floor 2 + tesslod %llu + overlay 1 triangles\n", f, (unsigned long long)triangles);
  }
  ok = ok && write_png(&e, o->out);
  if (ok) printf("wrote %s (%dx%d)\n", o->out, o->size, o->size);
  sample_scene_free(&s);
  engine_free(&e);
  return ok;
}

int main(int argc, char** argv) {
  options o;
  if (!parse_options(argc, argv, &o)) return 2;
  char err[512] = "";
  tlod_platform* p = NULL; /* only for a context: the engine draws into its own FBO */
  if (!tlod_platform_create(&(tlod_platform_desc){.width = 16, .height = 16}, &p, err, sizeof err)) {
    fprintf(stderr, "engine_gl: no GL context: %s\n", err);
    return 1;
  }
  sample_mesh m;
  bool ok = sample_sphere_make(&m, 6, 12) && run(&o, &m);
  sample_mesh_free(&m);
  tlod_platform_destroy(p);
  return ok ? 0 : 1;
}
