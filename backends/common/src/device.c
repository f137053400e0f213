/* tesslod::backend -- the registry of the backends in this build and the one
 * dispatch point for every call into a device: validation (so every backend,
 * "null" included, rejects the same wrong use with the same message) and the
 * counters every backend shares. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "device_internal.h"

struct tlod_device_surface {
  tlod_device* dev;
  const tlod_surface* surface;
  void* state;
  uint32_t patch_count;
  char label[64];
  tlod_device_surface *prev, *next;
};

struct tlod_device_texture {
  tlod_device* dev;
  void* state;
  char label[64];
  tlod_device_texture *prev, *next;
};

struct tlod_device {
  tlod_context* ctx;
  const char* backend;
  char label[64];
  const _tlod_device_vtbl* vtbl;
  void* state;
  uint32_t max_level; /* of the patterns */
  tlod_device_surface* surfaces;
  tlod_device_texture* textures;
  _tlod_draw_ref* refs;
  uint32_t ref_cap;
  tlod_draw_item_stats* item_stats;
  uint32_t item_stats_cap, last_item_count;
  tlod_device_stats stats;
};

typedef struct backend_entry {
  const char* name;
  const _tlod_device_vtbl* vtbl;
} backend_entry;

/* Only what is built; the order of tlod_backend_names(). */
static const backend_entry backends[] = {
    {"cpu", &_tlod_cpu_device_vtbl},
#if TLOD_HAS_GL
    {"gl", &_tlod_gl_device_vtbl},
#endif
    {"null", &_tlod_null_device_vtbl},
#if TLOD_HAS_VULKAN
    {"vulkan", &_tlod_vk_device_vtbl},
#endif
};
enum { BACKEND_COUNT = sizeof(backends) / sizeof(backends[0]) };

const char* tlod_backend_names(void) {
  return TLOD_HAS_GL ? (TLOD_HAS_VULKAN ? "cpu,gl,null,vulkan" : "cpu,gl,null")
                     : (TLOD_HAS_VULKAN ? "cpu,null,vulkan" : "cpu,null");
}

static const char* const gpu_eval_names[TLOD_GPU_EVAL_NUM] = {"default", "on", "off"};

const char* tlod_gpu_eval_name(tlod_gpu_eval e) { return (unsigned)e < TLOD_GPU_EVAL_NUM ? gpu_eval_names[e] : "?"; }

tlod_gpu_eval tlod_gpu_eval_from_name(const char* name) {
  if (name && !strcmp(name, "auto")) return TLOD_GPU_EVAL_DEFAULT;
  for (int e = 0; name && e < TLOD_GPU_EVAL_NUM; e++)
    if (!strcmp(name, gpu_eval_names[e])) return (tlod_gpu_eval)e;
  return TLOD_GPU_EVAL_NUM;
}

