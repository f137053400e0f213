/* tesslod::lod -- names of lod's enums, from the one table per enum in
 * tesslod/lod.h and tesslod/patterns.h, for parsing and printing. */
#include <string.h>

#include "tesslod/lod.h"

/* A table as data: one lookup pair serves every enum. */
typedef struct name_entry {
  int value;
  const char* name;
} name_entry;

#define NAME_ENTRY(value, text) {(int)(value), text},
#define COUNT(table) (sizeof(table) / sizeof((table)[0]))

static const name_entry k_policies[] = {TLOD_LOD_POLICY_NAMES(NAME_ENTRY)};
static const name_entry k_morphs[] = {TLOD_MORPH_MODE_NAMES(NAME_ENTRY)};
static const name_entry k_stages[] = {TLOD_STAGE_NAMES(NAME_ENTRY)};
static const name_entry k_shapes[] = {TLOD_PATTERN_SHAPE_NAMES(NAME_ENTRY)};

static const char* name_of(const name_entry* table, size_t count, int value) {
  for (size_t i = 0; i < count; i++)
    if (table[i].value == value) return table[i].name;
  return NULL;
}

/* The entry named name, or NULL. */
static const name_entry* entry_named(const name_entry* table, size_t count, const char* name) {
  for (size_t i = 0; name && i < count; i++)
    if (strcmp(table[i].name, name) == 0) return &table[i];
  return NULL;
}

/* NAME_name() and NAME_from_name() over a table. DEFAULT values have no
 * name of their own: they print as the value they resolve to. */
#define DEFINE_NAMES(fn, type, table, default_value, resolved)                                                         \
  const char* fn##_name(type value) {                                                                                  \
    return name_of(table, COUNT(table), (int)(value == (default_value) ? (resolved) : value));                         \
  }                                                                                                                    \
  bool fn##_from_name(const char* name, type* out) {                                                                   \
    const name_entry* e = entry_named(table, COUNT(table), name);                                                      \
    if (e && out) *out = (type)e->value;                                                                               \
    return e && out;                                                                                                   \
  }

DEFINE_NAMES(tlod_lod_policy, tlod_lod_policy, k_policies, TLOD_POLICY_DEFAULT, TLOD_POLICY_HYBRID)
DEFINE_NAMES(tlod_morph_mode, tlod_morph_mode, k_morphs, TLOD_MORPH_DEFAULT, TLOD_MORPH_TIME)
/* Stages and shapes have no DEFAULT: their zero value is a real one. */
DEFINE_NAMES(tlod_stage, tlod_stage, k_stages, TLOD_STAGE_SILHOUETTE, TLOD_STAGE_SILHOUETTE)
DEFINE_NAMES(tlod_pattern_shape, tlod_pattern_shape, k_shapes, TLOD_PATTERN_TRIANGLE, TLOD_PATTERN_TRIANGLE)
