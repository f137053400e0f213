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
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tesslod/backend.h"
#include "tesslod/lod.h"
#include "tlod_platform.h"

/* The sphere's material: tesslod calls it for every fragment it draws.
 * f.attributes[0] is the mesh attribute TEXCOORD_0 (u, v). */
static const char* const checker_hook =
    "vec4 tlod_shade(tlod_fragment f) {\n"
    "  vec2 cell = floor(f.attributes[0].xy * vec2(8.0, 4.0));\n"
    "  vec3 base = mod(cell.x + cell.y, 2.0) < 0.5 ? vec3(0.95, 0.7, 0.1) : vec3(0.1, 0.4, 0.95);\n"
    "  float lit = 0.25 + 0.75 * max(dot(f.normal, f.light_dir), 0.0);\n"
    "  float rim = pow(1.0 - max(dot(f.normal, normalize(f.eye - f.position)), 0.0), 4.0);\n"
    "  return vec4(base * lit + vec3(0.6 * rim), 1.0);\n"
    "}\n";

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

typedef struct sphere_mesh {
  float *positions, *uvs;
  uint32_t *indices, vertex_count, index_count;
} sphere_mesh;

typedef struct scene {
  tlod_context* ctx;
  tlod_patterns* patterns;
  tlod_device* dev;
  tlod_mesh* mesh;
  tlod_surface* surface;
  tlod_device_surface* dsurf;
  tlod_scheduler* scheduler;
} scene;

