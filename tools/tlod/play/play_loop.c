/* tlod play -- the frame loop of one mode: a fixed time step along the
 * camera path, a scheduler update per object and one device draw of every
 * object, every figure recorded in the trace. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "common/camera.h"
#include "common/gpu_target.h"
#include "play_run.h"
#include "play_run_folder.h"
#include "play_serve.h"
#include "tool_names.h"

#if TLOD_HAS_GL || TLOD_HAS_VULKAN
#include "tlod_platform.h"
#endif

volatile sig_atomic_t play_interrupted = 0;

/* A fresh scheduler per object for mode m; the trace takes the first one's settings. */
static int create_schedulers(play_run* r, const play_mode* m, play_trace* t) {
  play_scene* s = r->scene;
  char label[96];
  for (uint32_t i = 0; i < s->count; i++) {
    play_object* ob = &s->objects[i];
    snprintf(label, sizeof(label), "%s/%s", ob->info.name, m->name);
    tlod_scheduler_desc d = play_mode_desc(r->o, m, label);
    tlod_scheduler_destroy(ob->scheduler);
    ob->scheduler = NULL;
    const tlod_surface* surf = s->surfaces[ob->surface].setup.surface;
    if (tlod_scheduler_create(s->ctx, surf, s->patterns, &d, &ob->scheduler) != TLOD_SUCCESS)
      return cli_error(CLI_FAILED, "%s", tlod_context_last_error(s->ctx));
  }
  tlod_scheduler_desc q = tlod_scheduler_query_desc(s->objects[0].scheduler);
  t->policy = tool_policy_name(q.policy);
  t->epsilon = q.epsilon_px;
  t->max_level = q.max_level;
  t->scene_budget = m->kind == MODE_ADAPTIVE ? r->o->scene_budget : 0;
  return CLI_OK;
}

/* The camera of frame n (path time n / fps, whatever the frame took), recorded in fr. */
static tlod_view_desc frame_view(const play_run* r, uint32_t n, play_frame* fr) {
  const play_options* o = r->o;
  fr->time_s = (double)n / o->fps;
  tool_camera cam = {0};
  camera_path_eval(r->path, fr->time_s, o->loop, &cam);
  camera_fit_planes(cam.eye, r->scene->bmin, r->scene->bmax, &cam.near_z, &cam.far_z);
  memcpy(fr->eye, cam.eye, sizeof(fr->eye));
  memcpy(fr->target, cam.target, sizeof(fr->target));
  memcpy(fr->up, cam.up, sizeof(fr->up));
  fr->fovy = cam.fovy_deg;
  fr->near_z = cam.near_z;
  fr->far_z = cam.far_z;
  tlod_view_desc v = {.viewport_width = r->width, .viewport_height = r->height};
  camera_look_at(cam.eye, cam.target, cam.up, v.view);
  camera_perspective(cam.fovy_deg, (float)r->width / (float)r->height, cam.near_z, cam.far_z, v.proj);
  return v;
}

static void record_draw_list(const tlod_draw_list* dl, play_object_stats* st) {
  memcpy(st->stage_ms, dl->stage_ms, sizeof(st->stage_ms));
  st->patches = dl->patch_count;
  st->culled = dl->culled;
  st->instances = dl->instance_count;
  st->strips = dl->strip_count;
  st->pattern_triangles = dl->pattern_triangles;
  st->strip_triangles = dl->strip_triangles;
  memcpy(st->level_histogram, dl->level_histogram, sizeof(st->level_histogram));
  st->effective_epsilon = dl->effective_epsilon;
}

/* The scheduler's view of an object: view * world made rigid. It measures
 * errors in object units and takes the camera from a rigid view, so a
 * world matrix scaling by s is taken out of the view (its rows divided by
 * s: eye coordinates 1/s of the true ones) and the projection's near and
 * far planes scaled to match (proj[14] / s): the frustum and the pixels
 * per object unit come out as in world space. A non-uniform scale uses
 * the largest axis (levels err on the fine side). Identity: exact copy. */
static void object_view(const tlod_view_desc* view, const float world[16], tlod_view_desc* out) {
  *out = *view;
  anim_mat4_mul(view->view, world, out->view);
  double s = 0.0;
  for (int c = 0; c < 3; c++) {
    double n = sqrt((double)world[c * 4] * world[c * 4] + (double)world[c * 4 + 1] * world[c * 4 + 1] +
                    (double)world[c * 4 + 2] * world[c * 4 + 2]);
    s = n > s ? n : s;
  }
  if (s == 1.0 || !(s > 0.0)) return;
  for (int c = 0; c < 4; c++)
    for (int r = 0; r < 3; r++)
      out->view[c * 4 + r] = (float)(out->view[c * 4 + r] / s);
  out->proj[14] = (float)(out->proj[14] / s);
}

