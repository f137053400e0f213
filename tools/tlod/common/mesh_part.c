/* tlod -- one part of a scene import as a mesh of its own: vertices and
 * attributes copied and renumbered from 0, so each part becomes a core mesh
 * (instanced by the nodes that use its glTF mesh). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "mesh_load.h"

static void* copy_of(const void* src, size_t bytes) {
  void* p = malloc(bytes ? bytes : 1);
  if (p && bytes) memcpy(p, src, bytes);
  return p;
}

/* Index of the first index of face f. */
static size_t first_index(const tlod_import_result* r, uint32_t f) {
  if (!r->face_sizes) return 3 * (size_t)f;
  size_t i = 0;
  for (uint32_t k = 0; k < f; k++)
    i += r->face_sizes[k];
  return i;
}

static size_t index_span(const tlod_import_result* r, const tlod_import_part* p) {
  if (!r->face_sizes) return 3 * (size_t)p->face_count;
  size_t n = 0;
  for (uint32_t k = 0; k < p->face_count; k++)
    n += r->face_sizes[p->first_face + k];
  return n;
}

static int copy_vertices(const tlod_import_result* r, const tlod_import_part* p, cli_mesh* m) {
  const size_t v0 = p->first_vertex, n = p->vertex_count;
  m->vertex_count = p->vertex_count;
  m->positions = copy_of(r->positions + 3 * v0, 12 * n);
  m->normals = r->normals ? copy_of(r->normals + 3 * v0, 12 * n) : NULL;
  if (!m->positions || (r->normals && !m->normals)) return cli_error(CLI_FAILED, "out of memory");
  m->attribute_count = r->attribute_count < TLOD_MAX_ATTRIBUTES ? r->attribute_count : TLOD_MAX_ATTRIBUTES;
  for (uint32_t a = 0; a < m->attribute_count; a++) {
    const tlod_import_attribute* s = &r->attributes[a];
    cli_attribute* d = &m->attributes[a];
    snprintf(d->name, sizeof(d->name), "%s", s->name);
    d->components = s->components;
    d->data = copy_of(s->data + s->components * v0, sizeof(float) * s->components * n);
    if (!d->data) return cli_error(CLI_FAILED, "out of memory");
  }
  return CLI_OK;
}

static int copy_faces(const tlod_import_result* r, const tlod_import_part* p, cli_mesh* m) {
  const size_t first = first_index(r, p->first_face), count = index_span(r, p);
  m->index_count = (uint32_t)count;
  m->indices = copy_of(r->indices + first, sizeof(uint32_t) * count);
  m->face_count = p->face_count;
  m->face_sizes = r->face_sizes ? copy_of(r->face_sizes + p->first_face, p->face_count) : NULL;
  if (!m->indices || (r->face_sizes && !m->face_sizes)) return cli_error(CLI_FAILED, "out of memory");
  for (size_t i = 0; i < count; i++) {
    if (m->indices[i] < p->first_vertex || m->indices[i] - p->first_vertex >= p->vertex_count)
      return cli_error(CLI_FAILED, "%s: index %u outside the part's vertices", m->name, m->indices[i]);
    m->indices[i] -= p->first_vertex;
  }
  m->source_face_count = m->face_sizes ? m->face_count : m->index_count / 3;
  return CLI_OK;
}

static bool part_in_range(const tlod_import_result* r, const tlod_import_part* p) {
  return p->first_vertex <= r->vertex_count && p->vertex_count <= r->vertex_count - p->first_vertex &&
         p->first_face <= r->face_count && p->face_count <= r->face_count - p->first_face;
}

int cli_load_part(const tlod_import_result* r, uint32_t part, const cli_part_options* o, cli_mesh* out) {
  memset(out, 0, sizeof(*out));
  if (part >= r->part_count) return cli_error(CLI_FAILED, "part %u: out of range (%u parts)", part, r->part_count);
  const tlod_import_part* p = &r->parts[part];
  if (p->name[0])
    snprintf(out->name, sizeof(out->name), "%s", p->name);
  else
    snprintf(out->name, sizeof(out->name), "part %u", part);
  if (!part_in_range(r, p)) return cli_error(CLI_FAILED, "%s: faces or vertices out of range", out->name);
  memcpy(out->base_color, p->base_color, sizeof(out->base_color));
  out->has_color = true;
  int rc = copy_vertices(r, p, out);
  if (rc == CLI_OK) rc = copy_faces(r, p, out);
  if (rc == CLI_OK && o && o->split_quads) rc = cli_split_quads(out);
  if (rc != CLI_OK) cli_mesh_free(out);
  return rc;
}

int cli_create_part_mesh(tlod_context* ctx, const tlod_import_result* r, uint32_t part, const cli_part_options* o,
                         tlod_mesh** out) {
  cli_mesh m;
  *out = NULL;
  int rc = cli_load_part(r, part, o, &m);
  if (rc != CLI_OK) return rc;
  rc = cli_create_mesh(ctx, &m, o ? o->normals : TLOD_NORMALS_KEEP, o ? o->crease_deg : 0.0f, out);
  cli_mesh_free(&m);
  return rc;
}
