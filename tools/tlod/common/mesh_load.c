/* tlod -- loading an input mesh (file or built-in demo). */
#include "mesh_load.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

void cli_mesh_free(cli_mesh* m) {
  free(m->positions);
  free(m->normals);
  free(m->indices);
  free(m->face_sizes);
  free(m->face_source);
  free(m->face_nodes);
  for (uint32_t a = 0; a < m->attribute_count; a++)
    free(m->attributes[a].data);
  tlod_import_free(m->source);
  memset(m, 0, sizeof(*m));
}

/* The importer's attributes moved into m (both allocate with malloc). */
static void take_attributes(tlod_import_result* r, cli_mesh* m) {
  m->attribute_count = r->attribute_count < TLOD_MAX_ATTRIBUTES ? r->attribute_count : TLOD_MAX_ATTRIBUTES;
  for (uint32_t a = 0; a < m->attribute_count; a++) {
    cli_attribute* d = &m->attributes[a];
    snprintf(d->name, sizeof(d->name), "%s", r->attributes[a].name);
    d->components = r->attributes[a].components;
    d->data = r->attributes[a].data;
    r->attributes[a].data = NULL;
  }
}

/* The importer allocated with malloc (NULL allocator): take the arrays over;
 * the rest of the result (parts, materials, images) stays as m->source. */
static void take_over(tlod_import_result* r, cli_mesh* m) {
  m->vertex_count = r->vertex_count;
  m->positions = r->positions;
  m->normals = r->normals;
  m->index_count = r->index_count;
  m->indices = r->indices;
  m->face_count = r->face_count;
  m->face_sizes = r->face_sizes;
  m->face_nodes = r->face_nodes;
  snprintf(m->warnings, sizeof(m->warnings), "%s", r->warnings);
  m->has_color = r->part_count > 0;
  if (m->has_color) memcpy(m->base_color, r->parts[0].base_color, sizeof(m->base_color));
  take_attributes(r, m);
  r->positions = r->normals = NULL;
  r->indices = NULL;
  r->face_sizes = NULL;
  r->face_nodes = NULL;
  m->source = r;
}

static int load_file(const char* path, cli_mesh* m) {
  char err[512];
  tlod_import_result* r = NULL;
  tlod_import_desc d = {0};
  cli_progress_hook(&d);
  tlod_result res = tlod_import_file_desc(path, &d, &r, err, sizeof(err));
  cli_progress_end(&d);
  if (res != TLOD_SUCCESS) return cli_error(CLI_FAILED, "%s", err);
  take_over(r, m);
  return CLI_OK;
}

int cli_load(const char* in, cli_mesh* out) {
  memset(out, 0, sizeof(*out));
  snprintf(out->name, sizeof(out->name), "%s", in);
  int rc = !strncmp(in, "demo:", 5) ? cli_load_demo(in + 5, out) : load_file(in, out);
  if (rc != CLI_OK) cli_mesh_free(out);
  out->source_face_count = out->face_sizes ? out->face_count : out->index_count / 3;
  return rc;
}

int cli_load_scene(const char* in, tlod_import_result** out) {
  char err[512];
  *out = NULL;
  if (!strncmp(in, "demo:", 5))
    return cli_error(CLI_FAILED, "%s: built-in meshes have no scene (load them with cli_load)", in);
  tlod_import_desc d = {.keep_scene = true};
  if (tlod_import_file_desc(in, &d, out, err, sizeof(err)) != TLOD_SUCCESS) return cli_error(CLI_FAILED, "%s", err);
  return CLI_OK;
}

bool cli_mesh_is_vtk(const cli_mesh* m) { return m->source && m->source->vtk; }

tlod_surface_type cli_resolve_surface(tlod_surface_type asked, const cli_mesh* m) {
  if (asked != TLOD_SURFACE_DEFAULT) return asked;
  return m->face_nodes ? TLOD_SURFACE_QUADRATIC : TLOD_SURFACE_PHONG;
}

float cli_resolve_crease(float asked, const cli_mesh* m) {
  if (asked >= 0.0f) return asked;
  return cli_mesh_is_vtk(m) ? CLI_VTK_CREASE_DEG : 0.0f;
}

uint32_t cli_add_scalar_attribute(cli_mesh* m, const char* name, const float* values) {
  if (m->attribute_count >= TLOD_MAX_ATTRIBUTES) {
    cli_error(CLI_FAILED, "%s: %u attributes already: no room for '%s'", m->name, m->attribute_count, name);
    return UINT32_MAX;
  }
  float* data = malloc(sizeof(float) * ((size_t)m->vertex_count + 1));
  if (!data) {
    cli_error(CLI_FAILED, "%s: out of memory for attribute '%s'", m->name, name);
    return UINT32_MAX;
  }
  memcpy(data, values, sizeof(float) * m->vertex_count);
  cli_attribute* a = &m->attributes[m->attribute_count];
  snprintf(a->name, sizeof(a->name), "%s", name);
  a->components = 1;
  a->data = data;
  return m->attribute_count++;
}
