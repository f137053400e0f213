/* Camera matrices for the tools (column-major, OpenGL conventions). */
#ifndef TLOD_TOOLS_CAMERA_H
#define TLOD_TOOLS_CAMERA_H

#include <stdbool.h>

typedef struct tool_camera {
  float eye[3], target[3], up[3];
  float fovy_deg; /* 0: orthographic with ortho_height */
  float ortho_height;
  float near_z, far_z;
} tool_camera;

/* Why eye, target and up make no view: "eye and target are the same point",
 * "up is parallel to the view direction" (or zero); NULL when they do. */
const char* camera_view_problem(const float eye[3], const float target[3], const float up[3]);
/* Up parallel to the view direction takes any perpendicular (camera paths
 * pass through such poses); tools that take one camera refuse it first
 * (camera_view_problem). */
void camera_look_at(const float eye[3], const float target[3], const float up[3], float view[16]);
void camera_perspective(float fovy_deg, float aspect, float near_z, float far_z, float proj[16]);
void camera_orthographic(float height, float aspect, float near_z, float far_z, float proj[16]);
/* Near and far planes that hold a scene box seen from eye. */
void camera_fit_planes(const float eye[3], const float bmin[3], const float bmax[3], float* near_z, float* far_z);

#endif
