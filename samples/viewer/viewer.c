/*
 * viewer.c -- a model viewer on tesslod with either GPU API.
 *
 *   viewer [MODEL] [--backend gl|vulkan] [--frames N] [--size PIXELS] [--levels] [--wireframe]
 *          [--headless -o out.png]
 *
 * MODEL (.gltf .glb .obj .ply, through the tools' importer when the build has
 * it) is scaled into the unit sphere around the origin; without one, the
 * samples' checker sphere. A GLFW window (tlod_platform's window mode, both
 * APIs) with an orbit camera: drag with the left button to orbit, scroll to
 * zoom; keys L the levels view, W the wireframe overlay, Esc quits. The LOD
 * adapts every frame (the scheduler, 1 pixel error). --headless draws N
 * frames (default 3) offscreen, the camera turning by itself, and writes
 * the last one to -o (default viewer.png); in a window, -o with --frames
 * writes the last frame too (GL).
 */
#include <GLFW/glfw3.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sample_scene.h"
#include "tlod_platform_device.h" /* tlod_platform.h and the vulkan device desc from it */
#if VIEWER_HAS_IMPORT
#include "tlod_import.h"
#endif

typedef struct options {
  const char *model, *out;
  tlod_platform_api api;
  int frames; /* 0: until the window closes */
  uint32_t size;
  bool headless, levels, wireframe;
} options;

/* What the input callbacks change (the window's user pointer). */
typedef struct view_state {
  float yaw, pitch, distance;
  double last_x, last_y;
  bool dragging, levels, wireframe;
} view_state;

typedef struct model {
  sample_mesh sphere;
  float* positions; /* imported, scaled into the unit sphere */
  void* imported;   /* tlod_import_result* */
  tlod_attribute_desc attributes[8];
  tlod_mesh_desc desc;
} model;

static const float clear_rgba[4] = {0.08f, 0.08f, 0.1f, 1};

static bool parse_value(options* o, const char* flag, const char* value) {
  if (!strcmp(flag, "-o"))
    o->out = value;
  else if (!strcmp(flag, "--frames"))
    return sample_parse_int("viewer", flag, value, 0, 1000000, &o->frames);
  else if (!strcmp(flag, "--size")) {
    int size = 0;
    if (!sample_parse_int("viewer", flag, value, 16, 4096, &size)) return false;
    o->size = (uint32_t)size;
  } else if (!strcmp(flag, "--backend") && (!strcmp(value, "gl") || !strcmp(value, "vulkan")))
    o->api = !strcmp(value, "gl") ? TLOD_PLATFORM_GL : TLOD_PLATFORM_VULKAN;
  else
    return false;
  return true;
}

static bool parse_options(int argc, char** argv, options* o) {
  *o = (options){.frames = -1, .size = 512};
  for (int i = 1; i < argc; ++i) {
    bool ok = true;
    if (!strcmp(argv[i], "--headless"))
      o->headless = true;
    else if (!strcmp(argv[i], "--levels"))
      o->levels = true;
    else if (!strcmp(argv[i], "--wireframe"))
      o->wireframe = true;
    else if (argv[i][0] != '-' && !o->model)
      o->model = argv[i];
    else {
      ok = i + 1 < argc && parse_value(o, argv[i], argv[i + 1]);
      ++i; /* the value */
    }
    if (!ok) {
      fprintf(stderr, "usage: viewer [MODEL] [--backend gl|vulkan] [--frames N] [--size PIXELS] [--levels] "
                      "[--wireframe] [--headless -o out.png]\n");
      return false;
    }
  }
  if (o->frames < 0) o->frames = o->headless ? 3 : 0;
  if (o->headless && !o->out) o->out = "viewer.png";
  if ((o->headless && o->frames < 1) || o->size < 16 || o->size > 4096) {
    fprintf(stderr, "viewer: --headless needs --frames >= 1; --size 16..4096\n");
    return false;
  }
  return true;
}

/* ---- the model -------------------------------------------------------- */

#if VIEWER_HAS_IMPORT
/* Positions moved and scaled so the bounding box's centre is the origin and
 * its half diagonal 1. */