tlod_result tlod_device_create(tlod_context* ctx, const tlod_device_desc* desc, tlod_device** out) {
  if (out) *out = NULL;
  if (!ctx) return TLOD_ERROR_INVALID_ARGUMENT;
  if (!out) return tlod_context_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "tlod_device_create: out is NULL");
  if (!desc) return tlod_context_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "tlod_device_create: desc is NULL");
  if (!desc->patterns)
    return tlod_context_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT,
                             "tlod_device_create: desc.patterns is NULL (a device is made for one pattern set)");
  const char* name = desc->backend ? desc->backend : "cpu";
  const backend_entry* be = NULL;
  for (size_t i = 0; i < BACKEND_COUNT; i++)
    if (!strcmp(backends[i].name, name)) be = &backends[i];
  if (!be)
    return tlod_context_fail(ctx, TLOD_ERROR_UNSUPPORTED,
                             "tlod_device_create: no backend '%s' in this build (it has: %s)", name,
                             tlod_backend_names());
  if ((desc->gl.surface_types | desc->vk.surface_types) & ~((1u << TLOD_SURFACE_NUM) - 1u))
    return tlod_context_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT,
                             "tlod_device_create: desc.%s.surface_types 0x%x has bits past TLOD_SURFACE_NUM",
                             desc->gl.surface_types & ~((1u << TLOD_SURFACE_NUM) - 1u) ? "gl" : "vk",
                             desc->gl.surface_types & ~((1u << TLOD_SURFACE_NUM) - 1u) ? desc->gl.surface_types
                                                                                       : desc->vk.surface_types);
  if ((unsigned)desc->gl.gpu_eval >= TLOD_GPU_EVAL_NUM || (unsigned)desc->vk.gpu_eval >= TLOD_GPU_EVAL_NUM)
    return tlod_context_fail(
        ctx, TLOD_ERROR_INVALID_ARGUMENT, "tlod_device_create: desc.%s.gpu_eval %u is past TLOD_GPU_EVAL_NUM",
        (unsigned)desc->gl.gpu_eval >= TLOD_GPU_EVAL_NUM ? "gl" : "vk",
        (unsigned)desc->gl.gpu_eval >= TLOD_GPU_EVAL_NUM ? (unsigned)desc->gl.gpu_eval : (unsigned)desc->vk.gpu_eval);
  tlod_device* dev = tlod_context_calloc(ctx, 1, sizeof(*dev));
  if (!dev) return tlod_context_fail(ctx, TLOD_ERROR_OUT_OF_MEMORY, "tlod_device_create: out of memory");
  dev->ctx = ctx;
  dev->backend = be->name;
  dev->vtbl = be->vtbl;
  dev->max_level = tlod_patterns_max_level(desc->patterns);
  dev->stats.gpu_ms = -1.0;
  snprintf(dev->label, sizeof(dev->label), "%s", desc->label ? desc->label : be->name);
  tlod_device_desc d = *desc;
  d.backend = be->name;
  d.label = dev->label;
  tlod_result r = be->vtbl->create(ctx, &d, &dev->stats, &dev->state);
  if (r != TLOD_SUCCESS) {
    tlod_context_free(ctx, dev);
    return r;
  }
  *out = dev;
  return TLOD_SUCCESS;
}

static void unlink_surface(tlod_device* dev, tlod_device_surface* ds) {
  if (ds->prev) ds->prev->next = ds->next;
  if (ds->next) ds->next->prev = ds->prev;
  if (dev->surfaces == ds) dev->surfaces = ds->next;
}

static void free_surface(tlod_device* dev, tlod_device_surface* ds) {
  if (dev->vtbl->destroy_surface) dev->vtbl->destroy_surface(dev->state, ds->state);
  unlink_surface(dev, ds);
  tlod_context_free(dev->ctx, ds);
  dev->stats.surfaces_live--;
  dev->stats.surfaces_destroyed++;
}

static void free_texture(tlod_device* dev, tlod_device_texture* t) {
  if (dev->vtbl->destroy_texture) dev->vtbl->destroy_texture(dev->state, t->state);
  if (t->prev) t->prev->next = t->next;
  if (t->next) t->next->prev = t->prev;
  if (dev->textures == t) dev->textures = t->next;
  tlod_context_free(dev->ctx, t);
  dev->stats.textures_live--;
  dev->stats.textures_destroyed++;
}

void tlod_device_destroy(tlod_device* dev) {
  if (!dev) return;
  while (dev->surfaces)
    free_surface(dev, dev->surfaces);
  while (dev->textures)
    free_texture(dev, dev->textures);
  dev->vtbl->destroy(dev->state);
  tlod_context_free(dev->ctx, dev->refs);
  tlod_context_free(dev->ctx, dev->item_stats);
  tlod_context_free(dev->ctx, dev);
}

const char* tlod_device_backend(const tlod_device* dev) { return dev ? dev->backend : ""; }

/* ---- surfaces ---------------------------------------------------------------- */

