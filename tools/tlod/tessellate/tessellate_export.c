/* tlod tessellate -- a cpu tessellation as an export mesh. */
#include "tessellate_export.h"

#include <string.h>

void tess_export_of(const tlod_cpu_mesh* out, const tlod_mesh* mesh, tess_export* e) {
  memset(e, 0, sizeof(*e));
  uint32_t count = out->attributes ? out->attribute_count : 0;
  for (uint32_t a = 0; a < count && a < TLOD_MAX_ATTRIBUTES; a++) {
    e->info[a] = tlod_mesh_query_attribute(mesh, a);
    e->attributes[a] = (tlod_export_attribute){.name = e->info[a].name,
                                               .components = e->info[a].components,
                                               .data = out->attributes[a],
                                               .stride = (uint32_t)(sizeof(float[4]) * count)};
  }
  e->mesh = (tlod_export_mesh){.vertex_count = out->vertex_count,
                               .positions = out->positions,
                               .normals = out->normals,
                               .triangle_count = out->triangle_count,
                               .indices = out->indices,
                               .attribute_count = count,
                               .attributes = count ? e->attributes : NULL};
}
