/* tlod tessellate -- scene mode (tessellate_scene.h): load with keep_scene,
 * one core mesh and surface per part, tessellate, write with the scene. */
#include "tessellate_scene.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "common/mesh_load.h"
#include "tessellate_stats.h"
#include "tool_names.h"

static bool ends_with_nocase(const char* s, const char* tail) {
  const size_t n = strlen(s), k = strlen(tail);
  if (n < k) return false;
  for (size_t i = 0; i < k; i++)
    if (tolower((unsigned char)s[n - k + i]) != tail[i]) return false;
  return true;
}

bool tessellate_is_scene(const tess_options* o) {
  const bool gltf = ends_with_nocase(o->out, ".gltf") || ends_with_nocase(o->out, ".glb");
  return gltf && strncmp(o->in, "demo:", 5) != 0;
}

int tessellate_part(tess_scene* s, uint32_t p, const tlod_draw_list* dl, uint32_t level, tlod_cpu_mesh** out) {
  tlod_cpu_tessellate_desc td = {
      .level = level, .draw_list = dl, .no_weld = s->o->no_weld, .no_stitch = s->o->ad.no_stitch};
  if (tlod_cpu_tessellate(s->ctx, s->surfaces[p], s->patterns, &td, out) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "%s: part %u: %s", s->o->in, p, tlod_context_last_error(s->ctx));
  return CLI_OK;
}

static int make_part(tess_scene* s, uint32_t p) {
  const tess_options* o = s->o;
  cli_part_options po = {.normals = o->normals,
                         .crease_deg = o->crease < 0.0f ? 0.0f : o->crease,
                         .split_quads = o->surface == TLOD_SURFACE_PN};
  int rc = cli_create_part_mesh(s->ctx, s->r, p, &po, &s->meshes[p]);
  if (rc != CLI_OK) return rc;
  tlod_surface_desc sd = {.type = o->surface, .alpha_mode = TLOD_ALPHA_GLOBAL, .alpha = o->alpha, .label = o->in};
  if (tlod_surface_create(s->ctx, s->meshes[p], &sd, &s->surfaces[p]) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "%s: part %u: %s", o->in, p, tlod_context_last_error(s->ctx));
  return CLI_OK;
}

static int make_parts(tess_scene* s) {
  const uint32_t parts = s->r->part_count, level = s->o->ad.on ? s->o->ad.max_level : s->o->level;
  if (!parts) return cli_error(CLI_FAILED, "%s: no triangle geometry", s->o->in);
  s->meshes = calloc(parts, sizeof(tlod_mesh*));
  s->surfaces = calloc(parts, sizeof(tlod_surface*));
  s->parts = calloc(parts, sizeof(tess_item));
  s->node_first = calloc((size_t)s->r->node_count + 1, sizeof(uint32_t));
  if (!s->meshes || !s->surfaces || !s->parts || !s->node_first) return cli_error(CLI_FAILED, "out of memory");
  if (tlod_patterns_create(s->ctx, &(tlod_patterns_desc){.max_level = level ? level : 1}, &s->patterns) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "%s: %s", s->o->in, tlod_context_last_error(s->ctx));
  int rc = CLI_OK;
  for (uint32_t p = 0; rc == CLI_OK && p < parts; p++)
    rc = make_part(s, p);
  return rc;
}

static int tessellate_uniform(tess_scene* s) {
  int rc = CLI_OK;
  for (uint32_t n = 0; n < s->r->node_count; n++)
    s->node_first[n] = UINT32_MAX;
  for (uint32_t p = 0; rc == CLI_OK && p < s->r->part_count; p++)
    rc = tessellate_part(s, p, NULL, s->o->level, &s->parts[p].out);
  return rc;
}

static int write_scene(tess_scene* s) {
  const tlod_import_result* r = s->r;
  tlod_export_mesh* parts = calloc(r->part_count, sizeof(tlod_export_mesh));
  tlod_export_mesh* copies = calloc((size_t)s->copy_count + 1, sizeof(tlod_export_mesh));
  const tlod_export_mesh** node_parts = calloc((size_t)r->node_count + 1, sizeof(tlod_export_mesh*));
  int rc = parts && copies && node_parts ? CLI_OK : cli_error(CLI_FAILED, "out of memory");
  for (uint32_t p = 0; rc == CLI_OK && p < r->part_count; p++) {
    tess_export_of(s->parts[p].out, s->meshes[p], &s->parts[p].ex);
    parts[p] = s->parts[p].ex.mesh;
  }
  for (uint32_t c = 0; rc == CLI_OK && c < s->copy_count; c++) {
    tess_export_of(s->copies[c].out, s->meshes[s->copies[c].part], &s->copies[c].ex);
    copies[c] = s->copies[c].ex.mesh;
  }
  for (uint32_t n = 0; rc == CLI_OK && n < r->node_count; n++)
    node_parts[n] = s->node_first[n] == UINT32_MAX ? NULL : copies + s->node_first[n];
  char err[512];
  tlod_export_scene_desc d = {.source = r, .parts = parts, .node_parts = s->copy_count ? node_parts : NULL};
  if (rc == CLI_OK && tlod_export_scene_file_desc(s->o->out, &d, err, sizeof(err)) != TLOD_SUCCESS)
    rc = cli_error(CLI_FAILED, "%s", err);
  free(parts);
  free(copies);
  free((void*)node_parts);
  return rc;
}

