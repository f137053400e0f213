/* tlod play -- a glTF scene along the timeline: the chosen animation
 * sampled at the frame's time (looping over its duration), node world
 * matrices down the hierarchy, the objects' world matrices, and the skinned
 * surfaces skinned on the CPU, updated, refreshed (only the patches that
 * moved) and uploaded again (docs/play.md "Animation and skinning"). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "common/strict_number.h"
#include "play_scene.h"
#include "tlod_import.h"

static const float k_identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

/* --animation: NULL the first, "none", an index or a name; UINT32_MAX: none. */
static int pick_animation(const play_scene* s, const char* want, uint32_t* out) {
  const tlod_import_result* r = s->import;
  *out = UINT32_MAX;
  if (!want) return *out = r->animation_count ? 0 : UINT32_MAX, CLI_OK;
  if (!strcmp(want, "none")) return CLI_OK;
  for (uint32_t a = 0; a < r->animation_count; a++)
    if (!strcmp(r->animations[a].name, want)) return *out = a, CLI_OK;
  const char* end = NULL;
  int64_t v = 0;
  if (number_parse_int(want, &end, 0, INT64_MAX, &v) == NUMBER_OK && !*end && v < (int64_t)r->animation_count)
    return *out = (uint32_t)v, CLI_OK;
  return cli_error(CLI_USAGE, "--animation %s: %s has no such animation (%u animation%s: index 0..%d or a name)", want,
                   s->name, r->animation_count, r->animation_count == 1 ? "" : "s", (int)r->animation_count - 1);
}

static anim_channel adapt_channel(const tlod_import_channel* c) {
  static const anim_path paths[] = {ANIM_PATH_TRANSLATION, ANIM_PATH_ROTATION, ANIM_PATH_SCALE};
  static const anim_interp interps[] = {ANIM_INTERP_LINEAR, ANIM_INTERP_STEP, ANIM_INTERP_CUBICSPLINE};
  return (anim_channel){.node = c->node,
                        .path = paths[c->path <= TLOD_IMPORT_PATH_SCALE ? c->path : 0],
                        .interp = interps[c->interp <= TLOD_IMPORT_INTERP_CUBICSPLINE ? c->interp : 0],
                        .key_count = c->key_count,
                        .times = c->times,
                        .values = c->values};
}

static int adapt_animation(play_scene* s, uint32_t a) {
  const tlod_import_animation* ia = &s->import->animations[a];
  play_animation* pa = &s->animation;
  snprintf(pa->name, sizeof(pa->name), "%s", ia->name[0] ? ia->name : "0");
  if (!(pa->channels = calloc(ia->channel_count ? ia->channel_count : 1, sizeof(anim_channel))))
    return cli_error(CLI_FAILED, "out of memory");
  for (uint32_t c = 0; c < ia->channel_count; c++) {
    pa->channels[c] = adapt_channel(&ia->channels[c]);
    if (pa->channels[c].node < s->import->node_count) s->animated[pa->channels[c].node] = true;
  }
  pa->channel_count = ia->channel_count;
  pa->duration_s = anim_duration(pa->channels, pa->channel_count);
  return CLI_OK;
}

static int alloc_pose(play_scene* s) {
  const tlod_import_result* r = s->import;
  uint32_t n = r->node_count ? r->node_count : 1;
  for (uint32_t k = 0; k < r->skin_count; k++)
    s->max_joints = r->skins[k].joint_count > s->max_joints ? r->skins[k].joint_count : s->max_joints;
  s->rest = calloc(n, sizeof(anim_trs));
  s->pose = calloc(n, sizeof(anim_trs));
  s->local = calloc(n, sizeof(*s->local));
  s->world = calloc(n, sizeof(*s->world));
  s->parents = calloc(n, sizeof(uint32_t));
  s->scratch = calloc(2 * (size_t)n, sizeof(uint32_t));
  s->animated = calloc(n, sizeof(bool));
  s->joint_world = calloc(s->max_joints ? s->max_joints : 1, sizeof(*s->joint_world));
  s->joint_mats = calloc(s->max_joints ? s->max_joints : 1, sizeof(*s->joint_mats));
  bool ok = s->rest && s->pose && s->local && s->world && s->parents && s->scratch && s->animated && s->joint_world &&
            s->joint_mats;
  return ok ? CLI_OK : cli_error(CLI_FAILED, "out of memory for %u nodes", r->node_count);
}