static float* unit_positions(const tlod_import_result* r) {
  float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, half = 0;
  for (uint32_t v = 0; v < r->vertex_count; ++v)
    for (int k = 0; k < 3; ++k)
      lo[k] = fminf(lo[k], r->positions[3 * v + k]), hi[k] = fmaxf(hi[k], r->positions[3 * v + k]);
  for (int k = 0; k < 3; ++k)
    half += 0.25f * (hi[k] - lo[k]) * (hi[k] - lo[k]);
  float scale = half > 0 ? 1.0f / sqrtf(half) : 1.0f, *p = malloc(sizeof(float) * 3 * r->vertex_count);
  for (uint32_t v = 0; p && v < r->vertex_count; ++v)
    for (int k = 0; k < 3; ++k)
      p[3 * v + k] = (r->positions[3 * v + k] - 0.5f * (lo[k] + hi[k])) * scale;
  return p;
}

static bool import_model(model* m, const char* path) {
  char err[512] = "";
  tlod_import_result* r = NULL;
  if (tlod_import_file(path, NULL, &r, err, sizeof err) != TLOD_SUCCESS) {
    fprintf(stderr, "viewer: %s\n", err);
    return false;
  }
  m->imported = r;
  if (!(m->positions = unit_positions(r))) return false;
  m->desc = (tlod_mesh_desc){.positions = m->positions,
                             .normals = r->normals,
                             .vertex_count = r->vertex_count,
                             .indices = r->indices,
                             .index_count = r->index_count,
                             .face_type = r->face_sizes ? TLOD_FACE_MIXED : TLOD_FACE_TRIANGLES,
                             .face_sizes = r->face_sizes,
                             .face_count = r->face_count,
                             .normal_mode = r->normals ? TLOD_NORMALS_KEEP : TLOD_NORMALS_ANGLE,
                             .label = path,
                             .attributes = m->attributes};
  for (uint32_t i = 0; i < r->attribute_count && i < 8; ++i, ++m->desc.attribute_count)
    m->attributes[i] = (tlod_attribute_desc){
        .data = r->attributes[i].data, .components = r->attributes[i].components, .name = r->attributes[i].name};
  return true;
}
#endif

/* The model's mesh desc in m->desc; the checker material only for the sphere. */
static bool load_model(model* m, const char* path) {
  memset(m, 0, sizeof *m);
  if (!path) {
    if (!sample_sphere_make(&m->sphere, 6, 12)) return false;
    m->desc = sample_mesh_desc(&m->sphere, &m->attributes[0]);
    return true;
  }
#if VIEWER_HAS_IMPORT
  return import_model(m, path);
#else
  fprintf(stderr, "viewer: %s: this build has no importer (TLOD_BUILD_TOOLS off): only the built-in sphere\n", path);
  return false;
#endif
}

static void free_model(model* m) {
  sample_mesh_free(&m->sphere);
  free(m->positions);
#if VIEWER_HAS_IMPORT
  tlod_import_free(m->imported);
#endif
}

/* ---- input (window mode) ---------------------------------------------- */

static void on_key(GLFWwindow* w, int key, int scancode, int action, int mods) {
  (void)scancode, (void)mods;
  view_state* v = glfwGetWindowUserPointer(w);
  if (action != GLFW_PRESS) return;
  if (key == GLFW_KEY_L) v->levels = !v->levels;
  if (key == GLFW_KEY_W) v->wireframe = !v->wireframe;
  if (key == GLFW_KEY_ESCAPE) glfwSetWindowShouldClose(w, GLFW_TRUE);
}

static void on_scroll(GLFWwindow* w, double dx, double dy) {
  (void)dx;
  view_state* v = glfwGetWindowUserPointer(w);
  v->distance = fminf(fmaxf(v->distance * powf(0.9f, (float)dy), 1.2f), 20.0f);
}

/* Dragging with the left button orbits: 0.01 radians per pixel. */
static void poll_drag(GLFWwindow* w, view_state* v) {
  double x, y;
  glfwGetCursorPos(w, &x, &y);
  bool down = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
  if (down && v->dragging) {
    v->yaw -= 0.01f * (float)(x - v->last_x);
    v->pitch = fminf(fmaxf(v->pitch + 0.01f * (float)(y - v->last_y), -1.5f), 1.5f);
  }
  v->dragging = down, v->last_x = x, v->last_y = y;
}

/* ---- drawing ---------------------------------------------------------- */

/* PN for triangle meshes, Phong for meshes with quads (sample_scene_init). */
#define TYPES ((1u << TLOD_SURFACE_PN) | (1u << TLOD_SURFACE_PHONG))

