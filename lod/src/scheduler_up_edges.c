/* tesslod::lod -- the mesh's up edges: per patch the edges towards a
 * neighbour of higher index, the only edges the draw list counts a strip
 * from (each strip once), as a mask and as a packed list of the
 * neighbours. Built at create (a mesh's links are made with the mesh, and
 * tlod_mesh_update keeps its topology); the crease bits are made again
 * when an update moved the smooth flags (smooth_generation). The count pass
 * reads 4 bytes per up edge from the list instead of a patch's 32 bytes of
 * links, whose cache misses were most of its time. */
#include <string.h>

#include "scheduler_frame.h"

/* Neighbour indices are below this (the list keeps the crease in bit 31). */
#define MAX_PATCHES 0x80000000u

static uint32_t up_mask_of(const tlod_edge_link (*links)[4], const uint8_t* corners, uint32_t f) {
  uint32_t up = 0;
  for (uint32_t e = 0; e < corners[f]; e++) {
    uint32_t g = links[f][e].face;
    if (g != _TLOD_NO_FACE && g > f) up |= 1u << e;
  }
  return up;
}

/* Masks and per-block first entries; returns the up edge count. */
static size_t fill_masks(_tlod_up_edges* u, const tlod_mesh_view* m, uint32_t patches) {
  size_t count = 0;
  for (uint32_t f = 0; f < patches; f++) {
    if (f % FAST_BLOCK == 0) u->first[f / FAST_BLOCK] = (uint32_t)count;
    u->mask[f] = (uint8_t)up_mask_of(m->links, m->face_corners, f);
    count += (size_t)__builtin_popcount(u->mask[f]);
  }
  return count;
}

/* The neighbours of the up edges, each with its crease bit. */
static void fill_faces(_tlod_up_edges* u, const tlod_mesh_view* m, uint32_t patches) {
  uint32_t q = 0;
  for (uint32_t f = 0; f < patches; f++)
    for (uint32_t e = 0; e < 4; e++) {
      if (!((uint32_t)u->mask[f] >> e & 1u)) continue;
      tlod_edge_link link = m->links[f][e];
      u->faces[q++] = link.face | (link.smooth ? 0u : _TLOD_UP_CREASE);
    }
}

tlod_result _tlod_up_edges_build(tlod_scheduler* s) {
  _tlod_up_edges* u = &s->up;
  uint32_t n = s->patch_count;
  if (n >= MAX_PATCHES)
    return tlod_context_fail(s->ctx, TLOD_ERROR_INVALID_ARGUMENT, "scheduler '%s': %u patches is too many", s->label,
                             n);
  tlod_mesh_view m = tlod_mesh_query_view(s->mesh);
  u->mask = tlod_context_calloc(s->ctx, (size_t)n + 1, 1);
  u->first = tlod_context_calloc(s->ctx, (size_t)n / FAST_BLOCK + 1, sizeof(uint32_t));
  if (!u->mask || !u->first) return TLOD_ERROR_OUT_OF_MEMORY;
  size_t count = fill_masks(u, &m, n);
  u->faces = tlod_context_calloc(s->ctx, count + 1, sizeof(uint32_t));
  if (!u->faces) return TLOD_ERROR_OUT_OF_MEMORY;
  fill_faces(u, &m, n);
  u->smooth_generation = m.smooth_generation;
  return TLOD_SUCCESS;
}

void _tlod_up_edges_refresh(tlod_scheduler* s, const tlod_mesh_view* mesh) {
  if (mesh->smooth_generation == s->up.smooth_generation) return;
  fill_faces(&s->up, mesh, s->patch_count);
  s->up.smooth_generation = mesh->smooth_generation;
}

void _tlod_up_edges_free(tlod_context* ctx, _tlod_up_edges* u) {
  tlod_context_free(ctx, u->mask);
  tlod_context_free(ctx, u->first);
  tlod_context_free(ctx, u->faces);
  memset(u, 0, sizeof(*u));
}
