/* tlod play --serve: the page at /, built once when the server starts: the
 * dashboard's own page (dashboard/dashboard_page.h) with no runs and
 * "live": "/events" in its config, so it follows the event stream. */
#define _POSIX_C_SOURCE 200809L /* open_memstream */
#include <stdio.h>
#include <stdlib.h>

#include "dashboard/dashboard_page.h"
#include "play_serve_internal.h"

char* serve_page(size_t* len) {
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
