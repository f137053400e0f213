/*
 * sample_scene.h -- what every sample shares: a lat-long sphere mesh with
 * TEXCOORD_0, the checker material (a fragment hook), an orbit camera and
 * the tesslod objects of one surface (context, patterns, device, mesh,
 * surface, device surface, scheduler). Public tesslod headers only.
 */
#ifndef TLOD_SAMPLE_SCENE_H
#define TLOD_SAMPLE_SCENE_H

#include <stdbool.h>
#include <stdint.h>

#include "tesslod/backend.h"
#include "tesslod/lod.h"

/* The samples' material: a checker of the mesh's TEXCOORD_0
 * (f.attributes[0]), 8 x 4 cells of orange and blue, lit, plus a rim light.
 * GLSL 450 defining tlod_shade (tesslod/gl.h FRAGMENT HOOKS). */
extern const char* const sample_checker_hook;

/* (nlat + 1) x (nlon + 1) vertices of a unit sphere around the origin (z
 * up): the last column repeats the first (the UV seam), each pole is a row
 * of copies, so every vertex has its own UV; the copies share bitwise-equal
 * positions, which tesslod welds for adjacency. */
typedef struct sample_mesh {
  float *positions, *uvs;
  uint32_t *indices, vertex_count, index_count;
} sample_mesh;
bool sample_sphere_make(sample_mesh* m, uint32_t nlat, uint32_t nlon);
void sample_mesh_free(sample_mesh* m);
/* m's mesh desc (angle-weighted normals computed by tesslod, *uv its
 * TEXCOORD_0); points into m and uv. */
tlod_mesh_desc sample_mesh_desc(const sample_mesh* m, tlod_attribute_desc* uv);

/* A camera at `distance` from the origin, `height` above it, at `angle`
 * radians around z, looking at the origin; 45 degree vertical field of view,
 * GL conventions (column-major, clip z in -w..w: tesslod's devices take
 * that for both APIs). */
tlod_view_desc sample_orbit_camera(float angle, float distance, float height, uint32_t width, uint32_t height_px);

typedef struct sample_scene {
  tlod_context* ctx;
  tlod_patterns* patterns;
  tlod_device* dev;
  tlod_mesh* mesh;
  tlod_surface* surface;
  tlod_device_surface* dsurf;
  tlod_scheduler* scheduler;
} sample_scene;

/* Makes every object of *s (zeroed first) for mesh *md as a PN surface (a
 * Phong one when it has quads: the device must link that type), the
 * device from *device (its .patterns is set here). false with the reason
 * printed after `who`; sample_scene_free frees what was made. */
bool sample_scene_init(sample_scene* s, const tlod_mesh_desc* md, tlod_device_desc device, const char* who);
void sample_scene_free(sample_scene* s);

/* Plans the frame of view v and fills *item and *draw (items = item) for
 * it; false with the reason printed. */
bool sample_scene_plan(sample_scene* s, const tlod_view_desc* v, float dt_ms, tlod_draw_item* item,
                       tlod_draw_desc* draw, const char* who);

/* The value of option `flag` as a whole number in lo..hi into *out; false
 * with "<who>: <flag> '<text>': ..." printed otherwise (atoi read "12x" as
 * 12 and "x" as 0). The samples' one parser of numeric options. */
bool sample_parse_int(const char* who, const char* flag, const char* text, int lo, int hi, int* out);

/* Prints "<who>: <call>: <result>: <last error>" unless r is TLOD_SUCCESS. */
bool sample_check(tlod_result r, const sample_scene* s, const char* call, const char* who);

#endif
