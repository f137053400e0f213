/* export_text.c -- the glTF writer's JSON text: a growable string and JSON
 * strings from names that came from untrusted files (escaped, and bytes
 * that are not well-formed UTF-8 replaced by '?', since a name truncated to
 * its field may end inside a character and glTF JSON must be UTF-8).
 * Owned by the import/export layer (tools/import/). */
#include <stdarg.h>
#include <stdlib.h>

#include "export_internal.h"

static bool _exp_text_reserve(_exp_text* t, size_t more) {
  if (t->failed) return false;
  if (t->len + more + 1 <= t->cap) return true;
  size_t cap = (t->len + more + 1) * 2;
  char* p = realloc(t->s, cap);
  if (!p) {
    t->failed = true;
    return false;
  }
  t->s = p, t->cap = cap;
  return true;
}

void _exp_text_add(_exp_text* t, const char* fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  int n = vsnprintf(NULL, 0, fmt, ap);
  va_end(ap);
  if (n < 0) t->failed = true;
  if (n < 0 || !_exp_text_reserve(t, (size_t)n)) return;
  va_start(ap, fmt);
  vsnprintf(t->s + t->len, (size_t)n + 1, fmt, ap);
  va_end(ap);
  t->len += (size_t)n;
}

/* Length of the well-formed UTF-8 sequence at p (at most n bytes), 0 if none. */
static size_t _exp_utf8_length(const unsigned char* p, size_t n) {
  const size_t len = p[0] < 0x80             ? 1
                     : (p[0] & 0xE0) == 0xC0 ? 2
                     : (p[0] & 0xF0) == 0xE0 ? 3
                     : (p[0] & 0xF8) == 0xF0 ? 4
                                             : 0;
  if (!len || len > n || (len == 2 && p[0] < 0xC2)) return 0;
  for (size_t i = 1; i < len; ++i)
    if ((p[i] & 0xC0) != 0x80) return 0;
  return len;
}

void _exp_text_string(_exp_text* t, const char* s, size_t max_len) {
  _exp_text_add(t, "\"");
  const unsigned char* p = (const unsigned char*)s;
  size_t n = 0;
  while (n < max_len && p[n])
    ++n;
  for (size_t i = 0; i < n;) {
    const size_t len = _exp_utf8_length(p + i, n - i);
    if (len > 1)
      _exp_text_add(t, "%.*s", (int)len, (const char*)p + i);
    else if (len == 0)
      _exp_text_add(t, "?");
    else if (p[i] == '"' || p[i] == '\\')
      _exp_text_add(t, "\\%c", p[i]);
    else if (p[i] < 0x20)
      _exp_text_add(t, "\\u%04x", p[i]);
    else
      _exp_text_add(t, "%c", p[i]);
    i += len ? len : 1;
  }
  _exp_text_add(t, "\"");
}