static tlod_device_desc device_desc(tlod_platform* p, bool checker) {
  const char* hook = checker ? sample_checker_hook : NULL;
  tlod_device_desc d = {.backend = "gl", .gl = {.surface_types = TYPES, .fragment_hook = hook}};
  d.vk = (tlod_device_vk_desc){.surface_types = TYPES, .fragment_hook = hook};
  if (tlod_platform_vk_device_desc(p, &d.vk)) d.backend = "vulkan";
  return d;
}

/* One frame: the platform's clear, tesslod's draw, the platform's submit. */
static bool draw_frame(tlod_platform* p, sample_scene* s, const view_state* v, uint64_t* triangles) {
  uint32_t w, h;
  tlod_platform_size(p, &w, &h);
  float c = cosf(v->pitch), d = v->distance;
  tlod_view_desc view = sample_orbit_camera(v->yaw, d * c, d * sinf(v->pitch), w, h);
  tlod_draw_item item;
  tlod_draw_desc draw;
  char err[256] = "";
  tlod_platform_frame f;
  if (!sample_scene_plan(s, &view, 16.7f, &item, &draw, "viewer")) return false;
  draw.debug = v->levels ? TLOD_DEBUG_LEVELS : TLOD_DEBUG_NONE;
  draw.wireframe = v->wireframe;
  if (!tlod_platform_begin_frame(p, clear_rgba, &f, err, sizeof err)) {
    fprintf(stderr, "viewer: %s\n", err);
    return false;
  }
  draw.vk = (tlod_draw_vk_desc){.command_buffer = f.command_buffer, .frame_index = f.frame_index};
  bool ok = sample_check(tlod_device_draw(s->dev, &draw), s, "tlod_device_draw", "viewer");
  if (!tlod_platform_end_frame(p, NULL, err, sizeof err)) {
    fprintf(stderr, "viewer: %s\n", err);
    return false;
  }
  *triangles = tlod_device_query_stats(s->dev).triangles;
  return ok;
}

static bool screenshot(tlod_platform* p, const char* path) {
  uint32_t w, h;
  tlod_platform_size(p, &w, &h);
  uint8_t* px = malloc((size_t)w * h * 4);
  char err[256] = "";
  bool ok = px && tlod_platform_read_rgba(p, px) && tlod_png_write(path, w, h, px, err, sizeof err);
  if (!ok) fprintf(stderr, "viewer: screenshot %s failed %s\n", path, err);
  free(px);
  return ok;
}

static bool loop(tlod_platform* p, sample_scene* s, const options* o, view_state* v) {
  GLFWwindow* win = tlod_platform_glfw_window(p);
  if (win) {
    glfwSetWindowUserPointer(win, v);
    glfwSetKeyCallback(win, on_key);
    glfwSetScrollCallback(win, on_scroll);
  }
  bool ok = true;
  for (int f = 0; ok && (o->frames == 0 || f < o->frames) && !tlod_platform_should_close(p); ++f) {
    uint64_t triangles = 0;
    if (win) poll_drag(win, v);
    if (o->headless) v->yaw = 0.4f * (float)f; /* headless: the camera moves by itself */
    ok = draw_frame(p, s, v, &triangles);
    if (ok && (o->headless || f % 120 == 0)) printf("frame %d: %llu triangles\n", f, (unsigned long long)triangles);
    if (ok && o->out && f == o->frames - 1) ok = screenshot(p, o->out); /* GL window: before the swap */
    tlod_platform_swap(p);
  }
  return ok;
}

int main(int argc, char** argv) {
  options o;
  if (!parse_options(argc, argv, &o)) return 2;
  model m;
  char err[512] = "";
  tlod_platform* p = NULL;
  if (!load_model(&m, o.model)) {
    free_model(&m);
    return 1;
  }
  tlod_platform_desc pd = {.width = o.size,
                           .height = o.size,
                           .window = !o.headless,
                           .visible = true,
                           .title = "tesslod viewer",
                           .api = o.api};
  if (!tlod_platform_create(&pd, &p, err, sizeof err)) {
    fprintf(stderr, "viewer: %s\n", err);
    free_model(&m);
    return 1;
  }
  printf("%s\n", tlod_platform_describe(p, err, sizeof err));
  sample_scene s;
  view_state v = {.yaw = 0, .pitch = 0.25f, .distance = 3.5f, .levels = o.levels, .wireframe = o.wireframe};
  bool ok = sample_scene_init(&s, &m.desc, device_desc(p, !o.model), "viewer") && loop(p, &s, &o, &v);
  sample_scene_free(&s);
  tlod_platform_destroy(p);
  free_model(&m);
  return ok ? 0 : 1;
}
