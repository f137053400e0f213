/* Private to tesslod::lod: scheduler state and the metric helpers. */
#ifndef TESSLOD_SCHEDULER_INTERNAL_H
#define TESSLOD_SCHEDULER_INTERNAL_H

#include "internal.h"
#include "tesslod/lod.h"

typedef struct _tlod_camera {
  float eye[3], forward[3];
  float planes[6][4]; /* normalised, inside >= 0 */
  float near_z;       /* 0 when unknown or orthographic */
  bool ortho;
} _tlod_camera;

void _tlod_camera_from_view(const float view[16], const float proj[16], _tlod_camera* cam);
float _tlod_view_depth(const float view[16], const float p[3]);
bool _tlod_sphere_visible(const _tlod_camera* cam, const float c[3], float r);
/* n . (eye - p) (orthographic: n . -forward): > 0 where the normal faces the camera. */
float _tlod_facing(const _tlod_camera* cam, const float p[3], const float n[3]);
float _tlod_silhouette_depth(const _tlod_camera* cam, const float p[3], const float n[3], float m);
/* Projected error bound of a patch at level 0, pixels (nearest depth of its sphere). */
float _tlod_patch_e_max(const _tlod_camera* cam, const float view[16], const float proj[16], uint32_t height,
                        const tlod_patch_info* info);

/* What one view keeps between and within frames. */
typedef struct _tlod_view_state {
  tlod_draw_list list;
  _tlod_camera cam;
  int8_t* levels;
  float* e_max;
  float* depth;   /* per vertex d_i */
  float* contour; /* per patch s = max d_i / m */
  float* target;  /* per patch target level (continuous) */
  float* cont;    /* per patch current continuous level */
  uint8_t* visible;
  tlod_draw_instance* instances;
  tlod_draw_strip* strips;
  uint32_t strip_cap;
  tlod_draw_bucket buckets[2 * (TLOD_MAX_LEVEL + 1)];
  bool has_history;
} _tlod_view_state;

struct tlod_scheduler {
  tlod_context* ctx;
  const tlod_surface* surface;
  const tlod_mesh* mesh;
  const tlod_patterns* patterns;
  tlod_scheduler_desc desc; /* resolved */
  char label[64];
  uint32_t patch_count, vertex_count;
  _tlod_view_state* views;
  uint32_t view_count;
  float eps_scale;   /* frame-time control */
  float smoothed_ms; /* EMA of measured frame times */
};

#endif
