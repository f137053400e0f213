/* export_scene.c -- tlod_export_scene_file(): tessellated parts with the
 * scene of their import. glTF/glb: the scene model of the glTF writer (one
 * output mesh per source mesh, plus one per node given node_parts); OBJ/PLY:
 * the instances merged in world space (export_merge.c).
 * Owned by the import/export layer (tools/import/). */
#include <stdlib.h>
#include <string.h>

#include "export_merge.h"

bool _exp_flattened(const tlod_import_result* r) {
  static const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  bool named = false;
  for (uint32_t p = 0; p < r->part_count; ++p)
    named = named || r->parts[p].node != TLOD_IMPORT_NONE;
  const bool one_identity = r->node_count == 1 && r->mesh_count == 1 && r->nodes[0].mesh == 0 &&
                            r->nodes[0].parent == TLOD_IMPORT_NONE &&
                            !memcmp(r->nodes[0].world, identity, sizeof identity);
  return named && !one_identity;
}

static tlod_result _exp_check_source(_exp_job* job, const tlod_import_result* r) {
  for (uint32_t n = 0; n < r->node_count; ++n)
    if (r->nodes[n].mesh != TLOD_IMPORT_NONE && r->nodes[n].mesh >= r->mesh_count)
      return _exp_fail(job, TLOD_ERROR_INVALID_ARGUMENT, "node %u: mesh %u out of range", n, r->nodes[n].mesh);
  for (uint32_t m = 0; m < r->mesh_count; ++m)
    if (r->meshes[m].first_part > r->part_count || r->meshes[m].part_count > r->part_count - r->meshes[m].first_part)
      return _exp_fail(job, TLOD_ERROR_INVALID_ARGUMENT, "mesh %u: parts out of range", m);
  for (uint32_t p = 0; p < r->part_count; ++p)
    if (r->parts[p].material != TLOD_IMPORT_NONE && r->parts[p].material >= r->material_count)
      return _exp_fail(job, TLOD_ERROR_INVALID_ARGUMENT, "part %u: material out of range", p);
  return TLOD_SUCCESS;
}

static tlod_result _exp_check_parts(_exp_job* job, const tlod_export_mesh* parts, uint32_t count) {
  for (uint32_t p = 0; p < count; ++p) {
    char what[32];
    snprintf(what, sizeof what, "part %u: ", p);
    tlod_result res = _exp_check_mesh(job, &parts[p], what);
    if (res != TLOD_SUCCESS) return res;
  }
  return TLOD_SUCCESS;
}

static tlod_result _exp_check_desc(_exp_job* job, const tlod_export_scene_desc* d) {
  const tlod_import_result* r = d->source;
  if (!r || !d->parts || !r->part_count)
    return _exp_fail(job, TLOD_ERROR_INVALID_ARGUMENT, "a source with parts and the parts' meshes are required");
  tlod_result res = _exp_check_source(job, r);
  if (res == TLOD_SUCCESS) res = _exp_check_parts(job, d->parts, r->part_count);
  for (uint32_t n = 0; res == TLOD_SUCCESS && d->node_parts && n < r->node_count; ++n)
    if (d->node_parts[n] && r->nodes[n].mesh < r->mesh_count)
      res = _exp_check_parts(job, d->node_parts[n], r->meshes[r->nodes[n].mesh].part_count);
  return res;
}

/* ------------------------------------------------------------------------ */
/* glTF: source meshes, then a mesh of its own per node with node_parts     */
/* ------------------------------------------------------------------------ */

typedef struct _exp_gltf_build {
  _exp_scene scene;
  uint32_t* node_mesh;
  _exp_gltf_mesh* meshes;
  _exp_prim* prims;
} _exp_gltf_build;

static bool _exp_own_mesh(const tlod_export_scene_desc* d, uint32_t n) {
  return d->node_parts && d->node_parts[n] && d->source->nodes[n].mesh != TLOD_IMPORT_NONE;
}

static void _exp_add_mesh(_exp_gltf_build* b, const tlod_export_scene_desc* d, uint32_t mesh, const char* suffix,
                          const tlod_export_mesh* parts) {
  const tlod_import_mesh* me = &d->source->meshes[mesh];
  b->meshes[b->scene.mesh_count++] = (_exp_gltf_mesh){me->name, suffix, b->scene.prim_count, me->part_count};
  for (uint32_t p = 0; p < me->part_count; ++p)
    b->prims[b->scene.prim_count++] = (_exp_prim){&parts[p], d->source->parts[me->first_part + p].material};
}

