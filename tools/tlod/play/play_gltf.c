/* tlod play -- a glTF scene as objects: the importer keeps the scene
 * (keep_scene: each mesh's geometry once, in mesh space, and the nodes
 * instancing it); every (node, part) is an object with the part's material
 * and the node's world matrix; the parts of a mesh are surfaces made once
 * and drawn by every node using the mesh; a skinned node gets its own copy
 * of each part's surface (its vertices move every frame). Parts become
 * meshes through the loading layer (cli_create_part_mesh). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "cli.h"
#include "common/mesh_load.h"
#include "play_scene.h"
#include "tlod_import.h"

bool play_scene_is_gltf(const char* scene) {
  const char* ext = strrchr(scene, '.');
  return strncmp(scene, "demo:", 5) != 0 && ext && (!strcasecmp(ext, ".gltf") || !strcasecmp(ext, ".glb"));
}

/* Surface of part `part` into s->surfaces[s->surface_count]. */
static int add_surface(play_scene* s, const play_options* o, uint32_t part) {
  play_surface* sf = &s->surfaces[s->surface_count];
  cli_part_options po = {.split_quads = o->surface == TLOD_SURFACE_PN};
  int rc = cli_create_part_mesh(s->ctx, s->import, part, &po, &sf->setup.mesh);
  if (rc != CLI_OK) return rc;
  s->surface_count++; /* play_scene_free frees it from here on */
  tlod_surface_desc sd = {
      .type = o->surface, .alpha_mode = TLOD_ALPHA_GLOBAL, .alpha = 0.75f, .label = s->import->parts[part].name};
  if (tlod_surface_create(s->ctx, sf->setup.mesh, &sd, &sf->setup.surface) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "%s: %s", s->name, tlod_context_last_error(s->ctx));
  return CLI_OK;
}

/* A skinned copy's rest arrays (the import's) and skinned buffers. */
static int add_skinning(play_scene* s, play_surface* sf, uint32_t part, uint32_t skin) {
  const tlod_import_result* r = s->import;
  const tlod_import_part* p = &r->parts[part];
  play_skinning* k = calloc(1, sizeof(*k));
  if (!k) return cli_error(CLI_FAILED, "out of memory");
  sf->skinning = k;
  k->skin = skin;
  k->rest = (skin_vertices){p->vertex_count, r->positions + (size_t)3 * p->first_vertex,
                            r->normals ? r->normals + (size_t)3 * p->first_vertex : NULL,
                            r->joints + (size_t)4 * p->first_vertex, r->weights + (size_t)4 * p->first_vertex};
  k->positions = malloc(sizeof(float) * 3 * p->vertex_count);
  k->normals = malloc(sizeof(float) * 3 * p->vertex_count);
  return k->positions && k->normals ? CLI_OK : cli_error(CLI_FAILED, "out of memory");
}

static play_material material_of(const tlod_import_result* r, uint32_t m) {
  play_material pm = {.color = {1, 1, 1, 1}, .texture = UINT32_MAX, .texcoord = UINT32_MAX, .alpha_cutoff = 0.5f};
  if (m >= r->material_count) return pm;
  const tlod_import_material* im = &r->materials[m];
  memcpy(pm.color, im->base_color, sizeof(pm.color));
  uint32_t tex = im->base_color_texture;
  if (tex < r->texture_count && r->textures[tex].image < r->image_count && r->images[r->textures[tex].image].rgba &&
      im->base_color_texcoord < r->attribute_count)
    pm.texture = tex, pm.texcoord = im->base_color_texcoord;
  pm.blend = (uint32_t)im->alpha_mode;
  pm.alpha_cutoff = im->alpha_cutoff;
  pm.double_sided = im->double_sided;
  return pm;
}

/* Object for node n drawing surface sf of part `part` (its material). */
static void add_object(play_scene* s, uint32_t n, uint32_t part, uint32_t sf) {
  const tlod_import_result* r = s->import;
  play_object* ob = &s->objects[s->count++];
  *ob = (play_object){.surface = sf, .node = n, .material = material_of(r, r->parts[part].material)};
  memcpy(ob->world, r->nodes[n].world, sizeof(ob->world));
  char name[64];
  const tlod_import_mesh* m = &r->meshes[r->nodes[n].mesh];
  if (m->part_count > 1)
    snprintf(name, sizeof(name), "%.40s/%u", r->nodes[n].name, part - m->first_part);
  else
    snprintf(name, sizeof(name), "%s", r->nodes[n].name[0] ? r->nodes[n].name : m->name);
  play_object_describe(s, ob, s->name, name);
}

