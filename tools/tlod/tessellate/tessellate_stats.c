/* tlod tessellate -- the --stats file: counts, repairs, timings and, in
 * adaptive mode, the frame's levels. */
#include "tessellate_stats.h"

#include <stdlib.h>

#include "common/lod_json.h"
#include "tlod_atomic_file.h"
#include "tool_names.h"

/* Levels per face as loaded: the largest of its patches, -1 when culled
 * (or dropped as degenerate). */
static void write_levels(json_writer* w, const cli_mesh* in, const tlod_mesh* mesh, const tlod_draw_list* dl) {
  int* levels = malloc(sizeof(int) * ((size_t)in->source_face_count + 1));
  if (!levels) return;
  for (uint32_t f = 0; f < in->source_face_count; f++)
    levels[f] = -1;
  for (uint32_t p = 0; p < dl->patch_count; p++) {
    uint32_t face = tlod_mesh_face_input_index(mesh, p);
    if (in->face_source) face = in->face_source[face];
    if (face < in->source_face_count && dl->levels[p] > levels[face]) levels[face] = dl->levels[p];
  }
  json_array_begin(w, "levels");
  for (uint32_t f = 0; f < in->source_face_count; f++)
    json_int(w, NULL, levels[f]);
  json_array_end(w);
  free(levels);
}

static void write_adaptive(json_writer* w, const tess_options* o, const tlod_draw_list* dl, const tlod_cpu_mesh* out) {
  json_object_begin(w, "adaptive");
  json_array_begin(w, "eye");
  for (int i = 0; i < 3; i++)
    json_number(w, NULL, o->ad.cam.eye[i]);
  json_array_end(w);
  json_string(w, "policy", tool_policy_name(o->ad.policy));
  json_number(w, "epsilon", o->ad.epsilon);
  json_number(w, "effective_epsilon", dl->effective_epsilon);
  json_uint(w, "max_level", o->ad.max_level);
  json_uint(w, "viewport_width", o->ad.width);
  json_uint(w, "viewport_height", o->ad.height);
  json_uint(w, "patches", dl->patch_count);
  json_uint(w, "culled", dl->culled);
  json_uint(w, "pattern_triangles", dl->pattern_triangles);
  json_uint(w, "strip_triangles", out->strip_triangles);
  json_uint(w, "strip_triangles_planned", dl->strip_triangles);
  json_uint(w, "strips", dl->strip_count);
  json_number(w, "e_max_min", dl->e_max_min);
  json_number(w, "e_max_max", dl->e_max_max);
  json_level_histogram(w, "level_histogram", dl->level_histogram, o->ad.max_level + 1);
  json_stage_ms(w, "stage_ms", dl->stage_ms);
  json_object_end(w);
}

static void write_input_counts(json_writer* w, const cli_mesh* in, const tlod_mesh_info* info) {
  json_object_begin(w, "input_counts");
  json_uint(w, "vertices", in->vertex_count);
  json_uint(w, "faces", info->input_face_count);
  json_uint(w, "triangles", info->triangle_count);
  json_uint(w, "quads", info->quad_count);
  json_uint(w, "quads_split_for_pn", in->quads_split);
  json_uint(w, "welded_positions", info->welded_vertex_count);
  json_uint(w, "edges", info->edge_count);
  json_uint(w, "boundary_edges", info->boundary_edges);
  json_uint(w, "non_manifold_edges", info->non_manifold_edges);
  json_uint(w, "crease_edges", info->crease_edges);
  json_bool(w, "closed", info->closed);
  json_object_end(w);
}

static void write_repairs(json_writer* w, const tlod_mesh_info* info) {
  json_object_begin(w, "repairs");
  json_uint(w, "degenerate_faces_dropped", info->degenerate_faces_dropped);
  json_uint(w, "normals_repaired", info->normals_repaired);
  json_uint(w, "normals_computed", info->normals_computed);
  json_uint(w, "unused_vertices", info->unused_vertices);
  json_object_end(w);
}

static void write_output_counts(json_writer* w, const tlod_cpu_mesh* out) {
  json_object_begin(w, "output_counts");
  json_uint(w, "vertices", out->vertex_count);
  json_uint(w, "triangles", out->triangle_count);
  json_uint(w, "pattern_triangles", out->pattern_triangles);
  json_uint(w, "strip_triangles", out->strip_triangles);
  json_uint(w, "strips", out->strips);
  json_object_end(w);
}

static void write_timings(json_writer* w, const tess_timings* t) {
  json_object_begin(w, "timings_ms");
  json_number(w, "load", t->load);
  json_number(w, "mesh_create", t->mesh);
  json_number(w, "surface_create", t->surface);
  json_number(w, "patterns_create", t->patterns);
  json_number(w, "tessellate", t->tessellate);
  json_number(w, "write", t->write);
  json_number(w, "total", t->total);
  json_object_end(w);
}

static void write_settings(json_writer* w, const tess_options* o) {
  json_string(w, "input", o->in);
  json_string(w, "output", o->out);
  json_string(w, "surface", tool_surface_name(o->surface));
  json_number(w, "alpha", o->alpha);
  json_uint(w, "level", o->level);
  json_bool(w, "welded", !o->no_weld);
}

static bool stats_json(FILE* f, const void* data) {
  const tess_stats* s = data;
  tlod_mesh_info info = tlod_mesh_query_info(s->mesh);
  json_writer w;
  json_begin(&w, f);
  json_object_begin(&w, NULL);
  write_settings(&w, s->o);
  write_input_counts(&w, s->in, &info);
  write_repairs(&w, &info);
  write_output_counts(&w, s->out);
  if (s->dl) {
    write_adaptive(&w, s->o, s->dl, s->out);
    write_levels(&w, s->in, s->mesh, s->dl);
  }
  write_timings(&w, s->t);
  json_object_end(&w);
  return json_end(&w);
}

bool tessellate_write_stats(const tess_stats* s, char* error, size_t error_size) {
  return tlod_atomic_file_write(s->o->stats, stats_json, s, error, error_size);
}

static bool scene_stats_json(FILE* f, const void* data) {
  const tess_scene_stats* s = data;
  json_writer w;
  json_begin(&w, f);
  json_object_begin(&w, NULL);
  write_settings(&w, s->o);
  json_object_begin(&w, "scene");
  json_uint(&w, "parts", s->parts);
  json_uint(&w, "meshes", s->meshes);
  json_uint(&w, "nodes", s->nodes);
  json_uint(&w, "materials", s->materials);
  json_uint(&w, "textures", s->textures);
  json_uint(&w, "images", s->images);
  json_uint(&w, "instance_copies", s->copies);
  json_uint(&w, "culled_instances", s->culled);
  json_object_end(&w);
  json_object_begin(&w, "output_counts");
  json_uint(&w, "vertices", s->vertices);
  json_uint(&w, "triangles", s->triangles);
  json_object_end(&w);
  json_object_begin(&w, "timings_ms");
  json_number(&w, "total", s->total_ms);
  json_object_end(&w);
  json_object_end(&w);
  return json_end(&w);
}

bool tessellate_write_scene_stats(const tess_scene_stats* s, char* error, size_t error_size) {
  return tlod_atomic_file_write(s->o->stats, scene_stats_json, s, error, error_size);
}
