/* tlod tessellate -- uniform tessellation of a mesh on the CPU. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "camera.h"
#include "cli.h"
#include "commands.h"
#include "json_writer.h"
#include "tesslod/cpu.h"
#include "tlod_import.h"

static const char* const surface_names[] = {"flat", "phong", "pn", NULL};
static const char* const normal_names[] = {"keep", "angle", "area", NULL};
static const char* const policy_names[] = {"error", "silhouette", "hybrid", NULL};

/* Adaptive mode: one camera, one scheduler frame. */
typedef struct adaptive_options {
  bool on;
  tool_camera cam;
  uint32_t width, height, max_level;
  float epsilon;
  tlod_lod_policy policy;
  bool no_stitch;
} adaptive_options;

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
  adaptive_options ad;
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
          "  --stats FILE.json   write counts, repairs and timings (adaptive: levels per input face, ...)\n"
          "  -q, --quiet         print nothing on success\n"
          "Adaptive (view-dependent) when a camera is given:\n"
          "  --eye X,Y,Z         camera position\n"
          "  --target X,Y,Z      point looked at (default: the mesh's bounding-box centre)\n"
          "  --up X,Y,Z          up direction (default 0,1,0)\n"
          "  --fovy DEG          vertical field of view (default 45; 0: orthographic, see --ortho-height)\n"
          "  --ortho-height H    orthographic view height in world units\n"
          "  --size WxH          viewport in pixels (default 1280x720)\n"
          "  --epsilon PX        screen-space error bound in pixels (default 0.5)\n"
          "  --policy P          error | silhouette | hybrid (default hybrid)\n"
          "  --max-level L       finest level allowed, 1..%d (default 6)\n"
          "  --no-stitch         leave out connection strips (shows the cracks)\n",
          cli_demo_names(), TLOD_MAX_LEVEL, TLOD_MAX_LEVEL);
}

static int parse(int argc, char** argv, tess_options* o) {
  *o = (tess_options){.surface = TLOD_SURFACE_PHONG, .alpha = 0.75f, .level = 3, .normals = TLOD_NORMALS_KEEP};
  o->ad = (adaptive_options){.cam = {.up = {0, 1, 0}, .fovy_deg = 45.0f, .target = {NAN, NAN, NAN}},
                             .width = 1280,
                             .height = 720,
                             .max_level = 6,
                             .epsilon = 0.5f,
                             .policy = TLOD_POLICY_HYBRID};
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
    } else if (!strcmp(a, "--eye") || !strcmp(a, "--target") || !strcmp(a, "--up")) {
      float* dst = a[2] == 'e' ? o->ad.cam.eye : (a[2] == 't' ? o->ad.cam.target : o->ad.cam.up);
      if (!(v = cli_value(argc, argv, &i))) return CLI_USAGE;
      if (!camera_parse_vec3(v, dst)) return cli_error(CLI_USAGE, "%s: expected X,Y,Z, got '%s'", a, v);
      if (a[2] == 'e') o->ad.on = true;
    } else if (!strcmp(a, "--fovy")) {
      if (!(v = cli_value(argc, argv, &i)) || !cli_parse_float(a, v, 0.0, 179.0, &o->ad.cam.fovy_deg)) return CLI_USAGE;
    } else if (!strcmp(a, "--ortho-height")) {
      if (!(v = cli_value(argc, argv, &i)) || !cli_parse_float(a, v, 1e-30, 1e30, &o->ad.cam.ortho_height))
        return CLI_USAGE;
    } else if (!strcmp(a, "--size")) {
      char tail;
      if (!(v = cli_value(argc, argv, &i))) return CLI_USAGE;
      if (sscanf(v, "%ux%u%c", &o->ad.width, &o->ad.height, &tail) != 2 || !o->ad.width || !o->ad.height ||
          o->ad.width > 65536 || o->ad.height > 65536)
        return cli_error(CLI_USAGE, "--size: expected WxH (1..65536), got '%s'", v);
    } else if (!strcmp(a, "--epsilon")) {
      if (!(v = cli_value(argc, argv, &i)) || !cli_parse_float(a, v, 1e-6, 1e9, &o->ad.epsilon)) return CLI_USAGE;
    } else if (!strcmp(a, "--policy")) {
      if (!(v = cli_value(argc, argv, &i)) || (e = cli_parse_enum(a, v, policy_names)) < 0) return CLI_USAGE;
      o->ad.policy = (tlod_lod_policy)(TLOD_POLICY_ERROR + e);
    } else if (!strcmp(a, "--max-level")) {
      if (!(v = cli_value(argc, argv, &i)) || !cli_parse_uint(a, v, 1, TLOD_MAX_LEVEL, &o->ad.max_level))
        return CLI_USAGE;
    } else if (!strcmp(a, "--no-stitch")) {
      o->ad.no_stitch = true;
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
  if (o->ad.on && o->ad.cam.fovy_deg == 0.0f && o->ad.cam.ortho_height == 0.0f)
    return cli_error(CLI_USAGE, "tessellate: --fovy 0 (orthographic) needs --ortho-height");
  return CLI_OK;
}

