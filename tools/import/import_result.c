/* import_result.c -- the result: a deep copy of what a reader produced (_tlod_import_data) into the
 * caller's allocator, within the memory budget, and tlod_import_free(). Owned by the import/export layer. */
#include <string.h>

#include "import_internal.h"

/* Copies into allocator memory; a failed allocation clears ok (the caller frees what was made). */
typedef struct _tlod_copier {
  const tlod_allocator* a;
  bool ok;
} _tlod_copier;

static void* _tlod_dup(_tlod_copier* c, const void* src, size_t count, size_t each) {
  if (!src || count == 0 || !c->ok) return NULL;
  void* p = c->a->alloc_fn(count * each, c->a->user_data);
  if (!p) {
    c->ok = false;
    return NULL;
  }
  memcpy(p, src, count * each);
  return p;
}

/* total += count * each, overflow-checked. */
static bool _tlod_acc(size_t* total, size_t count, size_t each) {
  size_t n;
  return _tlod_size_mul(count, each, &n) && _tlod_size_add(*total, n, total);
}

/* The VTK parts: face nodes, fields (every step), series arrays, the info. */
static bool _tlod_vtk_bytes(const _tlod_import_data* d, size_t* t) {
  const size_t steps = d->step_count ? d->step_count : 1;
  bool ok = (!d->face_nodes || _tlod_acc(t, d->face_count, 4u * TLOD_FACE_NODES)) &&
            _tlod_acc(t, d->field_count, sizeof(tlod_import_field)) && _tlod_acc(t, 1, sizeof(tlod_import_vtk_info)) &&
            _tlod_acc(t, d->step_count, 4u);
  size_t per_step;
  ok = ok && _tlod_size_mul(steps, d->vertex_count, &per_step);
  for (uint32_t i = 0; ok && i < d->field_count; ++i)
    ok = _tlod_acc(t, per_step, 4u * d->fields[i].components);
  return ok && (!d->step_positions || _tlod_acc(t, per_step, 12u));
}

static bool _tlod_scene_bytes(const _tlod_import_data* d, size_t* t) {
  bool ok = _tlod_acc(t, d->attribute_count, 0);
  for (uint32_t i = 0; i < d->attribute_count; ++i)
    ok = ok && _tlod_acc(t, (size_t)d->vertex_count * d->attributes[i].components, 4);
  if (d->joints) ok = ok && _tlod_acc(t, d->vertex_count, 8 + 16);
  ok = ok && _tlod_acc(t, d->mesh_count + 1, sizeof(tlod_import_mesh)) &&
       _tlod_acc(t, d->node_count + 1, sizeof(tlod_import_node)) &&
       _tlod_acc(t, d->material_count, sizeof(tlod_import_material)) &&
       _tlod_acc(t, d->texture_count, sizeof(tlod_import_texture)) &&
       _tlod_acc(t, d->image_count, sizeof(tlod_import_image)) &&
       _tlod_acc(t, d->animation_count, sizeof(tlod_import_animation)) &&
       _tlod_acc(t, d->skin_count, sizeof(tlod_import_skin));
  for (uint32_t i = 0; ok && i < d->image_count; ++i) {
    const tlod_import_image* im = &d->images[i];
    ok = _tlod_acc(t, im->encoded_size, 1) && (!im->rgba || _tlod_acc(t, (size_t)im->width * im->height, 4));
  }
  for (uint32_t i = 0; ok && i < d->animation_count; ++i)
    for (uint32_t c = 0; ok && c < d->animations[i].channel_count; ++c)
      ok = _tlod_acc(t, d->animations[i].channels[c].key_count, 4 * (1 + 3 * 4)) &&
           _tlod_acc(t, 1, sizeof(tlod_import_channel));
  for (uint32_t i = 0; ok && i < d->skin_count; ++i)
    ok = _tlod_acc(t, d->skins[i].joint_count, 4 * 17);
  return ok && _tlod_vtk_bytes(d, t);
}

