/*
 * run_read_test.c -- the tolerant JSON reader (tools/tlod/common/json_read.h)
 * and the run reader on trace.json text (run_read.h): values decoded against
 * the text written here, a trace cut at every byte gives the frames complete
 * before the cut (never more, never a crash), nesting and bad input refused
 * with the file and the problem named.
 */
#include <stdint.h>
#include <stdio.h>

#include "common/json_read.h"
#include "common/run_read.h"
#include "test.h"

static const char* frame_text(int i, char* buf, size_t n) {
  snprintf(
      buf, n,
      "{\"frame\": %d, \"time_s\": %d.5, \"frame_ms\": %d.25, \"stage_ms\": {\"silhouette\": 0.5, \"strips\": %d},"
      " \"backend_gpu_ms\": -1, \"screenshot\": \"%s\", \"triangles\": %d, \"level_histogram\": [%d, 0, 0, 0, 0, 0,"
      " 0, 0, 0, 0, 9], \"eye\": [1, 2, %d]}",
      i, i, 10 + i, i, i % 2 ? "" : "screenshots/f.png", 1000 + i, i, i);
  return buf;
}

/* A trace of frames frames, into buf. */
static size_t trace_text(int frames, char* buf, size_t n) {
  size_t at = (size_t)snprintf(buf, n,
                               "{\"schema\": \"tlod-play-trace/2\", \"scene\": \"demo:scene\", \"mode\": \"adaptive\", "
                               "\"objects\": [{\"name\": \"cow \\\"A\\\" \\u00e9\\ud83d\\ude00\", \"patches\": 12}], "
                               "\"frames\": [");
  for (int i = 0; i < frames; i++) {
    char f[512];
    at += (size_t)snprintf(buf + at, n - at, "%s%s", i ? ", " : "", frame_text(i, f, sizeof f));
  }
  at += (size_t)snprintf(buf + at, n - at, "], \"frames_completed\": %d, \"stopped\": \"completed\"}", frames);
  return at;
}

TEST(test_values_decoded) {
  char text[8192], err[256] = "";
  size_t n = trace_text(3, text, sizeof text);
  run r;
  CHECK_MSG(run_read_trace_text("T", text, n, &r, err, sizeof err), "%s", err);
  CHECK(r.frame_count == 3 && !r.truncated && !strcmp(r.meta.stopped, "completed"));
  CHECK(!strcmp(r.objects[0].name, "cow \"A\" \xc3\xa9\xf0\x9f\x98\x80"));
  CHECK(r.objects[0].patches == 12);
  CHECK(r.column[RUN_COL_FRAME_MS][2] == 12.25 && r.column[RUN_COL_TIME_S][1] == 1.5);
  CHECK(r.column[RUN_COL_STRIPS_MS][2] == 2 && r.column[RUN_COL_SILHOUETTE_MS][0] == 0.5);
  CHECK(isnan(r.column[RUN_COL_METRIC_MS][0])); /* absent: NaN, not 0 */
  CHECK(r.column[RUN_COL_LEVEL_0][2] == 2 && r.column[RUN_COL_LEVEL_0 + 10][2] == 9);
  CHECK(r.column[RUN_COL_EYE_Z][2] == 2 && r.column[RUN_COL_BACKEND_GPU_MS][0] == -1);
  CHECK(!strcmp(r.screenshot[0], "screenshots/f.png") && !strcmp(r.screenshot[1], ""));
  CHECK(!strcmp(run_column_name(RUN_COL_LEVEL_0 + 10), "level_10") && !strcmp(run_column_name(RUN_COL_FOVY), "fovy"));
  run_free(&r);
}

