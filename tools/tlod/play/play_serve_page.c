/* tlod play --serve: the page at /, built once when the server starts: the
 * dashboard's own page (dashboard/dashboard_page.h) with no runs and
 * "live": "/events" in its config, so it follows the event stream. */
#define _POSIX_C_SOURCE 200809L /* open_memstream */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dashboard/dashboard_page.h"
#include "play_serve_internal.h"

/* Until the page builder's implementation is merged (branch d1-page), its
 * symbol is weak: NULL, and a minimal page that follows the stream stands in. */
#pragma weak dashboard_page_write

static const char placeholder[] =
    "<!doctype html>\n<html><head><meta charset=\"utf-8\"><title>tlod live</title></head><body>\n"
    "<script type=\"application/json\" id=\"tlod-config\">{\"live\":\"/events\"}</script>\n"
    "<p>tlod play: <span id=\"frames\">0</span> frames, <span id=\"dropped\">0</span> dropped</p>\n"
    "<script>\n"
    "const es = new EventSource('/events');\n"
    "let n = 0;\n"
    "es.onmessage = (e) => { const f = JSON.parse(e.data); n++;\n"
    "  document.getElementById('frames').textContent = n;\n"
    "  document.getElementById('dropped').textContent = f.dropped; };\n"
    "es.addEventListener('end', () => es.close());\n"
    "</script></body></html>\n";

static char* dashboard(size_t* len) {
  char *page = NULL, err[512];
  FILE* f = open_memstream(&page, len);
  if (!f) return NULL;
  run_set none = {0};
  dashboard_page_options opt = {.live = "/events", .title = "tesslod live"};
  bool ok = dashboard_page_write(f, &none, &opt, err, sizeof(err));
  if (fclose(f) != 0 || !ok) {
    free(page);
    return NULL;
  }
  return page;
}

char* serve_page(size_t* len) {
  if (dashboard_page_write) return dashboard(len);
  *len = sizeof(placeholder) - 1;
  char* page = malloc(*len + 1);
  if (page) memcpy(page, placeholder, *len + 1);
  return page;
}