static const char* const stage_names[TLOD_STAGE_NUM] = {"silhouette", "metric", "levels", "morph", "strips"};

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
  static const char* const policies[] = {"hybrid", "error", "silhouette", "hybrid"};
  json_object_begin(w, "adaptive");
  json_array_begin(w, "eye");
  for (int i = 0; i < 3; i++)
    json_number(w, NULL, o->ad.cam.eye[i]);
  json_array_end(w);
  json_string(w, "policy", policies[o->ad.policy]);
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
  json_array_begin(w, "level_histogram");
  for (uint32_t l = 0; l <= o->ad.max_level; l++)
    json_uint(w, NULL, dl->level_histogram[l]);
  json_array_end(w);
  json_object_begin(w, "stage_ms");
  for (int s = 0; s < TLOD_STAGE_NUM; s++)
    json_number(w, stage_names[s], dl->stage_ms[s]);
  json_object_end(w);
  json_object_end(w);
}

static bool write_stats(const tess_options* o, const cli_mesh* in, const tlod_mesh* mesh, const tlod_cpu_mesh* out,
                        const tlod_draw_list* dl, const tess_timings* t) {
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
  if (dl) {
    write_adaptive(&w, o, dl, out);
    write_levels(&w, in, mesh, dl);
  }
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
  tlod_scheduler* scheduler;
  tlod_cpu_mesh* out;
} tess_run;

static void run_free(tess_run* r) {
  tlod_cpu_mesh_destroy(r->ctx, r->out);
  tlod_scheduler_destroy(r->scheduler);
  tlod_patterns_destroy(r->patterns);
  tlod_surface_destroy(r->surface);
  tlod_mesh_destroy(r->mesh);
  tlod_context_destroy(r->ctx);
  cli_mesh_free(&r->in);
}

/* One scheduler frame for the camera of the options. */
static int plan_frame(const tess_options* o, tess_run* r, const tlod_draw_list** out) {
  tlod_mesh_info info = tlod_mesh_query_info(r->mesh);
  tool_camera cam = o->ad.cam;
  if (isnan(cam.target[0])) {
    for (int i = 0; i < 3; i++)
      cam.target[i] = 0.5f * (info.bbox_min[i] + info.bbox_max[i]);
  }
  camera_fit_planes(cam.eye, info.bbox_min, info.bbox_max, &cam.near_z, &cam.far_z);
  tlod_view_desc view = {.viewport_width = o->ad.width, .viewport_height = o->ad.height};
  float aspect = (float)o->ad.width / (float)o->ad.height;
  camera_look_at(cam.eye, cam.target, cam.up, view.view);
  if (cam.fovy_deg > 0.0f) {
    camera_perspective(cam.fovy_deg, aspect, cam.near_z, cam.far_z, view.proj);
  } else {
    camera_orthographic(cam.ortho_height, aspect, cam.near_z, cam.far_z, view.proj);
  }
  tlod_scheduler_desc sd = {.epsilon_px = o->ad.epsilon,
                            .max_level = o->ad.max_level,
                            .policy = o->ad.policy,
                            .morph = TLOD_MORPH_NONE,
                            .label = o->in};
  if (tlod_scheduler_create(r->ctx, r->surface, r->patterns, &sd, &r->scheduler) != TLOD_SUCCESS ||
      tlod_scheduler_update(r->scheduler, &(tlod_frame_desc){.views = &view, .view_count = 1}) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "%s", tlod_context_last_error(r->ctx));
  *out = tlod_scheduler_draw_list(r->scheduler, 0);
  return CLI_OK;
}

