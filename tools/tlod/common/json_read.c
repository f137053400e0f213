/* The tolerant JSON reader (json_read.h): recursive descent over RFC 8259.
 * Each parse step answers STEP_OK, STEP_EOF (the text ended: the value holds
 * what was read and is marked incomplete, and every caller stops) or
 * STEP_ERROR (err set; the caller frees). */
#include "json_read.h"

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef enum step { STEP_OK, STEP_EOF, STEP_ERROR } step;

typedef struct parser {
  const char* text;
  size_t size, at;
  int depth;
  char* err;
  size_t err_size;
} parser;

static step fail(parser* p, const char* fmt, ...) __attribute__((format(printf, 2, 3)));
static step fail(parser* p, const char* fmt, ...) {
  char what[96];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(what, sizeof what, fmt, ap);
  va_end(ap);
  snprintf(p->err, p->err_size, "%s at byte %zu", what, p->at);
  return STEP_ERROR;
}

static void skip_space(parser* p) {
  while (p->at < p->size && strchr(" \t\r\n", p->text[p->at]) && p->text[p->at])
    p->at++;
}

static step parse_value(parser* p, json_value* v);

static step parse_literal(parser* p, json_value* v, const char* word, json_type type, bool b) {
  size_t n = strlen(word), left = p->size - p->at;
  v->type = type;
  v->boolean = b;
  if (memcmp(p->text + p->at, word, left < n ? left : n)) return fail(p, "unexpected character");
  if (left < n) return p->at = p->size, STEP_EOF;
  p->at += n;
  v->complete = true;
  return STEP_OK;
}

static step parse_number(parser* p, json_value* v) {
  size_t start = p->at;
  while (p->at < p->size && strchr("+-.eE0123456789", p->text[p->at]) && p->text[p->at])
    p->at++;
  char buf[64];
  size_t n = p->at - start;
  if (n == 0 || n >= sizeof buf) return fail(p, "bad number");
  memcpy(buf, p->text + start, n);
  buf[n] = 0;
  char* end;
  v->type = JSON_NUMBER;
  v->number = strtod(buf, &end);
  if (p->at == p->size) return STEP_EOF; /* the number may go on */
  if (*end || !isfinite(v->number) || !strchr("-0123456789", buf[0])) return fail(p, "bad number");
  v->complete = true;
  return STEP_OK;
}

static int hex4(const char* s) {
  int x = 0;
  for (int i = 0; i < 4; i++) {
    char c = s[i];
    int d = c >= '0' && c <= '9'   ? c - '0'
            : c >= 'a' && c <= 'f' ? c - 'a' + 10
            : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                   : -1;
    if (d < 0) return -1;
    x = x * 16 + d;
  }
  return x;
}

static size_t put_utf8(char* out, uint32_t c) {
  if (c < 0x80) return out[0] = (char)c, 1;
  if (c < 0x800) return out[0] = (char)(0xC0 | c >> 6), out[1] = (char)(0x80 | (c & 63)), 2;
  if (c < 0x10000) {
    out[0] = (char)(0xE0 | c >> 12), out[1] = (char)(0x80 | (c >> 6 & 63)), out[2] = (char)(0x80 | (c & 63));
    return 3;
  }
  out[0] = (char)(0xF0 | c >> 18), out[1] = (char)(0x80 | (c >> 12 & 63));
  out[2] = (char)(0x80 | (c >> 6 & 63)), out[3] = (char)(0x80 | (c & 63));
  return 4;
}

/* One escape after the backslash at p->at; appends its UTF-8 to out. */
static step parse_escape(parser* p, char* out, size_t* n) {
  static const char from[] = "\"\\/bfnrt", to[] = "\"\\/\b\f\n\r\t";
  if (p->at + 1 >= p->size) return p->at = p->size, STEP_EOF;
  const char* e = strchr(from, p->text[p->at + 1]);
  if (e && p->text[p->at + 1]) return out[(*n)++] = to[e - from], p->at += 2, STEP_OK;
  if (p->text[p->at + 1] != 'u') return fail(p, "bad escape");
  if (p->at + 6 > p->size) return p->at = p->size, STEP_EOF;
  int c = hex4(p->text + p->at + 2);
  if (c < 0) return fail(p, "bad \\u escape");
  p->at += 6;
  if (c >= 0xD800 && c < 0xDC00 && p->at + 6 <= p->size && p->text[p->at] == '\\' && p->text[p->at + 1] == 'u') {
    int lo = hex4(p->text + p->at + 2);
    if (lo >= 0xDC00 && lo < 0xE000) {
      p->at += 6;
      c = 0x10000 + ((c - 0xD800) << 10) + (lo - 0xDC00);
    }
  }
  *n += put_utf8(out + *n, c >= 0xD800 && c < 0xE000 ? 0xFFFD : (uint32_t)c);
  return STEP_OK;
}

/* A string at p->at (its opening quote); *out malloc'd, NUL-terminated. */
static step parse_string_text(parser* p, char** out) {
  p->at++;
  /* Decoded text is never longer than the escaped text (an escape's first two bytes count 4 here). */
  size_t cap = 5, n = 0;
  for (size_t i = p->at; i < p->size && p->text[i] != '"'; i++, cap += 2)
    i += p->text[i] == '\\';
  char* s = malloc(cap + 4);
  if (!s) return fail(p, "out of memory");
  *out = s;
  while (p->at < p->size && p->text[p->at] != '"') {
    unsigned char c = (unsigned char)p->text[p->at];
    if (c < 0x20) return s[n] = 0, fail(p, "control character in string");
    step st = c == '\\' ? parse_escape(p, s, &n) : (s[n++] = (char)c, p->at++, STEP_OK);
    if (st != STEP_OK) return s[n] = 0, st;
  }
  s[n] = 0;
  if (p->at == p->size) return STEP_EOF;
  p->at++;
  return STEP_OK;
}

