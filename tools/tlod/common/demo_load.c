/* tlod -- the built-in demo meshes as input meshes. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "demo_mesh.h"
#include "demo_shapes.h"
#include "mesh_load.h"
#include "strict_number.h"

static void* dup_array(const void* src, size_t bytes) {
  void* p = malloc(bytes ? bytes : 1);
  if (p && bytes) memcpy(p, src, bytes);
  return p;
}

static int from_shape(demo_shape* s, cli_mesh* m) {
  m->vertex_count = s->vertex_count;
  m->positions = s->positions;
  m->normals = s->normals;
  m->indices = s->indices;
  m->index_count = s->quad_count * 4;
  m->face_count = s->quad_count;
  m->face_sizes = malloc(s->quad_count ? s->quad_count : 1);
  memset(s, 0, sizeof(*s));
  if (!m->face_sizes) return cli_error(CLI_FAILED, "out of memory");
  memset(m->face_sizes, 4, m->face_count);
  return CLI_OK;
}

static int from_demo_mesh(const tlod_demo_mesh* d, cli_mesh* m) {
  m->vertex_count = d->vertex_count;
  m->index_count = d->index_count;
  m->face_count = d->face_count;
  m->positions = dup_array(d->positions, sizeof(float) * 3 * d->vertex_count);
  m->indices = dup_array(d->indices, sizeof(uint32_t) * d->index_count);
  m->face_sizes = dup_array(d->face_sizes, d->face_count);
  if (!m->positions || !m->indices || !m->face_sizes) return cli_error(CLI_FAILED, "out of memory");
  return CLI_OK;
}

const char* cli_demo_names(void) { return "demo:cow, demo:cylinder, demo:torus, demo:torus-NxM"; }

enum { TORUS_MAX_QUADS = 50000000 };

/* "torus" or "torus-NxM" (N, M >= 3, at most 50M quads): NULL, or what is wrong. */
static const char* torus_size(const char* name, uint32_t* rings, uint32_t* segs) {
  *rings = 48, *segs = 24;
  if (!strcmp(name, "torus")) return NULL;
  const char* x = NULL;
  number_status s =
      strncmp(name, "torus-", 6) ? NUMBER_SYNTAX : number_parse_u32(name + 6, &x, 3, TORUS_MAX_QUADS, rings);
  if (s == NUMBER_OK && *x != 'x') s = NUMBER_SYNTAX;
  if (s == NUMBER_RANGE) return "rings out of range 3..50000000";
  if (s == NUMBER_OK) s = number_parse_u32(x + 1, NULL, 3, TORUS_MAX_QUADS, segs);
  if (s == NUMBER_RANGE) return "segments out of range 3..50000000";
  if (s != NUMBER_OK) return "unknown demo mesh";
  return (uint64_t)*rings * *segs > TORUS_MAX_QUADS ? "more than 50000000 quads" : NULL;
}

int cli_load_demo(const char* name, cli_mesh* m) {
  demo_shape s = {0};
  uint32_t rings = 0, segs = 0;
  if (!strcmp(name, "cow")) return from_demo_mesh(&tlod_demo_cow, m);
  if (!strcmp(name, "cylinder")) {
    if (!demo_cylinder(32, &s)) return cli_error(CLI_FAILED, "out of memory");
    return from_shape(&s, m);
  }
  const char* problem = torus_size(name, &rings, &segs);
  if (problem)
    return cli_error(CLI_FAILED, "demo:%s: %s (built-in: %s; torus-NxM with N, M >= 3)", name, problem,
                     cli_demo_names());
  if (!demo_torus(rings, segs, &s)) return cli_error(CLI_FAILED, "out of memory");
  return from_shape(&s, m);
}