tlod_result tlod_device_create_surface(tlod_device* dev, const tlod_surface* surface, tlod_device_surface** out) {
  if (out) *out = NULL;
  if (!dev) return TLOD_ERROR_INVALID_ARGUMENT;
  if (!surface || !out)
    return tlod_context_fail(dev->ctx, TLOD_ERROR_INVALID_ARGUMENT, "tlod_device_create_surface: %s is NULL",
                             surface ? "out" : "surface");
  tlod_device_surface* ds = tlod_context_calloc(dev->ctx, 1, sizeof(*ds));
  if (!ds) return tlod_context_fail(dev->ctx, TLOD_ERROR_OUT_OF_MEMORY, "tlod_device_create_surface: out of memory");
  const char* label = tlod_surface_query_desc(surface).label;
  snprintf(ds->label, sizeof(ds->label), "%s", label ? label : "surface");
  ds->dev = dev;
  ds->surface = surface;
  ds->patch_count = tlod_surface_patch_count(surface);
  tlod_result r = dev->vtbl->create_surface ? dev->vtbl->create_surface(dev->state, surface, &ds->state) : TLOD_SUCCESS;
  if (r != TLOD_SUCCESS) {
    tlod_context_free(dev->ctx, ds);
    return r;
  }
  ds->next = dev->surfaces;
  if (dev->surfaces) dev->surfaces->prev = ds;
  dev->surfaces = ds;
  dev->stats.surfaces_live++;
  dev->stats.surfaces_created++;
  *out = ds;
  return TLOD_SUCCESS;
}

static tlod_result foreign(tlod_device* dev, const char* fn, const char* what, const tlod_device_surface* ds) {
  return tlod_context_fail(dev->ctx, TLOD_ERROR_INVALID_ARGUMENT,
                           "%s: %ssurface '%s' belongs to another device ('%s', not '%s')", fn, what, ds->label,
                           ds->dev->label, dev->label);
}

tlod_result tlod_device_update_surface(tlod_device* dev, tlod_device_surface* ds) {
  if (!dev) return TLOD_ERROR_INVALID_ARGUMENT;
  if (!ds) return tlod_context_fail(dev->ctx, TLOD_ERROR_INVALID_ARGUMENT, "tlod_device_update_surface: ds is NULL");
  if (ds->dev != dev) return foreign(dev, "tlod_device_update_surface", "", ds);
  uint32_t n = tlod_surface_patch_count(ds->surface);
  if (n != ds->patch_count)
    return tlod_context_fail(dev->ctx, TLOD_ERROR_INVALID_ARGUMENT,
                             "tlod_device_update_surface: surface '%s' has %u patches, it had %u (topology is fixed)",
                             ds->label, n, ds->patch_count);
  tlod_result r =
      dev->vtbl->update_surface ? dev->vtbl->update_surface(dev->state, ds->state, ds->surface) : TLOD_SUCCESS;
  if (r == TLOD_SUCCESS) dev->stats.surface_updates++;
  return r;
}

void tlod_device_destroy_surface(tlod_device* dev, tlod_device_surface* ds) {
  if (!dev || !ds) return;
  if (ds->dev != dev) {
    foreign(dev, "tlod_device_destroy_surface", "", ds);
    return;
  }
  free_surface(dev, ds);
}

/* ---- textures ---------------------------------------------------------------- */

/* The desc's first wrong field, or NULL. */
static const char* texture_desc_error(const tlod_texture_desc* d, char* buf, size_t size) {
  if (!d->rgba8) return "rgba8 is NULL";
  if (d->width == 0 || d->height == 0 || d->width > TLOD_TEXTURE_MAX_SIZE || d->height > TLOD_TEXTURE_MAX_SIZE) {
    snprintf(buf, size, "%s %u outside [1, %u]", d->width == 0 || d->width > TLOD_TEXTURE_MAX_SIZE ? "width" : "height",
             d->width == 0 || d->width > TLOD_TEXTURE_MAX_SIZE ? d->width : d->height, TLOD_TEXTURE_MAX_SIZE);
    return buf;
  }
  const uint32_t enums[4] = {(uint32_t)d->wrap_s, (uint32_t)d->wrap_t, (uint32_t)d->min_filter,
                             (uint32_t)d->mag_filter};
  const uint32_t limits[4] = {TLOD_WRAP_NUM, TLOD_WRAP_NUM, TLOD_FILTER_NUM, TLOD_FILTER_NUM};
  static const char* const names[4] = {"wrap_s", "wrap_t", "min_filter", "mag_filter"};
  for (int k = 0; k < 4; k++) {
    if (enums[k] < limits[k]) continue;
    snprintf(buf, size, "%s %u is not a value of its enum (< %u)", names[k], enums[k], limits[k]);
    return buf;
  }
  return NULL;
}

