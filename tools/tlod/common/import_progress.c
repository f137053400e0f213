/* tlod -- progress of long imports on the terminal: VTK reads of large
 * meshes take seconds, so after half a second the importer's stage and
 * fraction are shown on stderr (a terminal only; cleared at the end). */
#define _POSIX_C_SOURCE 200809L /* isatty */
#include <stdio.h>
#include <unistd.h>

#include "cli.h"
#include "mesh_load.h"

typedef struct import_progress {
  double start_ms;
  bool shown;
} import_progress;

static import_progress g_progress; /* one import at a time per tlod process */

static void on_progress(void* user, const char* stage, double fraction) {
  import_progress* p = user;
  if (cli_now_ms() - p->start_ms < 500.0) return;
  fprintf(stderr, "\rtlod: importing: %-12s %3.0f%%", stage ? stage : "", fraction * 100.0);
  fflush(stderr);
  p->shown = true;
}

void cli_progress_hook(tlod_import_desc* d) {
  g_progress = (import_progress){.start_ms = cli_now_ms()};
  if (!isatty(STDERR_FILENO)) return;
  d->progress = on_progress;
  d->progress_user = &g_progress;
}

void cli_progress_end(const tlod_import_desc* d) {
  if (!d->progress || !g_progress.shown) return;
  fprintf(stderr, "\r%40s\r", "");
  fflush(stderr);
}