int play_anim_setup(play_scene* s, const play_options* o) {
  const tlod_import_result* r = s->import;
  int rc = alloc_pose(s);
  if (rc != CLI_OK) return rc;
  for (uint32_t n = 0; n < r->node_count; n++) {
    const tlod_import_node* nd = &r->nodes[n];
    memcpy(s->rest[n].translation, nd->translation, sizeof(nd->translation));
    memcpy(s->rest[n].rotation, nd->rotation, sizeof(nd->rotation));
    memcpy(s->rest[n].scale, nd->scale, sizeof(nd->scale));
    s->parents[n] = nd->parent;
  }
  uint32_t a;
  rc = pick_animation(s, o->animation, &a);
  return rc == CLI_OK && a != UINT32_MAX ? adapt_animation(s, a) : rc;
}

/* Node world matrices at animation time t. */
static int pose_nodes(play_scene* s, float t) {
  const tlod_import_result* r = s->import;
  memcpy(s->pose, s->rest, sizeof(anim_trs) * r->node_count);
  anim_apply(s->animation.channels, s->animation.channel_count, t, s->pose, r->node_count);
  for (uint32_t n = 0; n < r->node_count; n++) {
    if (s->animated[n])
      anim_trs_matrix(&s->pose[n], s->local[n]);
    else
      memcpy(s->local[n], r->nodes[n].local, sizeof(s->local[n]));
  }
  if (!anim_world_matrices(r->node_count, s->parents, (const float(*)[16])s->local, s->world, s->scratch))
    return cli_error(CLI_FAILED, "%s: the nodes' parents form a cycle", s->name);
  return CLI_OK;
}

/* Skins surface sf by its skin's joints this frame; mesh update, refresh, upload. */
static int skin_surface(play_scene* s, play_surface* sf) {
  const tlod_import_skin* sk = &s->import->skins[sf->skinning->skin];
  for (uint32_t j = 0; j < sk->joint_count; j++)
    memcpy(s->joint_world[j], sk->joints[j] < s->import->node_count ? s->world[sk->joints[j]] : k_identity,
           sizeof(s->joint_world[j]));
  skin_joint_matrices(sk->joint_count, (const float(*)[16])s->joint_world, (const float(*)[16])sk->inverse_bind,
                      s->joint_mats);
  play_skinning* k = sf->skinning;
  skin_apply(s->ctx, &k->rest, sk->joint_count, (const float(*)[16])s->joint_mats, k->positions,
             k->rest.rest_normals ? k->normals : NULL);
  tlod_result res = tlod_mesh_update(sf->setup.mesh, k->positions, 0, k->rest.rest_normals ? k->normals : NULL, 0);
  if (res == TLOD_SUCCESS) res = tlod_surface_refresh(sf->setup.surface, NULL);
  if (res == TLOD_SUCCESS && sf->device_surface) res = tlod_device_update_surface(s->device, sf->device_surface);
  return res == TLOD_SUCCESS ? CLI_OK
                             : cli_error(CLI_FAILED, "%s: skinning: %s", s->name, tlod_context_last_error(s->ctx));
}

int play_scene_pose(play_scene* s, double t) {
  if (!s->import) return CLI_OK;
  double d = s->animation.duration_s;
  int rc = pose_nodes(s, d > 0.0 ? (float)fmod(t, d) : 0.0f);
  for (uint32_t i = 0; rc == CLI_OK && i < s->count; i++) {
    play_object* ob = &s->objects[i];
    play_surface* sf = &s->surfaces[ob->surface];
    /* glTF: a skinned mesh's vertices are placed by its joints alone. */
    memcpy(ob->world, sf->skinning ? k_identity : s->world[ob->node], sizeof(ob->world));
    if (sf->skinning) rc = skin_surface(s, sf);
  }
  return rc;
}

void play_gltf_free(play_scene* s) {
  for (uint32_t i = 0; i < s->surface_count; i++) {
    play_skinning* k = s->surfaces[i].skinning;
    if (k) free(k->positions), free(k->normals), free(k);
  }
  free(s->animation.channels);
  free(s->rest), free(s->pose), free(s->local), free(s->world), free(s->parents), free(s->scratch);
  free(s->animated), free(s->joint_world), free(s->joint_mats);
  tlod_import_free(s->import);
}
