/* A 5x7 bitmap font for text drawn into images (tlod play's field legend):
 * digits, upper-case letters (lower case is drawn upper case) and common
 * punctuation; other characters draw as '?'. Cells are 6 x 8 pixels at
 * scale 1 (one column and one row of spacing). */
#ifndef TLOD_TOOLS_BITMAP_FONT_H
#define TLOD_TOOLS_BITMAP_FONT_H

#include <stdint.h>

#define FONT_CELL_W 6
#define FONT_CELL_H 8
#define FONT_GLYPH_H 7

/* Width in pixels of text at integer scale s (cells times s). */
uint32_t font_text_width(const char* text, uint32_t s);
/* Draws text with its cell's top-left at (x, y) (may lie partly outside)
 * into width x height RGBA8 pixels, top row first, opaque rgb. */
void font_draw(uint8_t* rgba, uint32_t width, uint32_t height, int x, int y, uint32_t s, const char* text,
               const uint8_t rgb[3]);

#endif
