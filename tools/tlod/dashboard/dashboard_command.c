/* tlod dashboard RUN_DIR... [-o FILE]: the runs as one self-contained HTML
 * page (docs/dashboard.md). */
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "commands.h"
#include "dashboard_page.h"
#include "tlod_atomic_file.h"

void dashboard_usage(FILE* f) {
  fprintf(f, "usage: tlod dashboard [RUN_DIR...] [-o FILE] [--title TEXT] [--live URL]\n"
             "Writes the runs (tlod play --out folders; a --compare folder stands for its modes) as one\n"
             "HTML page that opens from disk and fetches nothing: frame times, histogram, stages,\n"
             "triangles, levels, screenshots, and every run against the first as tlod compare does.\n"
             "  -o FILE        the page (default report.html)\n"
             "  --title TEXT   the page's title (default \"tesslod dashboard\")\n"
             "  --live URL     the page also opens an EventSource on URL (on the server it is served from)\n"
             "                 and plots each frame record it sends (tlod play --serve does this itself)\n");
}

typedef struct page_job {
  const run_set* runs;
  dashboard_page_options options;
  char err[1024];
} page_job;

static bool fill(FILE* f, const void* data) {
  page_job* job = (page_job*)data;
  return dashboard_page_write(f, job->runs, &job->options, job->err, sizeof job->err);
}

/* Warnings for what loaded but is not whole. */
static void warn_partial(const run_set* s) {
  for (size_t i = 0; i < s->count; i++) {
    if (s->runs[i].truncated)
      fprintf(stderr, "tlod: warning: %s (the page shows what it has)\n", s->runs[i].truncated_reason);
  }
}

static int write_page(const char** dirs, size_t count, const char* out, const dashboard_page_options* options) {
  run_set runs;
  char err[1024];
  if (!run_set_read(dirs, count, &runs, err, sizeof err)) return cli_error(CLI_FAILED, "%s", err);
  warn_partial(&runs);
  page_job job = {.runs = &runs, .options = *options};
  bool ok = tlod_atomic_file_write(out, fill, &job, err, sizeof err);
  size_t n = runs.count;
  run_set_free(&runs);
  if (!ok) return cli_error(CLI_FAILED, "%s: %s", out, job.err[0] ? job.err : err);
  printf("output: %s (%zu run%s)\n", out, n, n == 1 ? "" : "s");
  return CLI_OK;
}

int cmd_dashboard(int argc, char** argv) {
  const char* out = "report.html";
  dashboard_page_options options = {0};
  const char** dirs = calloc((size_t)argc + 1, sizeof *dirs);
  size_t count = 0;
  if (!dirs) return cli_error(CLI_FAILED, "out of memory");
  for (int i = 0; i < argc; i++) {
    const char* a = argv[i];
    if (!strcmp(a, "--help") || !strcmp(a, "-h")) return free(dirs), dashboard_usage(stdout), CLI_OK;
    const char** slot = !strcmp(a, "-o")        ? &out
                        : !strcmp(a, "--title") ? &options.title
                        : !strcmp(a, "--live")  ? &options.live
                                                : NULL;
    if (slot && !(*slot = cli_value(argc, argv, &i))) return free(dirs), CLI_USAGE;
    if (!slot && a[0] == '-') return free(dirs), cli_error(CLI_USAGE, "%s: unknown option (tlod dashboard --help)", a);
    if (!slot) dirs[count++] = a;
  }
  int rc = count || options.live ? write_page(dirs, count, out, &options)
                                 : cli_error(CLI_USAGE, "dashboard: no RUN_DIR given (tlod dashboard --help)");
  free(dirs);
  return rc;
}
