/* tlod -- the GLSL of a field's colour map, generated per run: the range
 * and the table are constants of the program (no uniforms or buffers the
 * device does not know of). */
#include "field_hook.h"

#include <stdio.h>
#include <stdlib.h>

/* 256 "0xRRGGBBu," of 11 characters, 8 a line, plus the fixed text. */
enum { HOOK_SIZE = 256 * 12 + 2048 };

static uint32_t byte_of(float c) { return (uint32_t)(c * 255.0f + 0.5f); }

/* The table as 8-bit RGB packed in uints: the framebuffer's precision, and
 * a quarter of the literals of vec3s (glslang, Vulkan's compiler, takes
 * seconds over 256 vec3 constructors on every stage variant). */
static size_t put_table(char* out, size_t size, colormap_kind k) {
  float rgb[COLORMAP_SIZE][3];
  colormap_table(k, rgb);
  size_t n = (size_t)snprintf(out, size, "const uint tlod_field_map[%d] = uint[%d](", COLORMAP_SIZE, COLORMAP_SIZE);
  for (int i = 0; i < COLORMAP_SIZE && n < size; i++)
    n += (size_t)snprintf(out + n, size - n, "%s0x%06Xu%s", i % 8 ? " " : "\n  ",
                          byte_of(rgb[i][0]) << 16 | byte_of(rgb[i][1]) << 8 | byte_of(rgb[i][2]),
                          i + 1 < COLORMAP_SIZE ? "," : ");\n");
  return n;
}

char* field_hook_glsl(const field_selection* f, uint32_t attribute) {
  char* out = malloc(HOOK_SIZE);
  if (!out) return NULL;
  size_t n = put_table(out, HOOK_SIZE, f->colormap);
  /* The midpoint form keeps a constant field (hi == lo) at the map's centre. */
  double mid = 0.5 * ((double)f->lo + f->hi), inv = f->hi > f->lo ? 1.0 / ((double)f->hi - f->lo) : 0.0;
  snprintf(out + n, HOOK_SIZE - n,
           "// The field's range [%.9g, %.9g] onto the colour map, lit as the built-in material.\n"
           "vec4 tlod_shade(tlod_fragment f) {\n"
           "  float t = clamp(0.5 + (f.attributes[%u].x - (%.9g)) * (%.9g), 0.0, 1.0);\n"
           "  uint c = tlod_field_map[min(int(t * %d.0), %d)];\n"
           "  vec3 base = vec3(float(c >> 16u), float((c >> 8u) & 255u), float(c & 255u)) / 255.0;\n"
           "  float lambert = 0.15 + 0.85 * max(dot(f.normal, f.light_dir), 0.0);\n"
           "  return vec4(base * lambert, 1.0);\n"
           "}\n",
           (double)f->lo, (double)f->hi, attribute, mid, inv, COLORMAP_SIZE, COLORMAP_SIZE - 1);
  return out;
}
