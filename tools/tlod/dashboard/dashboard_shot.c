/* Screenshots inlined as data: URIs (dashboard_data.h), within the page's budget. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dashboard_data.h"

static const char base64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

/* A path inside the run folder: relative, no ".." part. */
static bool inside(const char* rel) {
  if (rel[0] == '/' || !rel[0]) return false;
  for (const char* p = rel; *p; p = strchr(p, '/') ? strchr(p, '/') + 1 : p + strlen(p)) {
    if (!strncmp(p, "..", 2) && (p[2] == '/' || !p[2])) return false;
  }
  return true;
}

static char* encode(const unsigned char* d, size_t n) {
  static const char head[] = "data:image/png;base64,";
  char* out = malloc(sizeof head + (n + 2) / 3 * 4);
  if (!out) return NULL;
  char* o = out + strlen(head);
  memcpy(out, head, strlen(head));
  for (size_t i = 0; i < n; i += 3) {
    unsigned v = d[i] << 16 | (i + 1 < n ? d[i + 1] << 8 : 0) | (i + 2 < n ? d[i + 2] : 0);
    *o++ = base64[v >> 18];
    *o++ = base64[v >> 12 & 63];
    *o++ = i + 1 < n ? base64[v >> 6 & 63] : '=';
    *o++ = i + 2 < n ? base64[v & 63] : '=';
  }
  *o = 0;
  return out;
}

/* The file's bytes when it is a PNG of at most max bytes. */
static unsigned char* read_png(const char* path, size_t max, size_t* size) {
  FILE* f = fopen(path, "rb");
  if (!f) return NULL;
  long n = fseek(f, 0, SEEK_END) == 0 ? ftell(f) : -1;
  unsigned char* d = n > 8 && (size_t)n <= max && fseek(f, 0, SEEK_SET) == 0 ? malloc((size_t)n) : NULL;
  if (d && (fread(d, 1, (size_t)n, f) != (size_t)n || memcmp(d, "\x89PNG\r\n\x1a\n", 8))) free(d), d = NULL;
  fclose(f);
  *size = (size_t)n;
  return d;
}

char* dashboard_shot_uri(const char* dir, const char* rel, size_t* budget) {
  if (!inside(rel)) return NULL;
  size_t len = strlen(dir) + strlen(rel) + 2, size = 0;
  char* path = malloc(len);
  if (!path) return NULL;
  snprintf(path, len, "%s/%s", dir, rel);
  /* The budget counts the encoded size: 4 bytes for every 3. */
  unsigned char* d = read_png(path, *budget / 4 * 3, &size);
  free(path);
  size_t encoded = (size + 2) / 3 * 4;
  char* uri = d && encoded <= *budget ? encode(d, size) : NULL;
  free(d);
  if (uri) *budget -= encoded;
  return uri;
}
