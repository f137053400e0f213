/*
 * gl_parity_test.c -- the GL backend draws what the CPU reference
 * tessellator computes, for the same scheduler draw list (owned by the GL
 * tests). Public API only.
 *
 * For icosphere(2), torus(16, 10) and cube_soft (split normals), under
 * Phong and PN surfaces, and quadratic_cube.h's curved second-order cube
 * under TLOD_SURFACE_QUADRATIC (its silhouette), in two modes:
 *   adaptive: tlod_scheduler with its defaults (HYBRID, TIME geomorphs),
 *             a far frame then a nearer one 60 ms later, so the second
 *             draw list carries fractional geomorph blends;
 *   uniform:  policy ERROR, epsilon 1e-6 px, max level 3, no geomorphs:
 *             every patch with any curvature at level 3;
 * image A = tlod_device_draw ("gl", debug NONE, default light and colour)
 * into the headless FBO; image B = tlod_cpu_tessellate(draw_list) (welded,
 * with normals) drawn by the independent mesh renderer of gl_test.h, which
 * shades exactly as backend.h documents. Both 256 x 256, cleared to pure
 * blue, depth test LESS, no culling.
 *
 * TOLERANCES (why): the backend evaluates the surface in GPU float with its
 * own operation order, so vertices may differ from the CPU's in the last
 * bits; that moves a silhouette edge by far less than a pixel, which can
 * flip only pixels whose centres lie on the reference silhouette.
 *   coverage: every pixel covered in one image and not the other must lie
 *     on the reference's 1-pixel boundary band (it, or an 8-neighbour, has
 *     the other coverage in B), and there may be at most 0.5% of the
 *     pixels covered by either image;
 *   colour: on pixels covered by both, the largest RGB channel difference
 *     is <= 8/255 on >= 99% of them (normals evaluated on the GPU vs CPU,
 *     and pixels where a front and a back face swap at a silhouette);
 *   triangle count: exact. tlod_device_query_stats().triangles ==
 *     draw_list pattern_triangles + strip_triangles == the CPU mesh's
 *     triangle_count + folds_skipped (the degenerate strip triangles the
 *     CPU leaves out, which a GPU draws as zero-area).
 * CPU-MESH MODE (tlod_gpu_eval OFF): image C of a second "gl" device that
 * evaluates the list on the CPU is compared with image A (the GPU
 * evaluation as the reference) under the same tolerances; it reports the
 * mode, evaluates once, and a second draw of the same list re-evaluates
 * nothing and gives C again bitwise (as a second GPU-eval draw uploads no
 * buffer and gives A again bitwise: strips indexed, lists not re-sent).
 */
#include "gl_test.h"
#include "quadratic_cube.h"

#define W 256
#define H 256
#define MAX_LEVEL 5

/* Totals over the whole test, for the summary line. */
static struct {
  uint32_t comparisons;
  uint64_t coverage_diff, off_band, covered;
  uint32_t worst_colour;
  double worst_colour_fraction; /* smallest fraction of both-covered pixels within 8/255 */
  uint64_t triangles;
  uint32_t morphing; /* instances with a geomorph blend < 1 */
} s_totals = {.worst_colour_fraction = 1.0};

typedef struct gl_env {
  tlod_platform* platform;
  ref_renderer ref;
  uint8_t *img_a, *img_b, *img_c, *img_again;
  tlod_device* dev_cpu;        /* gpu_eval OFF */
  tlod_device_surface* ds_cpu; /* the fixture's surface on dev_cpu */
  unsigned char* prev;         /* the instances and strips dev_cpu drew last on ds_cpu */
  size_t prev_bytes;           /* SIZE_MAX: none */
} gl_env;

/* One draw of dl on dev (surface ds) into img; the device's stats after it in *t. */
static void draw_into(gl_env* env, tlod_device* dev, const tlod_device_surface* ds, const fixture* fx,
                      const tlod_draw_list* dl, const tlod_view_desc* v, uint8_t* img, const char* what,
                      tlod_device_stats* t) {
  tlod_platform_bind(env->platform);
  clear_frame(W, H);
  one_draw d;
  one_draw_make(&d, ds, dl, v);
  tlod_result r = tlod_device_draw(dev, &d.desc);
  CHECK_MSG(r == TLOD_SUCCESS, "%s: tlod_device_draw: %s: %s", what, tlod_result_string(r),
            tlod_context_last_error(fx->ctx));
  GLenum err = glGetError();
  CHECK_MSG(err == GL_NO_ERROR, "%s: GL error after tlod_device_draw: %s (0x%04X)", what, gl_error_name(err), err);
  gl_read_rgba(W, H, img);
  *t = tlod_device_query_stats(dev);
}