/* Levels depend on each instance's view of it: the scheduler plans in
 * object space with its object_view (the view itself for the demo scene). */
static int update_objects(play_run* r, const tlod_view_desc* view, uint32_t n, double run_start,
                          play_object_stats* os) {
  play_scene* s = r->scene;
  tlod_view_desc ov;
  tlod_frame_desc fd = {.views = &ov, .view_count = 1, .dt_ms = (float)(1000.0 / r->o->fps)};
  for (uint32_t i = 0; i < s->count; i++) {
    double t0 = cli_now_ms();
    object_view(view, s->objects[i].world, &ov);
    if (tlod_scheduler_update(s->objects[i].scheduler, &fd) != TLOD_SUCCESS)
      return cli_error(CLI_FAILED, "frame %u: %s", n, tlod_context_last_error(s->ctx));
    os[i].update_at_ms = t0 - run_start;
    os[i].update_ms = cli_now_ms() - t0;
    record_draw_list(tlod_scheduler_draw_list(s->objects[i].scheduler, 0), &os[i]);
  }
  return CLI_OK;
}

/* --scene-budget: every object in one group update, one budget for all;
 * the update's time is shared out evenly over the objects. */
static int update_group(play_run* r, const tlod_view_desc* view, uint32_t n, double run_start, play_object_stats* os) {
  play_scene* s = r->scene;
  for (uint32_t i = 0; i < s->count; i++) {
    r->group[i] = s->objects[i].scheduler;
    object_view(view, s->objects[i].world, &r->group_views[i]);
    r->group_frames[i] =
        (tlod_frame_desc){.views = &r->group_views[i], .view_count = 1, .dt_ms = (float)(1000.0 / r->o->fps)};
  }
  double t0 = cli_now_ms();
  if (tlod_scheduler_update_group(r->group, r->group_frames, s->count, r->o->scene_budget) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "frame %u: %s", n, tlod_context_last_error(s->ctx));
  double share = (cli_now_ms() - t0) / (s->count ? s->count : 1);
  for (uint32_t i = 0; i < s->count; i++) {
    os[i].update_at_ms = t0 - run_start + share * i;
    os[i].update_ms = share;
    record_draw_list(tlod_scheduler_draw_list(s->objects[i].scheduler, 0), &os[i]);
  }
  return CLI_OK;
}

/* The object's material and transform; the demo scene's objects (no node)
 * are drawn as before: identity, both sides, opaque. */
static tlod_draw_item draw_item(const play_scene* s, const play_object* ob) {
  const play_material* m = &ob->material;
  tlod_draw_item it = {.surface = s->surfaces[ob->surface].device_surface,
                       .draw_list = tlod_scheduler_draw_list(ob->scheduler, 0),
                       .has_model = ob->node != UINT32_MAX,
                       .has_color = true,
                       .blend = m->blend == 2   ? TLOD_BLEND_BLEND
                                : m->blend == 1 ? TLOD_BLEND_MASK
                                                : TLOD_BLEND_OPAQUE,
                       .alpha_cutoff = m->alpha_cutoff,
                       .has_alpha_cutoff = m->blend == 1,
                       .cull_back_faces = ob->node != UINT32_MAX && !m->double_sided};
  memcpy(it.model, ob->world, sizeof(it.model));
  memcpy(it.color, m->color, sizeof(it.color));
  if (m->texture != UINT32_MAX && s->textures && s->textures[m->texture]) {
    it.base_color_texture = s->textures[m->texture];
    it.base_color_texcoord = m->texcoord;
  }
  return it;
}

static const float play_clear_rgba[4] = {0.11f, 0.12f, 0.14f, 1.0f};

/* The device draw inside a platform frame (begun: GL bound and cleared,
 * Vulkan recording; ended: Vulkan submitted and, as gl's finish does,
 * waited for: the submit and the wait in *gpu_ms). */
static int framed_draw(play_run* r, tlod_draw_desc* d, uint32_t n, double* gpu_ms) {
  play_scene* s = r->scene;
  char err[512];
  *gpu_ms = 0.0;
  if (r->platform && !gpu_frame_begin(r->platform, play_clear_rgba, d, err, sizeof(err)))
    return cli_error(CLI_FAILED, "frame %u: %s", n, err);
  if (tlod_device_draw(s->device, d) != TLOD_SUCCESS) {
    int rc = cli_error(CLI_FAILED, "frame %u: %s", n, tlod_context_last_error(s->ctx));
    if (r->platform) gpu_frame_end(r->platform, false, gpu_ms, err, sizeof(err)); /* a begun frame is ended */
    return rc;
  }
  if (r->platform && !gpu_frame_end(r->platform, d->finish, gpu_ms, err, sizeof(err)))
    return cli_error(CLI_FAILED, "frame %u: %s", n, err);
  return CLI_OK;
}

