/* tlod -- option lists from the library's enum name tables and its backend registry. */
#include "tool_names.h"

#include <stdio.h>
#include <string.h>

#include "tesslod/backend.h"

#define NAME_OF(value, text) text,

const char* const tool_surface_options[] = {TLOD_SURFACE_TYPE_NAMES(NAME_OF) NULL};
const char* const tool_surface_auto_options[] = {"auto", TLOD_SURFACE_TYPE_NAMES(NAME_OF) NULL};
const char* const tool_normal_options[] = {TLOD_NORMAL_MODE_NAMES(NAME_OF) NULL};
const char* const tool_policy_options[] = {TLOD_LOD_POLICY_NAMES(NAME_OF) NULL};

/* cli_parse_enum's index is added to the first named value: the tables must
 * list the values in enum order. */
_Static_assert(TLOD_SURFACE_PN - TLOD_SURFACE_FLAT == 2, "surface names in enum order");
_Static_assert(TLOD_SURFACE_FLAT == TLOD_SURFACE_DEFAULT + 1, "auto (DEFAULT) just before the named surfaces");
_Static_assert(TLOD_NORMALS_AREA - TLOD_NORMALS_KEEP == 2, "normal mode names in enum order");
_Static_assert(TLOD_POLICY_FLAT - TLOD_POLICY_ERROR == 4, "policy names in enum order");

const char* tool_surface_name(tlod_surface_type type) { return tlod_surface_type_name(type); }

const char* tool_policy_name(tlod_lod_policy policy) { return tlod_lod_policy_name(policy); }

const char* tool_stage_name(int stage) {
  const char* name = tlod_stage_name((tlod_stage)stage);
  return name ? name : "?";
}

const char* const* tool_backend_options(void) {
  static char names[128];
  static const char* list[9];
  if (!list[0]) {
    snprintf(names, sizeof(names), "%s", tlod_backend_names());
    int n = 0;
    for (char* p = names; p && *p && n < 8; n++) {
      list[n] = p;
      p = strchr(p, ',');
      if (p) *p++ = '\0';
    }
  }
  return list;
}
