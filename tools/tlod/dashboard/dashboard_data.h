/* The runs as the page's JSON island (docs/dashboard.md "Page data"):
 * {"config": {"title", "live"}, "runs": [{"label", "dir", "meta": {...},
 * "truncated", "objects", "columns": {trace.csv name: [per frame]},
 * "object_triangles", "screenshots": {frame: data URI}, "screenshots_omitted"}],
 * "comparisons": [{"base", "run", "error", "result"}]}. */
#ifndef TLOD_TOOLS_DASHBOARD_DATA_H
#define TLOD_TOOLS_DASHBOARD_DATA_H

#include <stdbool.h>
#include <stdio.h>

#include "dashboard_page.h"

bool dashboard_data_write(FILE* f, const run_set* runs, const dashboard_page_options* opt, char* err, size_t n);

/* The PNG at dir/rel as a data: URI (malloc'd), charged to *budget; NULL
 * when it is missing, not a PNG, over the budget, or rel is absolute or
 * climbs with "..". */
char* dashboard_shot_uri(const char* dir, const char* rel, size_t* budget);

#endif
