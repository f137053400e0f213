/* Linear blend skinning (Magnenat-Thalmann et al., "Joint-dependent local
 * deformations for hand animation and object grasping", 1988; glTF 2.0
 * section 3.7.3): the four joint matrices are blended by weight, then the
 * blend transforms the rest position and, by its inverse transpose (the
 * cofactor matrix with the sign of the determinant), the rest normal.
 * Double precision inside, rounded once per coordinate. */
#include <math.h>

#include "common/anim_sample.h"
#include "common/skin_apply.h"

#define SKIN_CHUNK 1024u

void skin_joint_matrices(uint32_t joint_count, const float (*joint_world)[16], const float (*inverse_bind)[16],
                         float (*out)[16]) {
  for (uint32_t j = 0; j < joint_count; j++)
    anim_mat4_mul(joint_world[j], inverse_bind[j], out[j]);
}

/* The weighted sum of the vertex's joint matrices (3x4, column-major:
 * b[c * 3 + r]); false when no weight lands on a joint. */
static int blend(const uint16_t* joints, const float* weights, uint32_t joint_count, const float (*m)[16],
                 double b[12]) {
  double total = 0.0;
  for (int i = 0; i < 12; i++)
    b[i] = 0.0;
  for (int k = 0; k < 4; k++) {
    double w = weights[k];
    if (w == 0.0 || joints[k] >= joint_count) continue;
    const float* jm = m[joints[k]];
    for (int c = 0; c < 4; c++)
      for (int r = 0; r < 3; r++)
        b[c * 3 + r] += w * jm[c * 4 + r];
    total += w;
  }
  return total != 0.0;
}

static void transform_point(const double b[12], const float p[3], float out[3]) {
  for (int r = 0; r < 3; r++)
    out[r] = (float)(b[r] * p[0] + b[3 + r] * p[1] + b[6 + r] * p[2] + b[9 + r]);
}

/* n' = cofactor(B) n * sign(det B) = det(B) B^-T n up to a positive
 * factor, renormalised; false for a singular blend. */
static int transform_normal(const double b[12], const float n[3], float out[3]) {
  const double *c0 = b, *c1 = b + 3, *c2 = b + 6;
  double x[3] = {c1[1] * c2[2] - c1[2] * c2[1], c1[2] * c2[0] - c1[0] * c2[2], c1[0] * c2[1] - c1[1] * c2[0]};
  double y[3] = {c2[1] * c0[2] - c2[2] * c0[1], c2[2] * c0[0] - c2[0] * c0[2], c2[0] * c0[1] - c2[1] * c0[0]};
  double z[3] = {c0[1] * c1[2] - c0[2] * c1[1], c0[2] * c1[0] - c0[0] * c1[2], c0[0] * c1[1] - c0[1] * c1[0]};
  double det = c0[0] * x[0] + c0[1] * x[1] + c0[2] * x[2], r[3], len = 0.0;
  for (int i = 0; i < 3; i++) {
    r[i] = x[i] * n[0] + y[i] * n[1] + z[i] * n[2];
    len += r[i] * r[i];
  }
  if (!(det != 0.0) || !(len > 0.0)) return 0;
  double s = (det < 0.0 ? -1.0 : 1.0) / sqrt(len);
  for (int i = 0; i < 3; i++)
    out[i] = (float)(r[i] * s);
  return 1;
}

static void copy3(const float* a, float* out) {
  for (int i = 0; i < 3; i++)
    out[i] = a[i];
}

void skin_range(const skin_vertices* v, uint32_t joint_count, const float (*joint_matrices)[16], uint32_t begin,
                uint32_t end, float* positions, float* normals) {
  for (uint32_t i = begin; i < end; i++) {
    const float* p = v->rest_positions + (size_t)i * 3;
    const float* n = v->rest_normals ? v->rest_normals + (size_t)i * 3 : NULL;
    double b[12];
    int moved = blend(v->joints + (size_t)i * 4, v->weights + (size_t)i * 4, joint_count, joint_matrices, b);
    if (moved)
      transform_point(b, p, positions + (size_t)i * 3);
    else
      copy3(p, positions + (size_t)i * 3);
    if (n && normals && !(moved && transform_normal(b, n, normals + (size_t)i * 3))) copy3(n, normals + (size_t)i * 3);
  }
}

typedef struct skin_task {
  const skin_vertices* v;
  uint32_t joint_count;
  const float (*joint_matrices)[16];
  float *positions, *normals;
} skin_task;

static void skin_chunks(void* data, uint32_t begin, uint32_t end, uint32_t worker) {
  (void)worker;
  const skin_task* t = data;
  for (uint32_t c = begin; c < end; c++) {
    uint32_t first = c * SKIN_CHUNK,
             last = t->v->vertex_count - first < SKIN_CHUNK ? t->v->vertex_count : first + SKIN_CHUNK;
    skin_range(t->v, t->joint_count, t->joint_matrices, first, last, t->positions, t->normals);
  }
}

void skin_apply(const tlod_context* ctx, const skin_vertices* v, uint32_t joint_count,
                const float (*joint_matrices)[16], float* positions, float* normals) {
  skin_task t = {v, joint_count, joint_matrices, positions, normals};
  uint32_t chunks = (uint32_t)(((uint64_t)v->vertex_count + SKIN_CHUNK - 1) / SKIN_CHUNK);
  tlod_context_parallel_for(ctx, skin_chunks, &t, chunks);
}
