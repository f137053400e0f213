/* Procedural demo meshes (quads, with normals), allocated with malloc. */
#ifndef TLOD_TOOLS_DEMO_SHAPES_H
#define TLOD_TOOLS_DEMO_SHAPES_H

#include <stdbool.h>
#include <stdint.h>

typedef struct demo_shape {
  uint32_t vertex_count, quad_count;
  float* positions;
  float* normals;
  uint32_t* indices; /* 4 per quad, counter-clockwise seen from outside */
} demo_shape;

/* A torus of rings x segs quads (2 * rings * segs triangles when split). */
bool demo_torus(uint32_t rings, uint32_t segs, demo_shape* s);
/* A closed cylinder with sharp rims: segs must be even. */
bool demo_cylinder(uint32_t segs, demo_shape* s);
void demo_shape_free(demo_shape* s);

#endif
