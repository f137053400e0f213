/* A small tolerant JSON reader for the files tlod writes (run_read.h): the
 * whole text becomes a tree; a text that ends early (a trace cut short) still
 * gives the tree of what came before, each value marked complete or not.
 *
 * Why our own and not nlohmann-json: nlohmann's DOM parser discards
 * everything on a truncated text, its SAX interface would need a C++ shim
 * with its own error plumbing, and the subset needed here (RFC 8259 values,
 * UTF-8 strings) is about 250 lines of C that the fuzz target covers.
 *
 * Bounds: nesting at most JSON_READ_MAX_DEPTH; strings and containers grow
 * with the text only (the caller bounds its size). Duplicate keys: the first
 * wins (json_get). Numbers are doubles (strtod; overflow is an error). */
#ifndef TLOD_TOOLS_JSON_READ_H
#define TLOD_TOOLS_JSON_READ_H

#include <stdbool.h>
#include <stddef.h>

#define JSON_READ_MAX_DEPTH 64

typedef enum json_type { JSON_NULL, JSON_BOOL, JSON_NUMBER, JSON_STRING, JSON_ARRAY, JSON_OBJECT } json_type;

typedef struct json_value {
  json_type type;
  bool complete; /* false: the text ended inside this value */
  bool boolean;
  double number;
  char* string; /* JSON_STRING: decoded UTF-8, NUL-terminated */
  size_t count; /* JSON_ARRAY, JSON_OBJECT: items */
  struct json_value* items;
  char** keys; /* JSON_OBJECT: keys[i] names items[i] */
} json_value;

typedef enum json_read_status {
  JSON_READ_OK,
  JSON_READ_TRUNCATED, /* the text ended inside the root: *out holds what was read */
  JSON_READ_ERROR,     /* err says what and at which byte; *out is NULL */
} json_read_status;

/* Parses text[0..size) into *out (free with json_free). */
json_read_status json_read(const char* text, size_t size, json_value** out, char* err, size_t err_size);
void json_free(json_value* v);
/* The value of key in an object (first of duplicates), NULL when absent, when
 * v is not an object, or when the value is a scalar the text cut short (a
 * string or number that may go on: absent, not a wrong value). Containers
 * cut short are returned, marked incomplete. */
const json_value* json_get(const json_value* v, const char* key);

#endif
