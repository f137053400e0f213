/* tlod -- loading an input mesh (file or built-in demo). */
#include "mesh_load.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "tlod_import.h"

void cli_mesh_free(cli_mesh* m) {
  free(m->positions);
  free(m->normals);
  free(m->indices);
  free(m->face_sizes);
  free(m->face_source);
  memset(m, 0, sizeof(*m));
}

/* The importer allocated with malloc (NULL allocator): take the arrays over. */
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
  r->positions = r->normals = NULL;
  r->indices = NULL;
  r->face_sizes = NULL;
}

static int load_file(const char* path, cli_mesh* m) {
  char err[512];
  tlod_import_result* r = NULL;
  if (tlod_import_file(path, NULL, &r, err, sizeof(err)) != TLOD_SUCCESS) return cli_error(CLI_FAILED, "%s", err);
  take_over(r, m);
  tlod_import_free(r);
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
