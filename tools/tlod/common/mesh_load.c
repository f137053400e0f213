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
  snprintf(m->warnings, sizeof(m->warnings), "%s", r->warnings);
  m->has_color = r->part_count > 0;
  if (m->has_color) memcpy(m->base_color, r->parts[0].base_color, sizeof(m->base_color));
  take_attributes(r, m);
  r->positions = r->normals = NULL;
  r->indices = NULL;
  r->face_sizes = NULL;
  m->source = r;
}

static int load_file(const char* path, cli_mesh* m) {
  char err[512];
  tlod_import_result* r = NULL;
  if (tlod_import_file(path, NULL, &r, err, sizeof(err)) != TLOD_SUCCESS) return cli_error(CLI_FAILED, "%s", err);
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
