/* export_file.c -- tlod_export_file(): one mesh checked, then written in the
 * format of its extension. Owned by the import/export layer (tools/import/). */
#include <math.h>
#include <string.h>

#include "export_internal.h"

const tlod_export_attribute* _exp_find_attr(const tlod_export_mesh* m, const char* name) {
  for (uint32_t a = 0; a < m->attribute_count; ++a)
    if (m->attributes[a].name && !strcmp(m->attributes[a].name, name)) return &m->attributes[a];
  return NULL;
}

static tlod_result _exp_check_attributes(_exp_job* job, const tlod_export_mesh* m, const char* what) {
  if (m->attribute_count && !m->attributes)
    return _exp_fail(job, TLOD_ERROR_INVALID_ARGUMENT, "%s: %u attributes but no array", what, m->attribute_count);
  for (uint32_t a = 0; a < m->attribute_count; ++a) {
    const tlod_export_attribute* at = &m->attributes[a];
    if (!at->data || at->components < 1 || at->components > 4)
      return _exp_fail(job, TLOD_ERROR_INVALID_ARGUMENT, "%s: attribute %u: needs data and 1..4 components", what, a);
    for (uint32_t v = 0; v < m->vertex_count; ++v)
      for (uint32_t c = 0; c < at->components; ++c)
        if (!isfinite(_exp_attr_at(at, v)[c]))
          return _exp_fail(job, TLOD_ERROR_INVALID_ARGUMENT, "%s: attribute %u: vertex %u is not finite", what, a, v);
  }
  return TLOD_SUCCESS;
}

static tlod_result _exp_check_arrays(_exp_job* job, const tlod_export_mesh* m, const char* what) {
  for (size_t i = 0; i < 3 * (size_t)m->vertex_count; ++i) {
    if (!isfinite(m->positions[i]))
      return _exp_fail(job, TLOD_ERROR_INVALID_ARGUMENT, "%svertex %zu: position is not finite", what, i / 3);
    if (m->normals && !isfinite(m->normals[i]))
      return _exp_fail(job, TLOD_ERROR_INVALID_ARGUMENT, "%svertex %zu: normal is not finite", what, i / 3);
  }
  for (size_t i = 0; i < 3 * (size_t)m->triangle_count; ++i)
    if (m->indices[i] >= m->vertex_count)
      return _exp_fail(job, TLOD_ERROR_INVALID_ARGUMENT, "%striangle %zu: index %u out of range (%u vertices)", what,
                       i / 3, m->indices[i], m->vertex_count);
  return TLOD_SUCCESS;
}

/* what: "" for a single mesh, "part N: " in a scene. */
tlod_result _exp_check_mesh(_exp_job* job, const tlod_export_mesh* m, const char* what) {
  if (!m->positions || !m->indices || m->vertex_count == 0 || m->triangle_count == 0)
    return _exp_fail(job, TLOD_ERROR_INVALID_ARGUMENT, "%smesh needs positions, indices, >= 1 vertex and >= 1 triangle",
                     what);
  tlod_result res = _exp_check_arrays(job, m, what);
  return res == TLOD_SUCCESS ? _exp_check_attributes(job, m, *what ? what : "mesh") : res;
}

static tlod_result _exp_mesh_body(_exp_job* job, _exp_sink* s, const void* user) {
  const tlod_export_mesh* m = user;
  const _exp_format format = _exp_format_of(job->path);
  if (format == _EXP_OBJ) {
    _exp_obj(job, m);
    return TLOD_SUCCESS;
  }
  if (format == _EXP_PLY) {
    _exp_ply(job, s, m);
    return TLOD_SUCCESS;
  }
  const _exp_gltf_mesh mesh = {NULL, NULL, 0, 1};
  const _exp_prim prim = {m, TLOD_IMPORT_NONE};
  const _exp_scene scene = {NULL, 0, NULL, 1, &mesh, 1, &prim};
  return _exp_gltf(job, s, &scene, format == _EXP_GLB);
}

tlod_result tlod_export_file(const char* path, const tlod_export_mesh* mesh, char* error, size_t error_size) {
  _exp_job job = _exp_job_for(path, error, error_size);
  if (!path || !mesh) return _exp_fail(&job, TLOD_ERROR_INVALID_ARGUMENT, "path and mesh must not be NULL");
  if (_exp_format_of(path) == _EXP_UNKNOWN)
    return _exp_fail(&job, TLOD_ERROR_UNSUPPORTED, "unknown file extension (expected .obj, .ply, .gltf or .glb)");
  tlod_result res = _exp_check_mesh(&job, mesh, "");
  if (res != TLOD_SUCCESS) return res;
  return _exp_write_atomic(&job, _exp_mesh_body, mesh);
}
