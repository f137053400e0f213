/* tlod play -- the progress bar. */
#include <stdio.h>

#include "play_run.h"

void play_progress(const play_run* r, const play_mode* m, uint32_t done, double elapsed_ms, bool final) {
  if (!r->tty) return;
  if (final) {
    fputs("\r\033[K", stderr);
    return;
  }
  const int width = 30;
  int filled = (int)((double)width * done / r->frames);
  char bar[64];
  for (int i = 0; i < width; i++)
    bar[i] = i < filled ? '#' : '-';
  bar[width] = '\0';
  double fps = elapsed_ms > 0.0 ? 1000.0 * done / elapsed_ms : 0.0;
  double eta = fps > 0.0 ? (r->frames - done) / fps : 0.0;
  char which[48] = "";
  if (r->count > 1) snprintf(which, sizeof(which), "%u/%u ", r->index + 1, r->count);
  fprintf(stderr, "\r\033[K%s%s [%s] %u/%u frames  %.1f fps  ETA %.1f s", which, m->name, bar, done, r->frames, fps,
          eta);
  fflush(stderr);
}