/* What the result takes: vertex_count x 24 (positions, normals) + indices +
 * face sizes + parts + the scene, overflow-checked (false: does not fit). */
static bool _tlod_result_bytes(const _tlod_import_data* d, size_t* bytes) {
  size_t t = sizeof(tlod_import_result);
  return _tlod_acc(&t, d->vertex_count, 24u) && _tlod_acc(&t, d->index_count, 4u) &&
         _tlod_acc(&t, d->part_count, sizeof(tlod_import_part)) && _tlod_acc(&t, d->face_count, 1) &&
         _tlod_scene_bytes(d, &t) && (*bytes = t, true);
}

/* Keeps whole lines: a truncated list ends with "...". */
static void _tlod_copy_warnings(char* dst, size_t size, const char* src) {
  dst[0] = 0;
  if (!src) return;
  size_t n = strlen(src);
  if (n < size) {
    memcpy(dst, src, n + 1);
    return;
  }
  size_t keep = size - 5; /* room for "...\n" and the terminator */
  while (keep > 0 && src[keep - 1] != '\n')
    keep--;
  memcpy(dst, src, keep);
  memcpy(dst + keep, "...\n", 5);
}

static void _tlod_copy_geometry(_tlod_copier* c, tlod_import_result* r, const _tlod_import_data* d) {
  r->vertex_count = d->vertex_count;
  r->positions = (float*)_tlod_dup(c, d->positions, d->vertex_count, 12u);
  r->normals = (float*)_tlod_dup(c, d->normals, d->vertex_count, 12u);
  r->index_count = d->index_count;
  r->indices = (uint32_t*)_tlod_dup(c, d->indices, d->index_count, 4u);
  r->face_count = d->face_count;
  r->face_sizes = (uint8_t*)_tlod_dup(c, d->face_sizes, d->face_count, 1);
  r->part_count = d->part_count;
  r->parts = (tlod_import_part*)_tlod_dup(c, d->parts, d->part_count, sizeof(tlod_import_part));
  r->attribute_count = d->attribute_count;
  for (uint32_t i = 0; i < d->attribute_count; ++i) {
    r->attributes[i] = d->attributes[i];
    r->attributes[i].data =
        (float*)_tlod_dup(c, d->attributes[i].data, d->vertex_count, 4u * d->attributes[i].components);
  }
  r->joints = (uint16_t*)_tlod_dup(c, d->joints, d->vertex_count, 8u);
  r->weights = (float*)_tlod_dup(c, d->weights, d->vertex_count, 16u);
  r->weights_renormalised = d->weights_renormalised;
}

static void _tlod_copy_vtk(_tlod_copier* c, tlod_import_result* r, const _tlod_import_data* d) {
  const size_t steps = d->step_count ? d->step_count : 1;
  r->face_nodes = (uint32_t*)_tlod_dup(c, d->face_nodes, d->face_count, 4u * TLOD_FACE_NODES);
  r->field_count = d->field_count;
  r->fields = (tlod_import_field*)_tlod_dup(c, d->fields, d->field_count, sizeof(tlod_import_field));
  for (uint32_t i = 0; r->fields && i < d->field_count; ++i)
    r->fields[i].data = (float*)_tlod_dup(c, d->fields[i].data, steps * d->vertex_count, 4u * d->fields[i].components);
  if (!r->fields) r->field_count = 0;
  r->vtk = (tlod_import_vtk_info*)_tlod_dup(c, d->vtk, 1, sizeof(tlod_import_vtk_info));
  r->step_count = d->step_count;
  r->step_times = (float*)_tlod_dup(c, d->step_times, d->step_count, 4u);
  r->step_positions = (float*)_tlod_dup(c, d->step_positions, d->step_count * (size_t)d->vertex_count, 12u);
}

