/* tlod play -- loading the scene: a file or demo mesh, or the demo scene
 * (the VTK cow beside a creased cylinder). */
#include "play_scene.h"

#include <stdio.h>
#include <string.h>

#include "cli.h"

void play_scene_free(play_scene* s) {
  for (uint32_t i = 0; i < s->count; i++) {
    play_object* ob = &s->objects[i];
    tlod_scheduler_destroy(ob->scheduler);
    scene_setup_destroy(&ob->setup);
  }
  play_scene_destroy_device(s);
  tlod_patterns_destroy(s->patterns);
  tlod_context_destroy(s->ctx);
  memset(s, 0, sizeof(*s));
}

static void grow_bounds(play_scene* s, const tlod_mesh_info* info) {
  for (int k = 0; k < 3; k++) {
    bool first = s->count == 1;
    s->bmin[k] = first || info->bbox_min[k] < s->bmin[k] ? info->bbox_min[k] : s->bmin[k];
    s->bmax[k] = first || info->bbox_max[k] > s->bmax[k] ? info->bbox_max[k] : s->bmax[k];
  }
}

static void describe(play_object* ob, const char* source, const char* name, const float color[4]) {
  play_object_info* pi = &ob->info;
  const cli_mesh* in = &ob->setup.in;
  snprintf(pi->name, sizeof(pi->name), "%s", name);
  snprintf(pi->source, sizeof(pi->source), "%s", source);
  pi->vertices = tlod_mesh_vertex_count(ob->setup.mesh);
  pi->faces = tlod_mesh_query_info(ob->setup.mesh).face_count;
  pi->patches = tlod_surface_patch_count(ob->setup.surface);
  memcpy(pi->color, in->has_color ? in->base_color : color, sizeof(pi->color));
}

/* Loads SOURCE (file or demo:NAME) as object `name`; place, when given, moves it (see demo_place). */
static int add_object(play_scene* s, const play_options* o, const char* source, const char* name, const float color[4],
                      void (*place)(cli_mesh* m, const void* scene)) {
  play_object* ob = &s->objects[s->count];
  memset(ob, 0, sizeof(*ob));
  /* As tlod tessellate: alpha 0.75, so a frame matches a direct run of the same camera. */
  scene_setup_desc d = {.input = source,
                        .label = name,
                        .surface = o->surface,
                        .alpha_mode = TLOD_ALPHA_GLOBAL,
                        .alpha = 0.75f,
                        .place = place,
                        .place_user = s};
  int rc = scene_setup_create(s->ctx, &d, &ob->setup);
  if (rc != CLI_OK) return rc;
  s->count++; /* from here on play_scene_free frees it */
  tlod_mesh_info info = tlod_mesh_query_info(ob->setup.mesh);
  if (info.face_count == 0) return cli_error(CLI_FAILED, "%s: no faces left to draw", source);
  describe(ob, source, name, color);
  grow_bounds(s, &info);
  return CLI_OK;
}

/* The demo cylinder (radius 1, height 1.2 along z) stood upright beside the
 * cow's flank: a drum half the cow's height on the cow's ground. Rotation
 * (x, y, z) -> (x, z, -y) keeps the winding; the scale is the same in x and
 * z, so the normals (radial or axial) keep their directions. */
static void demo_place(cli_mesh* m, const void* scene) {
  const play_scene* s = scene;
  const float height = 0.6f * (s->bmax[1] - s->bmin[1]), radius = 0.25f * height;
  const float c[3] = {0.5f * (s->bmin[0] + s->bmax[0]), s->bmin[1] + 0.5f * height,
                      s->bmax[2] + 0.5f * radius + radius};
  for (uint32_t v = 0; v < m->vertex_count; v++) {
    float* p = m->positions + 3 * v;
    float x = p[0], y = p[1], z = p[2];
    p[0] = c[0] + radius * x;
    p[1] = c[1] + height / 1.2f * z;
    p[2] = c[2] - radius * y;
    if (m->normals) {
      float* n = m->normals + 3 * v;
      float ny = n[1];
      n[1] = n[2];
      n[2] = -ny;
    }
  }
}

static int add_objects(const play_options* o, play_scene* s) {
  if (!o->scene || !strcmp(o->scene, "demo:scene")) {
    snprintf(s->name, sizeof(s->name), "demo:scene");
    static const float cow[4] = {0.80f, 0.62f, 0.46f, 1.0f}, drum[4] = {0.42f, 0.58f, 0.82f, 1.0f};
    int rc = add_object(s, o, "demo:cow", "cow", cow, NULL);
    return rc == CLI_OK ? add_object(s, o, "demo:cylinder", "cylinder", drum, demo_place) : rc;
  }
  snprintf(s->name, sizeof(s->name), "%s", o->scene);
  const char* base = strrchr(o->scene, '/');
  base = base ? base + 1 : o->scene;
  if (!strncmp(base, "demo:", 5)) base += 5;
  static const float grey[4] = {0.8f, 0.8f, 0.8f, 1.0f};
  return add_object(s, o, o->scene, base, grey, NULL);
}

int play_scene_load(const play_options* o, play_scene* s) {
  memset(s, 0, sizeof(*s));
  if (tlod_context_create(&(tlod_context_desc){.label = "tlod play"}, &s->ctx) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "cannot create a context");
  int rc = add_objects(o, s);
  if (rc != CLI_OK) return rc;
  /* One pattern set for every object and mode: the finest level any mode needs. */
  tlod_patterns_desc pd = {.max_level = play_modes_max_level(o)};
  if (tlod_patterns_create(s->ctx, &pd, &s->patterns) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "%s", tlod_context_last_error(s->ctx));
  for (uint32_t i = 0; i < s->count; i++)
    s->infos[i] = s->objects[i].info;
  return CLI_OK;
}

int play_scene_create_device(play_scene* s, const char* backend, tlod_surface_type type) {
  play_scene_destroy_device(s);
  /* One surface type per run: the gl device links its two programs only. */
  tlod_device_desc d = {.backend = backend,
                        .patterns = s->patterns,
                        .gl = {.surface_types = 1u << (type == TLOD_SURFACE_DEFAULT ? TLOD_SURFACE_PHONG : type)},
                        .label = "tlod play"};
  if (tlod_device_create(s->ctx, &d, &s->device) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "backend %s: %s", backend, tlod_context_last_error(s->ctx));
  for (uint32_t i = 0; i < s->count; i++) {
    play_object* ob = &s->objects[i];
    if (tlod_device_create_surface(s->device, ob->setup.surface, &ob->surface) != TLOD_SUCCESS)
      return cli_error(CLI_FAILED, "backend %s: %s: %s", backend, ob->info.name, tlod_context_last_error(s->ctx));
  }
  return CLI_OK;
}

void play_scene_destroy_device(play_scene* s) {
  for (uint32_t i = 0; i < s->count; i++)
    s->objects[i].surface = NULL; /* destroyed with the device */
  tlod_device_destroy(s->device);
  s->device = NULL;
}