/* --debug-view: the first four play_debug_views are tlod_debug_view's;
 * wireframe is the shaded view with edges. */
static void set_debug_view(tlod_draw_desc* d, play_debug_view v) {
  d->wireframe = v == PLAY_DEBUG_WIREFRAME;
  d->debug = d->wireframe ? TLOD_DEBUG_NONE : (tlod_debug_view)v;
}

/* One draw of every object. Per object: its item's CPU time, triangles and
 * draw calls; the draw's wall time past the items' CPU times (GL: the
 * finish; Vulkan: the submit and the wait for the frame's fence, the GPU
 * work) and its GPU time are shared out by drawn triangles, so the objects
 * add up to the draw. Laid out back to back from the draw's start. */
static int draw_objects(play_run* r, const tlod_view_desc* view, uint32_t n, double run_start, play_object_stats* os) {
  play_scene* s = r->scene;
  tlod_draw_item* items = r->items;
  for (uint32_t i = 0; i < s->count; i++)
    items[i] = draw_item(s, &s->objects[i]);
  tlod_draw_desc d = {.items = items, .item_count = s->count, .viewport = {0, 0, r->width, r->height}, .finish = true};
  set_debug_view(&d, r->o->debug_view);
  memcpy(d.view, view->view, sizeof(d.view));
  memcpy(d.proj, view->proj, sizeof(d.proj));
  double t0 = cli_now_ms(), gpu_ms = 0.0;
  int rc = framed_draw(r, &d, n, &gpu_ms);
  if (rc != CLI_OK) return rc;
  double t1 = cli_now_ms();
  tlod_device_stats st = tlod_device_query_stats(s->device);
  st.wall_ms += gpu_ms; /* vulkan; gl's finish is in its wall_ms */
  bool gpu = st.gpu_ms >= 0.0 && st.gpu_draw >= r->first_draw;
  double items_cpu = 0.0;
  for (uint32_t i = 0; i < s->count; i++)
    items_cpu += tlod_device_query_item_stats(s->device, i).cpu_ms;
  double rest = st.wall_ms > items_cpu ? st.wall_ms - items_cpu : 0.0, at = t0 - run_start;
  for (uint32_t i = 0; i < s->count; i++) {
    tlod_draw_item_stats is = tlod_device_query_item_stats(s->device, i);
    double share = st.triangles ? (double)is.triangles / (double)st.triangles : 1.0 / s->count;
    os[i].backend_cpu_ms = is.cpu_ms;
    os[i].backend_wall_ms = is.cpu_ms + rest * share;
    os[i].backend_gpu_ms = gpu ? st.gpu_ms * share : -1.0;
    os[i].drawn_triangles = is.triangles;
    os[i].draw_calls = is.draw_calls;
    os[i].draw_at_ms = at;
    os[i].draw_ms = (t1 - t0) * (st.wall_ms > 0.0 ? os[i].backend_wall_ms / st.wall_ms : share);
    at += os[i].draw_ms;
  }
  return CLI_OK;
}

/* Window mode: shows the frame; true when the window was closed. */
static bool present(const play_run* r) {
#if TLOD_HAS_GL || TLOD_HAS_VULKAN
  if (!r->o->window || !r->platform) return false;
  tlod_platform_swap(r->platform);
  return tlod_platform_should_close(r->platform);
#else
  (void)r;
  return false;
#endif
}

/* A full window goes to the trace files before the next frame (between
 * frames: no frame's time includes it). */
static int make_room(play_trace* t) {
  char err[PLAY_PATH_MAX + 512];
  if (play_trace_window_full(t) && !play_trace_files_flush(t, err, sizeof(err)))
    return cli_error(CLI_FAILED, "%s", err);
  return CLI_OK;
}

/* After frame 1, 10, 100, ...: the soak test's samples. */
static void sample_resources(const play_run* r, play_trace* t) {
  uint32_t n = t->frame_count;
  while (n % 10 == 0)
    n /= 10;
  if (n == 1) play_resources_sample(t, !strcmp(r->backend, "gl"));
}

/* The framebuffer (with a platform) and the viewport become w x h. */
static int resize(play_run* r, uint32_t w, uint32_t h) {
  char err[512];
#if TLOD_HAS_GL || TLOD_HAS_VULKAN
  if (r->platform && !tlod_platform_resize(r->platform, w, h, err, sizeof(err)))
    return cli_error(CLI_FAILED, "--resize-at %u:%ux%u: %s", r->o->resize_frame, w, h, err);
#else
  (void)err;
#endif
  r->width = w, r->height = h;
  return CLI_OK;
}

