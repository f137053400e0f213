/* camera_contract.h -- what tools/tlod/common/camera_path.h promises about a loaded path,
 * checked on every fuzz input of the camera targets. */
#ifndef TLOD_FUZZ_CAMERA_CONTRACT_H
#define TLOD_FUZZ_CAMERA_CONTRACT_H

#include <stdbool.h>

#include "common/camera_path.h"

/* ok, p and error as camera_path_load*(path, ...) left them. Failure: a message naming the
 * file. Success: at least two keys with increasing times, and camera_path_eval() over the
 * path (looping and not) gives a finite camera. Frees p. */
void fuzz_check_camera_path(bool ok, camera_path* p, const char* error, const char* path);

#endif
