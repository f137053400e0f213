/* tlod -- the scene set-up shared by the commands. */
#include "scene_setup.h"

#include <stdlib.h>
#include <string.h>

#include "cli.h"

int scene_input_load(const scene_setup_desc* d, cli_mesh* out) {
  int rc = cli_load(d->input, out);
  if (rc != CLI_OK) return rc;
  if (d->place) d->place(out, d->place_user);
  if (d->split_quads || d->surface == TLOD_SURFACE_PN) rc = cli_split_quads(out);
  if (rc != CLI_OK) cli_mesh_free(out);
  return rc;
}

/* The chosen field's step-0 scalars as the mesh's last attribute. */
static int add_field(const scene_setup_desc* d, scene_setup* s) {
  if (!d->field || !d->field->spec) return CLI_OK;
  int rc = field_select(s->in.source, d->input, d->field, &s->field);
  if (rc != CLI_OK) return rc;
  float* values = malloc(sizeof(float) * ((size_t)s->in.vertex_count + 1));
  if (!values) return cli_error(CLI_FAILED, "%s: out of memory for field '%s'", d->input, s->field.label);
  field_scalars(s->in.source, &s->field, 0, values);
  s->field_attribute = cli_add_scalar_attribute(&s->in, s->field.name, values);
  free(values);
  s->has_field = s->field_attribute != UINT32_MAX;
  return s->has_field ? CLI_OK : CLI_FAILED;
}

static int make_surface(tlod_context* ctx, const scene_setup_desc* d, scene_setup* s) {
  tlod_surface_desc sd = {
      .type = s->surface_type, .alpha_mode = d->alpha_mode, .alpha = d->alpha, .label = d->label ? d->label : d->input};
  if (tlod_surface_create(ctx, s->mesh, &sd, &s->surface) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "%s: %s", d->input, tlod_context_last_error(ctx));
  return CLI_OK;
}

static int make_patterns(tlod_context* ctx, const scene_setup_desc* d, scene_setup* s) {
  if (!d->pattern_level) return CLI_OK;
  if (tlod_patterns_create(ctx, &(tlod_patterns_desc){.max_level = d->pattern_level}, &s->patterns) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "%s: %s", d->input, tlod_context_last_error(ctx));
  return CLI_OK;
}

static int create_steps(tlod_context* ctx, const scene_setup_desc* d, scene_setup* s) {
  double t0 = cli_now_ms();
  int rc = scene_input_load(d, &s->in);
  if (rc == CLI_OK) rc = add_field(d, s);
  s->surface_type = cli_resolve_surface(d->surface, &s->in);
  s->crease_deg = cli_resolve_crease(d->crease_deg, &s->in);
  double t1 = cli_now_ms();
  if (rc == CLI_OK) rc = cli_create_mesh(ctx, &s->in, d->normals, s->crease_deg, &s->mesh);
  double t2 = cli_now_ms();
  if (rc == CLI_OK) rc = make_surface(ctx, d, s);
  double t3 = cli_now_ms();
  if (rc == CLI_OK) rc = make_patterns(ctx, d, s);
  s->load_ms = t1 - t0, s->mesh_ms = t2 - t1, s->surface_ms = t3 - t2, s->patterns_ms = cli_now_ms() - t3;
  return rc;
}

int scene_setup_create(tlod_context* ctx, const scene_setup_desc* d, scene_setup* out) {
  memset(out, 0, sizeof(*out));
  int rc = create_steps(ctx, d, out);
  if (rc != CLI_OK) scene_setup_destroy(out);
  return rc;
}

void scene_setup_destroy(scene_setup* s) {
  tlod_patterns_destroy(s->patterns);
  tlod_surface_destroy(s->surface);
  tlod_mesh_destroy(s->mesh);
  cli_mesh_free(&s->in);
  memset(s, 0, sizeof(*s));
}