tlod_result tlod_device_create_texture(tlod_device* dev, const tlod_texture_desc* desc, tlod_device_texture** out) {
  const char* fn = "tlod_device_create_texture";
  if (out) *out = NULL;
  if (!dev) return TLOD_ERROR_INVALID_ARGUMENT;
  if (!desc || !out)
    return tlod_context_fail(dev->ctx, TLOD_ERROR_INVALID_ARGUMENT, "%s: %s is NULL", fn, desc ? "out" : "desc");
  const char* label = desc->label ? desc->label : "texture";
  char buf[96];
  const char* bad = texture_desc_error(desc, buf, sizeof(buf));
  if (bad) return tlod_context_fail(dev->ctx, TLOD_ERROR_INVALID_ARGUMENT, "%s: texture '%s': %s", fn, label, bad);
  tlod_device_texture* t = tlod_context_calloc(dev->ctx, 1, sizeof(*t));
  if (!t) return tlod_context_fail(dev->ctx, TLOD_ERROR_OUT_OF_MEMORY, "%s: out of memory", fn);
  snprintf(t->label, sizeof(t->label), "%s", label);
  t->dev = dev;
  tlod_texture_desc d = *desc;
  d.label = t->label;
  tlod_result r = dev->vtbl->create_texture ? dev->vtbl->create_texture(dev->state, &d, &t->state) : TLOD_SUCCESS;
  if (r != TLOD_SUCCESS) {
    tlod_context_free(dev->ctx, t);
    return r;
  }
  t->next = dev->textures;
  if (dev->textures) dev->textures->prev = t;
  dev->textures = t;
  dev->stats.textures_live++;
  dev->stats.textures_created++;
  dev->stats.texture_bytes += 4ull * desc->width * desc->height;
  *out = t;
  return TLOD_SUCCESS;
}

void tlod_device_destroy_texture(tlod_device* dev, tlod_device_texture* tex) {
  if (!dev || !tex) return;
  if (tex->dev != dev) {
    tlod_context_fail(dev->ctx, TLOD_ERROR_INVALID_ARGUMENT,
                      "tlod_device_destroy_texture: texture '%s' belongs to another device ('%s', not '%s')",
                      tex->label, tex->dev->label, dev->label);
    return;
  }
  free_texture(dev, tex);
}

/* ---- drawing ----------------------------------------------------------------- */

/* The draw list fits the surface and the device's patterns (a level past the
 * patterns would index past the pattern buffers). */
/* The arrays a backend reads: present wherever their count says so. */
static tlod_result check_draw_arrays(tlod_device* dev, uint32_t k, const tlod_draw_list* dl) {
  const char* missing = NULL;
  if (!dl->levels && dl->patch_count > 0) missing = "levels";
  if (!dl->instances && dl->instance_count > 0) missing = "instances";
  if (!dl->buckets && dl->bucket_count > 0) missing = "buckets";
  if (!dl->strips && dl->strip_count > 0) missing = "strips";
  if (!missing) return TLOD_SUCCESS;
  return tlod_context_fail(dev->ctx, TLOD_ERROR_INVALID_ARGUMENT, "tlod_device_draw: item %u: draw list %s is NULL", k,
                           missing);
}

/* Levels are -1 (culled) or the patterns'; instances name patches of the
 * surface; strips name edges of their patches. */