/* Cut at every byte: the frames read are exactly those whose record closed before the cut. */
TEST(test_cut_everywhere) {
  char text[16384], err[256];
  size_t n = trace_text(6, text, sizeof text);
  size_t closes[6];
  const char* p = strstr(text, "\"frames\": [");
  for (int i = 0; i < 6; i++) { /* the '}' ending frame i: after its "eye": [..] */
    p = strstr(strstr(p, "\"eye\""), "]}") + 1;
    closes[i] = (size_t)(p - text);
  }
  for (size_t cut = 0; cut < n; cut++) {
    run r;
    err[0] = 0;
    bool ok = run_read_trace_text("T", text, cut, &r, err, sizeof err);
    if (!ok) {
      CHECK_MSG(cut < (size_t)(strstr(text, "\"scene\"") - text), "cut %zu refused: %s", cut, err);
      CHECK_MSG(!strncmp(err, "T: ", 3), "%s", err);
      continue;
    }
    size_t want = 0;
    while (want < 6 && closes[want] < cut)
      want++;
    CHECK_MSG(r.frame_count == want, "cut %zu: %zu frames, want %zu", cut, r.frame_count, want);
    CHECK_MSG(r.truncated, "cut %zu: not marked truncated", cut);
    char reason[64];
    if (want)
      snprintf(reason, sizeof reason, "T: truncated after frame %d", (int)want - 1);
    else
      snprintf(reason, sizeof reason, "T: truncated before its first frame");
    CHECK_MSG(!strcmp(r.truncated_reason, reason), "cut %zu: %s", cut, r.truncated_reason);
    run_free(&r);
  }
}

TEST(test_refusals_name_the_problem) {
  static const struct {
    const char* text;
    const char* message;
  } cases[] = {
      {"{\"schema\": \"tlod-play-trace/1\"}", "T: schema 'tlod-play-trace/1' is not tlod-play-trace/2"},
      {"[1, 2]", "T: not a JSON object"},
      {"{\"schema\": \"tlod-play-trace/2\", \"frames\": [{\"frame_ms\": \"x\"}]}",
       "T: frames[0]: frame_ms: not a number"},
      {"{\"schema\": \"tlod-play-trace/2\", \"frames\": 3}", "T: frames: not an array"},
      {"{\"schema\": \"tlod-play-trace/2\"} x", "T: not JSON: text after the value at byte 32"},
      {"{\"a\": 1e999}", "T: not JSON: bad number at byte 11"},
      {"{\"a\": \"\x01\"}", "T: not JSON: control character in string at byte 7"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    run r;
    char err[256] = "";
    CHECK(!run_read_trace_text("T", cases[i].text, strlen(cases[i].text), &r, err, sizeof err));
    CHECK_MSG(!strcmp(err, cases[i].message), "got \"%s\", want \"%s\"", err, cases[i].message);
    CHECK(r.frame_count == 0 && r.meta.schema == NULL);
  }
}

TEST(test_nesting_bounded) {
  char deep[200], err[128] = "";
  memset(deep, '[', sizeof deep - 1);
  deep[sizeof deep - 1] = 0;
  json_value* v = NULL;
  CHECK(json_read(deep, strlen(deep), &v, err, sizeof err) == JSON_READ_ERROR && v == NULL);
  CHECK_MSG(strstr(err, "nested deeper than 64"), "%s", err);
}

/* An escaped quote early in a long string: the decoded buffer is sized past it (it once stopped counting
 * at the escaped quote and wrote past its end, which ASan saw). */
TEST(test_escaped_quote_then_long_string) {
  char text[300] = "\"a\\\"";
  memset(text + 4, 'b', 250);
  strcpy(text + 254, "\"");
  json_value* v = NULL;
  char err[128] = "";
  CHECK(json_read(text, strlen(text), &v, err, sizeof err) == JSON_READ_OK);
  CHECK(v->type == JSON_STRING && strlen(v->string) == 252 && !strncmp(v->string, "a\"bbb", 5));
  json_free(v);
}

int main(void) {
  RUN(test_values_decoded);
  RUN(test_cut_everywhere);
  RUN(test_refusals_name_the_problem);
  RUN(test_nesting_bounded);
  RUN(test_escaped_quote_then_long_string);
  TEST_END();
}
