/* tlod play -- a run's trace files written as it goes: each an atomic file
 * (a unique temporary in the run folder, renamed when complete), the heads
 * at the start, a window of frames at a time, the tails at the end. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "play_run_folder.h"
#include "play_trace_format.h"
#include "tlod_atomic_file.h"

enum { FILE_JSON, FILE_CSV, FILE_CHROME, FILE_OBJECTS, FILE_NUM };
static const char* const kNames[FILE_NUM] = {"trace.json", "trace.csv", "chrome_trace.json", "objects.csv"};

struct play_trace_files {
  char paths[FILE_NUM][PLAY_PATH_MAX + 64];
  tlod_atomic_file files[FILE_NUM];
  json_writer json;
  bool chrome_first;
};

static bool discard_all(play_trace* t) {
  for (int k = 0; k < FILE_NUM; k++)
    if (t->files->files[k].tmp) tlod_atomic_file_end(&t->files->files[k], false, NULL, 0);
  free(t->files);
  t->files = NULL;
  return false;
}

bool play_trace_files_open(play_trace* t, const char* dir, char* error, size_t error_size) {
  play_trace_files* tf = calloc(1, sizeof(*tf));
  if (!tf) {
    snprintf(error, error_size, "out of memory");
    return false;
  }
  t->files = tf;
  for (int k = 0; k < FILE_NUM; k++) {
    play_path_join(tf->paths[k], sizeof(tf->paths[k]), dir, kNames[k]);
    if (!tlod_atomic_file_begin(&tf->files[k], tf->paths[k], error, error_size)) return discard_all(t);
  }
  trace_json_head(&tf->json, tf->files[FILE_JSON].file, t);
  trace_csv_head(tf->files[FILE_CSV].file);
  chrome_trace_head(tf->files[FILE_CHROME].file);
  objects_csv_head(tf->files[FILE_OBJECTS].file);
  tf->chrome_first = true;
  return true;
}

/* A write error shows now (not at the end): the run stops at the first.
 * errno is not cleared here: a write that failed while the frames were
 * formatted (the stream flushing its full buffer) left its errno (EFBIG,
 * ENOSPC), and fflush of a stream already in error may fail without one. */
static bool flushed(play_trace* t, char* error, size_t error_size) {
  for (int k = 0; k < FILE_NUM; k++) {
    FILE* f = t->files->files[k].file;
    if (fflush(f) != 0 || ferror(f)) {
      snprintf(error, error_size, "cannot write '%s': %s", t->files->paths[k], strerror(errno ? errno : EIO));
      return discard_all(t);
    }
  }
  return true;
}

bool play_trace_files_flush(play_trace* t, char* error, size_t error_size) {
  if (!t->files) return true;
  play_trace_files* tf = t->files;
  errno = 0;
  trace_json_frames(&tf->json, t);
  trace_csv_frames(tf->files[FILE_CSV].file, t);
  chrome_trace_frames(tf->files[FILE_CHROME].file, t, &tf->chrome_first);
  objects_csv_frames(tf->files[FILE_OBJECTS].file, t);
  t->window_first += t->window_count;
  t->window_count = 0;
  return flushed(t, error, error_size);
}

bool play_trace_files_close(play_trace* t, bool keep, char* error, size_t error_size) {
  if (!t->files) return false;
  if (!keep) return discard_all(t);
  if (!play_trace_files_flush(t, error, error_size)) return false;
  play_trace_files* tf = t->files;
  trace_json_tail(&tf->json, t);
  chrome_trace_tail(tf->files[FILE_CHROME].file, t);
  for (int k = 0; k < FILE_NUM; k++)
    if (!tlod_atomic_file_end(&tf->files[k], true, error, error_size)) return discard_all(t); /* the rest too */
  free(tf);
  t->files = NULL;
  return true;
}
