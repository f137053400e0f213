/* tlod tessellate -- adaptive mode's one scheduler frame. */
#ifndef TLOD_TOOLS_TESSELLATE_FRAME_H
#define TLOD_TOOLS_TESSELLATE_FRAME_H

#include "common/scene_setup.h"
#include "tessellate_options.h"

/* Creates *sch and plans one frame for the camera of o->ad; *out is its draw list. */
int tessellate_plan_frame(const tess_options* o, tlod_context* ctx, const scene_setup* s, tlod_scheduler** sch,
                          const tlod_draw_list** out);

#endif