/* Surfaces of mesh m's parts, made at the first node using it. */
static int node_objects(play_scene* s, const play_options* o, uint32_t n, uint32_t* part_surface) {
  const tlod_import_result* r = s->import;
  const tlod_import_node* nd = &r->nodes[n];
  const tlod_import_mesh* m = &r->meshes[nd->mesh];
  bool skinned = nd->skin < r->skin_count && r->joints && r->weights;
  for (uint32_t k = 0; k < m->part_count; k++) {
    uint32_t part = m->first_part + k;
    int rc = CLI_OK;
    if (skinned) {
      rc = add_surface(s, o, part);
      if (rc == CLI_OK) rc = add_skinning(s, &s->surfaces[s->surface_count - 1], part, nd->skin);
      if (rc == CLI_OK) add_object(s, n, part, s->surface_count - 1);
    } else {
      if (part_surface[part] == UINT32_MAX && (rc = add_surface(s, o, part)) == CLI_OK)
        part_surface[part] = s->surface_count - 1;
      if (rc == CLI_OK) add_object(s, n, part, part_surface[part]);
    }
    if (rc != CLI_OK) return rc;
  }
  return CLI_OK;
}

/* Objects and surfaces a scene needs (nodes with a mesh x its parts). */
static void count_instances(const tlod_import_result* r, uint32_t* objects, uint32_t* skinned) {
  *objects = *skinned = 0;
  for (uint32_t n = 0; n < r->node_count; n++) {
    const tlod_import_node* nd = &r->nodes[n];
    if (nd->mesh >= r->mesh_count) continue;
    *objects += r->meshes[nd->mesh].part_count;
    if (nd->skin < r->skin_count) *skinned += r->meshes[nd->mesh].part_count;
  }
}

static int make_objects(play_scene* s, const play_options* o) {
  const tlod_import_result* r = s->import;
  uint32_t objects, skinned;
  count_instances(r, &objects, &skinned);
  if (objects == 0) return cli_error(CLI_FAILED, "%s: no node draws a mesh", s->name);
  int rc = play_scene_reserve(s, r->part_count + skinned, objects);
  uint32_t* part_surface = malloc(sizeof(uint32_t) * (r->part_count ? r->part_count : 1));
  if (rc == CLI_OK && !part_surface) rc = cli_error(CLI_FAILED, "out of memory");
  for (uint32_t p = 0; rc == CLI_OK && p < r->part_count; p++)
    part_surface[p] = UINT32_MAX;
  for (uint32_t n = 0; rc == CLI_OK && n < r->node_count; n++)
    if (r->nodes[n].mesh < r->mesh_count) rc = node_objects(s, o, n, part_surface);
  free(part_surface);
  return rc;
}

/* Importer warnings, kept for the trace and printed once, here. */
static void keep_warnings(play_scene* s, const play_options* o) {
  const tlod_import_result* r = s->import;
  snprintf(s->warnings, sizeof(s->warnings), "%s", r->warnings);
  s->warning_count = r->warning_count;
  if (o->quiet || !r->warning_count) return;
  fprintf(stderr, "tlod play: %s: %u importer warning%s:\n%s%s", s->name, r->warning_count,
          r->warning_count == 1 ? "" : "s", r->warnings,
          r->warnings[0] && r->warnings[strlen(r->warnings) - 1] != '\n' ? "\n" : "");
}

int play_gltf_load(const play_options* o, play_scene* s) {
  int rc = cli_load_scene(o->scene, &s->import);
  if (rc != CLI_OK) return rc;
  keep_warnings(s, o);
  rc = make_objects(s, o);
  if (rc == CLI_OK) rc = play_anim_setup(s, o);
  if (rc == CLI_OK) rc = play_scene_pose(s, 0.0);
  for (uint32_t i = 0; rc == CLI_OK && i < s->count; i++) {
    char name[64];
    snprintf(name, sizeof(name), "%s", s->objects[i].info.name);
    play_object_describe(s, &s->objects[i], s->name, name); /* skinned at rest now */
    play_scene_grow_bounds(s, &s->objects[i], i == 0);
  }
  return rc;
}
