/* tlod bench --suite objects -- the per-object cost of a scene: 50
 * instances of one small mesh (one surface drawn 50 times, one scheduler
 * and one draw item per instance, planned with view * world, as tlod play
 * draws a glTF scene) against the same 50 copies merged into one object
 * (the same triangles, one scheduler, one item). Frame = every scheduler
 * update + one device draw (finish); wall clock, min and median over the
 * frames, per backend (cpu, and --backend gl or vulkan when built) and
 * mode; vulkan's draw time includes its submit (lavapipe draws there). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench_eval.h"
#include "bench_gl.h"
#include "bench_stats.h"
#include "cli.h"
#include "common/anim_sample.h"
#include "common/camera.h"
#include "common/gpu_target.h"
#include "common/mesh_load.h"
#include "tesslod/backend.h"

#define OBJ_COLS 10
#define OBJ_ROWS 5
#define OBJ_COUNT (OBJ_COLS * OBJ_ROWS)
#define OBJ_SPACING 3.0f
#define OBJ_W 800
#define OBJ_H 450

typedef struct obj_scene {
  tlod_context* ctx;
  tlod_mesh* mesh;
  tlod_surface* surface;
  uint32_t count; /* instances drawn: OBJ_COUNT of the small mesh, or 1 of the merged one */
  float world[OBJ_COUNT][16];
} obj_scene;

static void grid_offset(uint32_t k, float out[3]) {
  out[0] = OBJ_SPACING * ((float)(k % OBJ_COLS) - 0.5f * (OBJ_COLS - 1));
  out[1] = OBJ_SPACING * ((float)(k / OBJ_COLS) - 0.5f * (OBJ_ROWS - 1));
  out[2] = 0.0f;
}

/* copies of m: OBJ_COUNT copies at the grid offsets merged into one mesh, or m itself. */
static int make_mesh(tlod_context* ctx, const cli_mesh* m, uint32_t copies, tlod_mesh** out) {
  size_t nv = (size_t)m->vertex_count * copies, ni = (size_t)m->index_count * copies;
  float *pos = malloc(sizeof(float) * 3 * nv), *nrm = malloc(sizeof(float) * 3 * nv);
  uint32_t* ix = malloc(sizeof(uint32_t) * ni);
  uint8_t* fs = m->face_sizes ? malloc((size_t)m->face_count * copies) : NULL;
  int rc = pos && nrm && ix && (fs || !m->face_sizes) && m->normals ? CLI_OK : cli_error(CLI_FAILED, "out of memory");
  for (uint32_t c = 0; rc == CLI_OK && c < copies; c++) {
    float off[3] = {0, 0, 0};
    if (copies > 1) grid_offset(c, off);
    for (size_t v = 0; v < 3 * (size_t)m->vertex_count; v++) {
      pos[c * 3 * (size_t)m->vertex_count + v] = m->positions[v] + off[v % 3];
      nrm[c * 3 * (size_t)m->vertex_count + v] = m->normals[v];
    }
    for (size_t i = 0; i < m->index_count; i++)
      ix[c * (size_t)m->index_count + i] = m->indices[i] + c * m->vertex_count;
    if (fs) memcpy(fs + (size_t)c * m->face_count, m->face_sizes, m->face_count);
  }
  tlod_mesh_desc d = {.positions = pos,
                      .normals = nrm,
                      .vertex_count = (uint32_t)nv,
                      .indices = ix,
                      .index_count = (uint32_t)ni,
                      .face_type = fs ? TLOD_FACE_MIXED : TLOD_FACE_TRIANGLES,
                      .face_sizes = fs,
                      .face_count = fs ? m->face_count * copies : 0};
  if (rc == CLI_OK && tlod_mesh_create(ctx, &d, out) != TLOD_SUCCESS)
    rc = cli_error(CLI_FAILED, "%s", tlod_context_last_error(ctx));
  free(pos), free(nrm), free(ix), free(fs);
  return rc;
}

static void scene_free(obj_scene* s) {
  tlod_surface_destroy(s->surface);
  tlod_mesh_destroy(s->mesh);
  s->surface = NULL, s->mesh = NULL;
}

