/* tlod tessellate -- uniform tessellation of a mesh on the CPU. */
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "commands.h"
#include "json_writer.h"
#include "tesslod/cpu.h"
#include "tlod_import.h"

static const char* const surface_names[] = {"flat", "phong", "pn", NULL};
static const char* const normal_names[] = {"keep", "angle", "area", NULL};

typedef struct tess_options {
  const char* in;
  const char* out;
  const char* stats;
  tlod_surface_type surface;
  float alpha;
  uint32_t level, threads;
  tlod_normal_mode normals;
  float crease;
  bool no_weld, quiet;
} tess_options;

typedef struct tess_timings {
  double load, mesh, surface, patterns, tessellate, write, total;
} tess_timings;

void tessellate_usage(FILE* f) {
  fprintf(f,
          "usage: tlod tessellate IN -o OUT [options]\n"
          "Tessellates every face of IN at one level and writes the result.\n"
          "  IN                  .gltf .glb .obj .ply file, or a built-in mesh (%s)\n"
          "  -o, --output OUT    .obj .ply .gltf .glb (format from the extension)\n"
          "  --surface S         flat | phong | pn (default phong; pn splits quads into triangles)\n"
          "  --alpha A           Phong shape factor in [0, 1] (default 0.75)\n"
          "  --level L           refinement level 0..%d: 2^L - 1 inserted vertices per edge (default 3)\n"
          "  --normals M         keep (given normals, normalised; default) | angle | area (recompute)\n"
          "  --crease DEG        with computed normals, split normals across edges sharper than DEG\n"
          "  --no-weld           keep each patch's own vertices, as a GPU draws them\n"
          "  --threads N         worker threads (default: all CPUs)\n"
          "  --stats FILE.json   write counts, repairs and timings\n"
          "  -q, --quiet         print nothing on success\n",
          cli_demo_names(), TLOD_MAX_LEVEL);
}

static int parse(int argc, char** argv, tess_options* o) {
  *o = (tess_options){.surface = TLOD_SURFACE_PHONG, .alpha = 0.75f, .level = 3, .normals = TLOD_NORMALS_KEEP};
  for (int i = 0; i < argc; i++) {
    const char* a = argv[i];
    const char* v = NULL;
    int e;
    if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
      tessellate_usage(stdout);
      exit(0);
    } else if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
      if (!(o->out = cli_value(argc, argv, &i))) return CLI_USAGE;
    } else if (!strcmp(a, "--stats")) {
      if (!(o->stats = cli_value(argc, argv, &i))) return CLI_USAGE;
    } else if (!strcmp(a, "--surface")) {
      if (!(v = cli_value(argc, argv, &i)) || (e = cli_parse_enum(a, v, surface_names)) < 0) return CLI_USAGE;
      o->surface = (tlod_surface_type)(TLOD_SURFACE_FLAT + e);
    } else if (!strcmp(a, "--normals")) {
      if (!(v = cli_value(argc, argv, &i)) || (e = cli_parse_enum(a, v, normal_names)) < 0) return CLI_USAGE;
      o->normals = (tlod_normal_mode)(TLOD_NORMALS_KEEP + e);
    } else if (!strcmp(a, "--alpha")) {
      if (!(v = cli_value(argc, argv, &i)) || !cli_parse_float(a, v, 0.0, 1.0, &o->alpha)) return CLI_USAGE;
    } else if (!strcmp(a, "--crease")) {
      if (!(v = cli_value(argc, argv, &i)) || !cli_parse_float(a, v, 0.0, 180.0, &o->crease)) return CLI_USAGE;
    } else if (!strcmp(a, "--level")) {
      if (!(v = cli_value(argc, argv, &i)) || !cli_parse_uint(a, v, 0, TLOD_MAX_LEVEL, &o->level)) return CLI_USAGE;
    } else if (!strcmp(a, "--threads")) {
      if (!(v = cli_value(argc, argv, &i)) || !cli_parse_uint(a, v, 1, 64, &o->threads)) return CLI_USAGE;
    } else if (!strcmp(a, "--no-weld")) {
      o->no_weld = true;
    } else if (!strcmp(a, "-q") || !strcmp(a, "--quiet")) {
      o->quiet = true;
    } else if (a[0] == '-' && a[1]) {
      return cli_error(CLI_USAGE, "tessellate: unknown option '%s' (see tlod tessellate --help)", a);
    } else if (!o->in) {
      o->in = a;
    } else {
      return cli_error(CLI_USAGE, "tessellate: unexpected argument '%s'", a);
    }
  }
  if (!o->in) return cli_error(CLI_USAGE, "tessellate: no input (see tlod tessellate --help)");
  if (!o->out) return cli_error(CLI_USAGE, "tessellate: no output: give -o OUT");
  return CLI_OK;
}

