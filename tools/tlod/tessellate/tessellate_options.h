/* tlod tessellate -- its options. */
#ifndef TLOD_TOOLS_TESSELLATE_OPTIONS_H
#define TLOD_TOOLS_TESSELLATE_OPTIONS_H

#include <stdbool.h>
#include <stdint.h>

#include "common/camera.h"
#include "tesslod/lod.h"

/* Adaptive mode: one camera, one scheduler frame. */
typedef struct adaptive_options {
  bool on;
  tool_camera cam;
  uint32_t width, height, max_level;
  float epsilon;
  tlod_lod_policy policy;
  bool no_stitch;
} adaptive_options;

typedef struct tess_options {
  const char* in;
  const char* out;
  const char* stats;
  tlod_surface_type surface; /* DEFAULT: auto, resolved per input (the report and stats say which) */
  float alpha;
  uint32_t level, threads;
  tlod_normal_mode normals;
  float crease; /* negative: the input's default (cli_resolve_crease) */
  bool no_weld, quiet;
  adaptive_options ad;
} tess_options;

/* CLI_OK, or CLI_USAGE with the error printed; --help prints and exits. */
int tessellate_parse(int argc, char** argv, tess_options* o);

#endif
