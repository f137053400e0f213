/* tlod -- the field legend in screenshots (geometry in field_legend.h). */
#include "field_legend.h"

#include <stdio.h>

#include "common/bitmap_font.h"

typedef struct legend_box {
  int x0, x1, y0, y1; /* the bar: columns [x0, x1), rows [y0, y1) */
  uint32_t s;
} legend_box;

static void put(uint8_t* rgba, uint32_t width, int x, int y, const uint8_t rgb[3]) {
  uint8_t* p = rgba + ((size_t)y * width + (size_t)x) * 4;
  p[0] = rgb[0], p[1] = rgb[1], p[2] = rgb[2], p[3] = 255;
}

static void fill_rect(uint8_t* rgba, uint32_t width, uint32_t height, int x0, int y0, int x1, int y1,
                      const uint8_t rgb[3]) {
  for (int y = y0 < 0 ? 0 : y0; y < y1 && y < (int)height; y++)
    for (int x = x0 < 0 ? 0 : x0; x < x1 && x < (int)width; x++)
      put(rgba, width, x, y, rgb);
}

static void draw_bar(const field_selection* f, const legend_box* b, uint8_t* rgba, uint32_t width) {
  float table[COLORMAP_SIZE][3];
  colormap_table(f->colormap, table);
  int rows = b->y1 - b->y0;
  for (int y = b->y0; y < b->y1; y++) {
    const float* c = table[colormap_index((float)(b->y1 - 1 - y) / (float)(rows - 1))];
    uint8_t rgb[3] = {(uint8_t)(c[0] * 255.0f + 0.5f), (uint8_t)(c[1] * 255.0f + 0.5f),
                      (uint8_t)(c[2] * 255.0f + 0.5f)};
    for (int x = b->x0; x < b->x1; x++)
      put(rgba, width, x, y, rgb);
  }
}

void field_legend_draw(const field_selection* f, uint8_t* rgba, uint32_t width, uint32_t height) {
  if (width < 64 || height < 64) return;
  uint32_t s = height / 360 > 1 ? height / 360 : 1;
  int m = 12 * (int)s, gh = FONT_GLYPH_H * (int)s;
  legend_box b = {.x1 = (int)width - m, .y0 = (int)(height / 4), .s = s};
  b.x0 = b.x1 - 12 * (int)s, b.y1 = b.y0 + (int)(height / 2);
  char hi[32], lo[32], name[128];
  snprintf(hi, sizeof(hi), "%.4g", (double)f->hi);
  snprintf(lo, sizeof(lo), "%.4g", (double)f->lo);
  snprintf(name, sizeof(name), f->units[0] ? "%s [%s]" : "%s", f->label, f->units);
  uint32_t wn = font_text_width(hi, s) > font_text_width(lo, s) ? font_text_width(hi, s) : font_text_width(lo, s);
  int left = b.x0 - 4 * (int)s - (int)wn, name_x = b.x1 - (int)font_text_width(name, s);
  static const uint8_t box[3] = {24, 24, 28}, white[3] = {255, 255, 255};
  fill_rect(rgba, width, height, (left < name_x ? left : name_x) - 4 * (int)s, b.y0 - 8 * (int)s - gh,
            b.x1 + 4 * (int)s, b.y1 + 4 * (int)s, box);
  draw_bar(f, &b, rgba, width);
  font_draw(rgba, width, height, b.x0 - 4 * (int)s - (int)font_text_width(hi, s), b.y0, s, hi, white);
  font_draw(rgba, width, height, b.x0 - 4 * (int)s - (int)font_text_width(lo, s), b.y1 - gh, s, lo, white);
  font_draw(rgba, width, height, name_x, b.y0 - 4 * (int)s - gh, s, name, white);
}
