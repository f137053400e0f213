/* tlod play -- loading the scene: the demo scene (the VTK cow beside a
 * creased cylinder), a file or demo mesh as one object, or a glTF scene
 * (play_gltf.c); the arrays, patterns and device every scene has. */
#include "play_scene.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "common/gpu_target.h"
#include "field/field_hook.h"

static const float k_identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

void play_scene_free(play_scene* s) {
  for (uint32_t i = 0; i < s->count; i++)
    tlod_scheduler_destroy(s->objects[i].scheduler);
  play_scene_destroy_device(s);
  for (uint32_t i = 0; i < s->surface_count; i++)
    scene_setup_destroy(&s->surfaces[i].setup);
  play_gltf_free(s);
  play_series_free(s);
  free(s->field.hook);
  free(s->surfaces);
  free(s->objects);
  free(s->infos);
  tlod_patterns_destroy(s->patterns);
  tlod_context_destroy(s->ctx);
  memset(s, 0, sizeof(*s));
}

/* Room for n surfaces and n objects. */
int play_scene_reserve(play_scene* s, uint32_t surfaces, uint32_t objects) {
  if (objects > PLAY_MAX_OBJECTS || surfaces > PLAY_MAX_OBJECTS)
    return cli_error(CLI_FAILED, "%s: %u objects, more than the %u tlod play draws", s->name,
                     objects > surfaces ? objects : surfaces, PLAY_MAX_OBJECTS);
  s->surfaces = calloc(surfaces ? surfaces : 1, sizeof(play_surface));
  s->objects = calloc(objects ? objects : 1, sizeof(play_object));
  s->infos = calloc(objects ? objects : 1, sizeof(play_object_info));
  return s->surfaces && s->objects && s->infos ? CLI_OK
                                               : cli_error(CLI_FAILED, "out of memory for %u objects", objects);
}

static void grow_bounds(play_scene* s, const float bmin[3], const float bmax[3], bool first) {
  for (int k = 0; k < 3; k++) {
    s->bmin[k] = first || bmin[k] < s->bmin[k] ? bmin[k] : s->bmin[k];
    s->bmax[k] = first || bmax[k] > s->bmax[k] ? bmax[k] : s->bmax[k];
  }
}

void play_scene_grow_bounds(play_scene* s, const play_object* ob, bool first) {
  tlod_mesh_info info = tlod_mesh_query_info(s->surfaces[ob->surface].setup.mesh);
  float lo[3], hi[3];
  for (int c = 0; c < 8; c++) {
    float p[3] = {c & 1 ? info.bbox_max[0] : info.bbox_min[0], c & 2 ? info.bbox_max[1] : info.bbox_min[1],
                  c & 4 ? info.bbox_max[2] : info.bbox_min[2]};
    for (int r = 0; r < 3; r++) {
      float w = ob->world[r] * p[0] + ob->world[4 + r] * p[1] + ob->world[8 + r] * p[2] + ob->world[12 + r];
      lo[r] = c == 0 || w < lo[r] ? w : lo[r];
      hi[r] = c == 0 || w > hi[r] ? w : hi[r];
    }
  }
  grow_bounds(s, lo, hi, first);
}

void play_object_describe(play_scene* s, play_object* ob, const char* source, const char* name) {
  play_object_info* pi = &ob->info;
  const play_surface* sf = &s->surfaces[ob->surface];
  snprintf(pi->name, sizeof(pi->name), "%s", name);
  snprintf(pi->source, sizeof(pi->source), "%s", source);
  pi->vertices = tlod_mesh_vertex_count(sf->setup.mesh);
  pi->faces = tlod_mesh_query_info(sf->setup.mesh).face_count;
  pi->patches = tlod_surface_patch_count(sf->setup.surface);
  memcpy(pi->color, ob->material.color, sizeof(pi->color));
  pi->surface = ob->surface;
  pi->node = ob->node == UINT32_MAX ? -1 : (int64_t)ob->node;
  pi->skinned = sf->skinning != NULL;
  pi->textured = ob->material.texture != UINT32_MAX;
}

/* Loads SOURCE (file or demo:NAME) as surface and object `name`; place,
 * when given, moves it (see demo_place). */