/* OBJ, PLY: one mesh of every part, at one identity node. */
static void _tlod_default_scene(_tlod_copier* c, tlod_import_result* r) {
  tlod_import_mesh mesh = {"mesh", 0, r->part_count};
  tlod_import_node node = {"root", TLOD_IMPORT_NONE, 0, TLOD_IMPORT_NONE, {0, 0, 0}, {0, 0, 0, 1}, {1, 1, 1}, {0}, {0}};
  for (int i = 0; i < 16; i += 5)
    node.local[i] = node.world[i] = 1.0f;
  r->mesh_count = r->node_count = 1;
  r->meshes = (tlod_import_mesh*)_tlod_dup(c, &mesh, 1, sizeof mesh);
  r->nodes = (tlod_import_node*)_tlod_dup(c, &node, 1, sizeof node);
  for (uint32_t i = 0; r->parts && i < r->part_count; ++i) {
    r->parts[i].mesh = 0;
    r->parts[i].node = 0;
  }
}

static void _tlod_copy_images(_tlod_copier* c, tlod_import_result* r, const _tlod_import_data* d) {
  r->image_count = d->image_count;
  r->images = (tlod_import_image*)_tlod_dup(c, d->images, d->image_count, sizeof(tlod_import_image));
  for (uint32_t i = 0; r->images && i < d->image_count; ++i) {
    tlod_import_image* im = &r->images[i];
    im->rgba = (uint8_t*)_tlod_dup(c, d->images[i].rgba, (size_t)im->width * im->height, 4u);
    im->encoded = (uint8_t*)_tlod_dup(c, d->images[i].encoded, im->encoded_size, 1);
    if (!im->encoded) im->encoded_size = 0;
  }
}

static void _tlod_copy_animations(_tlod_copier* c, tlod_import_result* r, const _tlod_import_data* d) {
  r->animation_count = d->animation_count;
  r->animations =
      (tlod_import_animation*)_tlod_dup(c, d->animations, d->animation_count, sizeof(tlod_import_animation));
  for (uint32_t i = 0; r->animations && i < d->animation_count; ++i) {
    tlod_import_animation* an = &r->animations[i];
    an->channels = (tlod_import_channel*)_tlod_dup(c, an->channels, an->channel_count, sizeof(tlod_import_channel));
    for (uint32_t k = 0; an->channels && k < an->channel_count; ++k) {
      tlod_import_channel* ch = &an->channels[k];
      const size_t n =
          (ch->path == TLOD_IMPORT_PATH_ROTATION ? 4u : 3u) * (ch->interp == TLOD_IMPORT_INTERP_CUBICSPLINE ? 3u : 1u);
      ch->times = (float*)_tlod_dup(c, ch->times, ch->key_count, 4u);
      ch->values = (float*)_tlod_dup(c, ch->values, ch->key_count, 4u * n);
    }
    if (!an->channels) an->channel_count = 0;
  }
}

static void _tlod_copy_scene(_tlod_copier* c, tlod_import_result* r, const _tlod_import_data* d) {
  if (d->mesh_count == 0 && d->node_count == 0) {
    _tlod_default_scene(c, r);
  } else {
    r->mesh_count = d->mesh_count;
    r->meshes = (tlod_import_mesh*)_tlod_dup(c, d->meshes, d->mesh_count, sizeof(tlod_import_mesh));
    r->node_count = d->node_count;
    r->nodes = (tlod_import_node*)_tlod_dup(c, d->nodes, d->node_count, sizeof(tlod_import_node));
  }
  r->material_count = d->material_count;
  r->materials = (tlod_import_material*)_tlod_dup(c, d->materials, d->material_count, sizeof(tlod_import_material));
  for (uint32_t i = 0; d->material_count == 0 && r->parts && i < r->part_count; ++i)
    r->parts[i].material = TLOD_IMPORT_NONE;
  r->texture_count = d->texture_count;
  r->textures = (tlod_import_texture*)_tlod_dup(c, d->textures, d->texture_count, sizeof(tlod_import_texture));
  _tlod_copy_images(c, r, d);
  _tlod_copy_animations(c, r, d);
  r->skin_count = d->skin_count;
  r->skins = (tlod_import_skin*)_tlod_dup(c, d->skins, d->skin_count, sizeof(tlod_import_skin));
  for (uint32_t i = 0; r->skins && i < d->skin_count; ++i) {
    r->skins[i].joints = (uint32_t*)_tlod_dup(c, d->skins[i].joints, d->skins[i].joint_count, 4u);
    r->skins[i].inverse_bind = (float*)_tlod_dup(c, d->skins[i].inverse_bind, d->skins[i].joint_count, 64u);
  }
}