static tlod_result check_draw_refs(tlod_device* dev, uint32_t k, const tlod_device_surface* ds,
                                   const tlod_draw_list* dl) {
  const char* fn = "tlod_device_draw";
  for (uint32_t f = 0; f < dl->patch_count; f++) {
    if (dl->levels[f] < -1 || dl->levels[f] > (int)dev->max_level)
      return tlod_context_fail(dev->ctx, TLOD_ERROR_INVALID_ARGUMENT,
                               "%s: item %u: patch %u: level %d outside [-1, %u] (the device's patterns)", fn, k, f,
                               dl->levels[f], dev->max_level);
  }
  for (uint32_t i = 0; i < dl->instance_count; i++) {
    const tlod_draw_instance* in = &dl->instances[i];
    if (in->patch >= dl->patch_count || in->level > dev->max_level)
      return tlod_context_fail(dev->ctx, TLOD_ERROR_INVALID_ARGUMENT,
                               "%s: item %u: instance %u (patch %u, level %u) outside surface '%s' (%u patches) or "
                               "the device's patterns (max level %u)",
                               fn, k, i, in->patch, in->level, ds->label, dl->patch_count, dev->max_level);
  }
  tlod_mesh_view mv = tlod_mesh_query_view(tlod_surface_mesh(ds->surface));
  for (uint32_t s = 0; s < dl->strip_count; s++) {
    const tlod_draw_strip* st = &dl->strips[s];
    if (st->edge_a >= mv.face_corners[st->patch_a] || st->edge_b >= mv.face_corners[st->patch_b])
      return tlod_context_fail(dev->ctx, TLOD_ERROR_INVALID_ARGUMENT,
                               "%s: item %u: strip %u: edge %u of patch %u or edge %u of patch %u does not exist", fn,
                               k, s, st->edge_a, st->patch_a, st->edge_b, st->patch_b);
  }
  return TLOD_SUCCESS;
}

static tlod_result check_draw_list(tlod_device* dev, uint32_t k, const tlod_device_surface* ds,
                                   const tlod_draw_list* dl) {
  const char* fn = "tlod_device_draw";
  if (dl->patch_count != ds->patch_count)
    return tlod_context_fail(dev->ctx, TLOD_ERROR_INVALID_ARGUMENT,
                             "%s: item %u: draw list of %u patches for surface '%s' of %u", fn, k, dl->patch_count,
                             ds->label, ds->patch_count);
  tlod_result r = check_draw_arrays(dev, k, dl);
  if (r != TLOD_SUCCESS) return r;
  for (uint32_t b = 0; b < dl->bucket_count; b++) {
    const tlod_draw_bucket* bk = &dl->buckets[b];
    if (bk->level > dev->max_level || (uint32_t)bk->shape >= TLOD_PATTERN_SHAPE_NUM || bk->first > dl->instance_count ||
        bk->count > dl->instance_count - bk->first)
      return tlod_context_fail(dev->ctx, TLOD_ERROR_INVALID_ARGUMENT,
                               "%s: item %u: bucket %u (level %u, instances [%u, +%u)) outside the device's patterns "
                               "(max level %u) or the list's %u instances",
                               fn, k, b, bk->level, bk->first, bk->count, dev->max_level, dl->instance_count);
  }
  for (uint32_t s = 0; s < dl->strip_count; s++) {
    const tlod_draw_strip* st = &dl->strips[s];
    if (st->level_a > dev->max_level || st->level_b > dev->max_level || st->patch_a >= dl->patch_count ||
        st->patch_b >= dl->patch_count)
      return tlod_context_fail(dev->ctx, TLOD_ERROR_INVALID_ARGUMENT,
                               "%s: item %u: strip %u (patches %u, %u; levels %u, %u) outside the surface or the "
                               "device's patterns (max level %u)",
                               fn, k, s, st->patch_a, st->patch_b, st->level_a, st->level_b, dev->max_level);
  }
  return check_draw_refs(dev, k, ds, dl);
}

/* The material fields every backend reads: the texture's device, the
 * attribute holding its coordinates, the blend mode and cutoff. */