static int add_object(play_scene* s, const play_options* o, const char* source, const char* name, const float color[4],
                      void (*place)(cli_mesh* m, const void* scene)) {
  play_surface* sf = &s->surfaces[s->surface_count];
  /* As tlod tessellate: alpha 0.75, so a frame matches a direct run of the same camera. */
  scene_setup_desc d = {.input = source,
                        .label = name,
                        .surface = o->surface,
                        .crease_deg = o->crease,
                        .field = &o->field,
                        .alpha_mode = TLOD_ALPHA_GLOBAL,
                        .alpha = 0.75f,
                        .place = place,
                        .place_user = s};
  int rc = scene_setup_create(s->ctx, &d, &sf->setup);
  if (rc != CLI_OK) return rc;
  play_object* ob = &s->objects[s->count];
  *ob = (play_object){.surface = s->surface_count++, .node = UINT32_MAX};
  s->count++; /* from here on play_scene_free frees it */
  memcpy(ob->world, k_identity, sizeof(ob->world));
  const cli_mesh* in = &sf->setup.in;
  ob->material = (play_material){.texture = UINT32_MAX, .texcoord = UINT32_MAX};
  memcpy(ob->material.color, in->has_color ? in->base_color : color, sizeof(ob->material.color));
  if (tlod_mesh_query_info(sf->setup.mesh).face_count == 0)
    return cli_error(CLI_FAILED, "%s: no faces left to draw", source);
  play_object_describe(s, ob, source, name);
  play_scene_grow_bounds(s, ob, s->count == 1);
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
    int rc = play_scene_reserve(s, 2, 2);
    if (rc == CLI_OK) rc = add_object(s, o, "demo:cow", "cow", cow, NULL);
    return rc == CLI_OK ? add_object(s, o, "demo:cylinder", "cylinder", drum, demo_place) : rc;
  }
  snprintf(s->name, sizeof(s->name), "%s", o->scene);
  if (play_scene_is_gltf(o->scene)) return play_gltf_load(o, s);
  const char* base = strrchr(o->scene, '/');
  base = base ? base + 1 : o->scene;
  if (!strncmp(base, "demo:", 5)) base += 5;
  static const float grey[4] = {0.8f, 0.8f, 0.8f, 1.0f};
  int rc = play_scene_reserve(s, 1, 1);
  return rc == CLI_OK ? add_object(s, o, o->scene, base, grey, NULL) : rc;
}

/* The surface type made and the field of surface 0 (a file scene: one
 * object); glTF scenes and the demo scene have no fields. */
static int describe_field(const play_options* o, play_scene* s) {
  const scene_setup* st = s->surface_count ? &s->surfaces[0].setup : NULL;
  bool file = !play_scene_is_gltf(s->name) && st && st->mesh && st->in.source;
  s->surface_type = file ? st->surface_type : o->surface == TLOD_SURFACE_DEFAULT ? TLOD_SURFACE_PHONG : o->surface;
  if (!o->field.spec) return CLI_OK;
  if (!file || !st->has_field)
    return cli_error(CLI_FAILED, "--field %s: %s has no fields (they come from VTK files)", o->field.spec, s->name);
  s->field = (play_field){.on = true, .sel = st->field, .attribute = st->field_attribute};
  if (!(s->field.hook = field_hook_glsl(&st->field, st->field_attribute)))
    return cli_error(CLI_FAILED, "out of memory for the field's shader");
  return CLI_OK;
}

int play_scene_load(const play_options* o, play_scene* s) {
  memset(s, 0, sizeof(*s));
  if (tlod_context_create(&(tlod_context_desc){.label = "tlod play"}, &s->ctx) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "cannot create a context");
  int rc = add_objects(o, s);
  if (rc == CLI_OK) rc = describe_field(o, s);
  if (rc == CLI_OK) rc = play_series_setup(s);
  if (rc != CLI_OK) return rc;
  /* One pattern set for every object and mode: the finest level any mode needs. */
  tlod_patterns_desc pd = {.max_level = play_modes_max_level(o)};
  if (tlod_patterns_create(s->ctx, &pd, &s->patterns) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "%s", tlod_context_last_error(s->ctx));
  for (uint32_t i = 0; i < s->count; i++)
    s->infos[i] = s->objects[i].info;
  return CLI_OK;
}

int play_scene_create_device(play_scene* s, const char* backend, tlod_platform* platform, const char* shader_cache_dir,
                             tlod_gpu_eval gpu_eval) {
  play_scene_destroy_device(s);
  /* One surface type per run: the gl device links its two programs only. */
  tlod_device_desc d = {
      .backend = backend,
      .patterns = s->patterns,
      .gl = {.surface_types = 1u << s->surface_type, .fragment_hook = s->field.hook, .gpu_eval = gpu_eval},
      .label = "tlod play"};
  gpu_target_device_desc(platform, shader_cache_dir, false, &d);
  if (tlod_device_create(s->ctx, &d, &s->device) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "backend %s: %s", backend, tlod_context_last_error(s->ctx));
  for (uint32_t i = 0; i < s->surface_count; i++) {
    play_surface* sf = &s->surfaces[i];
    if (tlod_device_create_surface(s->device, sf->setup.surface, &sf->device_surface) != TLOD_SUCCESS)
      return cli_error(CLI_FAILED, "backend %s: surface %u: %s", backend, i, tlod_context_last_error(s->ctx));
  }
  return play_scene_create_textures(s);
}

void play_scene_destroy_device(play_scene* s) {
  for (uint32_t i = 0; i < s->surface_count; i++)
    s->surfaces[i].device_surface = NULL; /* destroyed with the device */
  play_scene_destroy_textures(s);
  tlod_device_destroy(s->device);
  s->device = NULL;
}
