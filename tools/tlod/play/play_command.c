/* tlod play -- plays a scene along a camera path with a fixed time step and
 * records per-frame scheduler and backend timings (docs/play.md). */
#define _POSIX_C_SOURCE 200809L /* sigaction, isatty */
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"
#include "commands.h"
#include "common/folder.h"
#include "common/gpu_target.h"
#include "common/strict_number.h"
#include "play_run.h"
#include "play_run_folder.h"
#include "play_serve.h"
#include "tool_names.h"

/* Everything one `tlod play` holds from set-up to the end. */
typedef struct play_session {
  play_options o;
  camera_path path;
  play_scene scene;
  tlod_platform* platform;
  const char* backend;
  uint8_t* pixels;
  char out_dir[PLAY_PATH_MAX];
  char renderer[512];
  char gpu_eval[160];      /* describe_gpu_eval */
  char shader_cache[4096]; /* the default folder's name */
  const char* shader_dir;  /* vulkan: the SPIR-V cache folder in use; NULL none */
  char version[32];
  play_trace traces[PLAY_MAX_MODES];
  const play_trace* done[PLAY_MAX_MODES];
  char run_dirs[PLAY_MAX_MODES][PLAY_PATH_MAX + 32];
  uint32_t run_count;
  uint32_t frames;     /* of every mode */
  int lock_fd;         /* the run folder's lock (play_run_folder.h); -1: not held */
  char failure[1024];  /* the first error of a run that was played: summary.json's "error" */
  play_server* server; /* --serve: from set-up until playing ends */
  play_serve_stats serve_stats;
  bool served;
} play_session;

static void on_sigint(int sig) {
  (void)sig;
  play_interrupted = 1;
}

/* From here Ctrl-C only sets a flag: the run stops before its next frame
 * (during set-up: before the first) and writes what it played. */
static void catch_sigint(struct sigaction* old) {
  struct sigaction sa;
  memset(&sa, 0, sizeof(sa));
  sa.sa_handler = on_sigint;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  play_interrupted = 0;
  sigaction(SIGINT, &sa, old);
}

/* "gltf" or "gltf:N": true, with the camera in *camera; CLI_USAGE in *rc for a bad N. */
static bool gltf_path(const char* path, uint32_t* camera, int* rc) {
  *camera = 0;
  if (!strcmp(path, "gltf")) return true;
  if (strncmp(path, "gltf:", 5)) return false;
  number_status s = number_parse_u32(path + 5, NULL, 0, UINT32_MAX, camera);
  if (s != NUMBER_OK)
    *rc = cli_error(CLI_USAGE, "--path: %s: %s", path,
                    s == NUMBER_RANGE ? "camera out of range 0..4294967295" : "expected gltf or gltf:N");
  return true;
}

/* --path FILE.json or gltf[:N] (the built-ins need the scene bounds: later). */
static int load_path(const play_options* o, camera_path* path) {
  char err[1024];
  uint32_t gltf_camera = 0;
  int rc = CLI_OK;
  bool gltf = gltf_path(o->path, &gltf_camera, &rc);
  if (rc != CLI_OK) return rc;
  if (gltf && (!o->scene || !strncmp(o->scene, "demo:", 5)))
    return cli_error(CLI_USAGE, "--path %s: the scene must be a .gltf or .glb file with cameras", o->path);
  if (gltf && !camera_path_load_gltf(o->scene, gltf_camera, path, err, sizeof(err)))
    return cli_error(CLI_FAILED, "%s", err);
  if (!gltf && !camera_path_is_builtin(o->path) && !camera_path_load(o->path, path, err, sizeof(err)))
    return cli_error(CLI_FAILED, "%s", err);
  return CLI_OK;
}

/* --frames, else --duration * fps, else one pass of the path: more than
 * PLAY_MAX_FRAMES is refused, never cut short in silence (docs/play.md). */
static int frame_count(play_session* p) {
  const play_options* o = &p->o;
  if (o->frames) {
    p->frames = o->frames;
    return CLI_OK;
  }
  bool by_duration = o->duration > 0.0f;
  double n = by_duration ? fmax(1.0, floor((double)o->duration * o->fps + 0.5)) : camera_path_frames(&p->path, o->fps);
  if (n <= PLAY_MAX_FRAMES) {
    p->frames = (uint32_t)n;
    return CLI_OK;
  }
  if (by_duration)
    return cli_error(CLI_USAGE, "--duration: %g s at %g fps is %.0f frames, more than the cap of %u",
                     (double)o->duration, (double)o->fps, n, PLAY_MAX_FRAMES);
  return cli_error(CLI_USAGE,
                   "--path %s: %g s at %g fps is %.3g frames, more than the cap of %u (give --frames N or --duration S "
                   "to play part of it)",
                   o->path, camera_path_duration(&p->path), (double)o->fps, n, PLAY_MAX_FRAMES);
}

