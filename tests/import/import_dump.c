/* import_dump.c -- prints what tlod_import_file_desc() returned as JSON, for scene_test.py, which
 * checks it against values it reads from the files itself. Owned by the import/export layer.
 * Usage: import_dump [--keep-scene] [--limit BYTES] FILE
 * Floats are printed as their IEEE bit patterns (bitwise comparisons); images as size, an
 * FNV-1a hash of the pixels and the first pixel; peak RSS in KB (getrusage). */
#define _POSIX_C_SOURCE 200809L
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "tlod_import.h"

static void str(const char* key, const char* s) {
  printf("\"%s\":\"", key);
  for (; *s; ++s)
    if (*s == '"' || *s == '\\')
      printf("\\%c", *s);
    else if ((unsigned char)*s < 0x20)
      printf("\\u%04x", *s);
    else
      putchar(*s);
  printf("\",");
}

static void bits(const char* key, const float* f, size_t n) {
  printf("\"%s\":[", key);
  for (size_t i = 0; i < n; ++i) {
    uint32_t u;
    memcpy(&u, &f[i], 4);
    printf("%s%" PRIu32, i ? "," : "", u);
  }
  printf("],");
}

static void u32s(const char* key, const uint32_t* v, size_t n) {
  printf("\"%s\":[", key);
  for (size_t i = 0; i < n; ++i)
    printf("%s%" PRIu32, i ? "," : "", v[i]);
  printf("],");
}

static void attributes(const tlod_import_result* r) {
  printf("\"attributes\":[");
  for (uint32_t a = 0; a < r->attribute_count; ++a) {
    printf("%s{", a ? "," : "");
    str("name", r->attributes[a].name);
    printf("\"components\":%u,", r->attributes[a].components);
    bits("data", r->attributes[a].data, (size_t)r->vertex_count * r->attributes[a].components);
    printf("\"end\":0}");
  }
  printf("],");
  if (r->joints) {
    uint32_t* j = malloc((size_t)r->vertex_count * 16);
    for (size_t i = 0; j && i < (size_t)r->vertex_count * 4; ++i)
      j[i] = r->joints[i];
    u32s("joints", j, j ? (size_t)r->vertex_count * 4 : 0);
    free(j);
    bits("weights", r->weights, (size_t)r->vertex_count * 4);
  }
}

static void nodes(const tlod_import_result* r) {
  printf("\"nodes\":[");
  for (uint32_t i = 0; i < r->node_count; ++i) {
    const tlod_import_node* n = &r->nodes[i];
    printf("%s{", i ? "," : "");
    str("name", n->name);
    printf("\"parent\":%d,\"mesh\":%d,\"skin\":%d,", (int)n->parent, (int)n->mesh, (int)n->skin);
    bits("local", n->local, 16);
    bits("world", n->world, 16);
    bits("trs", n->translation, 3);
    bits("rotation", n->rotation, 4);
    bits("scale", n->scale, 3);
    printf("\"end\":0}");
  }
  printf("],\"meshes\":[");
  for (uint32_t i = 0; i < r->mesh_count; ++i)
    printf("%s[%u,%u]", i ? "," : "", r->meshes[i].first_part, r->meshes[i].part_count);
  printf("],\"parts\":[");
  for (uint32_t i = 0; i < r->part_count; ++i) {
    const tlod_import_part* p = &r->parts[i];
    printf("%s{\"mesh\":%d,\"node\":%d,\"material\":%d,\"first_vertex\":%u,\"vertex_count\":%u}", i ? "," : "",
           (int)p->mesh, (int)p->node, (int)p->material, p->first_vertex, p->vertex_count);
  }
  printf("],");
}

