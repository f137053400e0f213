/* tlod play -- one playback of one mode along the camera path. */
#ifndef TLOD_TOOLS_PLAY_RUN_H
#define TLOD_TOOLS_PLAY_RUN_H

#include <signal.h>

#include "common/camera_path.h"
#include "play_scene.h"
#include "play_trace.h"

typedef struct tlod_platform tlod_platform;
typedef struct play_server play_server;

typedef struct play_run {
  const play_options* o;
  play_scene* scene;
  const camera_path* path;
  tlod_platform* platform; /* NULL: cpu, null */
  const char* backend;
  uint32_t width, height; /* the framebuffer now (--resize-at changes it mid-run) */
  uint32_t frames;
  const char* run_dir;
  uint8_t* pixels;       /* screenshots */
  uint32_t index, count; /* of the modes, for the progress bar */
  uint64_t first_draw;   /* the device's number of this mode's first draw (gpu times of earlier draws are not its) */
  bool tty;
  play_server* server;   /* --serve; NULL: none */
  tlod_draw_item* items; /* one per object, reused every frame; freed by the caller */
  /* --scene-budget: the group update's arrays, one entry per object, reused
   * every frame; freed by the caller. */
  tlod_scheduler** group;
  tlod_view_desc* group_views;
  tlod_frame_desc* group_frames;
  bool grouped; /* this mode plays under --scene-budget (adaptive only) */
} play_run;

/* Set by the SIGINT handler, read between frames. */
extern volatile sig_atomic_t play_interrupted;

/* Plays mode m into trace t. Returns CLI_OK, or CLI_FAILED after an error
 * mid-run (t then holds the frames played). */
int play_mode_run(play_run* r, const play_mode* m, play_trace* t);

/* The progress bar on a terminal: done of r->frames; final clears it. */
void play_progress(const play_run* r, const play_mode* m, uint32_t done, double elapsed_ms, bool final);
/* Reads frame fr back and writes screenshots/frame_NNNNN.png (gl, vulkan). */
int play_screenshot(play_run* r, play_frame* fr, double run_start);

/* The GL context or Vulkan device (headless or window) when o asks for gl
 * or vulkan, or the default can use GL: NULL with *rc set when it was
 * required and cannot be had (vulkan always is); NULL with CLI_OK and
 * *backend "cpu" when the default falls back. */
tlod_platform* play_platform_open(const play_options* o, int* rc, const char** backend);
void play_platform_close(tlod_platform* p);
/* The renderer's description (without GL: the cpu or null device's). */
void play_platform_describe(tlod_platform* p, const char* backend, char* out, size_t size);

#endif
