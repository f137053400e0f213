/* Node animation for the tools (glTF 2.0 section 3.11 "Animations"): a
 * channel sampled at a time, node TRS to a local matrix, world matrices
 * from a parent hierarchy. Plain arrays, no import structs, so the tests
 * and the bench use the same code as `tlod play` (anim_import.h adapts the
 * importer's animations). Matrices are column-major 4x4 like OpenGL and
 * glTF; quaternions are (x, y, z, w). Products are formed in double and
 * rounded once to float. */
#ifndef TLOD_TOOLS_ANIM_SAMPLE_H
#define TLOD_TOOLS_ANIM_SAMPLE_H

#include <stdbool.h>
#include <stdint.h>

typedef enum anim_path { ANIM_PATH_TRANSLATION = 0, ANIM_PATH_ROTATION, ANIM_PATH_SCALE } anim_path;
typedef enum anim_interp { ANIM_INTERP_LINEAR = 0, ANIM_INTERP_STEP, ANIM_INTERP_CUBICSPLINE } anim_interp;

typedef struct anim_channel {
  uint32_t node; /* target node */
  anim_path path;
  anim_interp interp;
  uint32_t key_count;  /* >= 1 */
  const float* times;  /* key_count seconds, strictly increasing, finite */
  const float* values; /* key_count * n floats (n = 3, rotation 4); CUBICSPLINE: per key in-tangent, value,
                          out-tangent (3 * n floats) */
} anim_channel;

typedef struct anim_trs {
  float translation[3];
  float rotation[4]; /* unit quaternion x y z w */
  float scale[3];
} anim_trs;

/* Components of a path's values: 3, or 4 for rotations. */
uint32_t anim_path_components(anim_path path);
/* The channel's value at t seconds: before the first key the first value,
 * after the last key the last (a NaN t counts as before). STEP holds the
 * value of the key at or before t; LINEAR lerps translations and scales
 * and slerps rotations the short way; CUBICSPLINE is the glTF Hermite
 * spline, tangents scaled by the key interval. Rotations come out unit
 * length. out gets anim_path_components() floats. */
void anim_channel_sample(const anim_channel* c, float t, float out[4]);
/* Samples every channel at t into nodes[channel.node] (channels naming a
 * node >= node_count are skipped; the importer refuses them). */
void anim_apply(const anim_channel* channels, uint32_t channel_count, float t, anim_trs* nodes, uint32_t node_count);
/* Latest key time over the channels (0 when none): an animation's duration. */
float anim_duration(const anim_channel* channels, uint32_t channel_count);

/* Local matrix T * R * S (the rotation normalised first). */
void anim_trs_matrix(const anim_trs* trs, float m[16]);
/* out = a * b; out may alias neither input. */
void anim_mat4_mul(const float a[16], const float b[16], float out[16]);
/* world[i] = world[parent[i]] * local[i] (roots: parent[i] >= count).
 * Nodes come in any order: a node whose parent is not done yet is resolved
 * by walking up the parents. scratch: 2 * count uint32. False when the
 * parents form a cycle (world is then incomplete). */
bool anim_world_matrices(uint32_t count, const uint32_t* parent, const float (*local)[16], float (*world)[16],
                         uint32_t* scratch);

#endif