/* vulkan: the --shader-cache folder (made and writable, or an error) or the
 * default one (a warning and no disk cache when it cannot be had). */
static int shader_cache(play_session* p) {
  char warning[4200], err[4200];
  if (!tool_shader_cache_dir(p->o.shader_cache, p->shader_cache, sizeof(p->shader_cache), &p->shader_dir, warning,
                             sizeof(warning), err, sizeof(err)))
    return cli_error(CLI_FAILED, "--shader-cache: %s", err);
  if (warning[0] && !p->o.quiet) fprintf(stderr, "tlod: warning: %s\n", warning);
  return CLI_OK;
}

/* Screenshots: the larger of the sizes the run has (--resize-at). */
static int alloc_pixels(play_session* p) {
  const play_options* o = &p->o;
  size_t n = (size_t)o->width * o->height, m = o->resize ? (size_t)o->resize_w * o->resize_h : 0;
  if (!(p->pixels = malloc((n > m ? n : m) * 4)))
    return cli_error(CLI_FAILED, "out of memory for %ux%u screenshots", o->width, o->height);
  return CLI_OK;
}

/* --gpu-eval for the device: auto stays on GPU evaluation for the debug
 * views the CPU mesh does not carry (levels, strips). */
static tlod_gpu_eval gpu_eval(const play_options* o) {
  bool needs_gpu = o->debug_view == PLAY_DEBUG_LEVELS || o->debug_view == PLAY_DEBUG_STRIPS;
  if (o->gpu_eval == 0 && needs_gpu) return TLOD_GPU_EVAL_ON;
  return (tlod_gpu_eval)o->gpu_eval;
}

/* What the device chose and why (summary and trace: "gpu_eval"). */
static void describe_gpu_eval(play_session* p) {
  const play_options* o = &p->o;
  tlod_device_stats st = tlod_device_query_stats(p->scene.device);
  if (!gpu_backend(p->backend))
    snprintf(p->gpu_eval, sizeof(p->gpu_eval), "none (the %s backend)", p->backend);
  else if (o->gpu_eval == 0 && gpu_eval(o) == TLOD_GPU_EVAL_ON)
    snprintf(p->gpu_eval, sizeof(p->gpu_eval), "on (auto: --debug-view %s needs it)",
             play_debug_view_names[o->debug_view]);
  else
    snprintf(p->gpu_eval, sizeof(p->gpu_eval), "%s (%s)", st.cpu_mesh ? "off" : "on", st.gpu_eval_reason);
}

/* Everything that can fail on bad input happens before the run folder exists. */
static int set_up(play_session* p) {
  const play_options* o = &p->o;
  struct stat st;
  /* An --out in use fails before the scene is loaded (a new folder is locked as it is made). */
  int rc = o->out && stat(o->out, &st) == 0 && S_ISDIR(st.st_mode) ? play_lock_run_folder(o->out, &p->lock_fd) : CLI_OK;
  if (rc == CLI_OK) rc = load_path(o, &p->path);
  if (rc == CLI_OK) rc = play_scene_load(o, &p->scene);
  if (rc == CLI_OK && camera_path_is_builtin(o->path) &&
      !camera_path_builtin(o->path, p->scene.bmin, p->scene.bmax, &p->path))
    rc = cli_error(CLI_FAILED, "cannot build the %s path", o->path);
  if (rc == CLI_OK) rc = frame_count(p);
  p->backend = o->backend ? o->backend : "gl";
  if (rc == CLI_OK && gpu_backend(p->backend)) p->platform = play_platform_open(o, &rc, &p->backend);
  if (rc == CLI_OK && !strcmp(p->backend, "vulkan")) rc = shader_cache(p);
  if (rc == CLI_OK) rc = play_scene_create_device(&p->scene, p->backend, p->platform, p->shader_dir, gpu_eval(o));
  if (rc == CLI_OK) describe_gpu_eval(p);
  if (rc == CLI_OK && o->screenshot_every) rc = alloc_pixels(p);
  if (rc == CLI_OK) rc = play_server_start(o, &p->server); /* a port in use fails before the folder is made */
  if (rc == CLI_OK) rc = play_make_run_folder(o, p->out_dir, sizeof(p->out_dir), &p->lock_fd);
  return rc;
}

static play_field_info field_info(const play_scene* s) {
  const field_selection* f = &s->field.sel;
  if (!s->field.on) return (play_field_info){0};
  return (play_field_info){.name = f->name,
                           .label = f->label,
                           .units = f->units,
                           .component = f->component,
                           .min = f->lo,
                           .max = f->hi,
                           .colormap = colormap_names[f->colormap],
                           .from_cells = f->from_cells,
                           .steps = s->series.count};
}