static bool write_stats(const tess_options* o, const cli_mesh* in, const tlod_mesh* mesh, const tlod_cpu_mesh* out,
                        const tess_timings* t) {
  char tmp[4096];
  snprintf(tmp, sizeof(tmp), "%s.tmp", o->stats);
  FILE* f = fopen(tmp, "w");
  if (!f) return false;
  tlod_mesh_info info = tlod_mesh_query_info(mesh);
  json_writer w;
  json_begin(&w, f);
  json_object_begin(&w, NULL);
  json_string(&w, "input", o->in);
  json_string(&w, "output", o->out);
  json_string(&w, "surface", surface_names[o->surface - TLOD_SURFACE_FLAT]);
  json_number(&w, "alpha", o->alpha);
  json_uint(&w, "level", o->level);
  json_bool(&w, "welded", !o->no_weld);
  json_object_begin(&w, "input_counts");
  json_uint(&w, "vertices", in->vertex_count);
  json_uint(&w, "faces", info.input_face_count);
  json_uint(&w, "triangles", info.triangle_count);
  json_uint(&w, "quads", info.quad_count);
  json_uint(&w, "quads_split_for_pn", in->quads_split);
  json_uint(&w, "welded_positions", info.welded_vertex_count);
  json_uint(&w, "edges", info.edge_count);
  json_uint(&w, "boundary_edges", info.boundary_edges);
  json_uint(&w, "non_manifold_edges", info.non_manifold_edges);
  json_uint(&w, "crease_edges", info.crease_edges);
  json_bool(&w, "closed", info.closed);
  json_object_end(&w);
  json_object_begin(&w, "repairs");
  json_uint(&w, "degenerate_faces_dropped", info.degenerate_faces_dropped);
  json_uint(&w, "normals_repaired", info.normals_repaired);
  json_uint(&w, "normals_computed", info.normals_computed);
  json_uint(&w, "unused_vertices", info.unused_vertices);
  json_object_end(&w);
  json_object_begin(&w, "output_counts");
  json_uint(&w, "vertices", out->vertex_count);
  json_uint(&w, "triangles", out->triangle_count);
  json_uint(&w, "pattern_triangles", out->pattern_triangles);
  json_uint(&w, "strip_triangles", out->strip_triangles);
  json_uint(&w, "strips", out->strips);
  json_object_end(&w);
  json_object_begin(&w, "timings_ms");
  json_number(&w, "load", t->load);
  json_number(&w, "mesh_create", t->mesh);
  json_number(&w, "surface_create", t->surface);
  json_number(&w, "patterns_create", t->patterns);
  json_number(&w, "tessellate", t->tessellate);
  json_number(&w, "write", t->write);
  json_number(&w, "total", t->total);
  json_object_end(&w);
  json_object_end(&w);
  bool ok = json_end(&w);
  ok = (fclose(f) == 0) && ok;
  if (!ok || rename(tmp, o->stats) != 0) {
    remove(tmp);
    return false;
  }
  return true;
}

typedef struct tess_run {
  tlod_context* ctx;
  cli_mesh in;
  tlod_mesh* mesh;
  tlod_surface* surface;
  tlod_patterns* patterns;
  tlod_cpu_mesh* out;
} tess_run;