static tlod_result check_material(tlod_device* dev, uint32_t k, const tlod_draw_item* it) {
  const char* fn = "tlod_device_draw";
  if ((uint32_t)it->blend >= TLOD_BLEND_NUM)
    return tlod_context_fail(dev->ctx, TLOD_ERROR_INVALID_ARGUMENT, "%s: item %u: blend %u is not a tlod_blend_mode",
                             fn, k, (uint32_t)it->blend);
  if (it->has_alpha_cutoff && !isfinite(it->alpha_cutoff))
    return tlod_context_fail(dev->ctx, TLOD_ERROR_INVALID_ARGUMENT, "%s: item %u: alpha_cutoff is not finite", fn, k);
  const tlod_device_texture* t = it->base_color_texture;
  if (!t) return TLOD_SUCCESS;
  if (t->dev != dev)
    return tlod_context_fail(dev->ctx, TLOD_ERROR_INVALID_ARGUMENT,
                             "%s: item %u: base_color_texture '%s' belongs to another device ('%s', not '%s')", fn, k,
                             t->label, t->dev->label, dev->label);
  const tlod_mesh* mesh = tlod_surface_mesh(it->surface->surface);
  uint32_t count = tlod_mesh_attribute_count(mesh), a = it->base_color_texcoord;
  if (a >= count)
    return tlod_context_fail(dev->ctx, TLOD_ERROR_INVALID_ARGUMENT,
                             "%s: item %u: base_color_texcoord %u is not an attribute of surface '%s' (%u attributes)",
                             fn, k, a, it->surface->label, count);
  tlod_attribute_info info = tlod_mesh_query_attribute(mesh, a);
  if (info.components < 2)
    return tlod_context_fail(dev->ctx, TLOD_ERROR_INVALID_ARGUMENT,
                             "%s: item %u: base_color_texcoord %u ('%s') of surface '%s' has %u component (needs 2)",
                             fn, k, a, info.name, it->surface->label, info.components);
  return TLOD_SUCCESS;
}

static tlod_result check_draw(tlod_device* dev, const tlod_draw_desc* d) {
  const char* fn = "tlod_device_draw";
  if (!d) return tlod_context_fail(dev->ctx, TLOD_ERROR_INVALID_ARGUMENT, "%s: desc is NULL", fn);
  if (!dev->surfaces)
    return tlod_context_fail(dev->ctx, TLOD_ERROR_INVALID_ARGUMENT,
                             "%s: device '%s' has no surface yet (tlod_device_create_surface first)", fn, dev->label);
  if (d->item_count == 0)
    return tlod_context_fail(dev->ctx, TLOD_ERROR_INVALID_ARGUMENT, "%s: item_count is 0 (nothing to draw)", fn);
  if (!d->items)
    return tlod_context_fail(dev->ctx, TLOD_ERROR_INVALID_ARGUMENT, "%s: items is NULL with item_count %u", fn,
                             d->item_count);
  if (d->viewport[2] == 0 || d->viewport[3] == 0)
    return tlod_context_fail(dev->ctx, TLOD_ERROR_INVALID_ARGUMENT, "%s: viewport %u x %u is empty", fn, d->viewport[2],
                             d->viewport[3]);
  if ((uint32_t)d->debug >= TLOD_DEBUG_NUM)
    return tlod_context_fail(dev->ctx, TLOD_ERROR_INVALID_ARGUMENT, "%s: unknown debug view %u", fn,
                             (uint32_t)d->debug);
  for (int k = 0; k < 16; k++) {
    if (!isfinite(d->view[k]) || !isfinite(d->proj[k]))
      return tlod_context_fail(dev->ctx, TLOD_ERROR_INVALID_ARGUMENT, "%s: %s[%d] is not finite", fn,
                               isfinite(d->view[k]) ? "proj" : "view", k);
  }
  for (uint32_t k = 0; k < d->item_count; k++) {
    const tlod_draw_item* it = &d->items[k];
    if (!it->surface)
      return tlod_context_fail(dev->ctx, TLOD_ERROR_INVALID_ARGUMENT, "%s: item %u: surface is NULL", fn, k);
    if (it->surface->dev != dev) {
      char what[32];
      snprintf(what, sizeof(what), "item %u: ", k);
      return foreign(dev, fn, what, it->surface);
    }
    if (!it->draw_list)
      return tlod_context_fail(dev->ctx, TLOD_ERROR_INVALID_ARGUMENT, "%s: item %u: draw_list is NULL", fn, k);
    for (int c = 0; c < 16 && it->has_model; c++) {
      if (!isfinite(it->model[c]))
        return tlod_context_fail(dev->ctx, TLOD_ERROR_INVALID_ARGUMENT, "%s: item %u: model[%d] is not finite", fn, k,
                                 c);
    }
    tlod_result r = check_draw_list(dev, k, it->surface, it->draw_list);
    if (r == TLOD_SUCCESS) r = check_material(dev, k, it);
    if (r != TLOD_SUCCESS) return r;
  }
  return TLOD_SUCCESS;
}

