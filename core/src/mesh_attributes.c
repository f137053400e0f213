/* tesslod::core -- vertex attributes: checked, stored as padded vec4s, and
 * interpolated over a patch's grid (corners exact, edges through the one
 * canonical edge blend, interiors by the corner weights).
 * Owned by the mesh module (mesh.c, mesh_adjacency.c, mesh_attributes.c,
 * mesh_normals.c). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "internal.h"

static const char component_name[4] = {'x', 'y', 'z', 'w'};

/* "attribute 2 'COLOR_0'", or "attribute 2" without a name. */
static void attribute_label(char* buf, size_t size, uint32_t a, const char* name) {
  if (name && name[0])
    snprintf(buf, size, "attribute %u '%.31s'", a, name);
  else
    snprintf(buf, size, "attribute %u", a);
}

static uint32_t stride_of(const tlod_attribute_desc* d) { return d->stride ? d->stride : 4 * d->components; }

static tlod_result check_desc(tlod_context* ctx, const char* label, uint32_t a, const tlod_attribute_desc* d) {
  char what[64];
  attribute_label(what, sizeof(what), a, d->name);
  if (d->components < 1 || d->components > 4)
    return _tlod_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "mesh '%s': %s: components %u (1..4)", label, what,
                      d->components);
  if (!d->data) return _tlod_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "mesh '%s': %s: data is NULL", label, what);
  if (stride_of(d) < 4 * d->components)
    return _tlod_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT,
                      "mesh '%s': %s: stride %u bytes is smaller than an element (%u bytes)", label, what, d->stride,
                      4 * d->components);
  return TLOD_SUCCESS;
}

/* memcpy, because a stride need not keep floats aligned. */
static void load(const tlod_attribute_desc* d, uint32_t v, float out[4]) {
  static const float pad[4] = {0.0f, 0.0f, 0.0f, 1.0f};
  memcpy(out, pad, sizeof(pad));
  memcpy(out, (const unsigned char*)d->data + (size_t)stride_of(d) * v, sizeof(float) * d->components);
}

static tlod_result check_values(tlod_context* ctx, const char* label, uint32_t a, const tlod_attribute_desc* d,
                                uint32_t vertex_count) {
  for (uint32_t v = 0; v < vertex_count; v++) {
    float x[4];
    load(d, v, x);
    for (uint32_t c = 0; c < d->components; c++) {
      if (isfinite(x[c])) continue;
      char what[64];
      attribute_label(what, sizeof(what), a, d->name);
      return _tlod_fail(ctx, TLOD_ERROR_INVALID_MESH, "mesh '%s': vertex %u: %s.%c is %g (not finite)", label, v, what,
                        component_name[c], (double)x[c]);
    }
  }
  return TLOD_SUCCESS;
}

tlod_result _tlod_mesh_check_attributes(tlod_context* ctx, const char* label, const tlod_mesh_desc* d) {
  if (d->attribute_count > TLOD_MAX_ATTRIBUTES)
    return _tlod_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "mesh '%s': attribute_count %u (at most %u)", label,
                      d->attribute_count, TLOD_MAX_ATTRIBUTES);
  if (d->attribute_count > 0 && !d->attributes)
    return _tlod_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "mesh '%s': attributes is NULL (attribute_count %u)", label,
                      d->attribute_count);
  for (uint32_t a = 0; a < d->attribute_count; a++) {
    tlod_result r = check_desc(ctx, label, a, &d->attributes[a]);
    if (r == TLOD_SUCCESS) r = check_values(ctx, label, a, &d->attributes[a], d->vertex_count);
    if (r != TLOD_SUCCESS) return r;
  }
  return TLOD_SUCCESS;
}

tlod_result _tlod_mesh_copy_attributes(tlod_mesh* m, const tlod_mesh_desc* d) {
  uint32_t na = d->attribute_count, input = m->info.input_vertex_count;
  m->attribute_count = na;
  if (na == 0) return TLOD_SUCCESS;
  m->attributes = _tlod_calloc(m->ctx, (size_t)m->vertex_count * na, sizeof(*m->attributes));
  if (!m->attributes)
    return _tlod_fail(m->ctx, TLOD_ERROR_OUT_OF_MEMORY, "mesh '%s': out of memory (attributes)", m->label);
  for (uint32_t a = 0; a < na; a++) {
    const tlod_attribute_desc* ad = &d->attributes[a];
    snprintf(m->attribute_info[a].name, sizeof(m->attribute_info[a].name), "%s", ad->name ? ad->name : "");
    m->attribute_info[a].components = ad->components;
    for (uint32_t v = 0; v < input; v++)
      load(ad, v, m->attributes[(size_t)v * na + a]);
  }
  /* Crease-split vertices (appended after the input ones) copy their source. */
  for (uint32_t v = input; v < m->vertex_count; v++)
    memcpy(m->attributes[(size_t)v * na], m->attributes[(size_t)m->split_source[v - input] * na],
           sizeof(*m->attributes) * na);
  return TLOD_SUCCESS;
}

