/*
 * vk_stats_test.c -- the "vulkan" device's triangle counts are the draw
 * lists' (owned by the Vulkan tests). Public API only.
 *
 * tlod_device_stats.vk.primitives is the pipeline-statistics clipping
 * invocation count of the draw stats.gpu_draw names (read a few draws late,
 * never waited for). A torus (PN, strips at mixed levels) is drawn for 12
 * frames by a camera flying in, so levels and counts change every frame;
 * the test remembers each draw's pattern + strip triangles by draw number
 * and checks, whenever a reading is ready:
 *   pattern path:  stats.triangles == pattern + strip triangles of draw
 *                  n, every frame; primitives(draw n) is that count but
 *                  for degenerate strip triangles (two corners at one
 *                  position): strips are drawn indexed, and lavapipe drops
 *                  some of those before the clipper (at most the strip
 *                  triangles: pattern <= primitives <= pattern + strip);
 *   hardware path: stats.triangles == pattern triangles (no strips, as the
 *                  GL device documents); the tessellator makes its own
 *                  triangles (equal spacing, each edge at the finer side's
 *                  level), at least one per pattern triangle:
 *                  primitives(draw n) >= pattern triangles of draw n.
 * No wireframe (its lines would be counted too). At least 6 readings, of
 * at least 3 different counts, or the late read is not exercised.
 */
#include "vk_test.h"

#define W 160
#define H 120
#define FRAMES 12
#define MAX_LEVEL 5

typedef struct count_check {
  uint32_t readings, distinct;
  uint64_t last;
} count_check;

/* One frame k of the fly-in; returns the draw list drawn. */
static const tlod_draw_list* fly_in_frame(vk_session* s, fixture* fx, tlod_scheduler* sch, int k) {
  double d = 6.0 - 0.35 * k;
  camera cam = camera_look(d * 0.6, -d * 0.8, d * 0.3, 0, 0, 0, 50, W, H);
  tlod_view_desc v = make_view(&cam);
  const tlod_draw_list* dl = plan(fx, sch, &v, 16.0f);
  if (!dl) return NULL;
  one_draw od;
  one_draw_make(&od, fx->ds, dl, &v);
  return vk_draw_frame(s->platform, s->dev, s->ctx, &od.desc, NULL) ? dl : NULL;
}

static void count_frames(bool hardware, count_check* cc) {
  vk_session s;
  shape torus = shape_torus(16, 10);
  fixture fx;
  memset(&fx, 0, sizeof fx);
  tlod_scheduler* sch = NULL;
  memset(cc, 0, sizeof *cc);
  uint64_t expected[FRAMES + 2] = {0}, strips[FRAMES + 2] = {0};
  tlod_device_vk_desc opt = {.hardware_tessellation = hardware};
  CHECK_MSG(vk_session_open(&s, W, H, MAX_LEVEL, "vk_stats", false, opt), "no Vulkan device (see above)");
  CHECK_MSG(vk_desc_of(s.platform).host_query_reset, "the platform's device has no hostQueryReset: no readings");
  CHECK(fixture_make(&fx, s.ctx, &torus, TLOD_SURFACE_PN, s.pat, s.dev));
  tlod_scheduler_desc sd = {.max_level = MAX_LEVEL, .morph = hardware ? TLOD_MORPH_NONE : TLOD_MORPH_DEFAULT};
  CHECK(sch = new_scheduler(&fx, sd));
  for (int k = 0; k < FRAMES; ++k) {
    const tlod_draw_list* dl = fly_in_frame(&s, &fx, sch, k);
    CHECK_MSG(dl, "frame %d", k);
    tlod_device_stats st = tlod_device_query_stats(s.dev);
    uint64_t want = hardware ? dl->pattern_triangles : dl->pattern_triangles + dl->strip_triangles;
    CHECK_MSG(st.draws >= 1 && st.draws <= FRAMES, "stats.draws %llu", (unsigned long long)st.draws);
    expected[st.draws] = want;
    strips[st.draws] = hardware ? 0 : dl->strip_triangles;
    CHECK_MSG(st.triangles == want, "frame %d: stats.triangles %llu, draw list %llu", k,
              (unsigned long long)st.triangles, (unsigned long long)want);
    if (st.gpu_draw == 0) continue;
    CHECK_MSG(st.gpu_draw <= st.draws, "gpu_draw %llu of %llu draws", (unsigned long long)st.gpu_draw,
              (unsigned long long)st.draws);
    uint64_t then = expected[st.gpu_draw];
    printf("  %s frame %2d: draw %llu's primitives %llu, its draw list %llu (pattern %s)\n",
           hardware ? "hardware" : "pattern ", k, (unsigned long long)st.gpu_draw, (unsigned long long)st.vk.primitives,
           (unsigned long long)then, hardware ? "only" : "+ strip");
    if (hardware)
      CHECK_MSG(st.vk.primitives >= then && then > 0, "frame %d: %llu primitives < %llu pattern triangles", k,
                (unsigned long long)st.vk.primitives, (unsigned long long)then);
    else
      CHECK_MSG(st.vk.primitives <= then && st.vk.primitives + strips[st.gpu_draw] >= then,
                "frame %d: draw %llu: %llu primitives, draw list %llu triangles (%llu of them strip)", k,
                (unsigned long long)st.gpu_draw, (unsigned long long)st.vk.primitives, (unsigned long long)then,
                (unsigned long long)strips[st.gpu_draw]);
    cc->distinct += cc->readings == 0 || then != cc->last;
    cc->last = then;
    cc->readings++;
  }
  tlod_platform_finish(s.platform); /* the engine's duty before destroying what frames used */
  tlod_scheduler_destroy(sch);
  fixture_free(&fx);
  shape_free(&torus);
  vk_session_close(&s);
}

TEST(test_primitives_pattern_path) {
  count_check cc;
  CALL(count_frames(false, &cc));
  CHECK_MSG(cc.readings >= 6 && cc.distinct >= 3, "%u readings of %u different counts", cc.readings, cc.distinct);
}

TEST(test_primitives_hardware_path) {
  count_check cc;
  CALL(count_frames(true, &cc));
  CHECK_MSG(cc.readings >= 6 && cc.distinct >= 3, "%u readings of %u different counts", cc.readings, cc.distinct);
}

int main(void) {
  RUN(test_primitives_pattern_path);
  RUN(test_primitives_hardware_path);
  VK_TEST_END();
}
