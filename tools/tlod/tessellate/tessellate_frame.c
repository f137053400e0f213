/* tlod tessellate -- adaptive mode: the view of the camera options and one
 * scheduler frame for it. */
#include "tessellate_frame.h"

#include <math.h>

#include "cli.h"

/* The camera of the options, aimed at the bounding-box centre when no target was given. */
static tool_camera camera_of(const tess_options* o, const float bmin[3], const float bmax[3]) {
  tool_camera cam = o->ad.cam;
  if (isnan(cam.target[0])) {
    for (int i = 0; i < 3; i++)
      cam.target[i] = 0.5f * (bmin[i] + bmax[i]);
  }
  camera_fit_planes(cam.eye, bmin, bmax, &cam.near_z, &cam.far_z);
  return cam;
}

static tlod_view_desc view_of(const tess_options* o, const tool_camera* cam) {
  tlod_view_desc view = {.viewport_width = o->ad.width, .viewport_height = o->ad.height};
  float aspect = (float)o->ad.width / (float)o->ad.height;
  camera_look_at(cam->eye, cam->target, cam->up, view.view);
  if (cam->fovy_deg > 0.0f) {
    camera_perspective(cam->fovy_deg, aspect, cam->near_z, cam->far_z, view.proj);
  } else {
    camera_orthographic(cam->ortho_height, aspect, cam->near_z, cam->far_z, view.proj);
  }
  return view;
}

/* Refuses a camera with no view direction or no roll: it would draw nothing sensible. */
static int check_view(const tess_options* o, const tool_camera* cam) {
  const char* problem = camera_view_problem(cam->eye, cam->target, cam->up);
  if (!problem) return CLI_OK;
  const char* target = isnan(o->ad.cam.target[0]) ? " (default: the bounding-box centre)" : "";
  return cli_error(CLI_USAGE, "--eye %g,%g,%g, --target %g,%g,%g%s, --up %g,%g,%g: %s", (double)cam->eye[0],
                   (double)cam->eye[1], (double)cam->eye[2], (double)cam->target[0], (double)cam->target[1],
                   (double)cam->target[2], target, (double)cam->up[0], (double)cam->up[1], (double)cam->up[2], problem);
}

int tessellate_view(const tess_options* o, const float bmin[3], const float bmax[3], tlod_view_desc* out) {
  tool_camera cam = camera_of(o, bmin, bmax);
  int rc = check_view(o, &cam);
  if (rc == CLI_OK) *out = view_of(o, &cam);
  return rc;
}

int tessellate_plan_view(const tess_options* o, tlod_context* ctx, tlod_surface* surface, tlod_patterns* patterns,
                         const tlod_view_desc* view, tlod_scheduler** sch, const tlod_draw_list** out) {
  tlod_scheduler_desc sd = {.epsilon_px = o->ad.epsilon,
                            .max_level = o->ad.max_level,
                            .policy = o->ad.policy,
                            .morph = TLOD_MORPH_NONE,
                            .label = o->in};
  if (tlod_scheduler_create(ctx, surface, patterns, &sd, sch) != TLOD_SUCCESS ||
      tlod_scheduler_update(*sch, &(tlod_frame_desc){.views = view, .view_count = 1}) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "%s", tlod_context_last_error(ctx));
  *out = tlod_scheduler_draw_list(*sch, 0);
  return CLI_OK;
}

int tessellate_plan_frame(const tess_options* o, tlod_context* ctx, const scene_setup* s, tlod_scheduler** sch,
                          const tlod_draw_list** out) {
  tlod_mesh_info info = tlod_mesh_query_info(s->mesh);
  tlod_view_desc view;
  int rc = tessellate_view(o, info.bbox_min, info.bbox_max, &view);
  return rc == CLI_OK ? tessellate_plan_view(o, ctx, s->surface, s->patterns, &view, sch, out) : rc;
}
