/* tesslod::core -- second-order nodes of a mesh's faces (issue 14): checked
 * before anything is allocated, copied per kept face, shared onto a
 * neighbour's edge that has none, and compared in the smooth flags.
 * Owned by the mesh module (mesh.c, mesh_adjacency.c, mesh_attributes.c,
 * mesh_nodes.c, mesh_normals.c). Maths: docs/design.md "Quadratic faces". */
#include <string.h>

#include "internal.h"

/* Slots a face of k corners uses: its k edges, and the centre of a quad. */
static bool slot_used(uint32_t k, uint32_t slot) { return slot < k || (k == 4 && slot == 4); }

static tlod_result check_face(tlod_context* ctx, const char* label, const tlod_mesh_desc* d, uint32_t f,
                              const uint32_t* idx, uint32_t k) {
  const uint32_t* nodes = d->face_nodes + (size_t)f * TLOD_FACE_NODES;
  for (uint32_t s = 0; s < TLOD_FACE_NODES; s++) {
    uint32_t v = nodes[s];
    if (v == TLOD_NO_NODE || !slot_used(k, s)) continue;
    if (v >= d->vertex_count)
      return _tlod_fail(ctx, TLOD_ERROR_INVALID_MESH,
                        "mesh '%s': face %u: node %u: index %u out of range (%u vertices)", label, f, s, v,
                        d->vertex_count);
    for (uint32_t i = 0; i < k; i++)
      if (idx[i] == v)
        return _tlod_fail(ctx, TLOD_ERROR_INVALID_MESH,
                          "mesh '%s': face %u: node %u: vertex %u is corner %u of the face", label, f, s, v, i);
    for (uint32_t t = 0; t < s; t++)
      if (nodes[t] == v && slot_used(k, t))
        return _tlod_fail(ctx, TLOD_ERROR_INVALID_MESH, "mesh '%s': face %u: node %u: vertex %u is also node %u", label,
                          f, s, v, t);
  }
  return TLOD_SUCCESS;
}

tlod_result _tlod_mesh_check_nodes(tlod_context* ctx, const char* label, const tlod_mesh_desc* d, uint32_t face_size,
                                   uint32_t input_faces) {
  if (!d->face_nodes) return TLOD_SUCCESS;
  uint32_t first = 0;
  for (uint32_t f = 0; f < input_faces; f++) {
    uint32_t k = face_size ? face_size : d->face_sizes[f];
    tlod_result r = check_face(ctx, label, d, f, d->indices + first, k);
    if (r != TLOD_SUCCESS) return r;
    first += k;
  }
  return TLOD_SUCCESS;
}

/* Node-only vertices: a node of some kept face and a corner of none. */
static void mark_node_only(tlod_mesh* m) {
  for (uint32_t f = 0; f < m->face_count; f++)
    for (uint32_t s = 0; s < TLOD_FACE_NODES; s++)
      if (m->face_nodes[f][s] != _TLOD_NONE) m->node_only[m->face_nodes[f][s]] = 1;
  for (uint32_t f = 0; f < m->face_count; f++)
    for (uint32_t i = 0; i < m->face_corners[f]; i++)
      m->node_only[m->faces[f][i]] = 0;
}

tlod_result _tlod_mesh_copy_nodes(tlod_mesh* m, const uint32_t* face_nodes) {
  if (!face_nodes) return TLOD_SUCCESS;
  m->face_nodes = _tlod_calloc(m->ctx, m->face_count, sizeof(*m->face_nodes));
  m->node_given = _tlod_calloc(m->ctx, m->face_count, 1);
  m->node_only = _tlod_calloc(m->ctx, m->vertex_count, 1);
  if (!m->face_nodes || !m->node_given || !m->node_only)
    return _tlod_fail(m->ctx, TLOD_ERROR_OUT_OF_MEMORY, "mesh '%s': out of memory (face nodes)", m->label);
  for (uint32_t f = 0; f < m->face_count; f++) {
    const uint32_t* in = face_nodes + (size_t)m->face_input[f] * TLOD_FACE_NODES;
    for (uint32_t s = 0; s < TLOD_FACE_NODES; s++) {
      bool used = slot_used(m->face_corners[f], s) && in[s] != TLOD_NO_NODE;
      m->face_nodes[f][s] = used ? in[s] : _TLOD_NONE;
      m->node_given[f] |= (uint8_t)(used << s);
    }
    m->info.curved_faces += m->node_given[f] != 0;
  }
  mark_node_only(m);
  return TLOD_SUCCESS;
}

bool _tlod_mesh_is_node_only(const tlod_mesh* m, uint32_t v) { return m->node_only && m->node_only[v]; }

/* An edge without a node takes its neighbour's given node (never one the
 * neighbour took itself: sharing is one step, so the order of faces does
 * not matter). */
void _tlod_mesh_share_nodes(tlod_mesh* m) {
  if (!m->face_nodes) return;
  uint32_t shared = 0;
  for (uint32_t f = 0; f < m->face_count; f++)
    for (uint32_t e = 0; e < m->face_corners[f]; e++) {
      const tlod_edge_link* l = &m->links[f][e];
      if (l->face == _TLOD_NONE || m->face_nodes[f][e] != _TLOD_NONE) continue;
      if (!(((uint32_t)m->node_given[l->face] >> l->edge) & 1u)) continue;
      m->face_nodes[f][e] = m->face_nodes[l->face][l->edge];
      shared++;
    }
  m->info.nodes_shared = shared;
}

bool _tlod_mesh_same_nodes(const tlod_mesh* m, uint32_t f, uint32_t e, uint32_t g, uint32_t ge) {
  if (!m->face_nodes) return true;
  uint32_t a = m->face_nodes[f][e], b = m->face_nodes[g][ge];
  if (a == b) return true;
  if (a == _TLOD_NONE || b == _TLOD_NONE) return false;
  return memcmp(m->positions[a], m->positions[b], sizeof(m->positions[a])) == 0;
}
