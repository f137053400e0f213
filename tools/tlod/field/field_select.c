/* tlod -- choosing a result field and its range. */
#include "field_select.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "common/strict_number.h"

bool field_parse_range(const char* option, const char* text, float range[2]) {
  const char* comma = strchr(text, ',');
  char lo[64];
  double v[2];
  if (!comma || comma == text || (size_t)(comma - text) >= sizeof(lo)) {
    cli_error(CLI_USAGE, "%s: %s: expected MIN,MAX (e.g. 0,250)", option, text);
    return false;
  }
  snprintf(lo, sizeof(lo), "%.*s", (int)(comma - text), text);
  if (number_parse_real(lo, NULL, -1e30, 1e30, &v[0]) != NUMBER_OK ||
      number_parse_real(comma + 1, NULL, -1e30, 1e30, &v[1]) != NUMBER_OK) {
    cli_error(CLI_USAGE, "%s: %s: MIN and MAX must be finite numbers", option, text);
    return false;
  }
  if (!(v[0] < v[1])) {
    cli_error(CLI_USAGE, "%s: %s: MIN must be below MAX", option, text);
    return false;
  }
  range[0] = (float)v[0], range[1] = (float)v[1];
  return true;
}

/* "a, b, c (2 components)" of every field, or "none". */
static void list_fields(const tlod_import_result* r, char* out, size_t size) {
  size_t n = (size_t)snprintf(out, size, "%s", r && r->field_count ? "" : "none");
  for (uint32_t i = 0; r && i < r->field_count && n < size; i++)
    n += (size_t)snprintf(out + n, size - n, "%s%s (%u component%s)", i ? ", " : "", r->fields[i].name,
                          r->fields[i].components, r->fields[i].components == 1 ? "" : "s");
}

/* COMPONENT of a field with n components: -1 magnitude, else the index; -2: not one. */
static int parse_component(const char* text, uint32_t n) {
  static const char* const axes[] = {"x", "y", "z", "w"};
  if (!strcmp(text, "magnitude")) return -1;
  for (int a = 0; a < 4; a++)
    if (!strcmp(text, axes[a])) return (uint32_t)a < n ? a : -2;
  uint32_t c = 0;
  return number_parse_u32(text, NULL, 0, n ? n - 1 : 0, &c) == NUMBER_OK && c < n ? (int)c : -2;
}

static void default_range(const tlod_import_field* f, int component, float range[2]) {
  bool magnitude = component < 0 && f->components > 1;
  range[0] = magnitude ? f->magnitude_min : f->min[component < 0 ? 0 : component];
  range[1] = magnitude ? f->magnitude_max : f->max[component < 0 ? 0 : component];
}

static int find_field(const tlod_import_result* r, const char* name) {
  for (uint32_t i = 0; r && i < r->field_count; i++)
    if (!strcmp(r->fields[i].name, name)) return (int)i;
  return -1;
}

int field_select(const tlod_import_result* r, const char* input, const field_options* o, field_selection* out) {
  char name[64], list[1024];
  memset(out, 0, sizeof(*out));
  const char* colon = strchr(o->spec, ':');
  snprintf(name, sizeof(name), "%.*s", colon ? (int)(colon - o->spec) : (int)strlen(o->spec), o->spec);
  int i = find_field(r, name);
  list_fields(r, list, sizeof(list));
  if (i < 0) return cli_error(CLI_FAILED, "--field %s: %s has no field '%s' (fields: %s)", o->spec, input, name, list);
  const tlod_import_field* f = &r->fields[i];
  int c = colon ? parse_component(colon + 1, f->components) : (f->components > 1 ? -1 : 0);
  if (c == -2)
    return cli_error(CLI_FAILED, "--field %s: '%s' has %u component%s: expected 0..%u, x, y, z or magnitude", o->spec,
                     name, f->components, f->components == 1 ? "" : "s", f->components - 1);
  *out = (field_selection){.field = (uint32_t)i, .component = c, .from_cells = f->from_cells, .colormap = o->colormap};
  snprintf(out->name, sizeof(out->name), "%s", f->name);
  snprintf(out->units, sizeof(out->units), "%s", f->units);
  if (f->components == 1) c = 0, out->component = 0;
  snprintf(out->label, sizeof(out->label), "%s%s", f->name, f->components == 1 ? "" : c < 0 ? ":magnitude" : "");
  if (f->components > 1 && c >= 0) snprintf(out->label, sizeof(out->label), "%.60s:%d", f->name, c);
  float range[2];
  default_range(f, c, range);
  out->lo = o->has_range ? o->range[0] : range[0];
  out->hi = o->has_range ? o->range[1] : range[1];
  return CLI_OK;
}

void field_scalars(const tlod_import_result* r, const field_selection* sel, uint32_t step, float* out) {
  const tlod_import_field* f = &r->fields[sel->field];
  uint32_t n = f->components, v_count = r->vertex_count;
  const float* d = f->data + (size_t)step * v_count * n;
  for (uint32_t v = 0; v < v_count; v++, d += n) {
    if (sel->component >= 0) {
      out[v] = d[sel->component];
      continue;
    }
    double s = 0.0;
    for (uint32_t c = 0; c < n; c++)
      s += (double)d[c] * d[c];
    out[v] = (float)sqrt(s);
  }
}