static play_trace trace_of(const play_session* p, const play_mode* m, uint32_t frames) {
  const play_options* o = &p->o;
  return (play_trace){.tool_version = p->version,
                      .scene = p->scene.name,
                      .mode = m->name,
                      .backend = p->backend,
                      .renderer = p->renderer,
                      .gpu_eval = p->gpu_eval,
                      .surface = tool_surface_name(p->scene.surface_type),
                      .path = p->path.name,
                      .path_duration_s = camera_path_duration(&p->path),
                      .loop = o->loop,
                      .fps = o->fps,
                      .width = o->width,
                      .height = o->height,
                      .frames_requested = frames,
                      .screenshot_every = o->screenshot_every,
                      .debug_view = play_debug_view_names[o->debug_view],
                      .resize_frame = o->resize ? o->resize_frame : 0,
                      .resize_width = o->resize ? o->resize_w : 0,
                      .resize_height = o->resize ? o->resize_h : 0,
                      .validate = o->validate,
                      .shader_cache = p->shader_dir ? p->shader_dir : "",
                      .objects = p->scene.infos,
                      .object_count = p->scene.count,
                      .animation = p->scene.animation.channel_count ? p->scene.animation.name : "",
                      .animation_duration_s = p->scene.animation.duration_s,
                      .field = field_info(&p->scene),
                      .warnings = p->scene.warnings,
                      .warning_count = p->scene.warning_count,
                      .dir = o->compare ? m->dir : ".",
                      .stopped = "completed"};
}

/* The folder of mode k (a subfolder per mode with --compare) and its screenshots/. */
static int make_mode_folder(play_session* p, uint32_t k) {
  const play_options* o = &p->o;
  char* dir = p->run_dirs[k];
  if (o->compare) {
    play_path_join(dir, sizeof(p->run_dirs[k]), p->out_dir, o->modes[k].dir);
  } else {
    snprintf(dir, sizeof(p->run_dirs[k]), "%s", p->out_dir);
  }
  char shots[PLAY_PATH_MAX + 64];
  play_path_join(shots, sizeof(shots), dir, "screenshots");
  if (!tool_mkdir_p(dir) || (o->screenshot_every && !tool_mkdir_p(shots)))
    return cli_error(CLI_FAILED, "cannot create folder '%s': %s", o->screenshot_every ? shots : dir, strerror(errno));
  return CLI_OK;
}

/* The trace files' last window and tails (opened by play_mode_run; a write
 * error mid-run has closed them already). */
static int close_traces(play_trace* t) {
  char err[PLAY_PATH_MAX + 512];
  if (t->files && !play_trace_files_close(t, true, err, sizeof(err))) return cli_error(CLI_FAILED, "%s", err);
  return CLI_OK;
}

/* The first error of the session goes into summary.json. */
static void note_failure(play_session* p, int rc) {
  if (rc != CLI_OK && !p->failure[0]) snprintf(p->failure, sizeof(p->failure), "%s", cli_last_error());
}

/* --validate: any message of the validation layer fails the run. */
static int check_validation(const play_session* p, const play_trace* t) {
  if (!p->o.validate || !t->validation_messages) return CLI_OK;
  return cli_error(CLI_FAILED, "--validate: the Vulkan validation layer reported %llu message%s (printed above)",
                   (unsigned long long)t->validation_messages, t->validation_messages == 1 ? "" : "s");
}

/* Mode k into its trace and files. */
static int play_one_mode(play_session* p, play_run* run, uint32_t k) {
  const play_mode* m = &p->o.modes[k];
  int rc = make_mode_folder(p, k);
  if (rc != CLI_OK) return rc;
  play_trace* t = &p->traces[k];
  *t = trace_of(p, m, run->frames);
  run->run_dir = p->run_dirs[k];
  run->index = k;
  rc = play_mode_run(run, m, t);
  if (rc == CLI_OK) rc = check_validation(p, t);
  note_failure(p, rc);
  p->done[p->run_count++] = t;
  int wrc = close_traces(t);
  if (wrc != CLI_OK) t->stopped = "error"; /* the summary must not claim a complete run */
  note_failure(p, wrc);
  return rc == CLI_OK ? wrc : rc;
}

static int play_modes(play_session* p) {
  const play_options* o = &p->o;
  play_platform_describe(p->platform, p->backend, p->renderer, sizeof(p->renderer));
  snprintf(p->version, sizeof(p->version), "tlod %d.%d.%d", TLOD_VERSION / 1000, TLOD_VERSION / 10 % 100,
           TLOD_VERSION % 10);
  play_run run = {.o = o,
                  .scene = &p->scene,
                  .path = &p->path,
                  .platform = p->platform,
                  .backend = p->backend,
                  .width = o->width,
                  .height = o->height,
                  .frames = p->frames,
                  .pixels = p->pixels,
                  .count = o->mode_count,
                  .tty = !o->quiet && isatty(STDERR_FILENO),
                  .server = p->server};
  int rc = CLI_OK;
  for (uint32_t k = 0; k < o->mode_count && rc == CLI_OK && (k == 0 || !play_interrupted); k++)
    rc = play_one_mode(p, &run, k);
  free(run.items);
  free(run.group);
  free(run.group_views);
  free(run.group_frames);
  return rc;
}

