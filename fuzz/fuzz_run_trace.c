/* fuzz_run_trace.c -- the run reader (tools/tlod/common/run_read.h) on trace.json text: the
 * tolerant JSON reader (json_read.c) and the frame extraction. Contract: an answer, never a
 * crash; a refusal names the file; a loaded run has every string set and a truncated one says
 * after which frame (or that it ends before the first). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/run_read.h"

static void check(bool ok, const char* what) {
  if (!ok) {
    fprintf(stderr, "fuzz_run_trace: contract broken: %s\n", what);
    abort();
  }
}

static void check_run(const run* r) {
  const run_meta* m = &r->meta;
  const char* strings[] = {m->schema,   m->tool,    m->scene,  m->path,    m->mode,      m->backend,
                           m->renderer, m->surface, m->policy, m->stopped, m->debug_view};
  for (size_t i = 0; i < sizeof strings / sizeof strings[0]; i++)
    check(strings[i] != NULL, "a NULL string");
  check(!strcmp(m->schema, RUN_TRACE_SCHEMA), "loaded another schema");
  for (size_t i = 0; i < r->frame_count; i++)
    check(r->screenshot[i] != NULL, "a NULL screenshot path");
  for (size_t i = 0; i < r->object_count; i++)
    check(r->objects[i].name && r->objects[i].source, "object strings");
  check(!r->truncated || strstr(r->truncated_reason, r->frame_count ? "trace.json: truncated after frame "
                                                                    : "trace.json: truncated before its first frame"),
        "truncation reason");
}

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  run r;
  char err[512] = "";
  if (run_read_trace_text("RUN/trace.json", (const char*)data, size, &r, err, sizeof err)) {
    check_run(&r);
    run_free(&r);
  } else {
    check(!strncmp(err, "RUN/trace.json: ", 16), "a refusal that does not name the file");
  }
  return 0;
}
