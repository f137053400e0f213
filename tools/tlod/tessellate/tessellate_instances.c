/* tlod tessellate -- scene mode with a camera: one scheduler frame per
 * instance, in the mesh's space (view matrix times the node's world matrix),
 * so each instance gets the levels its own place on screen asks for. */
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "tessellate_frame.h"
#include "tessellate_scene.h"

/* c = a * b, column-major 4x4. */
static void mat4_mul(const float a[16], const float b[16], float c[16]) {
  for (int col = 0; col < 4; col++)
    for (int row = 0; row < 4; row++) {
      float v = 0.0f;
      for (int k = 0; k < 4; k++)
        v += a[4 * k + row] * b[4 * col + k];
      c[4 * col + row] = v;
    }
}

static void grow_box(const float w[16], const tlod_mesh_info* info, float lo[3], float hi[3]) {
  for (int corner = 0; corner < 8; corner++) {
    const float p[3] = {corner & 1 ? info->bbox_max[0] : info->bbox_min[0],
                        corner & 2 ? info->bbox_max[1] : info->bbox_min[1],
                        corner & 4 ? info->bbox_max[2] : info->bbox_min[2]};
    for (int k = 0; k < 3; k++) {
      const float v = w[k] * p[0] + w[4 + k] * p[1] + w[8 + k] * p[2] + w[12 + k];
      lo[k] = v < lo[k] ? v : lo[k];
      hi[k] = v > hi[k] ? v : hi[k];
    }
  }
}

/* The world box of every instance (the camera's default target and planes). */
static void world_box(const tess_scene* s, float lo[3], float hi[3]) {
  const tlod_import_result* r = s->r;
  for (int k = 0; k < 3; k++)
    lo[k] = 1e30f, hi[k] = -1e30f;
  for (uint32_t n = 0; n < r->node_count; n++) {
    if (r->nodes[n].mesh == TLOD_IMPORT_NONE) continue;
    const tlod_import_mesh* me = &r->meshes[r->nodes[n].mesh];
    for (uint32_t k = 0; k < me->part_count; k++) {
      tlod_mesh_info info = tlod_mesh_query_info(s->meshes[me->first_part + k]);
      grow_box(r->nodes[n].world, &info, lo, hi);
    }
  }
  if (lo[0] > hi[0])
    for (int k = 0; k < 3; k++)
      lo[k] = hi[k] = 0.0f;
}

/* One instance: part p seen through node n's world matrix. */
static int tessellate_instance(tess_scene* s, const tlod_view_desc* world_view, uint32_t n, uint32_t p,
                               tlod_cpu_mesh** out) {
  tlod_view_desc view = *world_view;
  mat4_mul(world_view->view, s->r->nodes[n].world, view.view);
  tlod_scheduler* sch = NULL;
  const tlod_draw_list* dl = NULL;
  int rc = tessellate_plan_view(s->o, s->ctx, s->surfaces[p], s->patterns, &view, &sch, &dl);
  if (rc == CLI_OK) rc = tessellate_part(s, p, dl, 0, out);
  tlod_scheduler_destroy(sch);
  if (rc == CLI_OK && (*out)->triangle_count == 0) {
    tlod_cpu_mesh_destroy(s->ctx, *out);
    *out = NULL;
    s->culled++;
    rc = tessellate_part(s, p, NULL, 0, out);
  }
  return rc;
}

static uint32_t count_copies(tess_scene* s, bool* seen) {
  const tlod_import_result* r = s->r;
  uint32_t copies = 0;
  for (uint32_t n = 0; n < r->node_count; n++) {
    const uint32_t m = r->nodes[n].mesh;
    s->node_first[n] = UINT32_MAX;
    if (m == TLOD_IMPORT_NONE) continue;
    if (seen[m]) s->node_first[n] = copies, copies += r->meshes[m].part_count;
    seen[m] = true;
  }
  return copies;
}

static int tessellate_nodes(tess_scene* s, const tlod_view_desc* view) {
  const tlod_import_result* r = s->r;
  int rc = CLI_OK;
  for (uint32_t n = 0; rc == CLI_OK && n < r->node_count; n++) {
    if (r->nodes[n].mesh == TLOD_IMPORT_NONE) continue;
    const tlod_import_mesh* me = &r->meshes[r->nodes[n].mesh];
    for (uint32_t k = 0; rc == CLI_OK && k < me->part_count; k++) {
      const uint32_t p = me->first_part + k;
      tess_item* item = s->node_first[n] == UINT32_MAX ? &s->parts[p] : &s->copies[s->node_first[n] + k];
      item->part = p;
      rc = tessellate_instance(s, view, n, p, &item->out);
    }
  }
  /* meshes no node uses: the uniform level, within the patterns' */
  const uint32_t level = s->o->level < s->o->ad.max_level ? s->o->level : s->o->ad.max_level;
  for (uint32_t p = 0; rc == CLI_OK && p < r->part_count; p++)
    if (!s->parts[p].out) rc = tessellate_part(s, p, NULL, level, &s->parts[p].out);
  return rc;
}

int tessellate_instances(tess_scene* s) {
  float lo[3], hi[3];
  world_box(s, lo, hi);
  tlod_view_desc view;
  int rc = tessellate_view(s->o, lo, hi, &view);
  if (rc != CLI_OK) return rc;
  bool* seen = calloc((size_t)s->r->mesh_count + 1, sizeof(bool));
  if (!seen) return cli_error(CLI_FAILED, "out of memory");
  s->copy_count = count_copies(s, seen);
  free(seen);
  s->copies = calloc((size_t)s->copy_count + 1, sizeof(tess_item));
  if (!s->copies) return cli_error(CLI_FAILED, "out of memory");
  return tessellate_nodes(s, &view);
}
