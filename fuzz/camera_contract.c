/* camera_contract.c -- camera_path_load*()'s promises (tools/tlod/common/camera_path.h). */
#include "camera_contract.h"

#include <math.h>
#include <string.h>

#include "fuzz_common.h"

enum { kMaxSegments = 64 };

/* camera_path.c names the file as it was given (the full path), the glTF reader by its name
 * (tests/data/fuzz/fuzz_gltf_camera/fovy_error_names_no_file.gltf once named "gltf:0"). */
static void check_error(const char* error, const char* path) {
  if (strncmp(error, path, strlen(path)) == 0)
    fuzz_check_error(error + strlen(path) - strlen(fuzz_base_name(path)), fuzz_base_name(path));
  else
    fuzz_check_error(error, fuzz_base_name(path));
}

static void check_eval(const camera_path* p, double t, bool loop) {
  tool_camera cam;
  memset(&cam, 0, sizeof cam);
  camera_path_eval(p, t, loop, &cam);
  for (int c = 0; c < 3; ++c)
    fuzz_check(isfinite(cam.eye[c]) && isfinite(cam.target[c]) && isfinite(cam.up[c]),
               "camera_path_eval gave a non-finite eye, target or up");
  fuzz_check(isfinite(cam.fovy_deg), "camera_path_eval gave a non-finite fovy");
}

void fuzz_check_camera_path(bool ok, camera_path* p, const char* error, const char* path) {
  if (!ok) {
    fuzz_check(p->keys == NULL, "a failed load left keys");
    check_error(error, path);
    return;
  }
  fuzz_check(p->count >= 2 && p->keys != NULL, "a loaded path has fewer than two keys");
  for (uint32_t i = 1; i < p->count; ++i)
    fuzz_check(p->keys[i].time > p->keys[i - 1].time, "a loaded path's times do not increase");
  const double d = camera_path_duration(p);
  const double ts[] = {-1.0, 0.0, 0.3 * d, 0.5 * d, d, 1.7 * d + 0.1};
  for (size_t i = 0; i < sizeof ts / sizeof ts[0]; ++i) {
    check_eval(p, ts[i], false);
    check_eval(p, ts[i], true);
  }
  /* Segment midpoints: where a spline overshoots most. */
  for (uint32_t i = 0; i + 1 < p->count && i < kMaxSegments; ++i)
    check_eval(p, 0.5 * (p->keys[i].time + p->keys[i + 1].time) - p->keys[0].time, false);
  (void)camera_path_frames(p, 60.0);
  camera_path_free(p);
}
