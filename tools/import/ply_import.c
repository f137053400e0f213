/* ply_import.c -- PLY reader (ascii, binary little and big endian) in C11.
 * Owned by the import/export layer (tools/import/).
 *
 * Reads the "vertex" element (x y z, optional nx ny nz, texture coordinates
 * u v / s t / texture_u texture_v as TEXCOORD_0, colours red green blue
 * [alpha] as COLOR_0 (integers scaled to 0..1), any scalar types) and the
 * "face" element's vertex_indices / vertex_index list; every other
 * element and property is parsed and skipped. Every read is bounds-checked
 * against the file, and counts from the header are checked against the
 * bytes left before anything is allocated for them. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "import_internal.h"

#define _PLY_MAX_ELEMENTS 16
#define _PLY_MAX_PROPERTIES 64
#define _PLY_MAX_HEADER 65536
#define _PLY_MAX_CORNERS 65536

typedef enum { _PLY_ASCII, _PLY_LE, _PLY_BE } _ply_format;

typedef struct _ply_type {
  const char* name;
  const char* alias;
  uint8_t size;
  bool is_float, is_signed;
} _ply_type;

static const _ply_type _ply_types[] = {
    {"char", "int8", 1, false, true},      {"uchar", "uint8", 1, false, false},  {"short", "int16", 2, false, true},
    {"ushort", "uint16", 2, false, false}, {"int", "int32", 4, false, true},     {"uint", "uint32", 4, false, false},
    {"float", "float32", 4, true, true},   {"double", "float64", 8, true, true},
};

typedef struct _ply_property {
  char name[32];
  int type;       /* index into _ply_types; the item type of a list */
  int count_type; /* list only */
  bool is_list;
} _ply_property;

typedef struct _ply_element {
  char name[32];
  size_t count;
  uint32_t property_count;
  _ply_property properties[_PLY_MAX_PROPERTIES];
} _ply_element;

typedef struct _ply_reader {
  const _tlod_import_job* job;
  const unsigned char* data;
  size_t size, pos;
  _ply_format format;
  uint32_t element_count;
  _ply_element elements[_PLY_MAX_ELEMENTS];
  const char* where; /* element being read, for messages */
  size_t item;       /* its instance */
} _ply_reader;

/* A scalar read from the body: d for counts and indices, f for floats
 * (parsed straight to float so ascii values round exactly once). */
typedef struct _ply_value {
  double d;
  float f;
} _ply_value;

/* Growable output arrays (malloc; _tlod_import_finish copies them). */
typedef struct _ply_out {
  float* positions;
  float* normals;
  float* texcoords; /* u v per vertex, as stored; NULL: none */
  float* colors;    /* rgba per vertex; NULL: none */
  uint32_t vertex_count;
  uint32_t* indices;
  size_t index_count, index_cap;
  uint8_t* face_sizes;
  size_t face_count, face_cap;
  bool any_quads;
  uint32_t polygons_triangulated;
} _ply_out;

/* ------------------------------------------------------------------------ */
/* Header                                                                   */
/* ------------------------------------------------------------------------ */

static int _ply_find_type(const char* name) {
  for (int i = 0; i < (int)(sizeof _ply_types / sizeof _ply_types[0]); ++i)
    if (!strcmp(name, _ply_types[i].name) || !strcmp(name, _ply_types[i].alias)) return i;
  return -1;
}

/* Splits a header line into words in place (strtok is not reentrant);
 * a seventh word makes the count 7, which every caller rejects. */
static int _ply_words(char* line, char* words[6]) {
  int n = 0;
  char* s = line;
  for (;;) {
    while (*s == ' ' || *s == '\t')
      *s++ = 0;
    if (!*s) return n;
    if (n == 6) return 7;
    words[n++] = s;
    while (*s && *s != ' ' && *s != '\t')
      s++;
  }
}

