/* A generated skinned test object: a closed cylinder along +y with two
 * joints, for the skinning tests and `tlod bench --suite skin`. Joint 0 sits
 * at the origin, joint 1 (its child) at half the height; weights blend from
 * joint 0 to joint 1 between 0.3 and 0.7 of the height (smoothstep). Caps
 * are fans round a centre vertex; their rim vertices repeat the side's end
 * rows bitwise with the cap normal, so the rims are creases. */
#ifndef TLOD_TOOLS_SKIN_CYLINDER_H
#define TLOD_TOOLS_SKIN_CYLINDER_H

#include <stdbool.h>
#include <stdint.h>

#include "tesslod/core.h"

typedef struct skin_cylinder {
  uint32_t vertex_count, index_count; /* triangles, counter-clockwise seen from outside */
  float *positions, *normals;         /* xyz per vertex */
  uint16_t* joints;                   /* 4 per vertex: 0, 1, 0, 0 */
  float* weights;                     /* 4 per vertex: w0, w1, 0, 0 */
  uint32_t* indices;
  float height, radius;
} skin_cylinder;

/* segments >= 3 round, rings >= 1 along; false when out of memory or the
 * counts overflow 32 bits. */
bool skin_cylinder_create(uint32_t segments, uint32_t rings, float radius, float height, skin_cylinder* out);
void skin_cylinder_free(skin_cylinder* c);
/* Skinning matrices (skin_joint_matrices) of the pose where joint 1 turns
 * by the unit quaternion `rotation` about its rest place, joint 0 fixed:
 * world = {I, T(0, h/2, 0) R}, inverse bind = {I, T(0, -h/2, 0)}. */
void skin_cylinder_pose(const skin_cylinder* c, const float rotation[4], float mats[2][16]);
/* The cylinder as a tesslod mesh and Phong surface in ctx, with buffers
 * for its skinned positions and normals (xyz per vertex). */
typedef struct skin_cylinder_model {
  skin_cylinder cyl;
  tlod_mesh* mesh;
  tlod_surface* surface;
  float *positions, *normals;
} skin_cylinder_model;

/* False (ctx's last error, or out of memory) when a step fails; out then holds nothing. */
bool skin_cylinder_model_create(tlod_context* ctx, uint32_t segments, uint32_t rings, float radius, float height,
                                skin_cylinder_model* out);
void skin_cylinder_model_free(skin_cylinder_model* m);
/* Weight of joint 1 at height y. */
float skin_cylinder_weight(const skin_cylinder* c, float y);

#endif