/* summary.txt, then summary.json, which says whether everything before it
 * was written ("status": "failed" with the first error); a failed write
 * fails the run. */
static int write_summary(play_session* p, int rc) {
  char path[PLAY_PATH_MAX + 64], err[PLAY_PATH_MAX + 512];
  play_path_join(path, sizeof(path), p->out_dir, "summary.txt");
  if (!play_write_summary_text(p->done, p->run_count, p->out_dir, path, err, sizeof(err))) {
    note_failure(p, rc = cli_error(CLI_FAILED, "%s", err));
  }
  play_outcome outcome = {
      .status = rc == CLI_OK ? "ok" : "failed", .error = p->failure, .serve = p->served ? &p->serve_stats : NULL};
  play_path_join(path, sizeof(path), p->out_dir, "summary.json");
  if (!play_write_summary_json(p->done, p->run_count, p->out_dir, &outcome, path, err, sizeof(err)))
    rc = cli_error(CLI_FAILED, "%s", err);
  return rc;
}

/* --serve: the streams' end, --serve-linger, then the server's counts for the summary. */
static void stop_server(play_session* p) {
  if (!p->server) return;
  sig_atomic_t interrupted = play_interrupted;
  play_server_end(p->server, interrupted ? 0.0f : p->o.serve_linger);
  play_interrupted = interrupted; /* Ctrl-C while lingering stops the server, not the (complete) run */
  play_server_stop(p->server, &p->serve_stats);
  p->server = NULL;
  p->served = true;
  if (!p->o.quiet)
    fprintf(stderr, "tlod: live dashboard: %u streams, %llu frames dropped\n", p->serve_stats.streams,
            (unsigned long long)p->serve_stats.dropped);
}

static void session_free(play_session* p) {
  play_server_stop(p->server, NULL); /* set-up failed after the server started */
  for (uint32_t k = 0; k < p->run_count; k++)
    play_trace_free(&p->traces[k]);
  play_scene_destroy_device(&p->scene);
  play_platform_close(p->platform);
  free(p->pixels);
  play_scene_free(&p->scene);
  camera_path_free(&p->path);
  play_unlock_run_folder(p->out_dir[0] ? p->out_dir : p->o.out, p->lock_fd);
  free(p);
}

/* The device and the platform go before the summary, so what the
 * validation layer says about their shutdown (vkDestroyDevice's object
 * tracker included) is counted in it. */
static int shut_gpu(play_session* p, int rc) {
  play_scene_destroy_device(&p->scene);
  bool counted = p->run_count && p->platform;
  play_platform_close(p->platform);
  p->platform = NULL;
  if (!counted) return rc;
  play_trace* last = &p->traces[p->run_count - 1];
  uint64_t before = last->validation_messages;
  last->validation_messages = gpu_target_validation_messages(NULL);
  return rc == CLI_OK && last->validation_messages > before ? check_validation(p, last) : rc;
}

static int finish(play_session* p, int rc) {
  rc = shut_gpu(p, rc);
  note_failure(p, rc);
  if (play_interrupted && !p->o.quiet)
    fprintf(stderr, "tlod: interrupted: wrote the %u frames played so far\n",
            p->run_count ? p->done[p->run_count - 1]->frame_count : 0);
  if (p->run_count) rc = write_summary(p, rc);
  if (p->run_count && !p->o.quiet) play_print_summary(stdout, p->done, p->run_count, p->out_dir);
  return rc;
}

int cmd_play(int argc, char** argv) {
  play_session* p = calloc(1, sizeof(*p));
  if (!p) return cli_error(CLI_FAILED, "out of memory");
  p->lock_fd = -1;
  int rc = play_parse(argc, argv, &p->o);
  if (rc != CLI_OK) {
    free(p);
    return rc;
  }
  struct sigaction old;
  catch_sigint(&old);
  rc = set_up(p);
  if (rc == CLI_OK) rc = play_modes(p);
  stop_server(p); /* Ctrl-C ends --serve-linger */
  sigaction(SIGINT, &old, NULL);
  if (rc == CLI_OK || p->run_count) rc = finish(p, rc);
  bool interrupted = play_interrupted;
  session_free(p);
  return rc == CLI_OK && interrupted ? 130 : rc;
}
