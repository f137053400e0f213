/* tesslod::lod -- the mesh's up edges: per patch the edges towards a
 * neighbour of higher index, the only edges the draw list counts a strip
 * from (each strip once), in up to four slots per patch with both edge
 * numbers and the crease beside the neighbour. Built at create (a mesh's
 * links are made with the mesh, and tlod_mesh_update keeps its topology);
 * the crease bits are made again when an update moved the smooth flags
 * (smooth_generation). The strip test reads a block's slots densely
 * (4 bytes per slot up to the block's most up edges) and makes a strip
 * from its slot, where a patch's 32 bytes of links, read for both, missed
 * the caches; an unused slot names the patch itself, which never strips
 * to itself, so the test needs no per-patch count (scheduler_list_kernels.c). */
#include <string.h>

#include "scheduler_frame.h"

/* Neighbour indices fit the slot's face bits. */
#define MAX_PATCHES (_TLOD_UP_FACE + 1u)

/* Patch f's slots; returns how many hold an up edge. */
static uint32_t fill_patch(_tlod_up_edges* u, const tlod_mesh_view* m, uint32_t n, uint32_t f) {
  uint32_t k = 0;
  for (uint32_t e = 0; e < m->face_corners[f]; e++) {
    tlod_edge_link link = m->links[f][e];
    if (link.face == _TLOD_NO_FACE || link.face <= f) continue;
    u->slot[(size_t)k++ * n + f] = link.face | (uint32_t)link.edge << _TLOD_UP_EDGE_B_SHIFT | e << _TLOD_UP_EDGE_SHIFT |
                                   (link.smooth ? 0u : _TLOD_UP_CREASE);
  }
  for (uint32_t j = k; j < _TLOD_UP_SLOTS; j++)
    u->slot[(size_t)j * n + f] = f;
  return k;
}

/* Every patch's slots and every block's most used slots. */
static void fill_slots(_tlod_up_edges* u, const tlod_mesh_view* m, uint32_t n) {
  for (uint32_t b = 0; b * FAST_BLOCK < n; b++) {
    uint32_t most = 0, end = n - b * FAST_BLOCK < FAST_BLOCK ? n : b * FAST_BLOCK + FAST_BLOCK;
    for (uint32_t f = b * FAST_BLOCK; f < end; f++) {
      uint32_t k = fill_patch(u, m, n, f);
      most = k > most ? k : most;
    }
    u->block_slots[b] = (uint8_t)most;
  }
}

tlod_result _tlod_up_edges_build(tlod_scheduler* s) {
  _tlod_up_edges* u = &s->up;
  uint32_t n = s->patch_count;
  if (n >= MAX_PATCHES)
    return tlod_context_fail(s->ctx, TLOD_ERROR_INVALID_ARGUMENT, "scheduler '%s': %u patches is too many (at most %u)",
                             s->label, n, MAX_PATCHES - 1u);
  tlod_mesh_view m = tlod_mesh_query_view(s->mesh);
  u->slot = tlod_context_alloc(s->ctx, sizeof(uint32_t) * ((size_t)_TLOD_UP_SLOTS * n + 1));
  u->block_slots = tlod_context_calloc(s->ctx, (size_t)n / FAST_BLOCK + 1, 1);
  if (!u->slot || !u->block_slots) return TLOD_ERROR_OUT_OF_MEMORY;
  fill_slots(u, &m, n);
  u->smooth_generation = m.smooth_generation;
  return TLOD_SUCCESS;
}

void _tlod_up_edges_refresh(tlod_scheduler* s, const tlod_mesh_view* mesh) {
  if (mesh->smooth_generation == s->up.smooth_generation) return;
  fill_slots(&s->up, mesh, s->patch_count);
  s->up.smooth_generation = mesh->smooth_generation;
}

void _tlod_up_edges_free(tlod_context* ctx, _tlod_up_edges* u) {
  tlod_context_free(ctx, u->slot);
  tlod_context_free(ctx, u->block_slots);
  memset(u, 0, sizeof(*u));
}