static void _exp_build_gltf(_exp_gltf_build* b, const tlod_export_scene_desc* d) {
  const tlod_import_result* r = d->source;
  for (uint32_t m = 0; m < r->mesh_count; ++m)
    _exp_add_mesh(b, d, m, NULL, d->parts + r->meshes[m].first_part);
  for (uint32_t n = 0; n < r->node_count; ++n) {
    b->node_mesh[n] = r->nodes[n].mesh;
    if (!_exp_own_mesh(d, n)) continue;
    b->node_mesh[n] = b->scene.mesh_count;
    _exp_add_mesh(b, d, r->nodes[n].mesh, r->nodes[n].name, d->node_parts[n]);
  }
}

static tlod_result _exp_scene_gltf(_exp_job* job, _exp_sink* s, const tlod_export_scene_desc* d, bool glb) {
  const tlod_import_result* r = d->source;
  size_t meshes = r->mesh_count, prims = r->part_count;
  for (uint32_t n = 0; n < r->node_count; ++n)
    if (_exp_own_mesh(d, n)) meshes += 1, prims += r->meshes[r->nodes[n].mesh].part_count;
  _exp_gltf_build b = {{r, r->node_count, NULL, 0, NULL, 0, NULL},
                       malloc(sizeof(uint32_t) * ((size_t)r->node_count + 1)),
                       malloc(sizeof(_exp_gltf_mesh) * (meshes + 1)),
                       malloc(sizeof(_exp_prim) * (prims + 1))};
  tlod_result res = TLOD_ERROR_OUT_OF_MEMORY;
  if (b.node_mesh && b.meshes && b.prims) {
    _exp_build_gltf(&b, d);
    b.scene.node_mesh = b.node_mesh, b.scene.meshes = b.meshes, b.scene.prims = b.prims;
    res = _exp_gltf(job, s, &b.scene, glb);
  } else {
    _exp_fail(job, res, "out of memory");
  }
  free(b.node_mesh);
  free(b.meshes);
  free(b.prims);
  return res;
}

static tlod_result _exp_scene_body(_exp_job* job, _exp_sink* s, const void* user) {
  const tlod_export_scene_desc* d = user;
  const _exp_format format = _exp_format_of(job->path);
  if (format == _EXP_GLTF || format == _EXP_GLB) return _exp_scene_gltf(job, s, d, format == _EXP_GLB);
  _exp_merged merged;
  tlod_result res = _exp_merge(job, d, &merged);
  if (res != TLOD_SUCCESS) return res;
  if (format == _EXP_OBJ)
    _exp_obj(job, &merged.mesh);
  else
    _exp_ply(job, s, &merged.mesh);
  _exp_merged_free(&merged);
  return TLOD_SUCCESS;
}

tlod_result tlod_export_scene_file_desc(const char* path, const tlod_export_scene_desc* desc, char* error,
                                        size_t error_size) {
  _exp_job job = _exp_job_for(path, error, error_size);
  if (!path || !desc) return _exp_fail(&job, TLOD_ERROR_INVALID_ARGUMENT, "path and desc must not be NULL");
  const _exp_format format = _exp_format_of(path);
  if (format == _EXP_UNKNOWN)
    return _exp_fail(&job, TLOD_ERROR_UNSUPPORTED, "unknown file extension (expected .obj, .ply, .gltf or .glb)");
  tlod_result res = _exp_check_desc(&job, desc);
  if (res != TLOD_SUCCESS) return res;
  if ((format == _EXP_GLTF || format == _EXP_GLB) && _exp_flattened(desc->source))
    return _exp_fail(&job, TLOD_ERROR_INVALID_ARGUMENT,
                     "source was imported without keep_scene (parts in world space)");
  return _exp_write_atomic(&job, _exp_scene_body, desc);
}

tlod_result tlod_export_scene_file(const char* path, const tlod_import_result* source, const tlod_export_mesh* parts,
                                   char* error, size_t error_size) {
  const tlod_export_scene_desc desc = {source, parts, NULL};
  return tlod_export_scene_file_desc(path, &desc, error, error_size);
}