/* The tolerances of the file comment, image a against reference b. */
static void check_tolerances(const compare_result* c, const char* what, const char* against) {
  double colour_fraction = c->covered_both ? (double)c->colour_ok / c->covered_both : 1.0;
  CHECK_MSG(c->covered_b > 500, "%s: the %s covers only %u pixels (camera misses the object)", what, against,
            c->covered_b);
  CHECK_MSG(c->covered_a > 0, "%s: nothing drawn", what);
  CHECK_MSG(c->off_band == 0,
            "%s: %u pixels differ from the %s in coverage off the silhouette band, first at (%d, %d) (row 0 = "
            "bottom)",
            what, c->off_band, against, c->off_band_x, c->off_band_y);
  CHECK_MSG(c->coverage_diff * 1000 <= 5 * c->covered_either,
            "%s: coverage differs from the %s on %u of %u pixels "
            "(> 0.5%%)",
            what, against, c->coverage_diff, c->covered_either);
  CHECK_MSG(colour_fraction >= 0.99, "%s: only %.2f%% of the %u pixels covered with the %s within 8/255 (max %u)", what,
            100.0 * colour_fraction, c->covered_both, against, c->max_colour_diff);
}

/* Image C (CPU mesh) against image A, the mode reported, the skips. */
static void compare_cpu_mesh(gl_env* env, tlod_device* dev, const fixture* fx, const tlod_draw_list* dl,
                             const tlod_view_desc* v, const char* what) {
  char label[128];
  snprintf(label, sizeof label, "%s cpu mesh", what);
  tlod_device_stats t;
  CALL(draw_into(env, env->dev_cpu, env->ds_cpu, fx, dl, v, env->img_c, label, &t));
  CHECK_MSG(t.cpu_mesh && strstr(t.gpu_eval_reason, "off"), "%s: mode not reported: cpu_mesh %d, reason '%s'", label,
            t.cpu_mesh, t.gpu_eval_reason);
  /* Equal to the last list (another camera, every patch at one level): the mesh is kept. */
  size_t ib = sizeof(tlod_draw_instance) * dl->instance_count, sb = sizeof(tlod_draw_strip) * dl->strip_count;
  bool same = env->prev && env->prev_bytes == ib + sb && (ib == 0 || !memcmp(env->prev, dl->instances, ib)) &&
              (sb == 0 || !memcmp(env->prev + ib, dl->strips, sb));
  CHECK_MSG(t.mesh_evaluations == (same ? 0u : 1u) && (same || t.mesh_bytes > 0),
            "%s: %u evaluations, %llu bytes (expected %u)", label, t.mesh_evaluations, (unsigned long long)t.mesh_bytes,
            same ? 0u : 1u);
  free(env->prev);
  env->prev = malloc(ib + sb + 1u);
  CHECK(env->prev);
  if (ib) memcpy(env->prev, dl->instances, ib);
  if (sb) memcpy(env->prev + ib, dl->strips, sb);
  env->prev_bytes = ib + sb;
  CHECK_MSG(t.triangles == dl->pattern_triangles + dl->strip_triangles, "%s: %llu triangles, the list has %llu", label,
            (unsigned long long)t.triangles, (unsigned long long)(dl->pattern_triangles + dl->strip_triangles));
  compare_result c = compare_images(env->img_c, env->img_a, W, H, 8);
  printf("  %-30s against GPU eval: covered %5u/%5u, differ %3u, off band %u | colour max %3u, %.2f%% <= 8\n", label,
         c.covered_a, c.covered_b, c.coverage_diff, c.off_band, c.max_colour_diff,
         c.covered_both ? 100.0 * c.colour_ok / c.covered_both : 100.0);
  check_tolerances(&c, label, "GPU-eval image");
  CALL(draw_into(env, env->dev_cpu, env->ds_cpu, fx, dl, v, env->img_again, label, &t));
  CHECK_MSG(t.mesh_evaluations == 0 && t.mesh_bytes == 0,
            "%s: the same list again: %u evaluations, %llu bytes (expected none)", label, t.mesh_evaluations,
            (unsigned long long)t.mesh_bytes);
  CHECK_MSG(!memcmp(env->img_again, env->img_c, 4 * W * H), "%s: the reused mesh draws another image", label);
  CALL(draw_into(env, dev, fx->ds, fx, dl, v, env->img_again, what, &t));
  CHECK_MSG(t.gl.buffer_streams == 0 && !t.cpu_mesh, "%s: the same list again: %u buffer uploads (expected 0)", what,
            t.gl.buffer_streams);
  CHECK_MSG(!memcmp(env->img_again, env->img_a, 4 * W * H), "%s: the list not re-sent draws another image", what);
}

