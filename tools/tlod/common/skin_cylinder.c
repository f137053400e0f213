/* The generated skinned cylinder (skin_cylinder.h). */
#include "common/skin_cylinder.h"

#include <math.h>
#include <stdlib.h>

#include "common/anim_sample.h"
#include "common/skin_apply.h"

float skin_cylinder_weight(const skin_cylinder* c, float y) {
  float s = (y / c->height - 0.3f) / 0.4f;
  s = s < 0.0f ? 0.0f : s > 1.0f ? 1.0f : s;
  return s * s * (3.0f - 2.0f * s);
}

/* One vertex; side and rim vertices at the same (j, y) get the same bits. */
static void put_vertex(skin_cylinder* c, uint32_t v, uint32_t j, uint32_t segments, float y, const float n[3],
                       bool centre) {
  double a = 2.0 * 3.14159265358979323846 * (double)j / (double)segments;
  float* p = c->positions + (size_t)v * 3;
  p[0] = centre ? 0.0f : c->radius * (float)cos(a);
  p[1] = y;
  p[2] = centre ? 0.0f : c->radius * (float)sin(a);
  float* nn = c->normals + (size_t)v * 3;
  nn[0] = n ? n[0] : (float)cos(a);
  nn[1] = n ? n[1] : 0.0f;
  nn[2] = n ? n[2] : (float)sin(a);
  float w1 = skin_cylinder_weight(c, y);
  uint16_t* jt = c->joints + (size_t)v * 4;
  float* w = c->weights + (size_t)v * 4;
  jt[0] = 0, jt[1] = 1, jt[2] = 0, jt[3] = 0;
  w[0] = 1.0f - w1, w[1] = w1, w[2] = 0.0f, w[3] = 0.0f;
}

static uint32_t* put_tri(uint32_t* ix, uint32_t a, uint32_t b, uint32_t d) {
  ix[0] = a, ix[1] = b, ix[2] = d;
  return ix + 3;
}

/* Height of side row i; the top cap takes row `rings` from here too. */
static float ring_y(const skin_cylinder* c, uint32_t i, uint32_t rings) { return c->height * (float)i / (float)rings; }

static void build_side(skin_cylinder* c, uint32_t segments, uint32_t rings, uint32_t** ix) {
  for (uint32_t i = 0; i <= rings; i++)
    for (uint32_t j = 0; j < segments; j++)
      put_vertex(c, i * segments + j, j, segments, ring_y(c, i, rings), NULL, false);
  for (uint32_t i = 0; i < rings; i++)
    for (uint32_t j = 0; j < segments; j++) {
      uint32_t a = i * segments + j, b = i * segments + (j + 1) % segments;
      *ix = put_tri(*ix, a, a + segments, b + segments);
      *ix = put_tri(*ix, a, b + segments, b);
    }
}

/* Cap at height y from vertex `first`: the centre, then the rim. */
static void build_cap(skin_cylinder* c, uint32_t segments, uint32_t first, float y, bool top, uint32_t** ix) {
  const float n[3] = {0.0f, top ? 1.0f : -1.0f, 0.0f};
  put_vertex(c, first, 0, segments, y, n, true);
  for (uint32_t j = 0; j < segments; j++)
    put_vertex(c, first + 1 + j, j, segments, y, n, false);
  for (uint32_t j = 0; j < segments; j++) {
    uint32_t a = first + 1 + j, b = first + 1 + (j + 1) % segments;
    *ix = top ? put_tri(*ix, first, b, a) : put_tri(*ix, first, a, b);
  }
}