static step parse_string(parser* p, json_value* v) {
  v->type = JSON_STRING;
  step st = parse_string_text(p, &v->string);
  v->complete = st == STEP_OK;
  return st;
}

/* Room for one more item (and key) in a container of *cap. */
static bool grow(json_value* v, size_t* cap) {
  if (v->count < *cap) return true;
  size_t c = *cap ? *cap * 2 : 8;
  json_value* items = realloc(v->items, c * sizeof *items);
  if (items) v->items = items;
  if (v->type == JSON_OBJECT) {
    char** keys = items ? realloc(v->keys, c * sizeof *keys) : NULL;
    if (!keys) return false;
    v->keys = keys;
  }
  return items ? (*cap = c, true) : false;
}

/* After an item: ',' (more), the closer (done) or the end of the text. */
static step after_item(parser* p, char closer, bool* more) {
  skip_space(p);
  if (p->at == p->size) return STEP_EOF;
  char c = p->text[p->at++];
  if (c == closer) return *more = false, STEP_OK;
  if (c == ',') return *more = true, STEP_OK;
  p->at--;
  return fail(p, "expected ',' or '%c'", closer);
}

static step parse_member(parser* p, json_value* v) {
  skip_space(p);
  if (p->at == p->size) return STEP_EOF;
  if (p->text[p->at] != '"') return fail(p, "expected a key");
  char* key = NULL;
  step st = parse_string_text(p, &key);
  skip_space(p);
  if (st == STEP_OK && p->at < p->size && p->text[p->at++] != ':') st = (p->at--, fail(p, "expected ':'"));
  if (st == STEP_OK && p->at == p->size) st = STEP_EOF;
  if (st != STEP_OK) return free(key), st;
  json_value* item = &v->items[v->count];
  memset(item, 0, sizeof *item);
  v->keys[v->count++] = key;
  return parse_value(p, item);
}

static step parse_container(parser* p, json_value* v, json_type type, char closer) {
  v->type = type;
  if (++p->depth > JSON_READ_MAX_DEPTH) return fail(p, "nested deeper than %d", JSON_READ_MAX_DEPTH);
  p->at++;
  skip_space(p);
  if (p->at == p->size) return STEP_EOF;
  bool more = p->text[p->at] != closer;
  if (!more) p->at++;
  for (size_t cap = 0; more;) {
    if (!grow(v, &cap)) return fail(p, "out of memory");
    step st = type == JSON_OBJECT
                  ? parse_member(p, v)
                  : (memset(&v->items[v->count], 0, sizeof *v->items), parse_value(p, &v->items[v->count++]));
    if (st == STEP_OK) st = after_item(p, closer, &more);
    if (st != STEP_OK) return st;
  }
  p->depth--;
  v->complete = true;
  return STEP_OK;
}

static step parse_value(parser* p, json_value* v) {
  skip_space(p);
  if (p->at == p->size) return STEP_EOF;
  switch (p->text[p->at]) {
  case '{':
    return parse_container(p, v, JSON_OBJECT, '}');
  case '[':
    return parse_container(p, v, JSON_ARRAY, ']');
  case '"':
    return parse_string(p, v);
  case 't':
    return parse_literal(p, v, "true", JSON_BOOL, true);
  case 'f':
    return parse_literal(p, v, "false", JSON_BOOL, false);
  case 'n':
    return parse_literal(p, v, "null", JSON_NULL, false);
  default:
    return parse_number(p, v);
  }
}

static void free_children(json_value* v) {
  for (size_t i = 0; i < v->count; i++) {
    free_children(&v->items[i]);
    if (v->keys) free(v->keys[i]);
  }
  free(v->items);
  free(v->keys);
  free(v->string);
}

void json_free(json_value* v) {
  if (!v) return;
  free_children(v);
  free(v);
}

json_read_status json_read(const char* text, size_t size, json_value** out, char* err, size_t err_size) {
  parser p = {.text = text, .size = size, .err = err, .err_size = err_size};
  json_value* root = calloc(1, sizeof *root);
  *out = NULL;
  if (!root) return snprintf(err, err_size, "out of memory"), JSON_READ_ERROR;
  step st = parse_value(&p, root);
  if (st == STEP_OK) skip_space(&p);
  if (st == STEP_OK && p.at < p.size) st = fail(&p, "text after the value");
  if (st == STEP_ERROR) return json_free(root), JSON_READ_ERROR;
  *out = root;
  return st == STEP_EOF ? JSON_READ_TRUNCATED : JSON_READ_OK;
}

const json_value* json_get(const json_value* v, const char* key) {
  if (!v || v->type != JSON_OBJECT) return NULL;
  for (size_t i = 0; i < v->count; i++) {
    const json_value* x = &v->items[i];
    bool container = x->type == JSON_ARRAY || x->type == JSON_OBJECT;
    if (!strcmp(v->keys[i], key)) return x->complete || container ? x : NULL;
  }
  return NULL;
}