/* Renders one draw list both ways and compares. */
static void compare_one(gl_env* env, tlod_device* dev, const fixture* fx, const tlod_draw_list* dl,
                        const tlod_view_desc* v, const char* what) {
  /* A: the GL device */
  tlod_device_stats t;
  CALL(draw_into(env, dev, fx->ds, fx, dl, v, env->img_a, what, &t));

  /* B: the CPU reference through the independent renderer */
  tlod_cpu_mesh* m = ref_draw_list(&env->ref, fx, dl, v, W, H, false);
  CHECK_MSG(m, "%s: CPU realisation failed", what);
  gl_read_rgba(W, H, env->img_b);
  uint64_t draw_list_triangles = dl->pattern_triangles + dl->strip_triangles;
  uint64_t cpu_triangles = (uint64_t)m->triangle_count + m->folds_skipped;
  uint32_t strips = m->strips, morphing = 0;
  for (uint32_t k = 0; k < dl->instance_count; ++k) {
    const tlod_draw_instance* in = &dl->instances[k];
    morphing += in->morph < 1.0f;
  }
  tlod_cpu_mesh_destroy(fx->ctx, m);
  CALL(compare_cpu_mesh(env, dev, fx, dl, v, what));

  compare_result c = compare_images(env->img_a, env->img_b, W, H, 8);
  double colour_fraction = c.covered_both ? (double)c.colour_ok / c.covered_both : 1.0;
  printf("  %-30s tris %6llu strips %3u morphing %3u | covered %5u/%5u, differ %3u (%.3f%%), off band %u | colour "
         "max %3u mean %.2f, %.2f%% <= 8\n",
         what, (unsigned long long)draw_list_triangles, strips, morphing, c.covered_a, c.covered_b, c.coverage_diff,
         c.covered_either ? 100.0 * c.coverage_diff / c.covered_either : 0.0, c.off_band, c.max_colour_diff,
         c.mean_colour_diff, 100.0 * colour_fraction);
  s_totals.comparisons++;
  s_totals.coverage_diff += c.coverage_diff;
  s_totals.off_band += c.off_band;
  s_totals.covered += c.covered_either;
  s_totals.triangles += draw_list_triangles;
  s_totals.morphing += morphing;
  if (c.max_colour_diff > s_totals.worst_colour) s_totals.worst_colour = c.max_colour_diff;
  if (colour_fraction < s_totals.worst_colour_fraction) s_totals.worst_colour_fraction = colour_fraction;

  CHECK_MSG(t.triangles == draw_list_triangles,
            "%s: device drew %llu triangles, the draw list has %llu (pattern %llu + strip %llu)", what,
            (unsigned long long)t.triangles, (unsigned long long)draw_list_triangles,
            (unsigned long long)dl->pattern_triangles, (unsigned long long)dl->strip_triangles);
  CHECK_MSG(cpu_triangles == draw_list_triangles, "%s: CPU mesh has %llu triangles + folds skipped, the draw list %llu",
            what, (unsigned long long)cpu_triangles, (unsigned long long)draw_list_triangles);
  check_tolerances(&c, what, "reference");
}

/* One surface on dev (a new device surface on the same device), both
 * modes, both cameras. */
static void one_surface(gl_env* env, tlod_device* dev, tlod_context* ctx, const tlod_patterns* pat,
                        const tlod_mesh_desc* md, tlod_surface_type type) {
  fixture fx;
  CHECK_MSG(fixture_make_desc(&fx, ctx, md, type, pat, dev), "fixture %s %s", md->label, type_name(type));
  CHECK(tlod_device_create_surface(env->dev_cpu, fx.surf, &env->ds_cpu) == TLOD_SUCCESS);
  env->prev_bytes = SIZE_MAX;
  for (int mode = 0; mode < 2; ++mode) {
    tlod_scheduler_desc sd = {.max_level = MAX_LEVEL};
    if (mode == 1)
      sd = (tlod_scheduler_desc){
          .policy = TLOD_POLICY_ERROR, .epsilon_px = 1e-6f, .max_level = 3, .morph = TLOD_MORPH_NONE};
    tlod_scheduler* sch = new_scheduler(&fx, sd);
    CHECK(sch);
    /* two cameras: an oblique one, then a closer grazing one (the
     * adaptive second frame morphs for 60 of 200 ms) */
    camera cams[2] = {camera_look(2.6, -3.4, 1.9, 0, 0, 0, 45, W, H),
                      camera_look(1.25, 1.9, 0.35, 0.15, 0.1, 0.05, 60, W, H)};
    for (int ci = 0; ci < 2; ++ci) {
      tlod_view_desc v = make_view(&cams[ci]);
      const tlod_draw_list* dl = plan(&fx, sch, &v, ci == 0 ? 0.0f : 60.0f);
      CHECK(dl);
      char what[96];
      snprintf(what, sizeof what, "%s %s %s cam %d", md->label, type_name(type), mode ? "uniform" : "adaptive", ci);
      if (mode == 1) {
        uint32_t at_max = dl->level_histogram[3], visible = dl->instance_count;
        CHECK_MSG(at_max * 10 >= visible * 9, "%s: uniform mode has only %u of %u patches at level 3", what, at_max,
                  visible);
      }
      int failed_before = _test_checks_failed;
      compare_one(env, dev, &fx, dl, &v, what);
      if (_test_checks_failed != failed_before) {
        char buf[256];
        camera_print(&cams[ci], buf, sizeof buf);
        fprintf(stderr, "  camera: %s\n", buf);
      }
    }
    tlod_scheduler_destroy(sch);
  }
  tlod_device_destroy_surface(env->dev_cpu, env->ds_cpu);
  fixture_free(&fx);
}

