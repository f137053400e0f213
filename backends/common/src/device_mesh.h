/* Private to the GPU backends (gl, vulkan): the CPU-mesh mode's
 * evaluation (tlod_gpu_eval OFF), shared so both devices evaluate the same
 * way: an item's draw list realised by tlod_cpu_tessellate_into (welded,
 * with normals) into the device surface's mesh, again only when the list,
 * the surface or its mesh changed (_tlod_list_snapshot). Header-only, as
 * device_stage.h. */
#ifndef TESSLOD_DEVICE_MESH_H
#define TESSLOD_DEVICE_MESH_H

#include <stdio.h>
#include <string.h>

#include "device_stage.h"
#include "tesslod/cpu.h"

/* One device surface's evaluated mesh and what it was made from. */
typedef struct _tlod_item_mesh {
  tlod_cpu_mesh* cpu; /* NULL until the first evaluation */
  _tlod_list_snapshot snap;
} _tlod_item_mesh;

/* Software rasterisers by a GL_RENDERER or Vulkan deviceName: every vertex
 * costs CPU time there, so the CPU mesh (each welded vertex evaluated once,
 * and only when its list changed) beats evaluating every pattern vertex in
 * the vertex shader. */
static inline bool _tlod_software_renderer(const char* name) {
  static const char* const names[] = {"llvmpipe", "lavapipe", "softpipe", "SwiftShader"};
  for (size_t k = 0; name && k < sizeof(names) / sizeof(names[0]); k++)
    if (strstr(name, names[k])) return true;
  return false;
}

/* Resolves e for a device named `name` (software: a CPU device) into the
 * stats' cpu_mesh and gpu_eval_reason; hardware tessellation stays on the
 * GPU. `field` names the desc field ("desc.gl.gpu_eval"). */
static inline bool _tlod_resolve_gpu_eval(tlod_device_stats* st, tlod_gpu_eval e, bool software, bool hardware,
                                          const char* field, const char* name) {
  size_t n = sizeof(st->gpu_eval_reason);
  bool cpu = e == TLOD_GPU_EVAL_OFF || (e == TLOD_GPU_EVAL_DEFAULT && software);
  if (cpu && hardware) {
    cpu = false;
    snprintf(st->gpu_eval_reason, n, "hardware tessellation evaluates on the GPU");
  } else if (e != TLOD_GPU_EVAL_DEFAULT) {
    snprintf(st->gpu_eval_reason, n, "asked for: %s %s", field, tlod_gpu_eval_name(e));
  } else {
    snprintf(st->gpu_eval_reason, n, "auto: %.56s %s", name ? name : "?",
             software ? "is a software rasteriser" : "is not a software rasteriser");
  }
  st->cpu_mesh = cpu;
  return cpu;
}

/* Evaluates the item's list into m unless m holds it (*evaluated false). */
static inline tlod_result _tlod_item_mesh_update(tlod_context* ctx, const tlod_patterns* p, const _tlod_draw_ref* it,
                                                 _tlod_item_mesh* m, bool* evaluated) {
  *evaluated = !_tlod_snapshot_same(&m->snap, it);
  if (!*evaluated) return TLOD_SUCCESS;
  m->snap.valid = false;
  tlod_cpu_tessellate_desc td = {.draw_list = it->item->draw_list};
  tlod_result r = m->cpu ? tlod_cpu_tessellate_into(ctx, it->surface, p, &td, m->cpu)
                         : tlod_cpu_tessellate(ctx, it->surface, p, &td, &m->cpu);
  if (r == TLOD_SUCCESS) _tlod_snapshot_take(ctx, &m->snap, it);
  return r;
}

static inline void _tlod_item_mesh_free(tlod_context* ctx, _tlod_item_mesh* m) {
  tlod_cpu_mesh_destroy(ctx, m->cpu);
  tlod_context_free(ctx, m->snap.bytes);
  *m = (_tlod_item_mesh){0};
}

#endif