static int build(const tess_options* o, tess_run* r, tess_timings* t) {
  double t0 = cli_now_ms();
  int rc = cli_load(o->in, &r->in);
  if (rc == CLI_OK && o->surface == TLOD_SURFACE_PN) rc = cli_split_quads(&r->in);
  if (rc != CLI_OK) return rc;
  double t1 = cli_now_ms();
  if ((rc = cli_create_mesh(r->ctx, &r->in, o->normals, o->crease, &r->mesh)) != CLI_OK) return rc;
  double t2 = cli_now_ms();
  tlod_surface_desc sd = {.type = o->surface, .alpha_mode = TLOD_ALPHA_GLOBAL, .alpha = o->alpha, .label = o->in};
  if (tlod_surface_create(r->ctx, r->mesh, &sd, &r->surface) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "%s", tlod_context_last_error(r->ctx));
  double t3 = cli_now_ms();
  uint32_t max_level = o->ad.on ? o->ad.max_level : o->level;
  tlod_patterns_desc pd = {.max_level = max_level ? max_level : 1};
  if (tlod_patterns_create(r->ctx, &pd, &r->patterns) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "%s", tlod_context_last_error(r->ctx));
  double t4 = cli_now_ms();
  tlod_cpu_tessellate_desc td = {.level = o->level, .no_weld = o->no_weld, .no_stitch = o->ad.no_stitch};
  if (o->ad.on && (rc = plan_frame(o, r, &td.draw_list)) != CLI_OK) return rc;
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
  if (rc == CLI_OK && o.stats &&
      !write_stats(&o, &r.in, r.mesh, r.out, r.scheduler ? tlod_scheduler_draw_list(r.scheduler, 0) : NULL, &t))
    rc = cli_error(CLI_FAILED, "cannot write stats file '%s'", o.stats);
  if (rc == CLI_OK && !o.quiet) {
    tlod_mesh_info info = tlod_mesh_query_info(r.mesh);
    char mode[64];
    if (r.scheduler) {
      snprintf(mode, sizeof(mode), "adaptive (eps %.3g px)",
               (double)tlod_scheduler_draw_list(r.scheduler, 0)->effective_epsilon);
    } else {
      snprintf(mode, sizeof(mode), "level %u", o.level);
    }
    printf(
        "%s: %u faces (%u triangles, %u quads) -> %s %s: %u vertices, %u triangles (%u in strips) in %.1f ms -> %s\n",
        o.in, info.face_count, info.triangle_count, info.quad_count, surface_names[o.surface - TLOD_SURFACE_FLAT], mode,
        r.out->vertex_count, r.out->triangle_count, r.out->strip_triangles, t.tessellate, o.out);
    if (r.scheduler) {
      const tlod_draw_list* dl = tlod_scheduler_draw_list(r.scheduler, 0);
      printf("  levels:");
      for (uint32_t l = 0; l <= o.ad.max_level; l++)
        printf(" %u", dl->level_histogram[l]);
      printf(" (patches per level 0..%u), %u culled, %u strips\n", o.ad.max_level, dl->culled, dl->strip_count);
    }
    if (info.degenerate_faces_dropped || info.normals_repaired || r.in.quads_split)
      printf("  repairs: %u degenerate faces dropped, %u normals recomputed, %u quads split for PN\n",
             info.degenerate_faces_dropped, info.normals_repaired, r.in.quads_split);
    if (r.in.warnings[0]) printf("  import warnings:\n%s\n", r.in.warnings);
  }
  run_free(&r);
  return rc;
}
