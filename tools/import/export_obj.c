/* export_obj.c -- one triangle mesh as Wavefront OBJ: v, vn, vt and faces.
 * Owned by the import/export layer (tools/import/).
 *
 * vt comes from TEXCOORD_0 with v flipped back to OBJ's bottom-left origin
 * (v = 1 - v'): the importer flips OBJ's v to glTF's top-left origin, so an
 * OBJ round trip gives the same texture coordinates. "%.9g" round-trips any
 * float through strtof. */
#include "export_internal.h"

static void _exp_obj_vertices(_exp_job* job, const tlod_export_mesh* m, const tlod_export_attribute* uv) {
  for (uint32_t i = 0; i < m->vertex_count; ++i) {
    const float* p = m->positions + 3 * (size_t)i;
    _exp_printf(job, "v %.9g %.9g %.9g\n", (double)p[0], (double)p[1], (double)p[2]);
  }
  for (uint32_t i = 0; m->normals && i < m->vertex_count; ++i) {
    const float* n = m->normals + 3 * (size_t)i;
    _exp_printf(job, "vn %.9g %.9g %.9g\n", (double)n[0], (double)n[1], (double)n[2]);
  }
  for (uint32_t i = 0; uv && i < m->vertex_count; ++i) {
    const float* t = _exp_attr_at(uv, i);
    _exp_printf(job, "vt %.9g %.9g\n", (double)t[0], (double)(1.0f - t[1]));
  }
}

/* One corner: "v", "v//vn", "v/vt" or "v/vt/vn" (all the same index). */
static void _exp_obj_corner(_exp_job* job, uint32_t i, bool normals, bool uv) {
  if (normals && uv)
    _exp_printf(job, " %u/%u/%u", i, i, i);
  else if (normals)
    _exp_printf(job, " %u//%u", i, i);
  else if (uv)
    _exp_printf(job, " %u/%u", i, i);
  else
    _exp_printf(job, " %u", i);
}

void _exp_obj(_exp_job* job, const tlod_export_mesh* m) {
  const tlod_export_attribute* uv = _exp_find_attr(m, "TEXCOORD_0");
  if (uv && uv->components < 2) uv = NULL;
  _exp_printf(job, "# tesslod export: %u vertices, %u triangles\n", m->vertex_count, m->triangle_count);
  _exp_obj_vertices(job, m, uv);
  for (uint32_t t = 0; t < m->triangle_count; ++t) {
    const uint32_t* c = m->indices + 3 * (size_t)t;
    _exp_printf(job, "f");
    for (int k = 0; k < 3; ++k)
      _exp_obj_corner(job, c[k] + 1, m->normals != NULL, uv != NULL);
    _exp_printf(job, "\n");
  }
}
