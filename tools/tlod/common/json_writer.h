/* A small streaming JSON writer for stats and traces: keys and values are
 * written as they come, commas and nesting are tracked here. */
#ifndef TLOD_TOOLS_JSON_WRITER_H
#define TLOD_TOOLS_JSON_WRITER_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

typedef struct json_writer {
  FILE* f;
  int depth;
  bool first[32];
  bool after_key;
} json_writer;

void json_begin(json_writer* w, FILE* f);
/* s as a JSON string (quoted, escaped) straight into f. */
void json_put_string(FILE* f, const char* s);
void json_object_begin(json_writer* w, const char* key);
void json_object_end(json_writer* w);
void json_array_begin(json_writer* w, const char* key);
void json_array_end(json_writer* w);
void json_string(json_writer* w, const char* key, const char* value);
void json_number(json_writer* w, const char* key, double value);
void json_uint(json_writer* w, const char* key, uint64_t value);
void json_int(json_writer* w, const char* key, int64_t value);
void json_bool(json_writer* w, const char* key, bool value);
/* Finishes the document with a newline; false when a write failed. */
bool json_end(json_writer* w);

#endif
