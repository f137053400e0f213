/* Colour maps of result fields (tlod play --colormap): 256 display (sRGB-
 * encoded) colours from the low end of the range (entry 0) to the high end
 * (entry 255). A value t in [0, 1] takes entry min(floor(t * 256), 255), as
 * matplotlib's colormaps index their tables (docs/play.md, "Fields"). */
#ifndef TLOD_TOOLS_COLORMAP_H
#define TLOD_TOOLS_COLORMAP_H

#include <stdint.h>

#define COLORMAP_SIZE 256

typedef enum colormap_kind { COLORMAP_VIRIDIS, COLORMAP_DIVERGING, COLORMAP_NUM } colormap_kind;

/* "viridis", "diverging", NULL: for cli_parse_enum, in colormap_kind order. */
extern const char* const colormap_names[];

/* The 256 entries of map k, rgb in [0, 1] (display values, written to the
 * framebuffer as they are). */
void colormap_table(colormap_kind k, float rgb[COLORMAP_SIZE][3]);

/* The entry a normalised value t takes (clamped to [0, 1]; NaN: 0). */
uint32_t colormap_index(float t);

#endif
