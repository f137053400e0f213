/* tlod tessellate -- adaptive mode's one scheduler frame. */
#ifndef TLOD_TOOLS_TESSELLATE_FRAME_H
#define TLOD_TOOLS_TESSELLATE_FRAME_H

#include "common/scene_setup.h"
#include "tessellate_options.h"

/* The view of the camera options for a scene box (default target: its
 * centre; near and far planes fitted to it); CLI_USAGE (printed) when the
 * camera has no view. */
int tessellate_view(const tess_options* o, const float bmin[3], const float bmax[3], tlod_view_desc* out);
/* Creates *sch for surface and plans one frame of view; *out is its draw list. */
int tessellate_plan_view(const tess_options* o, tlod_context* ctx, tlod_surface* surface, tlod_patterns* patterns,
                         const tlod_view_desc* view, tlod_scheduler** sch, const tlod_draw_list** out);
/* Creates *sch and plans one frame for the camera of o->ad; *out is its draw list. */
int tessellate_plan_frame(const tess_options* o, tlod_context* ctx, const scene_setup* s, tlod_scheduler** sch,
                          const tlod_draw_list** out);

#endif