static void run_free(tess_run* r) {
  tlod_cpu_mesh_destroy(r->ctx, r->out);
  tlod_patterns_destroy(r->patterns);
  tlod_surface_destroy(r->surface);
  tlod_mesh_destroy(r->mesh);
  tlod_context_destroy(r->ctx);
  cli_mesh_free(&r->in);
}

static int build(const tess_options* o, tess_run* r, tess_timings* t) {
  double t0 = cli_now_ms();
  int rc = cli_load(o->in, &r->in);
  if (rc == CLI_OK && o->surface == TLOD_SURFACE_PN) rc = cli_split_quads(&r->in);
  if (rc != CLI_OK) return rc;
  double t1 = cli_now_ms();
  if ((rc = cli_create_mesh(r->ctx, &r->in, o->normals, o->crease, &r->mesh)) != CLI_OK) return rc;
  double t2 = cli_now_ms();
  tlod_surface_desc sd = {.type = o->surface, .alpha = o->alpha, .alpha_set = true, .label = o->in};
  if (tlod_surface_create(r->ctx, r->mesh, &sd, &r->surface) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "%s", tlod_context_last_error(r->ctx));
  double t3 = cli_now_ms();
  tlod_patterns_desc pd = {.max_level = o->level ? o->level : 1};
  if (tlod_patterns_create(r->ctx, &pd, &r->patterns) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "%s", tlod_context_last_error(r->ctx));
  double t4 = cli_now_ms();
  tlod_cpu_tessellate_desc td = {.level = o->level, .no_weld = o->no_weld};
  if (tlod_cpu_tessellate(r->ctx, r->surface, r->patterns, &td, &r->out) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "%s", tlod_context_last_error(r->ctx));
  double t5 = cli_now_ms();
  *t = (tess_timings){.load = t1 - t0, .mesh = t2 - t1, .surface = t3 - t2, .patterns = t4 - t3, .tessellate = t5 - t4};
  return CLI_OK;
}

int cmd_tessellate(int argc, char** argv) {
  tess_options o;
  int rc = parse(argc, argv, &o);
  if (rc != CLI_OK) return rc;
  tess_run r = {0};
  tlod_context_desc cd = {.thread_count = o.threads, .label = "tlod"};
  if (tlod_context_create(&cd, &r.ctx) != TLOD_SUCCESS) return cli_error(CLI_FAILED, "cannot create a context");
  double start = cli_now_ms();
  tess_timings t = {0};
  rc = build(&o, &r, &t);
  if (rc == CLI_OK) {
    char err[512];
    double w0 = cli_now_ms();
    tlod_export_mesh em = {r.out->vertex_count, r.out->positions, r.out->normals, r.out->triangle_count,
                           r.out->indices};
    if (tlod_export_file(o.out, &em, err, sizeof(err)) != TLOD_SUCCESS) rc = cli_error(CLI_FAILED, "%s", err);
    t.write = cli_now_ms() - w0;
    t.total = cli_now_ms() - start;
  }
  if (rc == CLI_OK && o.stats && !write_stats(&o, &r.in, r.mesh, r.out, &t))
    rc = cli_error(CLI_FAILED, "cannot write stats file '%s'", o.stats);
  if (rc == CLI_OK && !o.quiet) {
    tlod_mesh_info info = tlod_mesh_query_info(r.mesh);
    printf("%s: %u faces (%u triangles, %u quads) -> %s level %u: %u vertices, %u triangles in %.1f ms -> %s\n", o.in,
           info.face_count, info.triangle_count, info.quad_count, surface_names[o.surface - TLOD_SURFACE_FLAT], o.level,
           r.out->vertex_count, r.out->triangle_count, t.tessellate, o.out);
    if (info.degenerate_faces_dropped || info.normals_repaired || r.in.quads_split)
      printf("  repairs: %u degenerate faces dropped, %u normals recomputed, %u quads split for PN\n",
             info.degenerate_faces_dropped, info.normals_repaired, r.in.quads_split);
    if (r.in.warnings[0]) printf("  import warnings:\n%s\n", r.in.warnings);
  }
  run_free(&r);
  return rc;
}
