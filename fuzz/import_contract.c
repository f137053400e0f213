/* import_contract.c -- tlod_import_file()'s promises (tools/import/tlod_import.h). */
#include "import_contract.h"

#include <math.h>
#include <string.h>

#include "fuzz_common.h"

static void check_arrays(const tlod_import_result* r) {
  for (size_t i = 0; i < (size_t)r->vertex_count * 3u; ++i)
    fuzz_check(isfinite(r->positions[i]), "a successful import has a non-finite position");
  for (uint32_t i = 0; i < r->index_count; ++i)
    fuzz_check(r->indices[i] < r->vertex_count, "a successful import has an index out of range");
  if (!r->face_sizes) {
    fuzz_check((uint64_t)r->face_count * 3u == r->index_count, "face_count * 3 != index_count (all triangles)");
    return;
  }
  uint64_t sum = 0;
  for (uint32_t f = 0; f < r->face_count; ++f) {
    fuzz_check(r->face_sizes[f] == 3 || r->face_sizes[f] == 4, "a face size other than 3 or 4");
    sum += r->face_sizes[f];
  }
  fuzz_check(sum == r->index_count, "the face sizes do not add up to index_count");
}

static void check_parts(const tlod_import_result* r) {
  for (uint32_t p = 0; p < r->part_count; ++p) {
    const tlod_import_part* part = &r->parts[p];
    fuzz_check((uint64_t)part->first_face + part->face_count <= r->face_count, "a part's faces run past the faces");
    fuzz_check((uint64_t)part->first_vertex + part->vertex_count <= r->vertex_count,
               "a part's vertices run past the vertices");
    fuzz_check(memchr(part->name, 0, sizeof part->name) != NULL, "a part name is not terminated");
  }
  fuzz_check(memchr(r->warnings, 0, sizeof r->warnings) != NULL, "the warnings are not terminated");
}

/* An index into an array of count, or TLOD_IMPORT_NONE where none is allowed. */
static int in_range(uint32_t i, uint32_t count, int none_ok) { return i < count || (none_ok && i == TLOD_IMPORT_NONE); }

static void check_attributes(const tlod_import_result* r) {
  fuzz_check(r->attribute_count <= TLOD_IMPORT_MAX_ATTRIBUTES, "more than TLOD_IMPORT_MAX_ATTRIBUTES attributes");
  for (uint32_t a = 0; a < r->attribute_count; ++a) {
    const tlod_import_attribute* at = &r->attributes[a];
    fuzz_check(at->components >= 1 && at->components <= 4 && (at->data || r->vertex_count == 0),
               "an attribute without 1..4 components or data");
    for (size_t i = 0; i < (size_t)r->vertex_count * at->components; ++i)
      fuzz_check(isfinite(at->data[i]), "a non-finite attribute value");
  }
  for (size_t v = 0; r->joints && v < r->vertex_count; ++v) {
    double sum = 0.0;
    for (int k = 0; k < 4; ++k) {
      fuzz_check(r->weights[v * 4 + k] >= 0.0f, "a negative weight");
      sum += r->weights[v * 4 + k];
    }
    fuzz_check(sum == 0.0 || fabs(sum - 1.0) < 1e-4, "weights of a vertex that sum neither to 0 nor to 1");
  }
}

static void check_scene(const tlod_import_result* r) {
  for (uint32_t p = 0; p < r->part_count; ++p)
    fuzz_check(in_range(r->parts[p].mesh, r->mesh_count, 0) && in_range(r->parts[p].material, r->material_count, 1) &&
                   in_range(r->parts[p].node, r->node_count, 1),
               "a part's mesh, material or node out of range");
  for (uint32_t m = 0; m < r->mesh_count; ++m)
    fuzz_check((uint64_t)r->meshes[m].first_part + r->meshes[m].part_count <= r->part_count,
               "a mesh's parts run past the parts");
  for (uint32_t n = 0; n < r->node_count; ++n)
    fuzz_check(in_range(r->nodes[n].parent, r->node_count, 1) && in_range(r->nodes[n].mesh, r->mesh_count, 1) &&
                   in_range(r->nodes[n].skin, r->skin_count, 1),
               "a node's parent, mesh or skin out of range");
  for (uint32_t m = 0; m < r->material_count; ++m)
    fuzz_check(in_range(r->materials[m].base_color_texture, r->texture_count, 1) &&
                   in_range(r->materials[m].base_color_texcoord, r->attribute_count, 1),
               "a material's texture or texcoord out of range");
  for (uint32_t t = 0; t < r->texture_count; ++t)
    fuzz_check(in_range(r->textures[t].image, r->image_count, 1), "a texture's image out of range");
  for (uint32_t i = 0; i < r->image_count; ++i) {
    const tlod_import_image* im = &r->images[i];
    fuzz_check(!im->rgba || ((uint64_t)im->width * im->height <= TLOD_IMPORT_MAX_IMAGE_PIXELS && im->width > 0 &&
                             im->height > 0),
               "decoded pixels without a size within the pixel limit");
    fuzz_check((im->encoded != NULL) == (im->encoded_size > 0), "encoded bytes and their size disagree");
  }
}

