/* fuzz_gltf_camera.c -- `tlod play --camera-path gltf:N`: camera 0 of a glTF scene and its
 * first animation (tools/import/gltf_camera_path.cpp over tinygltf), as camera_path.c checks
 * and evaluates it. Input starting with the GLB magic "glTF" is written as .glb, anything
 * else as .gltf, so one corpus covers both containers. */
#include <string.h>

#include "camera_contract.h"
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const int glb = size >= 4 && memcmp(data, "glTF", 4) == 0;
  const char* path = fuzz_input_file(glb ? ".glb" : ".gltf", data, size);
  camera_path p;
  char error[512];
  error[0] = 0;
  bool ok = camera_path_load_gltf(path, 0, &p, error, sizeof error);
  fuzz_check_camera_path(ok, &p, error, path);
  return 0;
}
