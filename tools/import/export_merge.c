/* export_merge.c -- a scene's instances merged into one world-space mesh
 * for OBJ and PLY: positions by the node's world matrix, normals by its
 * inverse transpose (renormalised), triangles of mirroring nodes
 * (negative determinant) reversed so they stay front-facing, TEXCOORD_0
 * and COLOR_0 copied (parts without them: 0,0 and 1,1,1,1).
 * Owned by the import/export layer (tools/import/). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "export_merge.h"

static const float _exp_identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

/* Calls visit(part mesh, world matrix) for every instance, in node order. */
typedef void (*_exp_visit)(void* user, const tlod_export_mesh* m, const float world[16]);

static void _exp_instances(const tlod_export_scene_desc* d, _exp_visit visit, void* user) {
  const tlod_import_result* r = d->source;
  if (_exp_flattened(r)) { /* flattened: already in world space */
    for (uint32_t p = 0; p < r->part_count; ++p)
      visit(user, &d->parts[p], _exp_identity);
    return;
  }
  for (uint32_t n = 0; n < r->node_count; ++n) {
    if (r->nodes[n].mesh == TLOD_IMPORT_NONE) continue;
    const tlod_import_mesh* me = &r->meshes[r->nodes[n].mesh];
    const tlod_export_mesh* parts = d->node_parts && d->node_parts[n] ? d->node_parts[n] : d->parts + me->first_part;
    for (uint32_t p = 0; p < me->part_count; ++p)
      visit(user, &parts[p], r->nodes[n].world);
  }
}

typedef struct _exp_totals {
  size_t vertices, triangles;
  bool all_normals, uv, color;
} _exp_totals;

static void _exp_count(void* user, const tlod_export_mesh* m, const float world[16]) {
  (void)world;
  _exp_totals* t = user;
  t->vertices += m->vertex_count, t->triangles += m->triangle_count;
  t->all_normals = t->all_normals && m->normals;
  const tlod_export_attribute* uv = _exp_find_attr(m, "TEXCOORD_0");
  const tlod_export_attribute* color = _exp_find_attr(m, "COLOR_0");
  t->uv = t->uv || (uv && uv->components >= 2);
  t->color = t->color || (color && color->components >= 3);
}

typedef struct _exp_fill {
  _exp_merged* out;
  uint32_t vertex, triangle;
} _exp_fill;

static void _exp_place(const float w[16], const float* p, float* out) {
  for (int k = 0; k < 3; ++k)
    out[k] = w[k] * p[0] + w[4 + k] * p[1] + w[8 + k] * p[2] + w[12 + k];
}

/* Normal matrix: the cofactors of the upper 3x3 (the inverse transpose up
 * to the determinant, whose sign is applied). Returns the determinant. */
static float _exp_normal_matrix(const float w[16], float n[9]) {
  const float a = w[0], b = w[4], c = w[8], d = w[1], e = w[5], f = w[9], g = w[2], h = w[6], i = w[10];
  const float cof[9] = {e * i - f * h,    -(d * i - f * g), d * h - e * g,    -(b * i - c * h), a * i - c * g,
                        -(a * h - b * g), b * f - c * e,    -(a * f - c * d), a * e - b * d};
  const float det = a * cof[0] + b * cof[1] + c * cof[2];
  const float s = det < 0.0f ? -1.0f : 1.0f;
  /* cof is row-major; n is column-major */
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col)
      n[3 * col + row] = s * cof[3 * row + col];
  return det;
}

static void _exp_place_normal(const float nm[9], const float* v, float* out) {
  for (int k = 0; k < 3; ++k)
    out[k] = nm[k] * v[0] + nm[3 + k] * v[1] + nm[6 + k] * v[2];
  const float len = sqrtf(out[0] * out[0] + out[1] * out[1] + out[2] * out[2]);
  for (int k = 0; len > 0.0f && k < 3; ++k)
    out[k] /= len;
}

