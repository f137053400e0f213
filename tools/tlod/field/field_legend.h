/* The legend of a colour-mapped field, drawn into a screenshot: a vertical
 * colour bar at the right edge (high values at the top), the range's ends
 * beside it and the field's name and units above it, on a dark box.
 *
 * Geometry (the tests read it; docs/play.md "Fields"), for a W x H image,
 * top row first, s = max(1, H / 360), all in pixels:
 *   bar: columns W - 12s - 12s .. W - 12s - 1, rows H/4 .. H/4 + H/2 - 1;
 *        row y shows the unlit map entry colormap_index(t),
 *        t = (H/4 + H/2 - 1 - y) / (H/2 - 1) (top: t = 1, bottom: 0);
 *   the maximum, right-aligned 4s left of the bar, its top at row H/4;
 *   the minimum likewise, its bottom at the bar's bottom;
 *   "NAME [UNITS]" right-aligned to the bar's right edge, its bottom 4s
 *   above the bar; text white, at font scale s (common/bitmap_font.h). */
#ifndef TLOD_TOOLS_FIELD_LEGEND_H
#define TLOD_TOOLS_FIELD_LEGEND_H

#include <stdint.h>

#include "field_select.h"

/* Draws f's legend into width x height RGBA8 pixels (top row first);
 * images under 64 x 64 pixels get none. */
void field_legend_draw(const field_selection* f, uint8_t* rgba, uint32_t width, uint32_t height);

#endif
