/* tlod play -- the glTF textures on the device: one device texture per
 * distinct (image, sampler) pair, made once per device (every object and
 * mode draws it), sRGB as glTF base colour textures are. glTF sampler
 * values are GL enums (glTF 2.0 section 5.26). */
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "play_scene.h"
#include "tlod_import.h"

static tlod_wrap wrap_of(int gl) {
  return gl == 33071 ? TLOD_WRAP_CLAMP_TO_EDGE : gl == 33648 ? TLOD_WRAP_MIRRORED_REPEAT : TLOD_WRAP_REPEAT;
}

/* NEAREST (9728) and the NEAREST_MIPMAP_* minifications (9984, 9986) are nearest; 0 (unset): the default. */
static tlod_filter filter_of(int gl) {
  if (gl == 0) return TLOD_FILTER_DEFAULT;
  return gl == 9728 || gl == 9984 || gl == 9986 ? TLOD_FILTER_NEAREST : TLOD_FILTER_LINEAR;
}

static bool same_sampler(const tlod_import_texture* a, const tlod_import_texture* b) {
  return a->image == b->image && a->wrap_s == b->wrap_s && a->wrap_t == b->wrap_t && a->min_filter == b->min_filter &&
         a->mag_filter == b->mag_filter;
}

static int make_texture(play_scene* s, uint32_t t) {
  const tlod_import_result* r = s->import;
  const tlod_import_texture* tx = &r->textures[t];
  for (uint32_t e = 0; e < t; e++)
    if (s->textures[e] && same_sampler(&r->textures[e], tx)) return s->textures[t] = s->textures[e], CLI_OK;
  if (tx->image >= r->image_count || !r->images[tx->image].rgba) return CLI_OK; /* the importer warned */
  const tlod_import_image* im = &r->images[tx->image];
  tlod_texture_desc d = {.width = im->width,
                         .height = im->height,
                         .rgba8 = im->rgba,
                         .srgb = true,
                         .wrap_s = wrap_of(tx->wrap_s),
                         .wrap_t = wrap_of(tx->wrap_t),
                         .min_filter = filter_of(tx->min_filter),
                         .mag_filter = filter_of(tx->mag_filter),
                         .mipmaps_off = tx->min_filter == 9728 || tx->min_filter == 9729,
                         .label = im->uri[0] ? im->uri : "embedded image"};
  if (tlod_device_create_texture(s->device, &d, &s->textures[t]) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "%s: texture %u: %s", s->name, t, tlod_context_last_error(s->ctx));
  return CLI_OK;
}

int play_scene_create_textures(play_scene* s) {
  if (!s->import || !s->import->texture_count) return CLI_OK;
  if (!(s->textures = calloc(s->import->texture_count, sizeof(*s->textures))))
    return cli_error(CLI_FAILED, "out of memory");
  int rc = CLI_OK;
  for (uint32_t t = 0; t < s->import->texture_count && rc == CLI_OK; t++)
    rc = make_texture(s, t);
  return rc;
}

void play_scene_destroy_textures(play_scene* s) {
  /* Shared entries point at one texture; the device destroys the textures still made from it. */
  free(s->textures);
  s->textures = NULL;
}