static void _exp_copy_attrs(_exp_merged* o, const tlod_export_mesh* m, uint32_t base) {
  const tlod_export_attribute* uv = _exp_find_attr(m, "TEXCOORD_0");
  const tlod_export_attribute* color = _exp_find_attr(m, "COLOR_0");
  for (uint32_t v = 0; v < m->vertex_count; ++v) {
    float* t = o->uv ? o->uv + 2 * (size_t)(base + v) : NULL;
    float* k = o->color ? o->color + 4 * (size_t)(base + v) : NULL;
    if (t) t[0] = uv && uv->components >= 2 ? _exp_attr_at(uv, v)[0] : 0.0f;
    if (t) t[1] = uv && uv->components >= 2 ? _exp_attr_at(uv, v)[1] : 0.0f;
    for (uint32_t c = 0; k && c < 4; ++c)
      k[c] = color && c < color->components && color->components >= 3 ? _exp_attr_at(color, v)[c] : 1.0f;
  }
}

static void _exp_put(void* user, const tlod_export_mesh* m, const float world[16]) {
  _exp_fill* f = user;
  _exp_merged* o = f->out;
  float nm[9];
  const bool mirror = _exp_normal_matrix(world, nm) < 0.0f;
  for (uint32_t v = 0; v < m->vertex_count; ++v) {
    _exp_place(world, m->positions + 3 * (size_t)v, o->positions + 3 * (size_t)(f->vertex + v));
    if (o->normals) _exp_place_normal(nm, m->normals + 3 * (size_t)v, o->normals + 3 * (size_t)(f->vertex + v));
  }
  _exp_copy_attrs(o, m, f->vertex);
  for (uint32_t t = 0; t < m->triangle_count; ++t) {
    const uint32_t* c = m->indices + 3 * (size_t)t;
    uint32_t* dst = o->indices + 3 * (size_t)(f->triangle + t);
    dst[0] = f->vertex + c[0], dst[1] = f->vertex + c[mirror ? 2 : 1], dst[2] = f->vertex + c[mirror ? 1 : 2];
  }
  f->vertex += m->vertex_count, f->triangle += m->triangle_count;
}

void _exp_merged_free(_exp_merged* m) {
  free(m->positions);
  free(m->normals);
  free(m->uv);
  free(m->color);
  free(m->indices);
  memset(m, 0, sizeof *m);
}

static bool _exp_alloc(_exp_merged* o, const _exp_totals* t) {
  o->positions = malloc(12 * t->vertices);
  o->normals = t->all_normals ? malloc(12 * t->vertices) : NULL;
  o->uv = t->uv ? malloc(8 * t->vertices) : NULL;
  o->color = t->color ? malloc(16 * t->vertices) : NULL;
  o->indices = malloc(12 * t->triangles);
  return o->positions && o->indices && (o->normals || !t->all_normals) && (o->uv || !t->uv) && (o->color || !t->color);
}

static void _exp_describe(_exp_merged* o, const _exp_totals* t) {
  uint32_t n = 0;
  if (o->uv) o->attributes[n++] = (tlod_export_attribute){"TEXCOORD_0", 2, o->uv, 0};
  if (o->color) o->attributes[n++] = (tlod_export_attribute){"COLOR_0", 4, o->color, 0};
  o->mesh = (tlod_export_mesh){(uint32_t)t->vertices, o->positions, o->normals, (uint32_t)t->triangles, o->indices, n,
                               o->attributes};
}

tlod_result _exp_merge(_exp_job* job, const tlod_export_scene_desc* d, _exp_merged* out) {
  memset(out, 0, sizeof *out);
  _exp_totals t = {0, 0, true, false, false};
  _exp_instances(d, _exp_count, &t);
  if (t.vertices == 0 || t.triangles == 0)
    return _exp_fail(job, TLOD_ERROR_INVALID_ARGUMENT, "no node instances a mesh: nothing to write");
  if (t.vertices > UINT32_MAX || t.triangles > UINT32_MAX / 3)
    return _exp_fail(job, TLOD_ERROR_UNSUPPORTED, "%zu vertices, %zu triangles: too many for one mesh", t.vertices,
                     t.triangles);
  if (!_exp_alloc(out, &t)) {
    _exp_merged_free(out);
    return _exp_fail(job, TLOD_ERROR_OUT_OF_MEMORY, "out of memory");
  }
  _exp_fill f = {out, 0, 0};
  _exp_instances(d, _exp_put, &f);
  _exp_describe(out, &t);
  return TLOD_SUCCESS;
}