bool _tlod_mesh_same_attributes(const tlod_mesh* m, uint32_t a, uint32_t b) {
  size_t na = m->attribute_count;
  return a == b || na == 0 || memcmp(m->attributes[a * na], m->attributes[b * na], sizeof(*m->attributes) * na) == 0;
}

/* ------------------------------------------------------------------------ */
/* Update (time series of a field)                                          */
/* ------------------------------------------------------------------------ */

static tlod_result check_update(tlod_mesh* m, uint32_t a, const tlod_attribute_desc* d) {
  if (a >= m->attribute_count)
    return _tlod_fail(m->ctx, TLOD_ERROR_INVALID_ARGUMENT, "mesh '%s': update attribute %u: the mesh has %u attributes",
                      m->label, a, m->attribute_count);
  tlod_result r = check_desc(m->ctx, m->label, a, d);
  return r == TLOD_SUCCESS ? check_values(m->ctx, m->label, a, d, m->info.input_vertex_count) : r;
}

tlod_result tlod_mesh_update_attribute(tlod_mesh* mesh, uint32_t attribute, const float* data, uint32_t stride) {
  if (!mesh) return TLOD_ERROR_INVALID_ARGUMENT;
  uint32_t na = mesh->attribute_count, input = mesh->info.input_vertex_count;
  /* The attribute's own components and name; an index past the end is refused by check_update. */
  tlod_attribute_desc d = {.data = data, .stride = stride};
  if (attribute < na)
    d.components = mesh->attribute_info[attribute].components, d.name = mesh->attribute_info[attribute].name;
  tlod_result r = check_update(mesh, attribute, &d);
  if (r != TLOD_SUCCESS) return r;
  for (uint32_t v = 0; v < input; v++)
    load(&d, v, mesh->attributes[(size_t)v * na + attribute]);
  for (uint32_t v = input; v < mesh->vertex_count; v++)
    memcpy(mesh->attributes[(size_t)v * na + attribute],
           mesh->attributes[(size_t)mesh->split_source[v - input] * na + attribute], sizeof(*mesh->attributes));
  /* Seam flags compare attribute values bitwise. */
  _tlod_mesh_refresh_smooth(mesh);
  mesh->generation++;
  return TLOD_SUCCESS;
}

/* ------------------------------------------------------------------------ */
/* Queries                                                                  */
/* ------------------------------------------------------------------------ */

uint32_t tlod_mesh_attribute_count(const tlod_mesh* mesh) { return mesh ? mesh->attribute_count : 0; }

tlod_attribute_info tlod_mesh_query_attribute(const tlod_mesh* mesh, uint32_t a) {
  if (!mesh || a >= mesh->attribute_count) return (tlod_attribute_info){{0}, 0};
  return mesh->attribute_info[a];
}

tlod_result tlod_mesh_patch_attributes(const tlod_mesh* m, uint32_t first, uint32_t count, float (*out)[4]) {
  if (!m) return TLOD_ERROR_INVALID_ARGUMENT;
  uint32_t na = m->attribute_count;
  if (first > m->face_count || count > m->face_count - first || (!out && count > 0 && na > 0))
    return _tlod_fail(m->ctx, TLOD_ERROR_INVALID_ARGUMENT,
                      "mesh '%s': patch attributes [%u, %u + %u) outside its %u patches (or out is NULL)", m->label,
                      first, first, count, m->face_count);
  if (na == 0) return TLOD_SUCCESS;
  for (uint32_t p = 0; p < count; p++) {
    uint32_t f = first + p;
    float(*dst)[4] = out + (size_t)p * 4 * na;
    memset(dst, 0, sizeof(*dst) * 4 * na);
    for (uint32_t c = 0; c < m->face_corners[f]; c++)
      memcpy(dst + (size_t)c * na, m->attributes[(size_t)m->faces[f][c] * na], sizeof(*dst) * na);
  }
  return TLOD_SUCCESS;
}