static tlod_result _ply_header_format(_ply_reader* r, char** w, int n, size_t line) {
  if (n != 3 || strcmp(w[2], "1.0") != 0)
    return _tlod_import_fail(r->job, TLOD_ERROR_PARSE, "header line %zu: bad format line", line);
  if (!strcmp(w[1], "ascii"))
    r->format = _PLY_ASCII;
  else if (!strcmp(w[1], "binary_little_endian"))
    r->format = _PLY_LE;
  else if (!strcmp(w[1], "binary_big_endian"))
    r->format = _PLY_BE;
  else
    return _tlod_import_fail(r->job, TLOD_ERROR_UNSUPPORTED, "header line %zu: format '%.40s'", line, w[1]);
  return TLOD_SUCCESS;
}

static tlod_result _ply_header_element(_ply_reader* r, char** w, int n, size_t line) {
  char* end = NULL;
  if (n != 3 || r->element_count == _PLY_MAX_ELEMENTS)
    return _tlod_import_fail(r->job, TLOD_ERROR_PARSE, "header line %zu: bad element line", line);
  unsigned long long count = strtoull(w[2], &end, 10);
  if (*end || w[2][0] == '-' || count > (unsigned long long)SIZE_MAX / 2)
    return _tlod_import_fail(r->job, TLOD_ERROR_PARSE, "header line %zu: bad element count '%.40s'", line, w[2]);
  _ply_element* e = &r->elements[r->element_count++];
  snprintf(e->name, sizeof e->name, "%s", w[1]);
  e->count = (size_t)count;
  e->property_count = 0;
  return TLOD_SUCCESS;
}

static tlod_result _ply_header_property(_ply_reader* r, char** w, int n, size_t line) {
  if (r->element_count == 0)
    return _tlod_import_fail(r->job, TLOD_ERROR_PARSE, "header line %zu: property before any element", line);
  _ply_element* e = &r->elements[r->element_count - 1];
  if (e->property_count == _PLY_MAX_PROPERTIES)
    return _tlod_import_fail(r->job, TLOD_ERROR_UNSUPPORTED, "header line %zu: too many properties", line);
  _ply_property* p = &e->properties[e->property_count];
  p->is_list = n >= 2 && !strcmp(w[1], "list");
  const int want = p->is_list ? 5 : 3;
  if (n != want) return _tlod_import_fail(r->job, TLOD_ERROR_PARSE, "header line %zu: bad property line", line);
  p->count_type = p->is_list ? _ply_find_type(w[2]) : 0;
  p->type = _ply_find_type(w[want - 2]);
  if (p->type < 0 || p->count_type < 0 || (p->is_list && _ply_types[p->count_type].is_float))
    return _tlod_import_fail(r->job, TLOD_ERROR_PARSE, "header line %zu: bad property type", line);
  snprintf(p->name, sizeof p->name, "%s", w[want - 1]);
  e->property_count++;
  return TLOD_SUCCESS;
}

static tlod_result _ply_header_line(_ply_reader* r, char* text, size_t line, bool* done) {
  char* w[6];
  const int n = _ply_words(text, w);
  if (n == 0 || !strcmp(w[0], "comment") || !strcmp(w[0], "obj_info")) return TLOD_SUCCESS;
  if (!strcmp(w[0], "format")) return _ply_header_format(r, w, n, line);
  if (!strcmp(w[0], "element")) return _ply_header_element(r, w, n, line);
  if (!strcmp(w[0], "property")) return _ply_header_property(r, w, n, line);
  if (!strcmp(w[0], "end_header")) {
    *done = true;
    return TLOD_SUCCESS;
  }
  return _tlod_import_fail(r->job, TLOD_ERROR_PARSE, "header line %zu: unknown keyword '%.40s'", line, w[0]);
}

