/* tlod play -- its options and modes. */
#ifndef TLOD_TOOLS_PLAY_OPTIONS_H
#define TLOD_TOOLS_PLAY_OPTIONS_H

#include <stdbool.h>
#include <stdint.h>

#include "field/field_select.h"
#include "tesslod/lod.h"

#define PLAY_MAX_MODES 8
#define PLAY_MAX_FRAMES 1000000u
#define PLAY_PATH_MAX 1024 /* the run folder's name, and then some */

typedef enum mode_kind { MODE_ADAPTIVE, MODE_UNIFORM, MODE_FLAT } mode_kind;

typedef struct play_mode {
  mode_kind kind;
  uint32_t level; /* uniform */
  char name[24];  /* "adaptive", "uniform:3", "flat" */
  char dir[24];   /* "adaptive", "uniform-3", "flat" */
} play_mode;

/* --debug-view: none (shaded), the backend's debug colourings
 * (tlod_debug_view, in its order), or wireframe (shaded, edges drawn over). */
typedef enum play_debug_view {
  PLAY_DEBUG_NONE,
  PLAY_DEBUG_LEVELS,
  PLAY_DEBUG_SILHOUETTE,
  PLAY_DEBUG_STRIPS,
  PLAY_DEBUG_WIREFRAME
} play_debug_view;
/* "none", "levels", "silhouette", "strips", "wireframe", NULL: by play_debug_view. */
extern const char* const play_debug_view_names[];
/* "auto", "on", "off", NULL: --gpu-eval, in tlod_gpu_eval's order. */
extern const char* const play_gpu_eval_names[];

typedef struct play_options {
  const char* scene;   /* NULL: the built-in demo scene */
  const char* backend; /* NULL: gl when a context can be made, else cpu; "vulkan" never falls back */
  play_mode modes[PLAY_MAX_MODES];
  uint32_t mode_count;
  bool compare, mode_given;
  tlod_surface_type surface; /* DEFAULT: auto (cli_resolve_surface) */
  float crease;              /* negative: the input's default (cli_resolve_crease) */
  field_options field;       /* --field, --range, --colormap; spec NULL: no field */
  bool colormap_given;
  float epsilon;
  tlod_lod_policy policy;
  uint32_t max_level;
  uint32_t scene_budget; /* triangles per frame over all objects; 0: none */
  uint32_t width, height;
  uint32_t frames; /* 0: from --duration or the path */
  float duration;  /* 0: not given */
  float fps;
  const char* path;
  const char* animation; /* NULL: the first; "none"; a name or an index */
  bool loop;
  uint32_t screenshot_every;
  play_debug_view debug_view;
  int gpu_eval; /* --gpu-eval: 0 auto, 1 on, 2 off (tlod_gpu_eval's order, play_gpu_eval_names) */
  bool window;
  bool validate;            /* vulkan: the validation layer on; any message fails the run */
  const char* shader_cache; /* vulkan: --shader-cache DIR or "off"; NULL: the default folder */
  bool resize;              /* --resize-at: before frame resize_frame the framebuffer becomes resize_w x resize_h */
  uint32_t resize_frame, resize_w, resize_h;
  const char* out;
  bool quiet;
  const char* serve;  /* --serve [ADDR:]PORT (play_serve.h); NULL: none */
  float serve_linger; /* seconds the server stays up after playing */
} play_options;

/* CLI_OK, or CLI_USAGE with the error printed; --help prints and exits. */
int play_parse(int argc, char** argv, play_options* o);

/* "adaptive", "uniform:L" or "flat" into m: NULL, or what is wrong with text. */
const char* play_mode_parse(const char* text, play_mode* m);
/* Scheduler settings of a mode. */
tlod_scheduler_desc play_mode_desc(const play_options* o, const play_mode* m, const char* label);
/* The finest level any mode of o needs (at least 1). */
uint32_t play_modes_max_level(const play_options* o);

#endif
