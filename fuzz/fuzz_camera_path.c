/* fuzz_camera_path.c -- the `tlod play` camera path reader (docs/play.md): the JSON shim
 * (tools/import/camera_path_json.cpp, nlohmann::json) and the checks and spline of
 * tools/tlod/common/camera_path.c. */
#include "camera_contract.h"
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const char* path = fuzz_input_file(".json", data, size);
  camera_path p;
  char error[512];
  error[0] = 0;
  bool ok = camera_path_load(path, &p, error, sizeof error);
  fuzz_check_camera_path(ok, &p, error, path);
  return 0;
}