TEST(test_parity) {
  char err[512] = "";
  gl_env env = {0};
  env.platform = gl_test_platform(W, H, err, sizeof err);
  CHECK_MSG(env.platform, "cannot create a GL context: %s", err);
  env.img_a = malloc(4 * W * H);
  env.img_b = malloc(4 * W * H);
  env.img_c = malloc(4 * W * H);
  env.img_again = malloc(4 * W * H);
  CHECK(env.img_a && env.img_b && env.img_c && env.img_again);
  CHECK_MSG(ref_init(&env.ref), "reference renderer failed");

  tlod_context* ctx = NULL;
  CHECK(tlod_context_create(&(tlod_context_desc){.thread_count = 2}, &ctx) == TLOD_SUCCESS);
  tlod_patterns* pat = new_patterns(ctx, MAX_LEVEL);
  CHECK(pat);
  tlod_device* dev = new_gl_device(ctx, pat, "gl_parity", (tlod_device_gl_desc){0});
  CHECK(dev);
  CHECK_MSG(strcmp(tlod_device_backend(dev), "gl") == 0, "backend name %s", tlod_device_backend(dev));
  env.dev_cpu = new_gl_device(ctx, pat, "gl_parity cpu mesh", (tlod_device_gl_desc){.gpu_eval = TLOD_GPU_EVAL_OFF});
  CHECK(env.dev_cpu);
  tlod_device_stats on = tlod_device_query_stats(dev);
  CHECK_MSG(!on.cpu_mesh && strstr(on.gpu_eval_reason, "on"), "GPU-eval device reports cpu_mesh %d, '%s'", on.cpu_mesh,
            on.gpu_eval_reason);

  shape shapes[3] = {shape_icosphere(2), shape_torus(16, 10), shape_cube_soft()};
  const tlod_surface_type types[2] = {TLOD_SURFACE_PHONG, TLOD_SURFACE_PN};
  for (int si = 0; si < 3; ++si)
    for (int ti = 0; ti < 2; ++ti) {
      tlod_mesh_desc md = shape_mesh_desc(&shapes[si]);
      CALL(one_surface(&env, dev, ctx, pat, &md, types[ti]));
    }
  /* second-order faces: quadratic_cube.h's curved cube (9- and 8-node quads, 6-node triangles) */
  qcube q;
  qcube_make(&q);
  CALL(one_surface(&env, dev, ctx, pat, &q.desc, TLOD_SURFACE_QUADRATIC));
  CHECK_MSG(s_totals.morphing > 0, "no draw list had a geomorph blend < 1: morph parity not exercised");
  printf("  %u comparisons, %llu triangles, %u morphing instances: coverage differs on %llu of %llu covered pixels "
         "(%.4f%%), %llu off the "
         "band; worst colour diff %u/255, worst within-8 fraction %.3f%%\n",
         s_totals.comparisons, (unsigned long long)s_totals.triangles, s_totals.morphing,
         (unsigned long long)s_totals.coverage_diff, (unsigned long long)s_totals.covered,
         s_totals.covered ? 100.0 * (double)s_totals.coverage_diff / (double)s_totals.covered : 0.0,
         (unsigned long long)s_totals.off_band, s_totals.worst_colour, 100.0 * s_totals.worst_colour_fraction);
  for (int k = 0; k < 3; ++k)
    shape_free(&shapes[k]);
  tlod_device_destroy(env.dev_cpu);
  tlod_device_destroy(dev);
  tlod_patterns_destroy(pat);
  tlod_context_destroy(ctx);
  ref_free(&env.ref);
  free(env.img_a);
  free(env.img_b);
  free(env.img_c);
  free(env.img_again);
  free(env.prev);
  tlod_platform_destroy(env.platform);
}

int main(void) {
  RUN(test_parity);
  GL_TEST_END();
}
