/* Run folders (run_read.h): trace.json loaded whole (bounded), objects.csv,
 * and --compare parents expanded into their mode runs. */
#define _POSIX_C_SOURCE 200809L /* dirent, stat */
#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "run_read_internal.h"

/* dir + "/" + name, malloc'd. */
static char* join(const char* dir, const char* name) {
  size_t n = strlen(dir) + strlen(name) + 2;
  char* p = malloc(n);
  if (p) snprintf(p, n, "%s/%s", dir, name);
  return p;
}

static bool is_file(const char* path) {
  struct stat st;
  return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

/* The whole of path (at most max bytes) into *text; NULL with errno on failure. */
static char* slurp(const char* path, size_t max, size_t* size, bool* too_big) {
  FILE* f = fopen(path, "rb");
  *too_big = false;
  if (!f) return NULL;
  size_t cap = 1 << 16, n = 0;
  char* text = malloc(cap);
  while (text) {
    n += fread(text + n, 1, cap - n, f);
    if (n < cap || ferror(f)) break;
    if (cap >= max) break;
    char* bigger = realloc(text, cap * 2 > max ? max + 1 : cap * 2);
    if (!bigger) free(text);
    text = bigger;
    cap = cap * 2 > max ? max + 1 : cap * 2;
  }
  int bad = ferror(f) ? EIO : 0;
  fclose(f);
  if (text && (bad || n > max)) {
    *too_big = !bad;
    free(text);
    return errno = bad ? bad : EFBIG, NULL;
  }
  *size = n;
  return text;
}

/* The last part of dir, without trailing slashes. */
static char* last_part(const char* dir) {
  size_t n = strlen(dir);
  while (n > 1 && dir[n - 1] == '/')
    n--;
  size_t s = n;
  while (s > 0 && dir[s - 1] != '/')
    s--;
  char* p = malloc(n - s + 1);
  if (p) memcpy(p, dir + s, n - s), p[n - s] = 0;
  return p;
}

bool run_read(const char* dir, run* out, char* err, size_t err_size) {
  memset(out, 0, sizeof *out);
  char* path = join(dir, "trace.json");
  if (!path) return run_fail(err, err_size, "%s: out of memory", dir);
  if (!is_file(path)) return free(path), run_fail(err, err_size, "%s: not a run (no trace.json)", dir);
  size_t size = 0;
  bool too_big;
  char* text = slurp(path, RUN_READ_MAX_BYTES, &size, &too_big);
  if (!text) {
    bool ok = too_big ? run_fail(err, err_size, "%s: larger than %u bytes", path, RUN_READ_MAX_BYTES)
                      : run_fail(err, err_size, "%s: %s", path, strerror(errno));
    return free(path), ok;
  }
  bool ok = run_read_trace_text(path, text, size, out, err, err_size);
  free(text);
  free(path);
  if (!ok) return false;
  out->dir = run_strdup(dir);
  out->label = last_part(dir);
  if (!out->dir || !out->label) return run_free(out), run_fail(err, err_size, "%s: out of memory", dir);
  run_read_object_counts(out);
  return true;
}

static int by_name(const void* a, const void* b) { return strcmp(*(char* const*)a, *(char* const*)b); }

/* dir/name when it is a folder holding a trace.json (a mode run), else NULL. */
static char* mode_folder(const char* dir, const char* name) {
  char* sub = name[0] == '.' ? NULL : join(dir, name);
  char* trace = sub ? join(sub, "trace.json") : NULL;
  bool is_run = trace && is_file(trace);
  free(trace);
  if (!is_run) free(sub);
  return is_run ? sub : NULL;
}

/* The sub-folders of dir that hold a trace.json, sorted by name. */
static char** mode_folders(const char* dir, size_t* count) {
  DIR* d = opendir(dir);
  size_t cap = 0;
  char** names = NULL;
  *count = 0;
  for (struct dirent* e; d && (e = readdir(d));) {
    char* sub = mode_folder(dir, e->d_name);
    if (sub && *count == cap) {
      char** more = realloc(names, (cap = cap ? cap * 2 : 8) * sizeof *names);
      if (!more) { /* out of memory: the folders so far */
        free(sub);
        break;
      }
      names = more;
    }
    if (sub) names[(*count)++] = sub;
  }
  if (d) closedir(d);
  if (names) qsort(names, *count, sizeof *names, by_name);
  return names;
}

static void free_names(char** names, size_t count) {
  for (size_t i = 0; i < count; i++)
    free(names[i]);
  free(names);
}

/* One more run slot in s. */
static run* add_run(run_set* s) {
  run* runs = realloc(s->runs, (s->count + 1) * sizeof *runs);
  if (!runs) return NULL;
  s->runs = runs;
  return &runs[s->count];
}

/* dir, or its mode runs when it is a --compare parent. */
static bool read_folder(const char* dir, run_set* s, char* err, size_t err_size) {
  size_t count = 0;
  char* trace = join(dir, "trace.json");
  char** modes = trace && !is_file(trace) ? mode_folders(dir, &count) : NULL;
  free(trace);
  bool ok = true;
  for (size_t i = 0; ok && i < (count ? count : 1); i++) {
    run* r = add_run(s);
    ok = r ? run_read(count ? modes[i] : dir, r, err, err_size) : run_fail(err, err_size, "%s: out of memory", dir);
    if (ok) s->count++;
  }
  free_names(modes, count);
  return ok;
}

bool run_set_read(const char* const* dirs, size_t dir_count, run_set* out, char* err, size_t err_size) {
  memset(out, 0, sizeof *out);
  for (size_t i = 0; i < dir_count; i++) {
    if (!read_folder(dirs[i], out, err, err_size)) return run_set_free(out), false;
  }
  return true;
}

void run_set_free(run_set* s) {
  if (!s) return;
  for (size_t i = 0; i < s->count; i++)
    run_free(&s->runs[i]);
  free(s->runs);
  memset(s, 0, sizeof *s);
}