/* ------------------------------------------------------------------------ */
/* Grid evaluation                                                          */
/* ------------------------------------------------------------------------ */

static const float (*vertex_attributes(const tlod_mesh* m, uint32_t v))[4] {
  return (const float(*)[4])m->attributes + (size_t)v * m->attribute_count;
}

/* The one canonical edge blend: from the end with the smaller weld id, so
 * both patches of an edge compute the same float operations. */
static void edge_point(const tlod_mesh* m, uint32_t patch, uint32_t edge, float t_end, float (*out)[4]) {
  uint32_t n = m->face_corners[patch];
  uint32_t a = m->faces[patch][edge], b = m->faces[patch][(edge + 1) % n];
  if (m->weld_id[a] > m->weld_id[b]) {
    uint32_t swap = a;
    a = b;
    b = swap;
    t_end = 1.0f - t_end;
  }
  const float(*x)[4] = vertex_attributes(m, a), (*y)[4] = vertex_attributes(m, b);
  for (uint32_t k = 0; k < m->attribute_count; k++)
    for (int c = 0; c < 4; c++)
      out[k][c] = (1.0f - t_end) * x[k][c] + t_end * y[k][c];
}

/* Barycentric (u on corner 0, v on 1, w on 2) or bilinear weights. */
static void interior_point(const tlod_mesh* m, uint32_t patch, float u, float v, float (*out)[4]) {
  const uint32_t* f = m->faces[patch];
  float wt[4];
  uint32_t n = m->face_corners[patch];
  if (n == 3) {
    wt[0] = u, wt[1] = v, wt[2] = 1.0f - u - v, wt[3] = 0.0f;
  } else {
    wt[0] = (1.0f - u) * (1.0f - v), wt[1] = u * (1.0f - v), wt[2] = u * v, wt[3] = (1.0f - u) * v;
  }
  for (uint32_t k = 0; k < m->attribute_count; k++)
    for (int c = 0; c < 4; c++) {
      float s = 0.0f;
      for (uint32_t i = 0; i < n; i++)
        s += wt[i] * vertex_attributes(m, f[i])[k][c];
      out[k][c] = s;
    }
}

static void grid_point(const tlod_mesh* m, uint32_t patch, uint32_t grid_log2, const uint16_t ij[2], float (*out)[4]) {
  uint32_t param = 0, kind = tlod_grid_point_kind(m->face_corners[patch], grid_log2, ij[0], ij[1], &param);
  float nn = (float)(1u << grid_log2);
  if (kind < TLOD_GRID_EDGE)
    memcpy(out, vertex_attributes(m, m->faces[patch][kind]), sizeof(*out) * m->attribute_count);
  else if (kind < TLOD_GRID_INTERIOR)
    edge_point(m, patch, kind - TLOD_GRID_EDGE, (float)param / nn, out);
  else
    interior_point(m, patch, (float)ij[0] / nn, (float)ij[1] / nn, out);
}

static bool grid_valid(uint32_t corners, uint32_t grid_log2, const uint16_t* ij, size_t ij_stride, uint32_t count) {
  const char* at = (const char*)ij;
  for (uint32_t k = 0; k < count; k++, at += ij_stride) {
    uint16_t point[2];
    memcpy(point, at, sizeof(point));
    if (tlod_grid_point_kind(corners, grid_log2, point[0], point[1], &(uint32_t){0}) == TLOD_GRID_OFF) return false;
  }
  return true;
}

tlod_result tlod_mesh_eval_attributes_grid(const tlod_mesh* m, uint32_t patch, uint32_t grid_log2, const uint16_t* ij,
                                           size_t ij_stride, uint32_t count, float (*out)[4]) {
  if (!m || patch >= m->face_count || grid_log2 > TLOD_GRID_MAX_LOG2) return TLOD_ERROR_INVALID_ARGUMENT;
  if (count == 0) return TLOD_SUCCESS;
  if (!ij || !grid_valid(m->face_corners[patch], grid_log2, ij, ij_stride, count)) return TLOD_ERROR_INVALID_ARGUMENT;
  if (m->attribute_count == 0) return TLOD_SUCCESS;
  if (!out) return TLOD_ERROR_INVALID_ARGUMENT;
  const char* at = (const char*)ij;
  for (uint32_t k = 0; k < count; k++, at += ij_stride) {
    uint16_t point[2];
    memcpy(point, at, sizeof(point));
    grid_point(m, patch, grid_log2, point, out + (size_t)k * m->attribute_count);
  }
  return TLOD_SUCCESS;
}
