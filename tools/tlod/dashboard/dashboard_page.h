/* The dashboard page (docs/dashboard.md): one self-contained HTML file with
 * the runs' data, the page's script and style (tools/dashboard/) and uPlot
 * inlined, so it opens from disk and fetches nothing.
 *
 * `tlod dashboard` writes it to a file; `tlod play --serve` answers GET / with
 * it (options.live = "/events"): the page then opens an EventSource on that
 * URL and appends each event's frame record (the keys of a trace.json frame
 * record, plus `dropped`: frames dropped for this client) to a run of its own.
 *
 * Screenshots are inlined as data: URIs, at most options.screenshot_bytes of
 * encoded images in all (0: DASHBOARD_SCREENSHOT_BYTES); past the budget a
 * frame's picture is left out (the page says how many) rather than the page
 * growing without bound. */
#ifndef TLOD_TOOLS_DASHBOARD_PAGE_H
#define TLOD_TOOLS_DASHBOARD_PAGE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "common/run_read.h"

#define DASHBOARD_SCREENSHOT_BYTES (32u * 1024u * 1024u)

typedef struct dashboard_page_options {
  const char* live;        /* NULL: a static report; else the event-stream URL ("/events") */
  const char* title;       /* NULL: "tesslod dashboard" */
  size_t screenshot_bytes; /* 0: DASHBOARD_SCREENSHOT_BYTES; screenshots are read from run.dir */
} dashboard_page_options;

/* Writes the page for runs (NULL or count 0 is fine: a live page starts
 * empty) to f. opt may be NULL (a static report). A screenshot that is
 * missing, not a PNG, outside its run folder (absolute, "..") or over the
 * budget is left out and counted, never an error. False when a write failed
 * (err says so); f then holds a partial page. */
bool dashboard_page_write(FILE* f, const run_set* runs, const dashboard_page_options* opt, char* err, size_t err_size);

#endif
