/* Result fields of an import (VTK point and cell data) as one scalar per
 * vertex, for colour mapping (tlod play --field NAME[:COMPONENT|magnitude],
 * --range MIN,MAX). */
#ifndef TLOD_TOOLS_FIELD_SELECT_H
#define TLOD_TOOLS_FIELD_SELECT_H

#include <stdbool.h>
#include <stdint.h>

#include "colormap.h"
#include "tlod_import.h"

/* What the command line asks for; spec NULL: no field. */
typedef struct field_options {
  const char* spec; /* "NAME", "NAME:COMPONENT" (0-based index, or x y z w), "NAME:magnitude" */
  bool has_range;   /* --range given */
  float range[2];   /* MIN < MAX, finite */
  colormap_kind colormap;
} field_options;

/* The chosen scalar. component -1: the Euclidean norm of the tuple (the
 * default for fields of 2 or more components); 1-component fields: the
 * value itself. */
typedef struct field_selection {
  uint32_t field; /* index into the import's fields */
  int component;
  char name[64], units[32];
  char label[80]; /* "stress", "displacement:magnitude", "velocity:1" */
  bool from_cells;
  float lo, hi; /* the range mapped onto the colour map: --range, else the field's over all steps */
  colormap_kind colormap;
} field_selection;

/* Parses --range's "MIN,MAX" (finite, MIN < MAX): false with the error printed. */
bool field_parse_range(const char* option, const char* text, float range[2]);

/* Chooses o->spec among r's fields (r may be NULL: no fields). CLI_OK, or
 * CLI_FAILED with an error naming the input and listing the fields found. */
int field_select(const tlod_import_result* r, const char* input, const field_options* o, field_selection* out);

/* The scalar of every vertex of r at step s (< max(1, r->step_count)) into out[vertex_count]. */
void field_scalars(const tlod_import_result* r, const field_selection* f, uint32_t step, float* out);

#endif
