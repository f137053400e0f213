/* tlod play -- the scene: one object per mesh (the demo scene has two),
 * each with its surface, scheduler and device surface, one pattern set, and
 * one device for the whole run (every mode). */
#ifndef TLOD_TOOLS_PLAY_SCENE_H
#define TLOD_TOOLS_PLAY_SCENE_H

#include "common/scene_setup.h"
#include "play_options.h"
#include "play_trace.h"
#include "tesslod/backend.h"

#define PLAY_MAX_OBJECTS 4

typedef struct play_object {
  play_object_info info;
  scene_setup setup; /* mesh and surface (the patterns are the scene's) */
  tlod_scheduler* scheduler;
  tlod_device_surface* surface; /* on the scene's device */
} play_object;

typedef struct play_scene {
  char name[256];
  tlod_context* ctx;
  play_object objects[PLAY_MAX_OBJECTS];
  play_object_info infos[PLAY_MAX_OBJECTS];
  uint32_t count;
  tlod_patterns* patterns;
  tlod_device* device; /* one per run, reused by every mode */
  float bmin[3], bmax[3];
} play_scene;

/* o->scene (or the demo scene) with patterns for every mode of o. */
int play_scene_load(const play_options* o, play_scene* s);
void play_scene_free(play_scene* s);

/* The run's device (programs and patterns made once) and one device surface
 * per object. */
int play_scene_create_device(play_scene* s, const char* backend, tlod_surface_type type);
/* The device draws with the platform's context: destroy it while it exists. */
void play_scene_destroy_device(play_scene* s);

#endif