static void materials(const tlod_import_result* r) {
  printf("\"materials\":[");
  for (uint32_t i = 0; i < r->material_count; ++i) {
    const tlod_import_material* m = &r->materials[i];
    printf("%s{", i ? "," : "");
    str("name", m->name);
    bits("base_color", m->base_color, 4);
    printf("\"texture\":%d,\"texcoord\":%d,\"alpha_mode\":%d,\"double_sided\":%d}", (int)m->base_color_texture,
           (int)m->base_color_texcoord, (int)m->alpha_mode, (int)m->double_sided);
  }
  printf("],\"textures\":[");
  for (uint32_t i = 0; i < r->texture_count; ++i)
    printf("%s[%d,%d,%d,%d,%d]", i ? "," : "", (int)r->textures[i].image, r->textures[i].wrap_s, r->textures[i].wrap_t,
           r->textures[i].min_filter, r->textures[i].mag_filter);
  printf("],\"images\":[");
  for (uint32_t i = 0; i < r->image_count; ++i) {
    const tlod_import_image* im = &r->images[i];
    uint64_t h = 1469598103934665603ull;
    for (size_t k = 0; im->rgba && k < (size_t)im->width * im->height * 4; ++k)
      h = (h ^ im->rgba[k]) * 1099511628211ull;
    printf("%s{", i ? "," : "");
    str("uri", im->uri);
    str("mime", im->mime);
    printf("\"width\":%u,\"height\":%u,\"decoded\":%d,\"encoded_size\":%zu,\"hash\":\"%016" PRIx64
           "\",\"px0\":[%d,%d,%d,%d]}",
           im->width, im->height, im->rgba != NULL, im->encoded_size, h, im->rgba ? im->rgba[0] : -1,
           im->rgba ? im->rgba[1] : -1, im->rgba ? im->rgba[2] : -1, im->rgba ? im->rgba[3] : -1);
  }
  printf("],");
}

static void animations(const tlod_import_result* r) {
  printf("\"animations\":[");
  for (uint32_t i = 0; i < r->animation_count; ++i) {
    printf("%s[", i ? "," : "");
    for (uint32_t c = 0; c < r->animations[i].channel_count; ++c) {
      const tlod_import_channel* ch = &r->animations[i].channels[c];
      const size_t n =
          (ch->path == TLOD_IMPORT_PATH_ROTATION ? 4 : 3) * (ch->interp == TLOD_IMPORT_INTERP_CUBICSPLINE ? 3 : 1);
      printf("%s{\"node\":%u,\"path\":%d,\"interp\":%d,", c ? "," : "", ch->node, (int)ch->path, (int)ch->interp);
      bits("times", ch->times, ch->key_count);
      bits("values", ch->values, ch->key_count * n);
      printf("\"end\":0}");
    }
    printf("]");
  }
  printf("],\"skins\":[");
  for (uint32_t i = 0; i < r->skin_count; ++i) {
    printf("%s{", i ? "," : "");
    u32s("joints", r->skins[i].joints, r->skins[i].joint_count);
    bits("inverse_bind", r->skins[i].inverse_bind, (size_t)r->skins[i].joint_count * 16);
    printf("\"end\":0}");
  }
  printf("],");
}

int main(int argc, char** argv) {
  tlod_import_desc desc = {0};
  int i = 1;
  for (; i + 1 < argc; ++i)
    if (!strcmp(argv[i], "--keep-scene"))
      desc.keep_scene = true;
    else if (!strcmp(argv[i], "--limit") && i + 2 < argc)
      desc.memory_limit = (size_t)strtoull(argv[++i], NULL, 10);
    else
      break;
  if (i != argc - 1) {
    fprintf(stderr, "usage: import_dump [--keep-scene] [--limit BYTES] FILE\n");
    return 2;
  }
  char err[512];
  tlod_import_result* r = NULL;
  const tlod_result res = tlod_import_file_desc(argv[i], &desc, &r, err, sizeof err);
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  printf("{\"result\":%d,\"rss_kb\":%ld,", (int)res, ru.ru_maxrss);
  str("error", err);
  if (r) {
    str("warnings", r->warnings);
    printf("\"vertex_count\":%u,\"weights_renormalised\":%u,", r->vertex_count, r->weights_renormalised);
    bits("positions", r->positions, (size_t)r->vertex_count * 3);
    attributes(r);
    nodes(r);
    materials(r);
    animations(r);
  }
  printf("\"end\":0}\n");
  tlod_import_free(r);
  return 0;
}