static tlod_result _ply_read_header(_ply_reader* r) {
  if (r->size < 4 || memcmp(r->data, "ply", 3) != 0 || (r->data[3] != '\n' && r->data[3] != '\r'))
    return _tlod_import_fail(r->job, TLOD_ERROR_PARSE, "not a PLY file (no 'ply' line)");
  r->format = (_ply_format)-1;
  bool done = false;
  size_t pos = 0, line = 0;
  char text[512];
  while (!done) {
    const unsigned char* nl = memchr(r->data + pos, '\n', r->size - pos);
    if (!nl || (size_t)(nl - r->data) > _PLY_MAX_HEADER)
      return _tlod_import_fail(r->job, TLOD_ERROR_PARSE, "header without end_header");
    size_t len = (size_t)(nl - (r->data + pos));
    if (len >= sizeof text) return _tlod_import_fail(r->job, TLOD_ERROR_PARSE, "header line %zu too long", line + 1);
    memcpy(text, r->data + pos, len);
    text[len] = 0;
    if (len && text[len - 1] == '\r') text[len - 1] = 0;
    line++;
    pos += len + 1;
    if (line == 1) continue; /* "ply" */
    tlod_result res = _ply_header_line(r, text, line, &done);
    if (res != TLOD_SUCCESS) return res;
  }
  if ((int)r->format < 0) return _tlod_import_fail(r->job, TLOD_ERROR_PARSE, "header has no format line");
  r->pos = pos;
  return TLOD_SUCCESS;
}

/* ------------------------------------------------------------------------ */
/* Body values                                                              */
/* ------------------------------------------------------------------------ */

static tlod_result _ply_truncated(_ply_reader* r) {
  return _tlod_import_fail(r->job, TLOD_ERROR_PARSE, "%s %zu: unexpected end of data", r->where, r->item);
}

static tlod_result _ply_binary(_ply_reader* r, int type, _ply_value* v) {
  const _ply_type* t = &_ply_types[type];
  if (t->size > r->size - r->pos) return _ply_truncated(r);
  uint64_t u = 0;
  for (unsigned i = 0; i < t->size; ++i) {
    const unsigned shift = r->format == _PLY_LE ? 8u * i : 8u * (t->size - 1u - i);
    u |= (uint64_t)r->data[r->pos + i] << shift;
  }
  r->pos += t->size;
  if (t->is_float && t->size == 4) {
    uint32_t b = (uint32_t)u;
    memcpy(&v->f, &b, 4);
    v->d = v->f;
  } else if (t->is_float) {
    memcpy(&v->d, &u, 8);
    v->f = (float)v->d;
  } else if (t->is_signed) {
    const uint64_t sign = (uint64_t)1 << (8u * t->size - 1u);
    v->d = (double)(int64_t)((u ^ sign) - sign); /* sign-extend */
    v->f = (float)v->d;
  } else {
    v->d = (double)u;
    v->f = (float)v->d;
  }
  return TLOD_SUCCESS;
}

