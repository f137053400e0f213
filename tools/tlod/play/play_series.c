/* tlod play -- a VTK time series over the timeline: the step of each
 * frame's time, its positions through tlod_mesh_update +
 * tlod_surface_refresh + tlod_device_update_surface (the topology is the
 * same at every step: the importer checks it), and the field's values of
 * that step. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "play_scene.h"
#include "tlod_import.h"

/* The one surface of a file scene, or NULL. */
static play_surface* series_surface(play_scene* s) {
  if (s->surface_count != 1 || s->count != 1 || play_scene_is_gltf(s->name)) return NULL;
  const tlod_import_result* r = s->surfaces[0].setup.in.source;
  return r && r->step_count >= 2 && r->step_positions && r->step_times ? &s->surfaces[0] : NULL;
}

int play_series_setup(play_scene* s) {
  play_surface* sf = series_surface(s);
  if (!sf) return CLI_OK;
  const tlod_import_result* r = sf->setup.in.source;
  s->series = (play_series){.count = r->step_count};
  if (s->field.on && !(s->series.scalars = malloc(sizeof(float) * ((size_t)r->vertex_count + 1))))
    return cli_error(CLI_FAILED, "%s: out of memory for the series' field", s->name);
  return CLI_OK;
}

void play_series_free(play_scene* s) {
  free(s->series.scalars);
  memset(&s->series, 0, sizeof(s->series));
}

uint32_t play_series_step(const tlod_import_result* r, double t, bool loop) {
  uint32_t n = r->step_count;
  const float* times = r->step_times;
  double span = (double)times[n - 1] - times[0], period = span + span / (n - 1);
  if (loop && period > 0.0 && t >= times[0]) t = times[0] + fmod(t - times[0], period);
  uint32_t step = 0;
  while (step + 1 < n && (double)times[step + 1] <= t)
    step++;
  return step;
}

/* Step k's field values into the mesh's field attribute. */
static int update_field(play_scene* s, play_surface* sf, uint32_t k) {
  if (!s->field.on) return CLI_OK;
  field_scalars(sf->setup.in.source, &s->field.sel, k, s->series.scalars);
  if (tlod_mesh_update_attribute(sf->setup.mesh, s->field.attribute, s->series.scalars, 0) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "%s: step %u: %s", s->name, k, tlod_context_last_error(s->ctx));
  return CLI_OK;
}

int play_scene_series(play_scene* s, double t, bool loop) {
  play_surface* sf = s->series.count ? series_surface(s) : NULL;
  if (!sf) return CLI_OK;
  const tlod_import_result* r = sf->setup.in.source;
  uint32_t k = play_series_step(r, t, loop);
  if (k == s->series.step) return CLI_OK;
  const float* p = r->step_positions + (size_t)k * r->vertex_count * 3;
  int rc = CLI_OK;
  if (tlod_mesh_update(sf->setup.mesh, p, 0, NULL, 0) != TLOD_SUCCESS ||
      tlod_surface_refresh(sf->setup.surface, NULL) != TLOD_SUCCESS)
    rc = cli_error(CLI_FAILED, "%s: step %u: %s", s->name, k, tlod_context_last_error(s->ctx));
  if (rc == CLI_OK) rc = update_field(s, sf, k);
  if (rc == CLI_OK && sf->device_surface && tlod_device_update_surface(s->device, sf->device_surface) != TLOD_SUCCESS)
    rc = cli_error(CLI_FAILED, "%s: step %u: %s", s->name, k, tlod_context_last_error(s->ctx));
  s->series.step = k;
  return rc;
}
