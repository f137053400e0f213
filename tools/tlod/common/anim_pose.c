/* Node poses: TRS to a local matrix and world matrices down the node
 * hierarchy (glTF 2.0 section 3.5.3 "Transformations": M = T * R * S,
 * world = parent world * local). */
#include "common/anim_sample.h"

void anim_mat4_mul(const float a[16], const float b[16], float out[16]) {
  for (int c = 0; c < 4; c++)
    for (int r = 0; r < 4; r++) {
      double s = 0.0;
      for (int k = 0; k < 4; k++)
        s += (double)a[k * 4 + r] * b[c * 4 + k];
      out[c * 4 + r] = (float)s;
    }
}

void anim_trs_matrix(const anim_trs* trs, float m[16]) {
  const float* q = trs->rotation;
  double len2 = (double)q[0] * q[0] + (double)q[1] * q[1] + (double)q[2] * q[2] + (double)q[3] * q[3];
  double s2 = len2 > 0.0 ? 2.0 / len2 : 0.0, x = q[0], y = q[1], z = q[2], w = q[3];
  double r[9] = {1 - s2 * (y * y + z * z), s2 * (x * y + w * z),     s2 * (x * z - w * y),
                 s2 * (x * y - w * z),     1 - s2 * (x * x + z * z), s2 * (y * z + w * x),
                 s2 * (x * z + w * y),     s2 * (y * z - w * x),     1 - s2 * (x * x + y * y)};
  for (int c = 0; c < 3; c++) {
    for (int k = 0; k < 3; k++)
      m[c * 4 + k] = (float)(r[c * 3 + k] * trs->scale[c]);
    m[c * 4 + 3] = 0.0f;
    m[12 + c] = trs->translation[c];
  }
  m[15] = 1.0f;
}

static void copy16(const float a[16], float out[16]) {
  for (int i = 0; i < 16; i++)
    out[i] = a[i];
}

/* Resolves node i and its unresolved ancestors: pushes the chain up to a
 * done node or a root, then fills it top down. done[] = scratch[0..count),
 * the chain = scratch[count..2 count). False on a cycle. */
static bool resolve(uint32_t i, uint32_t count, const uint32_t* parent, const float (*local)[16], float (*world)[16],
                    uint32_t* scratch) {
  uint32_t *done = scratch, *chain = scratch + count, n = 0;
  for (uint32_t v = i; v < count && !done[v]; v = parent[v]) {
    if (n == count) return false;
    chain[n++] = v;
  }
  while (n > 0) {
    uint32_t v = chain[--n], p = parent[v];
    if (p < count)
      anim_mat4_mul(world[p], local[v], world[v]);
    else
      copy16(local[v], world[v]);
    done[v] = 1;
  }
  return true;
}

bool anim_world_matrices(uint32_t count, const uint32_t* parent, const float (*local)[16], float (*world)[16],
                         uint32_t* scratch) {
  for (uint32_t i = 0; i < count; i++)
    scratch[i] = 0;
  for (uint32_t i = 0; i < count; i++)
    if (!scratch[i] && !resolve(i, count, parent, local, world, scratch)) return false;
  return true;
}