static bool _ply_space(unsigned char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

static tlod_result _ply_ascii(_ply_reader* r, int type, _ply_value* v) {
  while (r->pos < r->size && _ply_space(r->data[r->pos]))
    r->pos++;
  size_t end = r->pos;
  while (end < r->size && !_ply_space(r->data[end]))
    end++;
  if (end == r->pos) return _ply_truncated(r);
  char tok[64];
  if (end - r->pos >= sizeof tok)
    return _tlod_import_fail(r->job, TLOD_ERROR_PARSE, "%s %zu: number too long", r->where, r->item);
  memcpy(tok, r->data + r->pos, end - r->pos);
  tok[end - r->pos] = 0;
  r->pos = end;
  char* stop = NULL;
  if (_ply_types[type].is_float) {
    v->f = strtof(tok, &stop);
    v->d = strtod(tok, NULL);
  } else {
    v->d = (double)strtoll(tok, &stop, 10);
    v->f = (float)v->d;
  }
  if (*stop)
    return _tlod_import_fail(r->job, TLOD_ERROR_PARSE, "%s %zu: '%s' is not a %s", r->where, r->item, tok,
                             _ply_types[type].name);
  return TLOD_SUCCESS;
}

static tlod_result _ply_value_read(_ply_reader* r, int type, _ply_value* v) {
  return r->format == _PLY_ASCII ? _ply_ascii(r, type, v) : _ply_binary(r, type, v);
}

/* A list length: integral and within bounds. */
static tlod_result _ply_list_count(_ply_reader* r, const _ply_property* p, size_t* n) {
  _ply_value v;
  tlod_result res = _ply_value_read(r, p->count_type, &v);
  if (res != TLOD_SUCCESS) return res;
  if (!(v.d >= 0.0) || v.d > _PLY_MAX_CORNERS)
    return _tlod_import_fail(r->job, TLOD_ERROR_PARSE, "%s %zu: list '%s' has %g items", r->where, r->item, p->name,
                             v.d);
  *n = (size_t)v.d;
  return TLOD_SUCCESS;
}

static tlod_result _ply_skip_property(_ply_reader* r, const _ply_property* p) {
  _ply_value v;
  if (!p->is_list) return _ply_value_read(r, p->type, &v);
  size_t n = 0;
  tlod_result res = _ply_list_count(r, p, &n);
  for (size_t i = 0; i < n && res == TLOD_SUCCESS; ++i)
    res = _ply_value_read(r, p->type, &v);
  return res;
}

/* Smallest number of body bytes one instance can take: guards allocations
 * sized from a header count against a corrupt count. */
static size_t _ply_min_bytes(const _ply_reader* r, const _ply_element* e) {
  size_t n = 0;
  for (uint32_t i = 0; i < e->property_count; ++i) {
    const _ply_property* p = &e->properties[i];
    if (r->format == _PLY_ASCII)
      n += 2; /* a digit and a separator */
    else
      n += _ply_types[p->is_list ? p->count_type : p->type].size;
  }
  return n ? n : 1;
}

static tlod_result _ply_check_count(_ply_reader* r, const _ply_element* e) {
  if (e->count > (r->size - r->pos) / _ply_min_bytes(r, e))
    return _tlod_import_fail(r->job, TLOD_ERROR_PARSE, "element '%s' count %zu does not fit in the %zu bytes left",
                             e->name, e->count, r->size - r->pos);
  return TLOD_SUCCESS;
}

/* ------------------------------------------------------------------------ */
/* Elements                                                                 */
/* ------------------------------------------------------------------------ */

static int _ply_find_property(const _ply_element* e, const char* name) {
  for (uint32_t i = 0; i < e->property_count; ++i)
    if (!e->properties[i].is_list && !strcmp(e->properties[i].name, name)) return (int)i;
  return -1;
}

/* Vertex properties read, by slot: position, normal, texture coordinate, colour. */
enum { _PLY_X = 0, _PLY_NX = 3, _PLY_U = 6, _PLY_RED = 8, _PLY_ALPHA = 11, _PLY_SLOTS = 12 };

/* Where each slot comes from: slot[i] = property index or -1. Texture coordinates are the
 * first complete pair of u v, s t, texture_u texture_v. */
static tlod_result _ply_vertex_slots(_ply_reader* r, const _ply_element* e, int slot[_PLY_SLOTS]) {
  static const char* const names[_PLY_SLOTS] = {"x", "y", "z",   "nx",    "ny",   "nz",
                                                "",  "",  "red", "green", "blue", "alpha"};
  static const char* const uv[3][2] = {{"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}};
  for (int i = 0; i < _PLY_SLOTS; ++i)
    slot[i] = names[i][0] ? _ply_find_property(e, names[i]) : -1;
  for (int k = 0; k < 3 && slot[_PLY_U] < 0; ++k)
    if (_ply_find_property(e, uv[k][0]) >= 0 && _ply_find_property(e, uv[k][1]) >= 0) {
      slot[_PLY_U] = _ply_find_property(e, uv[k][0]);
      slot[_PLY_U + 1] = _ply_find_property(e, uv[k][1]);
    }
  if (slot[0] < 0 || slot[1] < 0 || slot[2] < 0)
    return _tlod_import_fail(r->job, TLOD_ERROR_PARSE, "element 'vertex' lacks an x, y or z property");
  return TLOD_SUCCESS;
}

static bool _ply_has(const int slot[_PLY_SLOTS], int first, int n) {
  for (int i = first; i < first + n; ++i)
    if (slot[i] < 0) return false;
  return true;
}

/* Colours: integers scaled to 0..1 by their type's maximum (uchar /255), floats as stored. */
static float _ply_unit(const _ply_property* p, const _ply_value* v) {
  const _ply_type* t = &_ply_types[p->type];
  if (t->is_float) return v->f;
  const double max = t->size == 1 ? 255.0 : t->size == 2 ? 65535.0 : 4294967295.0;
  return (float)(v->d / max);
}

static tlod_result _ply_read_vertex(_ply_reader* r, const _ply_element* e, const int slot[_PLY_SLOTS],
                                    float out[_PLY_SLOTS]) {
  for (uint32_t i = 0; i < e->property_count; ++i) {
    const _ply_property* p = &e->properties[i];
    _ply_value v;
    int target = -1;
    for (int s = 0; s < _PLY_SLOTS; ++s)
      if (slot[s] == (int)i) target = s;
    if (target < 0 || p->is_list) {
      tlod_result res = _ply_skip_property(r, p);
      if (res != TLOD_SUCCESS) return res;
      continue;
    }
    tlod_result res = _ply_value_read(r, p->type, &v);
    if (res != TLOD_SUCCESS) return res;
    out[target] = target >= _PLY_RED ? _ply_unit(p, &v) : v.f;
  }
  for (int k = 0; k < _PLY_SLOTS; ++k)
    if (!isfinite(out[k]))
      return _tlod_import_fail(r->job, TLOD_ERROR_INVALID_MESH, "vertex %zu: property '%s' is not finite", r->item,
                               e->properties[slot[k] >= 0 ? slot[k] : 0].name);
  return TLOD_SUCCESS;
}

/* The vertex arrays, from the budget first (count was checked against the file). */
static tlod_result _ply_alloc_vertices(_ply_reader* r, const _ply_element* e, const int slot[_PLY_SLOTS], _ply_out* o) {
  const bool normals = _ply_has(slot, _PLY_NX, 3), uv = _ply_has(slot, _PLY_U, 2), rgb = _ply_has(slot, _PLY_RED, 3);
  if (!_tlod_budget_take(r->job->budget, e->count * (12 + 12 + 8 + 16) + 48))
    return _tlod_import_fail(r->job, TLOD_ERROR_OUT_OF_MEMORY,
                             "element 'vertex': %zu vertices exceed the import's memory budget (%zu bytes; "
                             "tlod_import_desc.memory_limit)",
                             e->count, r->job->budget->limit);
  o->positions = malloc(e->count * 12 + 12);
  o->normals = normals ? malloc(e->count * 12 + 12) : NULL;
  o->texcoords = uv ? malloc(e->count * 8 + 8) : NULL;
  o->colors = rgb ? malloc(e->count * 16 + 16) : NULL;
  if (!o->positions || (normals && !o->normals) || (uv && !o->texcoords) || (rgb && !o->colors))
    return _tlod_import_fail(r->job, TLOD_ERROR_OUT_OF_MEMORY, "out of memory for %zu vertices", e->count);
  return TLOD_SUCCESS;
}

static tlod_result _ply_read_vertices(_ply_reader* r, const _ply_element* e, _ply_out* o) {
  int slot[_PLY_SLOTS];
  tlod_result res = _ply_vertex_slots(r, e, slot);
  if (res == TLOD_SUCCESS) res = _ply_check_count(r, e);
  if (res != TLOD_SUCCESS) return res;
  if (e->count > _TLOD_IMPORT_MAX_VERTICES || o->positions)
    return _tlod_import_fail(r->job, TLOD_ERROR_UNSUPPORTED, "%zu vertices (one vertex element of at most %zu)",
                             e->count, (size_t)_TLOD_IMPORT_MAX_VERTICES);
  res = _ply_alloc_vertices(r, e, slot, o);
  if (res != TLOD_SUCCESS) return res;
  o->vertex_count = (uint32_t)e->count;
  r->where = "vertex";
  for (r->item = 0; r->item < e->count; ++r->item) {
    float v[_PLY_SLOTS] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1};
    res = _ply_read_vertex(r, e, slot, v);
    if (res != TLOD_SUCCESS) return res;
    memcpy(o->positions + 3 * r->item, v, 12);
    if (o->normals) memcpy(o->normals + 3 * r->item, v + _PLY_NX, 12);
    if (o->texcoords) memcpy(o->texcoords + 2 * r->item, v + _PLY_U, 8);
    if (o->colors) memcpy(o->colors + 4 * r->item, v + _PLY_RED, 16);
  }
  return TLOD_SUCCESS;
}

static bool _ply_reserve(void** p, size_t* cap, size_t need, size_t item) {
  if (need <= *cap) return true;
  size_t c = *cap ? *cap : 1024;
  while (c < need)
    c *= 2;
  void* q = realloc(*p, c * item);
  if (!q) return false;
  *p = q;
  *cap = c;
  return true;
}

static tlod_result _ply_emit(_ply_reader* r, _ply_out* o, const uint32_t* v, size_t n) {
  size_t tris = n <= 4 ? 1 : n - 2, idx = n <= 4 ? n : 3 * (n - 2);
  if (o->index_count + idx > _TLOD_IMPORT_MAX_INDICES)
    return _tlod_import_fail(r->job, TLOD_ERROR_UNSUPPORTED, "more than %zu indices", (size_t)_TLOD_IMPORT_MAX_INDICES);
  void* ip = o->indices;
  void* fp = o->face_sizes;
  if (!_ply_reserve(&ip, &o->index_cap, o->index_count + idx, 4) ||
      !_ply_reserve(&fp, &o->face_cap, o->face_count + tris, 1)) {
    o->indices = ip;
    o->face_sizes = fp;
    return _tlod_import_fail(r->job, TLOD_ERROR_OUT_OF_MEMORY, "out of memory for faces");
  }
  o->indices = ip;
  o->face_sizes = fp;
  if (n <= 4) {
    memcpy(o->indices + o->index_count, v, n * 4);
    o->index_count += n;
    o->face_sizes[o->face_count++] = (uint8_t)n;
    o->any_quads |= n == 4;
    return TLOD_SUCCESS;
  }
  for (size_t i = 1; i + 1 < n; ++i) { /* fan: keeps the polygon's winding */
    uint32_t* t = o->indices + o->index_count;
    t[0] = v[0], t[1] = v[i], t[2] = v[i + 1];
    o->index_count += 3;
    o->face_sizes[o->face_count++] = 3;
  }
  o->polygons_triangulated++;
  return TLOD_SUCCESS;
}

static tlod_result _ply_read_corners(_ply_reader* r, const _ply_property* p, _ply_out* o, uint32_t* v, size_t* n) {
  tlod_result res = _ply_list_count(r, p, n);
  if (res != TLOD_SUCCESS) return res;
  if (*n < 3)
    return _tlod_import_fail(r->job, TLOD_ERROR_INVALID_MESH, "face %zu has %zu corners (at least 3 needed)", r->item,
                             *n);
  for (size_t i = 0; i < *n; ++i) {
    _ply_value x;
    res = _ply_value_read(r, p->type, &x);
    if (res != TLOD_SUCCESS) return res;
    if (!(x.d >= 0.0) || x.d >= (double)o->vertex_count)
      return _tlod_import_fail(r->job, TLOD_ERROR_INVALID_MESH, "face %zu: index %.0f out of range (%u vertices)",
                               r->item, x.d, o->vertex_count);
    v[i] = (uint32_t)x.d;
  }
  return TLOD_SUCCESS;
}

static tlod_result _ply_read_face(_ply_reader* r, const _ply_element* e, int list, _ply_out* o, uint32_t* v) {
  for (uint32_t i = 0; i < e->property_count; ++i) {
    size_t n = 0;
    tlod_result res =
        (int)i == list ? _ply_read_corners(r, &e->properties[i], o, v, &n) : _ply_skip_property(r, &e->properties[i]);
    if (res == TLOD_SUCCESS && (int)i == list) res = _ply_emit(r, o, v, n);
    if (res != TLOD_SUCCESS) return res;
  }
  return TLOD_SUCCESS;
}

static tlod_result _ply_read_faces(_ply_reader* r, const _ply_element* e, _ply_out* o) {
  int list = -1;
  for (uint32_t i = 0; i < e->property_count; ++i)
    if (e->properties[i].is_list &&
        (!strcmp(e->properties[i].name, "vertex_indices") || !strcmp(e->properties[i].name, "vertex_index")))
      list = (int)i;
  if (list < 0 || _ply_types[e->properties[list].type].is_float)
    return _tlod_import_fail(r->job, TLOD_ERROR_PARSE, "element 'face' lacks an integer vertex_indices list");
  if (!o->positions) return _tlod_import_fail(r->job, TLOD_ERROR_PARSE, "element 'face' before element 'vertex'");
  tlod_result res = _ply_check_count(r, e);
  if (res != TLOD_SUCCESS) return res;
  uint32_t* v = malloc(_PLY_MAX_CORNERS * sizeof *v);
  if (!v) return _tlod_import_fail(r->job, TLOD_ERROR_OUT_OF_MEMORY, "out of memory");
  r->where = "face";
  for (r->item = 0; r->item < e->count && res == TLOD_SUCCESS; ++r->item)
    res = _ply_read_face(r, e, list, o, v);
  free(v);
  return res;
}

static tlod_result _ply_skip_element(_ply_reader* r, const _ply_element* e) {
  tlod_result res = _ply_check_count(r, e);
  r->where = e->name;
  for (r->item = 0; r->item < e->count && res == TLOD_SUCCESS; ++r->item)
    for (uint32_t i = 0; i < e->property_count && res == TLOD_SUCCESS; ++i)
      res = _ply_skip_property(r, &e->properties[i]);
  return res;
}

static tlod_result _ply_read_body(_ply_reader* r, _ply_out* o) {
  for (uint32_t i = 0; i < r->element_count; ++i) {
    const _ply_element* e = &r->elements[i];
    tlod_result res = !strcmp(e->name, "vertex") ? _ply_read_vertices(r, e, o)
                      : !strcmp(e->name, "face") ? _ply_read_faces(r, e, o)
                                                 : _ply_skip_element(r, e);
    if (res != TLOD_SUCCESS) return res;
  }
  if (!o->positions) return _tlod_import_fail(r->job, TLOD_ERROR_PARSE, "no 'vertex' element");
  if (o->face_count == 0) return _tlod_import_fail(r->job, TLOD_ERROR_INVALID_MESH, "no faces");
  return TLOD_SUCCESS;
}

static tlod_result _ply_finish(_ply_reader* r, const _ply_out* o) {
  tlod_import_part part = {.name = "ply",
                           .first_face = 0,
                           .face_count = (uint32_t)o->face_count,
                           .first_vertex = 0,
                           .vertex_count = o->vertex_count,
                           .base_color = {1, 1, 1, 1},
                           .had_normals = o->normals != NULL};
  _tlod_import_data d = {0};
  d.vertex_count = o->vertex_count;
  d.positions = o->positions;
  d.normals = o->normals;
  d.index_count = (uint32_t)o->index_count;
  d.indices = o->indices;
  d.face_count = (uint32_t)o->face_count;
  d.face_sizes = o->any_quads ? o->face_sizes : NULL;
  d.part_count = 1;
  d.parts = &part;
  d.polygons_triangulated = o->polygons_triangulated;
  tlod_import_attribute attrs[2];
  if (o->texcoords) attrs[d.attribute_count++] = (tlod_import_attribute){"TEXCOORD_0", 2, o->texcoords};
  if (o->colors) attrs[d.attribute_count++] = (tlod_import_attribute){"COLOR_0", 4, o->colors};
  d.attributes = attrs;
  return _tlod_import_finish(r->job, &d);
}

tlod_result _tlod_import_ply(const _tlod_import_job* job) {
  unsigned char* data = NULL;
  size_t size = 0;
  tlod_result res = _tlod_import_read_file(job, &data, &size);
  if (res != TLOD_SUCCESS) return res;
  _ply_reader* r = calloc(1, sizeof *r); /* ~70 KB of header tables: not on the stack */
  _ply_out o = {0};
  if (!r) res = _tlod_import_fail(job, TLOD_ERROR_OUT_OF_MEMORY, "out of memory");
  if (res == TLOD_SUCCESS) {
    r->job = job;
    r->data = data;
    r->size = size;
    res = _ply_read_header(r);
  }
  if (res == TLOD_SUCCESS) res = _ply_read_body(r, &o);
  if (res == TLOD_SUCCESS) res = _ply_finish(r, &o);
  free(o.positions);
  free(o.normals);
  free(o.texcoords);
  free(o.colors);
  free(o.indices);
  free(o.face_sizes);
  free(r);
  free(data);
  return res;
}