tlod_result _tlod_import_finish(const _tlod_import_job* job, const _tlod_import_data* d) {
  const tlod_allocator* a = &job->allocator;
  size_t bytes = 0;
  if (!_tlod_result_bytes(d, &bytes) || !_tlod_budget_take(job->budget, bytes))
    return _tlod_import_fail(job, TLOD_ERROR_OUT_OF_MEMORY,
                             "result: %u vertices and %u indices exceed the import's memory budget (%zu bytes; "
                             "tlod_import_desc.memory_limit)",
                             d->vertex_count, d->index_count, job->budget->limit);
  tlod_import_result* r = (tlod_import_result*)a->alloc_fn(sizeof *r, a->user_data);
  if (!r) return _tlod_import_fail(job, TLOD_ERROR_OUT_OF_MEMORY, "out of memory");
  memset(r, 0, sizeof *r);
  r->_allocator = *a;
  _tlod_copier c = {a, true};
  _tlod_copy_geometry(&c, r, d);
  _tlod_copy_scene(&c, r, d);
  _tlod_copy_vtk(&c, r, d);
  r->polygons_triangulated = d->polygons_triangulated;
  r->strips_fans_converted = d->strips_fans_converted;
  r->primitives_skipped = d->primitives_skipped;
  r->warning_count = d->warning_count;
  _tlod_copy_warnings(r->warnings, sizeof r->warnings, d->warnings);
  if (!c.ok) {
    tlod_import_free(r);
    return _tlod_import_fail(job, TLOD_ERROR_OUT_OF_MEMORY, "out of memory for %u vertices", d->vertex_count);
  }
  *job->out = r;
  return TLOD_SUCCESS;
}

static void _tlod_free_scene(tlod_import_result* r, const tlod_allocator* a) {
  for (uint32_t i = 0; i < r->attribute_count; ++i)
    a->free_fn(r->attributes[i].data, a->user_data);
  for (uint32_t i = 0; r->images && i < r->image_count; ++i) {
    a->free_fn(r->images[i].rgba, a->user_data);
    a->free_fn(r->images[i].encoded, a->user_data);
  }
  for (uint32_t i = 0; r->animations && i < r->animation_count; ++i) {
    for (uint32_t k = 0; r->animations[i].channels && k < r->animations[i].channel_count; ++k) {
      a->free_fn(r->animations[i].channels[k].times, a->user_data);
      a->free_fn(r->animations[i].channels[k].values, a->user_data);
    }
    a->free_fn(r->animations[i].channels, a->user_data);
  }
  for (uint32_t i = 0; r->skins && i < r->skin_count; ++i) {
    a->free_fn(r->skins[i].joints, a->user_data);
    a->free_fn(r->skins[i].inverse_bind, a->user_data);
  }
  for (uint32_t i = 0; r->fields && i < r->field_count; ++i)
    a->free_fn(r->fields[i].data, a->user_data);
  void* arrays[] = {r->joints,   r->weights, r->meshes,     r->nodes,         r->materials,
                    r->textures, r->images,  r->animations, r->skins,         r->face_nodes,
                    r->fields,   r->vtk,     r->step_times, r->step_positions};
  for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; ++i)
    a->free_fn(arrays[i], a->user_data);
}

void tlod_import_free(tlod_import_result* r) {
  if (!r) return;
  tlod_allocator a = r->_allocator;
  _tlod_free_scene(r, &a);
  void* arrays[] = {r->positions, r->normals, r->indices, r->face_sizes, r->parts};
  for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; ++i)
    a.free_fn(arrays[i], a.user_data);
  a.free_fn(r, a.user_data);
}