tlod_result tlod_device_draw(tlod_device* dev, const tlod_draw_desc* desc) {
  if (!dev) return TLOD_ERROR_INVALID_ARGUMENT;
  tlod_result r = check_draw(dev, desc);
  if (r != TLOD_SUCCESS) return r;
  uint32_t n = desc->item_count;
  if (!_tlod_device_grow(dev->ctx, (void**)&dev->refs, &dev->ref_cap, n, sizeof(_tlod_draw_ref)) ||
      !_tlod_device_grow(dev->ctx, (void**)&dev->item_stats, &dev->item_stats_cap, n, sizeof(tlod_draw_item_stats)))
    return tlod_context_fail(dev->ctx, TLOD_ERROR_OUT_OF_MEMORY, "tlod_device_draw: out of memory for %u items", n);
  for (uint32_t k = 0; k < n; k++) {
    const tlod_device_surface* ds = desc->items[k].surface;
    const tlod_device_texture* t = desc->items[k].base_color_texture;
    dev->refs[k] = (_tlod_draw_ref){.item = &desc->items[k],
                                    .surface = ds->surface,
                                    .surface_state = ds->state,
                                    .texture_state = t ? t->state : NULL};
  }
  memset(dev->item_stats, 0, sizeof(tlod_draw_item_stats) * n);
  dev->last_item_count = 0;
  double t0 = tlod_now_ms();
  r = dev->vtbl->draw(dev->state, desc, dev->refs, dev->item_stats);
  if (r != TLOD_SUCCESS) return r;
  if (!dev->vtbl->times_draws) dev->stats.cpu_ms = dev->stats.wall_ms = tlod_now_ms() - t0;
  dev->stats.triangles = dev->stats.vertices = 0;
  dev->stats.draw_calls = 0;
  for (uint32_t k = 0; k < n; k++) {
    dev->stats.triangles += dev->item_stats[k].triangles;
    dev->stats.vertices += dev->item_stats[k].vertices;
    dev->stats.draw_calls += dev->item_stats[k].draw_calls;
  }
  dev->last_item_count = n;
  dev->stats.items = n;
  dev->stats.draws++;
  dev->stats.items_drawn += n;
  dev->stats.triangles_drawn += dev->stats.triangles;
  return TLOD_SUCCESS;
}

tlod_result tlod_device_read_image(tlod_device* dev, uint32_t width, uint32_t height, uint8_t* rgba) {
  if (!dev) return TLOD_ERROR_INVALID_ARGUMENT;
  if (!rgba || !width || !height)
    return tlod_context_fail(dev->ctx, TLOD_ERROR_INVALID_ARGUMENT, "tlod_device_read_image: %s (%u x %u, rgba %s)",
                             !rgba ? "rgba is NULL" : "empty image", width, height, rgba ? "set" : "NULL");
  if (!dev->vtbl->read_image)
    return tlod_context_fail(
        dev->ctx, TLOD_ERROR_UNSUPPORTED, "tlod_device_read_image: the %s device has no image%s", dev->backend,
        dev->vtbl == &_tlod_cpu_device_vtbl
            ? " (it realises meshes: tlod_cpu_device_mesh)"
            : (!strcmp(dev->backend, "vulkan") ? " (the image is the engine's: read it there)" : ""));
  return dev->vtbl->read_image(dev->state, width, height, rgba);
}

tlod_device_stats tlod_device_query_stats(const tlod_device* dev) {
  tlod_device_stats none = {0};
  none.gpu_ms = -1.0;
  if (!dev) return none;
  /* The device object is never const itself: its readings are refreshed here. */
  if (dev->vtbl->poll_stats) dev->vtbl->poll_stats(dev->state, (tlod_device_stats*)&dev->stats);
  return dev->stats;
}

tlod_draw_item_stats tlod_device_query_item_stats(const tlod_device* dev, uint32_t item) {
  if (!dev || item >= dev->last_item_count) return (tlod_draw_item_stats){0};
  return dev->item_stats[item];
}

const struct tlod_cpu_mesh* tlod_cpu_device_mesh(const tlod_device* dev, uint32_t item) {
  if (!dev || dev->vtbl != &_tlod_cpu_device_vtbl || item >= dev->last_item_count) return NULL;
  return _tlod_cpu_device_mesh(dev->state, item);
}
