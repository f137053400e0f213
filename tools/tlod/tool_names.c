/* tlod -- names of the library's enums. */
#include "tool_names.h"

#include <stdio.h>
#include <string.h>

#include "tesslod/backend.h"

const char* const tool_surface_options[] = {"flat", "phong", "pn", NULL};
const char* const tool_normal_options[] = {"keep", "angle", "area", NULL};
const char* const tool_policy_options[] = {"error", "silhouette", "hybrid", NULL};

static const char* const stage_names[TLOD_STAGE_NUM] = {"silhouette", "metric", "levels", "morph", "strips"};

const char* tool_surface_name(tlod_surface_type type) {
  if (type == TLOD_SURFACE_FLAT) return "flat";
  return type == TLOD_SURFACE_PN ? "pn" : "phong";
}

const char* tool_policy_name(tlod_lod_policy policy) {
  switch (policy) {
  case TLOD_POLICY_ERROR:
    return "error";
  case TLOD_POLICY_SILHOUETTE:
    return "silhouette";
  case TLOD_POLICY_UNIFORM:
    return "uniform";
  default:
    return "hybrid";
  }
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

const char* tool_stage_name(int stage) { return stage >= 0 && stage < TLOD_STAGE_NUM ? stage_names[stage] : "?"; }
