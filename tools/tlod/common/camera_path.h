/* Camera paths for `tlod play`: keyframes (time, eye, target, up, fovy) from
 * a JSON file (docs/play.md) or built from the scene bounds (orbit, flyby,
 * zoom), interpolated with centripetal Catmull-Rom splines on eye and target
 * and linearly on up and fovy. */
#ifndef TLOD_TOOLS_CAMERA_PATH_H
#define TLOD_TOOLS_CAMERA_PATH_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "common/camera.h"

typedef struct camera_key {
  double time; /* seconds */
  float eye[3], target[3], up[3];
  float fovy; /* degrees */
} camera_key;

typedef struct camera_path {
  char name[256]; /* "orbit", "flyby", "zoom" or the file name */
  camera_key* keys;
  uint32_t count;
  /* Periodic: the last key repeats the first and the spline wraps round, so
   * a looping path has no kink where it starts over. */
  bool closed;
} camera_path;

/* "orbit", "flyby" or "zoom". */
bool camera_path_is_builtin(const char* name);
/* A built-in path round the box [bmin, bmax]: orbit (one turn, 4 s, closed),
 * flyby (a pass close in front of the scene, 6 s), zoom (close to far and
 * back, 4 s, closed). False for an unknown name. */
bool camera_path_builtin(const char* name, const float bmin[3], const float bmax[3], camera_path* out);
/* Reads and checks a keyframe file. False with one line in error
 * ("<file>: <element>: <problem>") on any problem. */
bool camera_path_load(const char* file, camera_path* out, char* error, size_t error_size);
/* Camera `camera` of a glTF scene file, animated by its first animation
 * (see gltf_camera_path_load in tools/import/camera_path_json.h). */
bool camera_path_load_gltf(const char* scene, uint32_t camera, camera_path* out, char* error, size_t error_size);
void camera_path_free(camera_path* p);

/* Seconds from the first keyframe to the last. */
double camera_path_duration(const camera_path* p);
/* Frames of one pass at fps: closed paths round(duration * fps) (the end is
 * the start again), open paths floor(duration * fps) + 1 (both ends); at
 * least 1, not capped (a path of 3e38 s gives about 1.8e40: callers bound it). */
double camera_path_frames(const camera_path* p, double fps);
/* The camera at t seconds from the path's start: past the end the path
 * starts over (loop) or stays at its last keyframe. Writes eye, target, up
 * and fovy_deg of cam (the rest is left as it was). */
void camera_path_eval(const camera_path* p, double t, bool loop, tool_camera* cam);

#endif
