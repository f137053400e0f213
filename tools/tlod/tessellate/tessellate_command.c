/* tlod tessellate -- uniform or view-dependent tessellation of a mesh on the
 * CPU, written to a file. */
#include <stdio.h>

#include "cli.h"
#include "commands.h"
#include "common/scene_setup.h"
#include "tessellate_export.h"
#include "tessellate_frame.h"
#include "tessellate_options.h"
#include "tessellate_scene.h"
#include "tessellate_stats.h"
#include "tlod_import.h"
#include "tool_names.h"

typedef struct tess_run {
  tlod_context* ctx;
  scene_setup scene;
  tlod_scheduler* scheduler;
  const tlod_draw_list* dl; /* adaptive mode */
  tlod_cpu_mesh* out;
  tess_timings t;
} tess_run;

static void run_free(tess_run* r) {
  tlod_cpu_mesh_destroy(r->ctx, r->out);
  tlod_scheduler_destroy(r->scheduler);
  scene_setup_destroy(&r->scene);
  tlod_context_destroy(r->ctx);
}

static scene_setup_desc setup_of(const tess_options* o) {
  uint32_t level = o->ad.on ? o->ad.max_level : o->level;
  return (scene_setup_desc){.input = o->in,
                            .surface = o->surface,
                            .alpha_mode = TLOD_ALPHA_GLOBAL,
                            .alpha = o->alpha,
                            .normals = o->normals,
                            .crease_deg = o->crease,
                            .pattern_level = level ? level : 1};
}

static int tessellate(const tess_options* o, tess_run* r) {
  scene_setup_desc sd = setup_of(o);
  int rc = scene_setup_create(r->ctx, &sd, &r->scene);
  if (rc != CLI_OK) return rc;
  double t0 = cli_now_ms();
  tlod_cpu_tessellate_desc td = {.level = o->level, .no_weld = o->no_weld, .no_stitch = o->ad.no_stitch};
  if (o->ad.on && (rc = tessellate_plan_frame(o, r->ctx, &r->scene, &r->scheduler, &r->dl)) != CLI_OK) return rc;
  td.draw_list = r->dl;
  if (tlod_cpu_tessellate(r->ctx, r->scene.surface, r->scene.patterns, &td, &r->out) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "%s", tlod_context_last_error(r->ctx));
  const scene_setup* s = &r->scene;
  r->t = (tess_timings){.load = s->load_ms,
                        .mesh = s->mesh_ms,
                        .surface = s->surface_ms,
                        .patterns = s->patterns_ms,
                        .tessellate = cli_now_ms() - t0};
  return CLI_OK;
}

static int write_output(const tess_options* o, tess_run* r) {
  char err[512];
  double w0 = cli_now_ms();
  tess_export em;
  tess_export_of(r->out, r->scene.mesh, &em);
  int rc =
      tlod_export_file(o->out, &em.mesh, err, sizeof(err)) == TLOD_SUCCESS ? CLI_OK : cli_error(CLI_FAILED, "%s", err);
  r->t.write = cli_now_ms() - w0;
  return rc;
}

static int write_stats(const tess_options* o, const tess_run* r) {
  char err[1024];
  tess_stats st = {o, &r->scene.in, r->scene.mesh, r->out, r->dl, &r->t};
  if (!tessellate_write_stats(&st, err, sizeof(err))) return cli_error(CLI_FAILED, "stats: %s", err);
  return CLI_OK;
}

static void print_levels(const tess_options* o, const tlod_draw_list* dl) {
  printf("  levels:");
  for (uint32_t l = 0; l <= o->ad.max_level; l++)
    printf(" %u", dl->level_histogram[l]);
  printf(" (patches per level 0..%u), %u culled, %u strips\n", o->ad.max_level, dl->culled, dl->strip_count);
}

static void print_report(const tess_options* o, const tess_run* r) {
  tlod_mesh_info info = tlod_mesh_query_info(r->scene.mesh);
  const cli_mesh* in = &r->scene.in;
  char mode[64];
  if (r->dl) {
    snprintf(mode, sizeof(mode), "adaptive (eps %.3g px)", (double)r->dl->effective_epsilon);
  } else {
    snprintf(mode, sizeof(mode), "level %u", o->level);
  }
  printf("%s: %u faces (%u triangles, %u quads) -> %s %s: %u vertices, %u triangles (%u in strips) in %.1f ms -> %s\n",
         o->in, info.face_count, info.triangle_count, info.quad_count, tool_surface_name(o->surface), mode,
         r->out->vertex_count, r->out->triangle_count, r->out->strip_triangles, r->t.tessellate, o->out);
  if (r->dl) print_levels(o, r->dl);
  if (info.degenerate_faces_dropped || info.normals_repaired || in->quads_split)
    printf("  repairs: %u degenerate faces dropped, %u normals recomputed, %u quads split for PN\n",
           info.degenerate_faces_dropped, info.normals_repaired, in->quads_split);
  if (in->warnings[0]) printf("  import warnings:\n%s\n", in->warnings);
}

int cmd_tessellate(int argc, char** argv) {
  tess_options o;
  int rc = tessellate_parse(argc, argv, &o);
  if (rc != CLI_OK) return rc;
  if (tessellate_is_scene(&o)) return tessellate_scene(&o);
  tess_run r = {0};
  tlod_context_desc cd = {.thread_count = o.threads, .label = "tlod"};
  if (tlod_context_create(&cd, &r.ctx) != TLOD_SUCCESS) return cli_error(CLI_FAILED, "cannot create a context");
  double start = cli_now_ms();
  rc = tessellate(&o, &r);
  o.surface = r.scene.surface_type; /* auto resolved: the report and the stats name the type made */
  if (rc == CLI_OK) rc = write_output(&o, &r);
  r.t.total = cli_now_ms() - start;
  if (rc == CLI_OK && o.stats) rc = write_stats(&o, &r);
  if (rc == CLI_OK && !o.quiet) print_report(&o, &r);
  run_free(&r);
  return rc;
}