static void free_scene(tess_scene* s) {
  for (uint32_t c = 0; s->copies && c < s->copy_count; c++)
    tlod_cpu_mesh_destroy(s->ctx, s->copies[c].out);
  for (uint32_t p = 0; s->r && p < s->r->part_count; p++) {
    if (s->parts) tlod_cpu_mesh_destroy(s->ctx, s->parts[p].out);
    if (s->surfaces) tlod_surface_destroy(s->surfaces[p]);
    if (s->meshes) tlod_mesh_destroy(s->meshes[p]);
  }
  free(s->copies);
  free(s->parts);
  free(s->surfaces);
  free(s->meshes);
  free(s->node_first);
  tlod_patterns_destroy(s->patterns);
  tlod_import_free(s->r);
  tlod_context_destroy(s->ctx);
}

/* What the glTF output leaves out, said once on stderr (even with -q: the
 * file is not what the input was). */
static void warn_left_out(const tlod_import_result* r) {
  if (r->skin_count || r->animation_count)
    fprintf(stderr, "tlod: warning: %u skins and %u animations are not written (the output keeps the rest pose)\n",
            r->skin_count, r->animation_count);
  for (uint32_t i = 0; i < r->image_count; i++) {
    const tlod_import_image* im = &r->images[i];
    if (!tlod_export_image_mime(im))
      fprintf(stderr, "tlod: warning: image %u%s%s%s: %s, not written\n", i, im->uri[0] ? " '" : "", im->uri,
              im->uri[0] ? "'" : "", im->encoded ? "neither PNG nor JPEG" : "could not be read");
  }
}

static tess_scene_stats stats_of(const tess_scene* s, double ms) {
  const tlod_import_result* r = s->r;
  tess_scene_stats st = {s->o,
                         r->part_count,
                         r->mesh_count,
                         r->node_count,
                         r->material_count,
                         r->texture_count,
                         r->image_count,
                         s->copy_count,
                         s->culled,
                         0,
                         0,
                         ms};
  for (uint32_t p = 0; p < r->part_count; p++)
    st.vertices += s->parts[p].out->vertex_count, st.triangles += s->parts[p].out->triangle_count;
  for (uint32_t c = 0; c < s->copy_count; c++)
    st.vertices += s->copies[c].out->vertex_count, st.triangles += s->copies[c].out->triangle_count;
  return st;
}

static void report(const tess_scene* s, const tess_scene_stats* st) {
  char mode[64];
  if (s->o->ad.on)
    snprintf(mode, sizeof(mode), "adaptive per instance (eps %.3g px)", (double)s->o->ad.epsilon);
  else
    snprintf(mode, sizeof(mode), "level %u", s->o->level);
  printf("%s: %u parts of %u meshes at %u nodes, %u materials -> %s %s: %llu vertices, %llu triangles in %.1f ms -> "
         "%s\n",
         s->o->in, st->parts, st->meshes, st->nodes, st->materials, tool_surface_name(s->o->surface), mode,
         (unsigned long long)st->vertices, (unsigned long long)st->triangles, st->total_ms, s->o->out);
  if (s->copy_count)
    printf("  %u parts written again for further instances (meshes \"<mesh>@<node>\")\n", s->copy_count);
  if (s->culled) printf("  %u culled instances written at level 0\n", s->culled);
  if (s->r->warnings[0]) printf("  import warnings:\n%s\n", s->r->warnings);
}

static int write_stats(const tess_scene_stats* st) {
  char err[1024];
  if (!tessellate_write_scene_stats(st, err, sizeof(err))) return cli_error(CLI_FAILED, "stats: %s", err);
  return CLI_OK;
}

static int run_scene(tess_scene* s) {
  int rc = cli_load_scene(s->o->in, &s->r);
  if (rc == CLI_OK) rc = make_parts(s);
  if (rc == CLI_OK) rc = s->o->ad.on ? tessellate_instances(s) : tessellate_uniform(s);
  if (rc == CLI_OK) rc = write_scene(s);
  return rc;
}

int tessellate_scene(const tess_options* o) {
  tess_scene s = {.o = o};
  tlod_context_desc cd = {.thread_count = o->threads, .label = "tlod"};
  if (tlod_context_create(&cd, &s.ctx) != TLOD_SUCCESS) return cli_error(CLI_FAILED, "cannot create a context");
  double start = cli_now_ms();
  int rc = run_scene(&s);
  if (rc == CLI_OK) warn_left_out(s.r);
  tess_scene_stats st = rc == CLI_OK ? stats_of(&s, cli_now_ms() - start) : (tess_scene_stats){0};
  if (rc == CLI_OK && o->stats) rc = write_stats(&st);
  if (rc == CLI_OK && !o->quiet) report(&s, &st);
  free_scene(&s);
  return rc;
}
