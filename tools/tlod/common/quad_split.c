/* tlod -- quads split into triangles (PN triangles need triangles), keeping
 * the loaded face of every triangle. */
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "mesh_load.h"

static uint32_t quad_count(const cli_mesh* m) {
  uint32_t quads = 0;
  for (uint32_t f = 0; f < m->face_count; f++)
    quads += m->face_sizes[f] == 4;
  return quads;
}

/* Triangles of m into idx, the loaded face of each into source; returns the index count. */
static uint32_t split_into(const cli_mesh* m, uint32_t* idx, uint32_t* source) {
  uint32_t src = 0, dst = 0;
  for (uint32_t f = 0; f < m->face_count; f++) {
    const uint32_t* q = m->indices + src;
    source[dst / 3] = f;
    if (m->face_sizes[f] == 4) {
      uint32_t tris[6] = {q[0], q[1], q[2], q[0], q[2], q[3]};
      memcpy(idx + dst, tris, sizeof(tris));
      source[dst / 3 + 1] = f;
      dst += 6;
    } else {
      memcpy(idx + dst, q, sizeof(uint32_t) * 3);
      dst += 3;
    }
    src += m->face_sizes[f];
  }
  return dst;
}

int cli_split_quads(cli_mesh* m) {
  if (!m->face_sizes) return CLI_OK;
  uint32_t quads = quad_count(m);
  uint32_t* idx = malloc(sizeof(uint32_t) * ((size_t)m->index_count + 2u * quads + 1));
  uint32_t* source = malloc(sizeof(uint32_t) * ((size_t)m->face_count + quads + 1));
  if (!idx || !source) {
    free(idx);
    free(source);
    return cli_error(CLI_FAILED, "out of memory");
  }
  uint32_t count = split_into(m, idx, source);
  m->face_source = source;
  free(m->indices);
  free(m->face_sizes);
  m->indices = idx;
  m->index_count = count;
  m->face_count = count / 3;
  m->face_sizes = NULL;
  free(m->face_nodes); /* PN draws the split triangles' own surface: nodes do not apply */
  m->face_nodes = NULL;
  m->quads_split = quads;
  return CLI_OK;
}
