/* vtk_test_util.c -- see vtk_test_util.h. */
#include "vtk_test_util.h"

#include <stdio.h>
#include <stdlib.h>

#include "shapes.h"
#include "tesslod/lod.h"

void vtk_test_path(char* out, size_t size, const char* work, const char* name) {
  snprintf(out, size, "%s/%s", work, name);
}

tlod_import_result* vtk_test_write_import(const vtk_model* m, const char* work, const char* name, vtk_format format) {
  char path[1024], err[512];
  vtk_test_path(path, sizeof path, work, name);
  if (!vtk_model_write(m, path, format)) return NULL;
  tlod_import_result* r = NULL;
  tlod_result res = tlod_import_file(path, NULL, &r, err, sizeof err);
  if (res != TLOD_SUCCESS) {
    fprintf(stderr, "import %s: %s: %s\n", name, tlod_result_string(res), err);
    return NULL;
  }
  return r;
}

tlod_mesh* vtk_test_mesh(tlod_context* ctx, const tlod_import_result* r, float crease_deg, uint32_t attributes) {
  tlod_attribute_desc ad[TLOD_MAX_ATTRIBUTES];
  uint32_t na = 0;
  for (uint32_t k = 0; k < attributes && k < r->field_count && na < TLOD_MAX_ATTRIBUTES; ++k) {
    const tlod_import_field* f = &r->fields[k];
    if (f->components > 4) continue;
    ad[na++] = (tlod_attribute_desc){.data = f->data, .components = f->components, .name = f->name};
  }
  tlod_mesh_desc md = {.positions = r->positions,
                       .normals = r->normals,
                       .vertex_count = r->vertex_count,
                       .indices = r->indices,
                       .index_count = r->index_count,
                       .face_type = r->face_sizes ? TLOD_FACE_MIXED : TLOD_FACE_TRIANGLES,
                       .face_sizes = r->face_sizes,
                       .face_count = r->face_count,
                       .crease_angle_deg = crease_deg,
                       .label = "vtk test mesh",
                       .attributes = na ? ad : NULL,
                       .attribute_count = na,
                       .face_nodes = r->face_nodes};
  tlod_mesh* mesh = NULL;
  tlod_result res = tlod_mesh_create(ctx, &md, &mesh);
  if (res != TLOD_SUCCESS)
    fprintf(stderr, "tlod_mesh_create: %s: %s\n", tlod_result_string(res), tlod_context_last_error(ctx));
  return mesh;
}

tlod_surface* vtk_test_surface(tlod_context* ctx, const tlod_mesh* mesh, tlod_surface_type type) {
  tlod_surface* s = NULL;
  tlod_result res = tlod_surface_create(ctx, mesh, &(tlod_surface_desc){.type = type}, &s);
  if (res != TLOD_SUCCESS)
    fprintf(stderr, "tlod_surface_create: %s: %s\n", tlod_result_string(res), tlod_context_last_error(ctx));
  return s;
}

tlod_cpu_mesh* vtk_test_tessellate(tlod_context* ctx, const tlod_surface* s, uint32_t level, bool no_weld) {
  tlod_patterns* pat = NULL;
  tlod_cpu_mesh* out = NULL;
  tlod_result res = tlod_patterns_create(ctx, &(tlod_patterns_desc){.max_level = level}, &pat);
  if (res == TLOD_SUCCESS)
    res = tlod_cpu_tessellate(ctx, s, pat, &(tlod_cpu_tessellate_desc){.level = level, .no_weld = no_weld}, &out);
  if (res != TLOD_SUCCESS)
    fprintf(stderr, "tessellate level %u: %s: %s\n", level, tlod_result_string(res), tlod_context_last_error(ctx));
  tlod_patterns_destroy(pat);
  return out;
}

void vtk_test_area_volume(const tlod_cpu_mesh* m, double* area, double* volume) {
  double A = 0, V = 0;
  for (uint32_t t = 0; t < m->triangle_count; ++t) {
    double p[3][3];
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k)
        p[c][k] = m->positions[3 * (size_t)m->indices[3 * t + c] + k];
    double e[3], f[3], n[3];
    for (int k = 0; k < 3; ++k)
      e[k] = p[1][k] - p[0][k], f[k] = p[2][k] - p[0][k];
    n[0] = e[1] * f[2] - e[2] * f[1], n[1] = e[2] * f[0] - e[0] * f[2], n[2] = e[0] * f[1] - e[1] * f[0];
    A += 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    V += (p[0][0] * n[0] + p[0][1] * n[1] + p[0][2] * n[2]) / 6;
  }
  *area = A, *volume = V;
}

bool vtk_test_closed(const tlod_cpu_mesh* m, char* why, size_t why_size) {
  return shape_closed_manifold(m->positions, m->vertex_count, m->indices, m->triangle_count, m->triangle_patch, why,
                               why_size);
}

void vtk_test_face_sizes(const tlod_import_result* r, uint32_t* triangles, uint32_t* quads) {
  *triangles = *quads = 0;
  for (uint32_t f = 0; f < r->face_count; ++f) {
    uint32_t n = r->face_sizes ? r->face_sizes[f] : 3;
    *triangles += n == 3;
    *quads += n == 4;
  }
}
