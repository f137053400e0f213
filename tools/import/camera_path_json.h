/*
 * camera_path_json.h -- reads a `tlod play` camera path file (C API over a
 * C++17 nlohmann::json shim, camera_path_json.cpp). Owned by the CLI
 * (tools/tlod/common/camera_path.c is its only user); the format is documented in
 * docs/play.md:
 *
 *   {
 *     "name": "optional, any string",
 *     "description": "optional, any string",
 *     "keyframes": [
 *       {"time": 0.0, "eye": [0, 2, 10], "target": [0, 0, 0], "up": [0, 1, 0], "fovy": 45},
 *       {"time": 2.5, "eye": [8, 2, 0], "target": [0, 0, 0]}
 *     ]
 *   }
 *
 * WHAT IT CHECKS
 *   JSON syntax (with line and column), the top level is an object with a
 *   "keyframes" array and no keys besides name / description / keyframes;
 *   every keyframe is an object with time (number), eye and target (arrays
 *   of 3 numbers), optional up (3 numbers, default 0,1,0) and fovy (number,
 *   degrees, default 45), and no other key (a typo such as "fov" is an error,
 *   not a silent default). Every number must fit a float.
 *
 * DOES NOT
 *   check the values (at least two keyframes, increasing times, eye != target,
 *   fovy range): camera_path.c does, for files and built-in paths alike.
 *
 * ERRORS
 *   Returns false and writes one line "<file>: <element>: <problem>" into
 *   error (truncated to fit, always terminated), e.g.
 *   "path.json: keyframes[2]: missing key 'eye'". No exception leaves the shim.
 */
#ifndef TLOD_TOOLS_CAMERA_PATH_JSON_H
#define TLOD_TOOLS_CAMERA_PATH_JSON_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct camera_path_json_key {
  double time;
  double eye[3], target[3], up[3];
  double fovy; /* degrees */
} camera_path_json_key;

/* Reads path; on success *keys (malloc'ed, free with camera_path_json_free)
 * holds *count keyframes in file order. On failure *keys is NULL. */
bool camera_path_json_load(const char* path, camera_path_json_key** keys, uint32_t* count, char* error,
                           size_t error_size);
void camera_path_json_free(camera_path_json_key* keys);

/* Camera `camera` of a glTF file as keyframes (gltf_camera_path.cpp): its
 * node's world transform, moved by the translation/rotation channels of the
 * first animation that targets that node, sampled at their key times; a
 * still camera gives two keys one second apart. Free with
 * camera_path_json_free. */
bool gltf_camera_path_load(const char* path, uint32_t camera, camera_path_json_key** keys, uint32_t* count, char* error,
                           size_t error_size);

#ifdef __cplusplus
}
#endif
#endif