static bool parse_options(int argc, char** argv, options* o) {
  *o = (options){.out = "engine_gl.png", .frames = 3, .size = 256};
  for (int i = 1; i < argc; ++i) {
    bool has_value = i + 1 < argc;
    if (!strcmp(argv[i], "-o") && has_value)
      o->out = argv[++i];
    else if (!strcmp(argv[i], "--frames") && has_value)
      o->frames = atoi(argv[++i]);
    else if (!strcmp(argv[i], "--size") && has_value)
      o->size = atoi(argv[++i]);
    else {
      fprintf(stderr, "usage: engine_gl [-o out.png] [--frames N] [--size PIXELS]\n");
      return false;
    }
  }
  if (o->frames < 1 || o->size < 16 || o->size > 4096) {
    fprintf(stderr, "engine_gl: --frames must be >= 1 and --size 16..4096\n");
    return false;
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

/* ---- the mesh: a lat-long sphere with TEXCOORD_0 ---------------------- */

/* (nlat + 1) x (nlon + 1) vertices: the last column repeats the first (a UV
 * seam) and each pole is a row of copies, so every vertex has its own UV.
 * Seam and pole copies share bitwise-equal positions, which tesslod welds
 * for adjacency (tlod_mesh_desc.weld_epsilon 0). */
static bool sphere_make(sphere_mesh* m, uint32_t nlat, uint32_t nlon) {
  const double pi = 3.14159265358979323846;
  m->vertex_count = (nlat + 1) * (nlon + 1);
  m->index_count = 6 * nlon * (nlat - 1);
  m->positions = malloc(sizeof(float) * 3 * m->vertex_count);
  m->uvs = malloc(sizeof(float) * 2 * m->vertex_count);
  m->indices = malloc(sizeof(uint32_t) * m->index_count);
  if (!m->positions || !m->uvs || !m->indices) return false;
  for (uint32_t i = 0; i <= nlat; ++i)
    for (uint32_t j = 0; j <= nlon; ++j) {
      double th = pi * i / nlat, ph = 2 * pi * (j % nlon) / nlon;
      bool pole = i == 0 || i == nlat;
      float* p = m->positions + 3 * (i * (nlon + 1) + j);
      p[0] = pole ? 0.0f : (float)(sin(th) * cos(ph));
      p[1] = pole ? 0.0f : (float)(sin(th) * sin(ph));
      p[2] = (float)cos(th);
      m->uvs[2 * (i * (nlon + 1) + j)] = (float)j / (float)nlon;
      m->uvs[2 * (i * (nlon + 1) + j) + 1] = (float)i / (float)nlat;
    }
  uint32_t* ix = m->indices;
  for (uint32_t i = 0; i < nlat; ++i)
    for (uint32_t j = 0; j < nlon; ++j) {
      uint32_t a = i * (nlon + 1) + j, b = a + 1, c = a + nlon + 1, d = c + 1;
      if (i != 0) *ix++ = a, *ix++ = c, *ix++ = b; /* no triangle collapsed on a pole */
      if (i != nlat - 1) *ix++ = b, *ix++ = c, *ix++ = d;
    }
  return true;
}

static void sphere_free(sphere_mesh* m) {
  free(m->positions);
  free(m->uvs);
  free(m->indices);
}

/* ---- tesslod ---------------------------------------------------------- */

static bool check(tlod_result r, const scene* s, const char* call) {
  if (r == TLOD_SUCCESS) return true;
  fprintf(stderr, "engine_gl: %s: %s: %s\n", call, tlod_result_string(r),
          s->ctx ? tlod_context_last_error(s->ctx) : "");
  return false;
}

static bool scene_init(scene* s, const sphere_mesh* m) {
  memset(s, 0, sizeof *s);
  tlod_attribute_desc uv = {.data = m->uvs, .components = 2, .name = "TEXCOORD_0"};
  tlod_mesh_desc md = {.positions = m->positions,
                       .vertex_count = m->vertex_count,
                       .indices = m->indices,
                       .index_count = m->index_count,
                       .normal_mode = TLOD_NORMALS_ANGLE,
                       .label = "uv sphere",
                       .attributes = &uv,
                       .attribute_count = 1};
  tlod_device_desc dd = {.backend = "gl",
                         .gl = {.surface_types = 1u << TLOD_SURFACE_PN, .fragment_hook = checker_hook},
                         .label = "engine_gl"};
  return check(tlod_context_create(NULL, &s->ctx), s, "tlod_context_create") &&
         check(tlod_patterns_create(s->ctx, &(tlod_patterns_desc){.max_level = 5}, &s->patterns), s,
               "tlod_patterns_create") &&
         check((dd.patterns = s->patterns, tlod_device_create(s->ctx, &dd, &s->dev)), s, "tlod_device_create") &&
         check(tlod_mesh_create(s->ctx, &md, &s->mesh), s, "tlod_mesh_create") &&
         check(tlod_surface_create(s->ctx, s->mesh, &(tlod_surface_desc){.type = TLOD_SURFACE_PN}, &s->surface), s,
               "tlod_surface_create") &&
         check(tlod_device_create_surface(s->dev, s->surface, &s->dsurf), s, "tlod_device_create_surface") &&
         check(tlod_scheduler_create(s->ctx, s->surface, s->patterns, &(tlod_scheduler_desc){.epsilon_px = 1.0f},
                                     &s->scheduler),
               s, "tlod_scheduler_create");
}

/* Every destroy takes NULL (a half-made scene frees what it has). */
static void scene_free(scene* s) {
  tlod_scheduler_destroy(s->scheduler);
  tlod_device_destroy_surface(s->dev, s->dsurf);
  tlod_surface_destroy(s->surface);
  tlod_mesh_destroy(s->mesh);
  tlod_device_destroy(s->dev);
  tlod_patterns_destroy(s->patterns);
  tlod_context_destroy(s->ctx);
}

/* ---- camera (column-major, GL conventions) ---------------------------- */

static void look_at(const float eye[3], float m[16]) {
  float f[3] = {-eye[0], -eye[1], -eye[2]}, up[3] = {0, 0, 1}; /* looking at the origin, z up */
  float fl = sqrtf(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
  for (int k = 0; k < 3; ++k)
    f[k] /= fl;
  float s[3] = {f[1] * up[2] - f[2] * up[1], f[2] * up[0] - f[0] * up[2], f[0] * up[1] - f[1] * up[0]};
  float sl = sqrtf(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
  for (int k = 0; k < 3; ++k)
    s[k] /= sl;
  float u[3] = {s[1] * f[2] - s[2] * f[1], s[2] * f[0] - s[0] * f[2], s[0] * f[1] - s[1] * f[0]};
  memset(m, 0, 16 * sizeof *m);
  for (int k = 0; k < 3; ++k)
    m[4 * k] = s[k], m[4 * k + 1] = u[k], m[4 * k + 2] = -f[k];
  m[12] = -(s[0] * eye[0] + s[1] * eye[1] + s[2] * eye[2]);
  m[13] = -(u[0] * eye[0] + u[1] * eye[1] + u[2] * eye[2]);
  m[14] = f[0] * eye[0] + f[1] * eye[1] + f[2] * eye[2];
  m[15] = 1;
}

static void perspective(float fovy, float n, float fa, float p[16]) {
  float F = 1.0f / tanf(fovy / 2);
  memset(p, 0, 16 * sizeof *p);
  p[0] = F, p[5] = F, p[10] = (fa + n) / (n - fa), p[11] = -1, p[14] = 2 * fa * n / (n - fa);
}

/* The camera circles the sphere at distance 3.5, a little above it. */
static tlod_view_desc camera_at_frame(int frame, int size) {
  tlod_view_desc v = {.viewport_width = (uint32_t)size, .viewport_height = (uint32_t)size};
  float a = 0.4f * (float)frame;
  look_at((float[3]){3.4f * cosf(a), 3.4f * sinf(a), 0.8f}, v.view);
  perspective(0.785398f, 0.1f, 20.0f, v.proj);
  return v;
}

/* ---- the frame -------------------------------------------------------- */

static const float floor_green[4] = {0.1f, 0.8f, 0.2f, 1}, overlay_red[4] = {0.9f, 0.1f, 0.1f, 1};

static bool frame(const engine* e, const scene* s, int index, uint64_t* triangles) {
  tlod_view_desc v = camera_at_frame(index, e->size);
  tlod_frame_desc fd = {.views = &v, .view_count = 1, .dt_ms = 16.7f};
  if (!check(tlod_scheduler_update(s->scheduler, &fd), s, "tlod_scheduler_update")) return false;
  tlod_draw_item item = {.surface = s->dsurf, .draw_list = tlod_scheduler_draw_list(s->scheduler, 0)};
  tlod_draw_desc dd = {.items = &item, .item_count = 1, .viewport = {0, 0, (uint32_t)e->size, (uint32_t)e->size}};
  memcpy(dd.view, v.view, sizeof dd.view);
  memcpy(dd.proj, v.proj, sizeof dd.proj);

  glBindFramebuffer(GL_FRAMEBUFFER, e->fbo); /* the engine's pass */
  glViewport(0, 0, e->size, e->size);
  glEnable(GL_DEPTH_TEST);
  glClearColor(0.08f, 0.08f, 0.1f, 1);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  engine_draw(e, 0, 6, floor_green);
  if (!check(tlod_device_draw(s->dev, &dd), s, "tlod_device_draw")) return false;
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

static bool run(const options* o, const sphere_mesh* m) {
  engine e;
  scene s = {0};
  bool ok = engine_init(&e, o->size);
  if (!ok) fprintf(stderr, "engine_gl: the engine's own GL setup failed\n");
  ok = ok && scene_init(&s, m);
  for (int f = 0; ok && f < o->frames; ++f) {
    uint64_t triangles = 0;
    ok = frame(&e, &s, f, &triangles);
    if (ok) printf("frame %d: floor 2 + tesslod %llu + overlay 1 triangles\n", f, (unsigned long long)triangles);
  }
  ok = ok && write_png(&e, o->out);
  if (ok) printf("wrote %s (%dx%d)\n", o->out, o->size, o->size);
  scene_free(&s);
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
  sphere_mesh m = {0};
  bool ok = sphere_make(&m, 6, 12) && run(&o, &m);
  sphere_free(&m);
  tlod_platform_destroy(p);
  return ok ? 0 : 1;
}
