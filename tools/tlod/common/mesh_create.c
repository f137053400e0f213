/* tlod -- a core mesh from a loaded one, with its attributes. */
#include "cli.h"
#include "mesh_load.h"

int cli_create_mesh(tlod_context* ctx, const cli_mesh* m, tlod_normal_mode normals, float crease_deg, tlod_mesh** out) {
  tlod_attribute_desc attributes[TLOD_MAX_ATTRIBUTES];
  for (uint32_t a = 0; a < m->attribute_count; a++)
    attributes[a] = (tlod_attribute_desc){
        .data = m->attributes[a].data, .components = m->attributes[a].components, .name = m->attributes[a].name};
  tlod_mesh_desc desc = {
      .positions = m->positions,
      .normals = m->normals,
      .vertex_count = m->vertex_count,
      .indices = m->indices,
      .index_count = m->index_count,
      .face_type = m->face_sizes ? TLOD_FACE_MIXED : TLOD_FACE_TRIANGLES,
      .face_sizes = m->face_sizes,
      .face_count = m->face_sizes ? m->face_count : 0,
      .normal_mode = normals,
      .crease_angle_deg = crease_deg,
      .label = m->name,
      .attributes = m->attribute_count ? attributes : NULL,
      .attribute_count = m->attribute_count,
      .face_nodes = m->face_nodes,
  };
  if (tlod_mesh_create(ctx, &desc, out) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "%s", tlod_context_last_error(ctx));
  return CLI_OK;
}