bool skin_cylinder_create(uint32_t segments, uint32_t rings, float radius, float height, skin_cylinder* out) {
  *out = (skin_cylinder){.radius = radius, .height = height};
  uint64_t side = (uint64_t)(rings + 1ull) * segments, verts = side + 2ull * (segments + 1ull);
  uint64_t indices = 6ull * rings * segments + 6ull * segments;
  if (segments < 3 || rings < 1 || verts > UINT32_MAX / 4 || indices > UINT32_MAX) return false;
  out->vertex_count = (uint32_t)verts, out->index_count = (uint32_t)indices;
  out->positions = malloc(sizeof(float) * 3 * verts);
  out->normals = malloc(sizeof(float) * 3 * verts);
  out->joints = malloc(sizeof(uint16_t) * 4 * verts);
  out->weights = malloc(sizeof(float) * 4 * verts);
  out->indices = malloc(sizeof(uint32_t) * indices);
  if (!out->positions || !out->normals || !out->joints || !out->weights || !out->indices)
    return skin_cylinder_free(out), false;
  uint32_t* ix = out->indices;
  build_side(out, segments, rings, &ix);
  build_cap(out, segments, (uint32_t)side, 0.0f, false, &ix);
  build_cap(out, segments, (uint32_t)side + segments + 1, ring_y(out, rings, rings), true, &ix);
  return true;
}

void skin_cylinder_free(skin_cylinder* c) {
  free(c->positions);
  free(c->normals);
  free(c->joints);
  free(c->weights);
  free(c->indices);
  *c = (skin_cylinder){0};
}

void skin_cylinder_pose(const skin_cylinder* c, const float rotation[4], float mats[2][16]) {
  float half = 0.5f * c->height, local[2][16], world[2][16], inverse_bind[2][16];
  anim_trs trs[2] = {{{0, 0, 0}, {0, 0, 0, 1}, {1, 1, 1}}, {{0, half, 0}, {0, 0, 0, 1}, {1, 1, 1}}};
  anim_trs inv[2] = {{{0, 0, 0}, {0, 0, 0, 1}, {1, 1, 1}}, {{0, -half, 0}, {0, 0, 0, 1}, {1, 1, 1}}};
  for (int i = 0; i < 4; i++)
    trs[1].rotation[i] = rotation[i];
  const uint32_t parent[2] = {UINT32_MAX, 0};
  uint32_t scratch[4];
  for (int j = 0; j < 2; j++) {
    anim_trs_matrix(&trs[j], local[j]);
    anim_trs_matrix(&inv[j], inverse_bind[j]);
  }
  anim_world_matrices(2, parent, (const float(*)[16])local, world, scratch);
  skin_joint_matrices(2, (const float(*)[16])world, (const float(*)[16])inverse_bind, mats);
}

void skin_cylinder_model_free(skin_cylinder_model* m) {
  tlod_surface_destroy(m->surface);
  tlod_mesh_destroy(m->mesh);
  skin_cylinder_free(&m->cyl);
  free(m->positions);
  free(m->normals);
  *m = (skin_cylinder_model){0};
}

bool skin_cylinder_model_create(tlod_context* ctx, uint32_t segments, uint32_t rings, float radius, float height,
                                skin_cylinder_model* out) {
  *out = (skin_cylinder_model){0};
  if (!skin_cylinder_create(segments, rings, radius, height, &out->cyl)) return false;
  const skin_cylinder* c = &out->cyl;
  tlod_mesh_desc md = {.positions = c->positions,
                       .normals = c->normals,
                       .vertex_count = c->vertex_count,
                       .indices = c->indices,
                       .index_count = c->index_count,
                       .label = "cylinder"};
  out->positions = malloc(sizeof(float) * 3 * c->vertex_count);
  out->normals = malloc(sizeof(float) * 3 * c->vertex_count);
  bool ok = out->positions && out->normals && tlod_mesh_create(ctx, &md, &out->mesh) == TLOD_SUCCESS &&
            tlod_surface_create(ctx, out->mesh, &(tlod_surface_desc){.type = TLOD_SURFACE_PHONG}, &out->surface) ==
                TLOD_SUCCESS;
  if (!ok) skin_cylinder_model_free(out);
  return ok;
}
