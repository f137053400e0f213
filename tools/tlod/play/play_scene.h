/* tlod play -- the scene: surfaces (a core mesh and surface with its device
 * surface) and objects drawing them. The demo scene and OBJ/PLY files give
 * one object per surface; a glTF scene (play_gltf.c) one object per (node,
 * part) instance, objects of one glTF mesh sharing its surfaces, each with
 * its own scheduler (levels depend on each instance's view) and world
 * matrix from the (animated) node hierarchy; a skinned instance has its own
 * surface, skinned on the CPU every frame (play_anim.c). One pattern set
 * and one device for the whole run (every mode). */
#ifndef TLOD_TOOLS_PLAY_SCENE_H
#define TLOD_TOOLS_PLAY_SCENE_H

#include "common/anim_sample.h"
#include "common/scene_setup.h"
#include "common/skin_apply.h"
#include "play_options.h"
#include "play_trace.h"
#include "tesslod/backend.h"

/* Objects a scene may have: real scenes have hundreds to a few thousand
 * node instances; the arrays are allocated to the scene's count. */
#define PLAY_MAX_OBJECTS 4096u

typedef struct tlod_import_result tlod_import_result;

/* A skinned surface's rest pose and skin (arrays of the import result). */
typedef struct play_skinning {
  skin_vertices rest;
  uint32_t skin;              /* index into the scene's skins */
  float *positions, *normals; /* skinned, xyz per vertex */
} play_skinning;

typedef struct play_surface {
  scene_setup setup; /* mesh and surface (the patterns are the scene's) */
  tlod_device_surface* device_surface;
  play_skinning* skinning; /* NULL: rigid */
} play_surface;

typedef struct play_material {
  float color[4];    /* linear RGBA base colour factor */
  uint32_t texture;  /* index into the scene's device textures; UINT32_MAX: none */
  uint32_t texcoord; /* mesh attribute of its UVs */
  uint32_t blend;    /* tlod_import_alpha_mode: 0 opaque, 1 mask, 2 blend */
  float alpha_cutoff;
  bool double_sided;
} play_material;

typedef struct play_object {
  play_object_info info;
  uint32_t surface; /* index into surfaces */
  uint32_t node;    /* glTF node, UINT32_MAX: none (placed at the identity) */
  play_material material;
  float world[16]; /* object to world, this frame */
  tlod_scheduler* scheduler;
} play_object;

/* The file's node animation, adapted to the tools' anim_channel. */
typedef struct play_animation {
  char name[64];
  anim_channel* channels;
  uint32_t channel_count;
  float duration_s;
} play_animation;

/* A result field drawn through a colour map (tlod play --field). */
typedef struct play_field {
  bool on;
  field_selection sel;
  uint32_t attribute; /* the field's mesh attribute of surface 0 */
  char* hook;         /* the device's fragment hook (field_hook_glsl); NULL: none */
} play_field;

/* A VTK time series (the import's step_count >= 2; one object): the step
 * drawn follows the timeline (play_series.c). */
typedef struct play_series {
  uint32_t count; /* 0: no series */
  uint32_t step;  /* drawn now */
  float* scalars; /* vertex_count floats: the field at a step */
} play_series;

typedef struct play_scene {
  char name[256];
  tlod_surface_type surface_type; /* of the surfaces (auto resolved): the trace's "surface" */
  play_field field;
  play_series series;
  tlod_context* ctx;
  play_surface* surfaces;
  uint32_t surface_count;
  play_object* objects;
  play_object_info* infos; /* objects[i].info, for the traces */
  uint32_t count;
  tlod_patterns* patterns;
  tlod_device* device; /* one per run, reused by every mode */
  float bmin[3], bmax[3];
  /* glTF scenes */
  tlod_import_result* import; /* kept for the rest poses, skins and textures */
  anim_trs* rest;             /* node TRS of the rest pose */
  anim_trs* pose;             /* this frame's */
  float (*local)[16], (*world)[16];
  uint32_t* parents;
  uint32_t* scratch;                           /* anim_world_matrices: 2 per node */
  bool* animated;                              /* node has a channel of the played animation */
  float (*joint_world)[16], (*joint_mats)[16]; /* the largest skin's joint count */
  uint32_t max_joints;
  play_animation animation;       /* channel_count 0: none played */
  tlod_device_texture** textures; /* per import image, made once on the device */
  char warnings[1024];            /* the importer's, printed once at start */
  uint32_t warning_count;
} play_scene;

/* o->scene (or the demo scene) with patterns for every mode of o. */
int play_scene_load(const play_options* o, play_scene* s);
void play_scene_free(play_scene* s);

typedef struct tlod_platform tlod_platform;

/* The run's device (programs and patterns made once), one device surface
 * per surface and one device texture per image. vulkan: on the platform's
 * device (NULL otherwise), SPIR-V cached in shader_cache_dir (NULL: none). */
int play_scene_create_device(play_scene* s, const char* backend, tlod_platform* platform, const char* shader_cache_dir,
                             tlod_gpu_eval gpu_eval);
/* The device draws with the platform's context: destroy it while it exists. */
void play_scene_destroy_device(play_scene* s);

/* Grows the scene bounds by the object's mesh box at its world matrix (first: start them). */
void play_scene_grow_bounds(play_scene* s, const play_object* ob, bool first);
/* Fills ob->info from its surface and material. */
void play_object_describe(play_scene* s, play_object* ob, const char* source, const char* name);
/* Device textures of the glTF images (none before gl-material: a no-op). */
int play_scene_create_textures(play_scene* s);
void play_scene_destroy_textures(play_scene* s);

/* glTF scenes (play_gltf.c): objects, surfaces and animation of an import
 * kept with keep_scene; true when SCENE is a .gltf or .glb file. */
bool play_scene_is_gltf(const char* scene);
int play_gltf_load(const play_options* o, play_scene* s);
/* Room for the surfaces and objects (each at most PLAY_MAX_OBJECTS). */
int play_scene_reserve(play_scene* s, uint32_t surfaces, uint32_t objects);
void play_gltf_free(play_scene* s);
/* The animation o asks for (--animation) and the pose arrays. */
int play_anim_setup(play_scene* s, const play_options* o);
/* The pose at animation time t seconds (looping over the animation's
 * duration): world matrices of every object, skinned surfaces skinned,
 * updated, refreshed and uploaded (play_anim.c). */
int play_scene_pose(play_scene* s, double t);

/* Series (play_series.c): set up after loading (a no-op without steps). */
int play_series_setup(play_scene* s);
void play_series_free(play_scene* s);
/* The step of timeline time t seconds: the last whose time is <= t (step 0
 * before the first); loop: t wraps over the series' period (its span plus
 * one mean step, so each step shows as long). */
uint32_t play_series_step(const tlod_import_result* r, double t, bool loop);
/* Shows the step of time t: positions (and the field) updated, refreshed
 * and uploaded when the step changed. */
int play_scene_series(play_scene* s, double t, bool loop);

#endif