static void check_motion(const tlod_import_result* r) {
  for (uint32_t a = 0; a < r->animation_count; ++a)
    for (uint32_t c = 0; c < r->animations[a].channel_count; ++c) {
      const tlod_import_channel* ch = &r->animations[a].channels[c];
      fuzz_check(ch->node < r->node_count && ch->key_count >= 1, "a channel without a node or keys");
      for (uint32_t k = 0; k < ch->key_count; ++k)
        fuzz_check(isfinite(ch->times[k]) && (k == 0 || ch->times[k] > ch->times[k - 1]),
                   "key times not finite and strictly increasing");
    }
  for (uint32_t s = 0; s < r->skin_count; ++s)
    for (uint32_t j = 0; j < r->skins[s].joint_count; ++j)
      fuzz_check(r->skins[s].joints[j] < r->node_count, "a skin joint that is not a node");
}

/* VTK (issue 14): nodes in range and not a corner of their face; fields finite within their ranges. */
static void check_vtk(const tlod_import_result* r) {
  size_t at = 0;
  for (uint32_t f = 0; r->face_nodes && f < r->face_count; ++f) {
    const uint32_t n = r->face_sizes ? r->face_sizes[f] : 3;
    for (int k = 0; k < TLOD_FACE_NODES; ++k) {
      const uint32_t node = r->face_nodes[(size_t)f * TLOD_FACE_NODES + (size_t)k];
      fuzz_check(node == TLOD_NO_NODE || node < r->vertex_count, "a face node out of range");
      for (uint32_t c = 0; node != TLOD_NO_NODE && c < n; ++c)
        fuzz_check(node != r->indices[at + c], "a face node equal to a corner of its face");
    }
    at += n;
  }
  const size_t steps = r->step_count ? r->step_count : 1;
  fuzz_check(r->field_count <= TLOD_IMPORT_MAX_FIELDS, "more than TLOD_IMPORT_MAX_FIELDS fields");
  for (uint32_t i = 0; i < r->field_count; ++i) {
    const tlod_import_field* f = &r->fields[i];
    fuzz_check(f->components >= 1 && f->components <= TLOD_IMPORT_MAX_FIELD_COMPONENTS, "a field's components");
    for (size_t v = 0; v < steps * r->vertex_count * f->components; ++v) {
      const uint32_t c = (uint32_t)(v % f->components);
      fuzz_check(isfinite(f->data[v]) && f->data[v] >= f->min[c] && f->data[v] <= f->max[c],
                 "a field value not finite or outside its component's range");
    }
  }
  for (size_t v = 0; r->step_positions && v < steps * r->vertex_count * 3; ++v)
    fuzz_check(isfinite(r->step_positions[v]), "a non-finite step position");
}

void fuzz_check_import(tlod_result res, const tlod_import_result* r, const char* error, const char* path) {
  fuzz_check(res >= TLOD_SUCCESS && res <= TLOD_ERROR_PARSE && res != TLOD_ERROR_BACKEND,
             "a result code tlod_import_file() does not list");
  if (res != TLOD_SUCCESS) {
    fuzz_check(r == NULL, "a failed import left a result");
    fuzz_check_error(error, fuzz_base_name(path));
    return;
  }
  fuzz_check(r != NULL, "a successful import left no result");
  fuzz_check(error[0] == 0, "a successful import left an error message");
  fuzz_check(r->vertex_count == 0 || r->positions != NULL, "vertices without positions");
  fuzz_check(r->index_count == 0 || r->indices != NULL, "index_count without indices");
  check_arrays(r);
  check_parts(r);
  check_attributes(r);
  check_scene(r);
  check_motion(r);
  check_vtk(r);
}

void fuzz_import_and_check(const char* path) {
  char error[256];
  tlod_import_result* r = NULL;
  const tlod_result res = tlod_import_file(path, NULL, &r, error, sizeof error);
  fuzz_check_import(res, r, error, path);
  tlod_import_free(r);
}