static int scene_make(tlod_context* ctx, const cli_mesh* m, bool merged, obj_scene* s) {
  *s = (obj_scene){.ctx = ctx, .count = merged ? 1 : OBJ_COUNT};
  int rc = make_mesh(ctx, m, merged ? OBJ_COUNT : 1, &s->mesh);
  if (rc == CLI_OK &&
      tlod_surface_create(ctx, s->mesh, &(tlod_surface_desc){.type = TLOD_SURFACE_PHONG}, &s->surface) != TLOD_SUCCESS)
    rc = cli_error(CLI_FAILED, "%s", tlod_context_last_error(ctx));
  for (uint32_t k = 0; k < s->count; k++) {
    anim_trs trs = {{0, 0, 0}, {0, 0, 0, 1}, {1, 1, 1}};
    if (!merged) grid_offset(k, trs.translation);
    anim_trs_matrix(&trs, s->world[k]);
  }
  return rc;
}

/* The camera of frame k: in front of the grid, swinging a little. */
static void frame_view(uint32_t k, tlod_view_desc* v) {
  float eye[3] = {6.0f * sinf(0.05f * (float)k), 4.0f, 24.0f}, target[3] = {0, 0, 0}, up[3] = {0, 1, 0};
  *v = (tlod_view_desc){.viewport_width = OBJ_W, .viewport_height = OBJ_H};
  camera_look_at(eye, target, up, v->view);
  camera_perspective(45.0f, (float)OBJ_W / OBJ_H, 1.0f, 100.0f, v->proj);
}

typedef struct obj_figures {
  double frame[2], sched[2], draw[2]; /* min, median ms */
  uint64_t triangles;
} obj_figures;

/* One frame: every instance's scheduler, then one draw of every item. */
static int run_frame(obj_scene* s, tlod_platform* p, tlod_device* dev, tlod_device_surface* ds, tlod_scheduler** sch,
                     tlod_draw_item* items, uint32_t k, double t[3]) {
  tlod_view_desc v, ov;
  frame_view(k, &v);
  double t0 = cli_now_ms();
  for (uint32_t i = 0; i < s->count; i++) {
    ov = v;
    anim_mat4_mul(v.view, s->world[i], ov.view); /* translations: rigid */
    tlod_scheduler_update(sch[i], &(tlod_frame_desc){.views = &ov, .view_count = 1, .dt_ms = 16.7f});
    items[i] =
        (tlod_draw_item){.surface = ds, .draw_list = tlod_scheduler_draw_list(sch[i], 0), .has_model = s->count > 1};
    memcpy(items[i].model, s->world[i], sizeof(items[i].model));
  }
  double t1 = cli_now_ms();
  tlod_draw_desc d = {.items = items, .item_count = s->count, .viewport = {0, 0, OBJ_W, OBJ_H}, .finish = true};
  memcpy(d.view, v.view, sizeof(d.view));
  memcpy(d.proj, v.proj, sizeof(d.proj));
  double wall;
  int rc = bench_frame(p, s->ctx, dev, &d, &wall);
  double t2 = cli_now_ms();
  t[0] = t2 - t0, t[1] = t1 - t0, t[2] = t2 - t1;
  return rc;
}

static int run_case(obj_scene* s, tlod_platform* p, tlod_device* dev, tlod_patterns* pat, const tlod_scheduler_desc* sd,
                    uint32_t frames, obj_figures* f) {
  tlod_scheduler* sch[OBJ_COUNT] = {0};
  tlod_draw_item items[OBJ_COUNT];
  tlod_device_surface* ds = NULL;
  double* t = malloc(sizeof(double) * 3 * frames);
  int rc =
      t && tlod_device_create_surface(dev, s->surface, &ds) == TLOD_SUCCESS ? CLI_OK : cli_error(CLI_FAILED, "set-up");
  for (uint32_t i = 0; rc == CLI_OK && i < s->count; i++)
    if (tlod_scheduler_create(s->ctx, s->surface, pat, sd, &sch[i]) != TLOD_SUCCESS)
      rc = cli_error(CLI_FAILED, "%s", tlod_context_last_error(s->ctx));
  for (uint32_t k = 0; rc == CLI_OK && k < frames + 2; k++) {
    double ft[3];
    rc = run_frame(s, p, dev, ds, sch, items, k, ft);
    for (int j = 0; j < 3 && k >= 2; j++)
      t[j * frames + (k - 2)] = ft[j]; /* two warm-up frames */
  }
  if (rc == CLI_OK) {
    bench_min_median(t, frames, 1.0, f->frame);
    bench_min_median(t + frames, frames, 1.0, f->sched);
    bench_min_median(t + 2 * frames, frames, 1.0, f->draw);
    f->triangles = tlod_device_query_stats(dev).triangles;
  }
  for (uint32_t i = 0; i < s->count; i++)
    tlod_scheduler_destroy(sch[i]);
  tlod_device_destroy_surface(dev, ds);
  free(t);
  return rc;
}

