/* The fragment hook (tlod_device_gl_desc.fragment_hook, the Vulkan
 * device's likewise) that colours a result field: the field's mesh
 * attribute mapped through the range onto the colour map, lit as the
 * built-in material (tesslod/backend.h, tlod_draw_desc.light_dir). */
#ifndef TLOD_TOOLS_FIELD_HOOK_H
#define TLOD_TOOLS_FIELD_HOOK_H

#include <stdint.h>

#include "field_select.h"

/* GLSL 4.50 defining tlod_shade() for field f held in mesh attribute
 * `attribute` (its .x): t = clamp((v - lo) / (hi - lo), 0, 1) (hi == lo:
 * 0.5), colour = table[min(floor(t * 256), 255)] (8-bit RGB) * (0.15 + 0.85 *
 * max(dot(n, l), 0)), alpha 1. Malloc'd (free it); NULL when out of memory. */
char* field_hook_glsl(const field_selection* f, uint32_t attribute);

#endif
