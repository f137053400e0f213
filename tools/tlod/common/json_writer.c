/* tlod tool -- streaming JSON writer. */
#include "json_writer.h"

#include <math.h>

void json_begin(json_writer* w, FILE* f) {
  *w = (json_writer){.f = f};
  w->first[0] = true;
}

void json_put_string(FILE* f, const char* s) {
  fputc('"', f);
  for (; *s; s++) {
    unsigned char c = (unsigned char)*s;
    if (c == '"' || c == '\\') {
      fprintf(f, "\\%c", c);
    } else if (c < 0x20) {
      fprintf(f, "\\u%04x", c);
    } else {
      fputc(c, f);
    }
  }
  fputc('"', f);
}

/* Separator, indentation and key before a value. */
static void prefix(json_writer* w, const char* key) {
  if (!w->first[w->depth]) fputc(',', w->f);
  w->first[w->depth] = false;
  if (w->depth > 0) {
    fputc('\n', w->f);
    for (int i = 0; i < w->depth; i++)
      fputs("  ", w->f);
  }
  if (key) {
    json_put_string(w->f, key);
    fputs(": ", w->f);
  }
}

static void container_begin(json_writer* w, const char* key, char c) {
  prefix(w, key);
  fputc(c, w->f);
  if (w->depth < 31) w->depth++;
  w->first[w->depth] = true;
}

static void container_end(json_writer* w, char c) {
  bool empty = w->first[w->depth];
  if (w->depth > 0) w->depth--;
  if (!empty) {
    fputc('\n', w->f);
    for (int i = 0; i < w->depth; i++)
      fputs("  ", w->f);
  }
  fputc(c, w->f);
}

void json_object_begin(json_writer* w, const char* key) { container_begin(w, key, '{'); }
void json_object_end(json_writer* w) { container_end(w, '}'); }
void json_array_begin(json_writer* w, const char* key) { container_begin(w, key, '['); }
void json_array_end(json_writer* w) { container_end(w, ']'); }

void json_string(json_writer* w, const char* key, const char* value) {
  prefix(w, key);
  json_put_string(w->f, value ? value : "");
}

void json_number(json_writer* w, const char* key, double value) {
  prefix(w, key);
  /* JSON has no NaN or infinity. */
  if (isfinite(value)) {
    fprintf(w->f, "%.9g", value);
  } else {
    fputs("null", w->f);
  }
}

void json_uint(json_writer* w, const char* key, uint64_t value) {
  prefix(w, key);
  fprintf(w->f, "%llu", (unsigned long long)value);
}

void json_int(json_writer* w, const char* key, int64_t value) {
  prefix(w, key);
  fprintf(w->f, "%lld", (long long)value);
}

void json_bool(json_writer* w, const char* key, bool value) {
  prefix(w, key);
  fputs(value ? "true" : "false", w->f);
}

bool json_end(json_writer* w) {
  fputc('\n', w->f);
  return !ferror(w->f);
}