static void report(const char* backend, const char* mode, const obj_figures f[2], FILE* csv) {
  for (int m = 0; m < 2; m++) {
    printf("objects    %-6s %-10s %2u object%s frame min %8.3f median %8.3f ms  (schedulers %7.3f, draw %8.3f)  "
           "%8llu tris",
           backend, mode, m ? 1u : (unsigned)OBJ_COUNT, m ? " " : "s", f[m].frame[0], f[m].frame[1], f[m].sched[1],
           f[m].draw[1], (unsigned long long)f[m].triangles);
    if (m) printf("  | %u objects / 1: x%.2f (median)", OBJ_COUNT, f[0].frame[1] / f[1].frame[1]);
    printf("\n");
    if (csv)
      fprintf(csv, "objects,%s,%s,%u,%.4f,%.4f,%.4f,%.4f,%llu\n", backend, mode, m ? 1u : (unsigned)OBJ_COUNT,
              f[m].frame[0], f[m].frame[1], f[m].sched[1], f[m].draw[1], (unsigned long long)f[m].triangles);
  }
}

/* One backend's cases; p: its platform (NULL: cpu). */
static int run_backend(tlod_context* ctx, const cli_mesh* m, tlod_platform* p, const bench_gpu* gpu, uint32_t frames,
                       FILE* csv) {
  const char* backend = p ? gpu->backend : "cpu";
  static const struct {
    const char* name;
    tlod_scheduler_desc d;
  } modes[] = {{"uniform:1", {.policy = TLOD_POLICY_UNIFORM, .max_level = 1, .morph = TLOD_MORPH_NONE}},
               {"adaptive", {.morph = TLOD_MORPH_NONE}}};
  tlod_patterns* pat = NULL;
  tlod_device* dev = NULL;
  int rc = tlod_patterns_create(ctx, &(tlod_patterns_desc){.max_level = 6}, &pat) == TLOD_SUCCESS
               ? CLI_OK
               : cli_error(CLI_FAILED, "%s", tlod_context_last_error(ctx));
  tlod_device_desc dd = {.backend = backend, .patterns = pat};
  gpu_target_device_desc(p, gpu->shader_cache, false, &dd);
  if (rc == CLI_OK && tlod_device_create(ctx, &dd, &dev) != TLOD_SUCCESS)
    rc = cli_error(CLI_FAILED, "%s: %s", backend, tlod_context_last_error(ctx));
  for (size_t k = 0; rc == CLI_OK && k < sizeof modes / sizeof modes[0]; k++) {
    obj_figures f[2];
    for (int merged = 0; merged < 2 && rc == CLI_OK; merged++) {
      obj_scene s;
      rc = scene_make(ctx, m, merged, &s);
      if (rc == CLI_OK) rc = run_case(&s, p, dev, pat, &modes[k].d, frames, &f[merged]);
      scene_free(&s);
    }
    if (rc == CLI_OK) report(backend, modes[k].name, f, csv);
  }
  tlod_device_destroy(dev);
  tlod_patterns_destroy(pat);
  return rc;
}

int bench_objects(const bench_options* o, const bench_gpu* gpu, FILE* csv) {
  cli_mesh m;
  int rc = cli_load("demo:torus-24x12", &m);
  if (rc != CLI_OK) return rc;
  tlod_context* ctx = NULL;
  if (tlod_context_create(&(tlod_context_desc){.label = "bench"}, &ctx) != TLOD_SUCCESS)
    rc = cli_error(CLI_FAILED, "cannot create a context");
  printf("tlod bench --suite objects: demo:torus-24x12 (%u faces) x %u: %u instances against one merged object, "
         "%ux%u, %u frames, wall clock (ms)\n",
         m.face_sizes ? m.face_count : m.index_count / 3, OBJ_COUNT, OBJ_COUNT, OBJ_W, OBJ_H, o->frames);
  if (csv) fprintf(csv, "suite,backend,mode,objects,frame_min,frame_median,schedulers_median,draw_median,triangles\n");
  if (rc == CLI_OK) rc = run_backend(ctx, &m, NULL, gpu, o->frames, csv);
#if TLOD_HAS_GL || TLOD_HAS_VULKAN
  tlod_platform* p = NULL;
  if (rc == CLI_OK) rc = bench_gpu_open(gpu, OBJ_W, OBJ_H, &p);
  if (rc == CLI_OK) rc = run_backend(ctx, &m, p, gpu, o->frames, csv);
  gpu_target_close(p);
#endif
  tlod_context_destroy(ctx);
  cli_mesh_free(&m);
  return rc;
}