/* Frame n: CLI_OK, or CLI_FAILED with t->stopped set ("window closed" stops with CLI_OK). */
static int play_frame_n(play_run* r, uint32_t n, double run_start, play_trace* t, bool* stop) {
  play_object_stats* os = NULL;
  int rc = make_room(t);
  if (rc != CLI_OK) return rc;
  play_frame* fr = play_trace_add_frame(t, &os);
  if (!fr) return cli_error(CLI_FAILED, "out of memory after %u frames", t->frame_count);
  if (r->o->resize && n == r->o->resize_frame && (rc = resize(r, r->o->resize_w, r->o->resize_h)) != CLI_OK)
    return rc; /* between frames: no frame's time includes it */
  tlod_view_desc view = frame_view(r, n, fr);
  const double f0 = cli_now_ms();
  fr->at_ms = f0 - run_start;
  if (r->scene->animation.channel_count) {
    double a0 = cli_now_ms();
    rc = play_scene_pose(r->scene, fr->time_s);
    fr->anim_ms = cli_now_ms() - a0;
  }
  if (rc == CLI_OK && r->scene->series.count) rc = play_scene_series(r->scene, fr->time_s, r->o->loop);
  if (rc == CLI_OK)
    rc = r->grouped ? update_group(r, &view, n, run_start, os) : update_objects(r, &view, n, run_start, os);
  if (rc == CLI_OK) rc = draw_objects(r, &view, n, run_start, os);
  fr->frame_ms = cli_now_ms() - f0;
  if (rc != CLI_OK) return rc; /* the failed frame is not a record */
  if (!play_trace_commit_frame(t))
    return cli_error(CLI_FAILED, "cannot write the frame digests in '%s': %s", r->run_dir,
                     strerror(errno ? errno : EIO));
  sample_resources(r, t);
  if (r->o->screenshot_every && n % r->o->screenshot_every == 0 && (rc = play_screenshot(r, fr, run_start)) != CLI_OK)
    return rc;
  play_server_frame(r->server, t); /* after the frame's timing and its screenshot: hands over, never waits */
  if (present(r)) t->stopped = "window closed", *stop = true;
  return CLI_OK;
}

/* The group update's arrays, once per run (kept for later modes). */
static int alloc_group(play_run* r) {
  uint32_t n = r->scene->count ? r->scene->count : 1;
  if (!r->group) r->group = calloc(n, sizeof(*r->group));
  if (!r->group_views) r->group_views = calloc(n, sizeof(*r->group_views));
  if (!r->group_frames) r->group_frames = calloc(n, sizeof(*r->group_frames));
  if (!r->group || !r->group_views || !r->group_frames)
    return cli_error(CLI_FAILED, "out of memory for %u group members", n);
  return CLI_OK;
}

int play_mode_run(play_run* r, const play_mode* m, play_trace* t) {
  int rc = create_schedulers(r, m, t);
  if (rc == CLI_OK && !r->items && !(r->items = calloc(r->scene->count, sizeof(tlod_draw_item))))
    rc = cli_error(CLI_FAILED, "out of memory for %u draw items", r->scene->count);
  r->grouped = r->o->scene_budget && m->kind == MODE_ADAPTIVE;
  if (rc == CLI_OK && r->grouped) rc = alloc_group(r);
  if (rc != CLI_OK) return rc;
  char err[PLAY_PATH_MAX + 512];
  if (!play_trace_digests_open(t, r->run_dir, err, sizeof(err)) ||
      !play_trace_files_open(t, r->run_dir, err, sizeof(err)))
    return cli_error(CLI_FAILED, "%s", err);
  play_server_run(r->server, t);
  r->first_draw = tlod_device_query_stats(r->scene->device).draws + 1;
  /* Every mode starts at the given size (an earlier one may have resized). */
  if ((r->width != r->o->width || r->height != r->o->height) && (rc = resize(r, r->o->width, r->o->height)) != CLI_OK)
    return rc;
  const double run_start = cli_now_ms();
  double last_progress = -1e30;
  bool stop = false;
  t->stopped = "completed";
  for (uint32_t n = 0; n < r->frames && !stop; n++) {
    if (play_interrupted) {
      t->stopped = "interrupted";
      break;
    }
    if ((rc = play_frame_n(r, n, run_start, t, &stop)) != CLI_OK) {
      t->stopped = "error";
      break;
    }
    double now = cli_now_ms();
    if (!stop && !r->o->quiet && now - last_progress > 100.0) {
      play_progress(r, m, n + 1, now - run_start, false);
      last_progress = now;
    }
  }
  t->wall_s = (cli_now_ms() - run_start) * 1e-3;
  if (!t->sample_count || t->samples[t->sample_count - 1].frame != t->frame_count)
    play_resources_sample(t, !strcmp(r->backend, "gl"));
  if (!r->o->quiet) play_progress(r, m, t->frame_count, 0.0, true);
  t->vk = tlod_device_query_stats(r->scene->device).vk;
  t->validation_messages = gpu_target_validation_messages(r->platform);
  return rc;
}
