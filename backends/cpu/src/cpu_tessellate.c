/* tesslod::cpu -- the reference tessellator: surface x refinement patterns
 * (+ connection strips) -> indexed triangle mesh.
 *
 * This work is based on:
 *   T. Boubekeur, C. Schlick. Generic mesh refinement on GPU. Graphics
 *   Hardware 2005 (one pattern evaluated per patch);
 *   M. Schwarz, M. Staginski, M. Stamminger. GPU-based rendering of PN
 *   triangle meshes with adaptive tessellation. VMV 2006.
 *
 * Output vertex numbering (welded): corners by (welded position, normal,
 * alpha); edge points by edge slot and parameter, one slot per smooth shared
 * edge (so both sides use the same vertex) or per face edge otherwise;
 * interior points per patch. Without welding each patch owns its pattern
 * vertices, as a GPU would draw them. */
#include <stdlib.h>
#include <string.h>

#include "cpu_internal.h"
#include "internal.h"

enum { KIND_EDGE = 4, KIND_INTERIOR = 8 };

/* Per pattern vertex: what it is on the patch (corner c, edge e, interior)
 * and its parameter (edge: numerator of t_end over N; interior: ordinal). */
typedef struct level_table {
  uint32_t nv, interior;
  uint8_t* kind;
  uint32_t* param;
} level_table;

typedef struct tess {
  tlod_context* ctx;
  const tlod_surface* s;
  const tlod_mesh* m;
  const tlod_patterns* pat;
  tlod_cpu_tessellate_desc d;
  uint32_t lmax, n_grid;
  int8_t* level;
  level_table tables[2][TLOD_MAX_LEVEL + 1];
  uint32_t* corner_id;  /* welded: per mesh vertex */
  uint32_t* corner_src; /* welded: output corner -> mesh vertex */
  uint32_t corner_count;
  uint32_t* slot_owner; /* per face * 4 + edge */
  uint8_t* slot_level;
  uint32_t* slot_base;
  uint32_t* interior_base; /* welded: per patch; no_weld: patch base */
  uint32_t* tri_base;
  uint32_t vertex_count, pattern_tris;
  uint32_t (*strip_tris)[3];
  uint32_t strip_count, strip_cap;
  tlod_cpu_mesh* out;
} tess;

static tlod_pattern_shape shape_of(const tess* t, uint32_t f) {
  return t->m->face_corners[f] == 4 ? TLOD_PATTERN_QUAD : TLOD_PATTERN_TRIANGLE;
}

static void classify(uint32_t n_grid, tlod_pattern_shape shape, uint32_t i, uint32_t j, uint8_t* kind,
                     uint32_t* param) {
  uint32_t nn = n_grid;
  if (shape == TLOD_PATTERN_TRIANGLE) {
    uint32_t w = nn - i - j;
    if (i == nn || j == nn || w == nn) {
      *kind = i == nn ? 0 : (j == nn ? 1 : 2);
    } else if (w == 0) {
      *kind = KIND_EDGE + 0, *param = j;
    } else if (i == 0) {
      *kind = KIND_EDGE + 1, *param = w;
    } else if (j == 0) {
      *kind = KIND_EDGE + 2, *param = i;
    } else {
      *kind = KIND_INTERIOR;
    }
    return;
  }
  bool ei = i == 0 || i == nn, ej = j == 0 || j == nn;
  if (ei && ej) {
    *kind = i == 0 ? (j == 0 ? 0 : 3) : (j == 0 ? 1 : 2);
  } else if (j == 0) {
    *kind = KIND_EDGE + 0, *param = i;
  } else if (i == nn) {
    *kind = KIND_EDGE + 1, *param = j;
  } else if (j == nn) {
    *kind = KIND_EDGE + 2, *param = nn - i;
  } else if (i == 0) {
    *kind = KIND_EDGE + 3, *param = nn - j;
  } else {
    *kind = KIND_INTERIOR;
  }
}

static tlod_result build_table(tess* t, tlod_pattern_shape shape, uint32_t level) {
  level_table* lt = &t->tables[shape][level];
  if (lt->kind) return TLOD_SUCCESS;
  uint32_t count;
  const tlod_pattern_vertex* pv = tlod_patterns_vertices(t->pat, shape, &count);
  lt->nv = tlod_pattern_vertex_count(shape, level);
  lt->kind = _tlod_alloc(t->ctx, lt->nv);
  lt->param = _tlod_alloc(t->ctx, sizeof(uint32_t) * lt->nv);
  if (!lt->kind || !lt->param) return TLOD_ERROR_OUT_OF_MEMORY;
  lt->interior = 0;
  for (uint32_t x = 0; x < lt->nv; x++) {
    classify(t->n_grid, shape, pv[x].i, pv[x].j, &lt->kind[x], &lt->param[x]);
    if (lt->kind[x] == KIND_INTERIOR) lt->param[x] = lt->interior++;
  }
  return TLOD_SUCCESS;
}

static int level_of(const tess* t, uint32_t f) { return t->level[f]; }

/* ---- welded numbering ---------------------------------------------------- */

/* A corner's identity: welded position, normal and alpha bits. */
typedef struct corner_key {
  uint32_t key[5];
  uint32_t vertex;
} corner_key;

static int cmp_corner(const void* pa, const void* pb) {
  const corner_key *a = pa, *b = pb;
  for (int i = 0; i < 5; i++) {
    if (a->key[i] != b->key[i]) return a->key[i] < b->key[i] ? -1 : 1;
  }
  return a->vertex < b->vertex ? -1 : (a->vertex > b->vertex);
}

static tlod_result number_corners(tess* t) {
  const tlod_mesh* m = t->m;
  corner_key* keys = _tlod_alloc(t->ctx, sizeof(corner_key) * (m->vertex_count ? m->vertex_count : 1));
  t->corner_id = _tlod_alloc(t->ctx, sizeof(uint32_t) * (m->vertex_count + 1));
  t->corner_src = _tlod_alloc(t->ctx, sizeof(uint32_t) * (m->vertex_count + 1));
  if (!keys || !t->corner_id || !t->corner_src) {
    _tlod_free(t->ctx, keys);
    return TLOD_ERROR_OUT_OF_MEMORY;
  }
  for (uint32_t v = 0; v < m->vertex_count; v++) {
    keys[v].key[0] = m->weld_id[v];
    memcpy(&keys[v].key[1], m->normals[v], sizeof(float) * 3);
    memcpy(&keys[v].key[4], &t->s->alpha[v], sizeof(float));
    keys[v].vertex = v;
  }
  qsort(keys, m->vertex_count, sizeof(corner_key), cmp_corner);
  uint32_t id = 0;
  for (uint32_t x = 0; x < m->vertex_count; x++) {
    if (x == 0 || memcmp(keys[x].key, keys[x - 1].key, sizeof(keys[x].key)) != 0) t->corner_src[id++] = keys[x].vertex;
    t->corner_id[keys[x].vertex] = id - 1;
  }
  t->corner_count = id;
  _tlod_free(t->ctx, keys);
  return TLOD_SUCCESS;
}

static bool linked(const tess* t, uint32_t f, uint32_t e, tlod_edge_link* link) {
  *link = t->m->links[f][e];
  return link->face != _TLOD_NONE && level_of(t, link->face) >= 0;
}

/* Edge slots: a smooth shared edge has one slot, owned by the smaller face. */
static void assign_slots(tess* t) {
  const tlod_mesh* m = t->m;
  uint32_t base = t->corner_count;
  for (uint32_t f = 0; f < m->face_count; f++) {
    if (level_of(t, f) < 0) continue;
    for (uint32_t e = 0; e < m->face_corners[f]; e++) {
      uint32_t slot = f * 4 + e;
      tlod_edge_link link;
      int lv = level_of(t, f);
      if (linked(t, f, e, &link) && link.smooth) {
        int lg = level_of(t, link.face);
        lv = lg > lv ? lg : lv;
        if (link.face < f) {
          t->slot_owner[slot] = link.face * 4 + link.edge;
          continue;
        }
      }
      t->slot_owner[slot] = slot;
      t->slot_level[slot] = (uint8_t)lv;
      t->slot_base[slot] = base;
      base += (1u << lv) - 1;
    }
  }
  for (uint32_t f = 0; f < m->face_count; f++) {
    if (level_of(t, f) < 0) continue;
    t->interior_base[f] = base;
    base += t->tables[shape_of(t, f)][level_of(t, f)].interior;
  }
  t->vertex_count = base;
}

static void assign_unwelded(tess* t) {
  uint32_t base = 0;
  for (uint32_t f = 0; f < t->m->face_count; f++) {
    if (level_of(t, f) < 0) continue;
    t->interior_base[f] = base;
    base += t->tables[shape_of(t, f)][level_of(t, f)].nv;
  }
  t->vertex_count = base;
}

/* Output vertex of pattern vertex x of patch f. */
static uint32_t vertex_id(const tess* t, uint32_t f, uint32_t x) {
  const level_table* lt = &t->tables[shape_of(t, f)][level_of(t, f)];
  if (t->d.no_weld) return t->interior_base[f] + x;
  uint8_t kind = lt->kind[x];
  if (kind < KIND_EDGE) return t->corner_id[t->m->faces[f][kind]];
  if (kind == KIND_INTERIOR) return t->interior_base[f] + lt->param[x];
  uint32_t slot = f * 4 + (kind - KIND_EDGE), owner = t->slot_owner[slot];
  uint32_t k = owner == slot ? lt->param[x] : t->n_grid - lt->param[x];
  return t->slot_base[owner] + (k >> (t->lmax - t->slot_level[owner])) - 1;
}

/* ---- evaluation ------------------------------------------------------------ */

static void put(tess* t, uint32_t id, const float* pos, const float* nrm) {
  memcpy(t->out->positions + 3 * (size_t)id, pos, sizeof(float) * 3);
  if (t->out->normals) memcpy(t->out->normals + 3 * (size_t)id, nrm, sizeof(float) * 3);
}

static void eval_local(tess* t, uint32_t f, uint32_t x, const tlod_pattern_vertex* pv, uint32_t id) {
  const level_table* lt = &t->tables[shape_of(t, f)][level_of(t, f)];
  uint8_t kind = lt->kind[x];
  if (kind < KIND_EDGE) {
    uint32_t v = t->m->faces[f][kind];
    put(t, id, t->m->positions[v], t->m->normals[v]);
  } else if (kind < KIND_INTERIOR) {
    float pos[3], nrm[3];
    _tlod_patch_edge_point(t->s, f, kind - KIND_EDGE, (float)lt->param[x] / (float)t->n_grid, pos, nrm);
    put(t, id, pos, nrm);
  } else {
    tlod_surface_point p;
    _tlod_patch_eval(t->s, f, pv[x].u, pv[x].v, &p);
    put(t, id, p.position, p.normal);
  }
}

static void eval_patches(void* data, uint32_t begin, uint32_t end, uint32_t worker) {
  (void)worker;
  tess* t = data;
  for (uint32_t f = begin; f < end; f++) {
    if (level_of(t, f) < 0) continue;
    uint32_t count;
    const tlod_pattern_vertex* pv = tlod_patterns_vertices(t->pat, shape_of(t, f), &count);
    const level_table* lt = &t->tables[shape_of(t, f)][level_of(t, f)];
    for (uint32_t x = 0; x < lt->nv; x++) {
      /* Welded: a patch evaluates only its interior; shared points once below. */
      if (!t->d.no_weld && lt->kind[x] != KIND_INTERIOR) continue;
      eval_local(t, f, x, pv, vertex_id(t, f, x));
    }
    if (t->d.no_weld) continue;
    for (uint32_t e = 0; e < t->m->face_corners[f]; e++) {
      uint32_t slot = f * 4 + e;
      if (t->slot_owner[slot] != slot) continue;
      uint32_t lv = t->slot_level[slot];
      for (uint32_t k = 1; k < (1u << lv); k++) {
        float pos[3], nrm[3];
        uint32_t num = k << (t->lmax - lv);
        _tlod_patch_edge_point(t->s, f, e, (float)num / (float)t->n_grid, pos, nrm);
        put(t, t->slot_base[slot] + k - 1, pos, nrm);
      }
    }
  }
}

static void eval_corners(tess* t) {
  if (t->d.no_weld) return;
  for (uint32_t c = 0; c < t->corner_count; c++) {
    uint32_t v = t->corner_src[c];
    put(t, c, t->m->positions[v], t->m->normals[v]);
  }
}

static void emit_patches(void* data, uint32_t begin, uint32_t end, uint32_t worker) {
  (void)worker;
  tess* t = data;
  for (uint32_t f = begin; f < end; f++) {
    int lv = level_of(t, f);
    if (lv < 0) continue;
    uint32_t count;
    const uint32_t* idx = tlod_patterns_indices(t->pat, shape_of(t, f), (uint32_t)lv, &count);
    uint32_t* dst = t->out->indices + 3 * (size_t)t->tri_base[f];
    for (uint32_t k = 0; k < count; k++)
      dst[k] = vertex_id(t, f, idx[k]);
    for (uint32_t k = 0; k < count / 3; k++)
      t->out->triangle_patch[t->tri_base[f] + k] = f;
  }
}

/* ---- strips ---------------------------------------------------------------- */

static bool same_position(const tess* t, uint32_t a, uint32_t b) {
  return a == b || !memcmp(t->out->positions + 3 * (size_t)a, t->out->positions + 3 * (size_t)b, sizeof(float) * 3);
}

static tlod_result push_strip_tri(tess* t, const uint32_t tri[3]) {
  if (t->strip_count == t->strip_cap) {
    uint32_t cap = t->strip_cap ? t->strip_cap * 2 : 1024;
    uint32_t(*grown)[3] = _tlod_alloc(t->ctx, sizeof(*grown) * cap);
    if (!grown) return TLOD_ERROR_OUT_OF_MEMORY;
    if (t->strip_count) memcpy(grown, t->strip_tris, sizeof(*grown) * t->strip_count);
    _tlod_free(t->ctx, t->strip_tris);
    t->strip_tris = grown;
    t->strip_cap = cap;
  }
  memcpy(t->strip_tris[t->strip_count++], tri, sizeof(uint32_t) * 3);
  return TLOD_SUCCESS;
}

/* Output ids and parameters of edge e of patch f, in f's direction. */
static uint32_t polyline(const tess* t, uint32_t f, uint32_t e, bool reverse, uint32_t* ids, uint32_t* params) {
  uint32_t lv = (uint32_t)level_of(t, f), local[(1u << TLOD_MAX_LEVEL) + 1];
  uint32_t n = tlod_patterns_edge(t->pat, shape_of(t, f), lv, e, local) - 1;
  for (uint32_t k = 0; k <= n; k++) {
    ids[k] = vertex_id(t, f, local[reverse ? n - k : k]);
    params[k] = k << (t->lmax - lv);
  }
  return n;
}

static tlod_result stitch_edge(tess* t, uint32_t f, uint32_t e, tlod_edge_link link) {
  static const uint32_t cap = (1u << TLOD_MAX_LEVEL) + 1;
  uint32_t ids[2][(1u << TLOD_MAX_LEVEL) + 1], params[2][(1u << TLOD_MAX_LEVEL) + 1];
  uint32_t tris[2 * ((1u << TLOD_MAX_LEVEL) + 1)][3];
  (void)cap;
  uint32_t na = polyline(t, f, e, false, ids[0], params[0]);
  uint32_t nb = polyline(t, link.face, link.edge, true, ids[1], params[1]);
  uint32_t count = _tlod_zip_polylines(params[0], na, params[1], nb, tris);
  t->out->strips++;
  for (uint32_t k = 0; k < count; k++) {
    uint32_t tri[3];
    for (int c = 0; c < 3; c++)
      tri[c] = tris[k][c] <= na ? ids[0][tris[k][c]] : ids[1][tris[k][c] - na - 1];
    if (same_position(t, tri[0], tri[1]) || same_position(t, tri[1], tri[2]) || same_position(t, tri[2], tri[0])) {
      t->out->folds_skipped++;
      continue;
    }
    if (push_strip_tri(t, tri) != TLOD_SUCCESS) return TLOD_ERROR_OUT_OF_MEMORY;
  }
  return TLOD_SUCCESS;
}

static tlod_result stitch(tess* t) {
  if (t->d.no_stitch) return TLOD_SUCCESS;
  for (uint32_t f = 0; f < t->m->face_count; f++) {
    if (level_of(t, f) < 0) continue;
    for (uint32_t e = 0; e < t->m->face_corners[f]; e++) {
      tlod_edge_link link;
      if (!linked(t, f, e, &link) || link.face < f) continue;
      if (link.smooth && level_of(t, link.face) == level_of(t, f)) continue;
      tlod_result r = stitch_edge(t, f, e, link);
      if (r != TLOD_SUCCESS) return r;
    }
  }
  return TLOD_SUCCESS;
}

/* ---- driver ---------------------------------------------------------------- */

static void tess_free(tess* t) {
  for (int sh = 0; sh < 2; sh++) {
    for (int l = 0; l <= TLOD_MAX_LEVEL; l++) {
      _tlod_free(t->ctx, t->tables[sh][l].kind);
      _tlod_free(t->ctx, t->tables[sh][l].param);
    }
  }
  void* arrays[] = {t->level,     t->corner_id,     t->corner_src, t->slot_owner, t->slot_level,
                    t->slot_base, t->interior_base, t->tri_base,   t->strip_tris};
  for (size_t i = 0; i < sizeof(arrays) / sizeof(arrays[0]); i++)
    _tlod_free(t->ctx, arrays[i]);
}

void tlod_cpu_mesh_destroy(tlod_context* ctx, tlod_cpu_mesh* mesh) {
  if (!ctx || !mesh) return;
  _tlod_free(ctx, mesh->positions);
  _tlod_free(ctx, mesh->normals);
  _tlod_free(ctx, mesh->indices);
  _tlod_free(ctx, mesh->triangle_patch);
  _tlod_free(ctx, mesh);
}

static tlod_result resolve_levels(tess* t) {
  uint32_t faces = t->m->face_count;
  t->level = _tlod_alloc(t->ctx, faces ? faces : 1);
  if (!t->level) return _tlod_fail(t->ctx, TLOD_ERROR_OUT_OF_MEMORY, "tlod_cpu_tessellate: out of memory");
  for (uint32_t f = 0; f < faces; f++) {
    int lv = t->d.levels ? t->d.levels[f] : (int)t->d.level;
    if (lv > (int)t->lmax || lv < -1)
      return _tlod_fail(t->ctx, TLOD_ERROR_INVALID_ARGUMENT,
                        "tlod_cpu_tessellate: patch %u: level %d outside [-1, %u] (patterns max level)", f, lv,
                        t->lmax);
    t->level[f] = (int8_t)lv;
    if (lv >= 0 && build_table(t, shape_of(t, f), (uint32_t)lv) != TLOD_SUCCESS)
      return _tlod_fail(t->ctx, TLOD_ERROR_OUT_OF_MEMORY, "tlod_cpu_tessellate: out of memory");
  }
  return TLOD_SUCCESS;
}

static tlod_result number_vertices(tess* t) {
  uint32_t faces = t->m->face_count;
  t->interior_base = _tlod_calloc(t->ctx, faces + 1u, sizeof(uint32_t));
  t->tri_base = _tlod_calloc(t->ctx, faces + 1u, sizeof(uint32_t));
  if (!t->interior_base || !t->tri_base) return TLOD_ERROR_OUT_OF_MEMORY;
  uint64_t tris = 0;
  for (uint32_t f = 0; f < faces; f++) {
    t->tri_base[f] = (uint32_t)tris;
    if (level_of(t, f) >= 0) tris += tlod_pattern_triangle_count(shape_of(t, f), (uint32_t)level_of(t, f));
  }
  if (tris > UINT32_MAX / 4) return TLOD_ERROR_UNSUPPORTED;
  t->pattern_tris = (uint32_t)tris;
  if (t->d.no_weld) {
    assign_unwelded(t);
    return TLOD_SUCCESS;
  }
  t->slot_owner = _tlod_calloc(t->ctx, (size_t)faces * 4 + 1, sizeof(uint32_t));
  t->slot_level = _tlod_calloc(t->ctx, (size_t)faces * 4 + 1, 1);
  t->slot_base = _tlod_calloc(t->ctx, (size_t)faces * 4 + 1, sizeof(uint32_t));
  if (!t->slot_owner || !t->slot_level || !t->slot_base) return TLOD_ERROR_OUT_OF_MEMORY;
  tlod_result r = number_corners(t);
  if (r != TLOD_SUCCESS) return r;
  assign_slots(t);
  return TLOD_SUCCESS;
}

static tlod_result alloc_output(tess* t, bool indices) {
  tlod_cpu_mesh* o = t->out;
  if (!indices) {
    o->vertex_count = t->vertex_count;
    o->positions = _tlod_alloc(t->ctx, sizeof(float) * 3 * ((size_t)t->vertex_count + 1));
    if (!t->d.no_normals) o->normals = _tlod_alloc(t->ctx, sizeof(float) * 3 * ((size_t)t->vertex_count + 1));
    return o->positions && (t->d.no_normals || o->normals) ? TLOD_SUCCESS : TLOD_ERROR_OUT_OF_MEMORY;
  }
  o->pattern_triangles = t->pattern_tris;
  o->strip_triangles = t->strip_count;
  o->triangle_count = t->pattern_tris + t->strip_count;
  o->indices = _tlod_alloc(t->ctx, sizeof(uint32_t) * 3 * ((size_t)o->triangle_count + 1));
  o->triangle_patch = _tlod_alloc(t->ctx, sizeof(uint32_t) * ((size_t)o->triangle_count + 1));
  return o->indices && o->triangle_patch ? TLOD_SUCCESS : TLOD_ERROR_OUT_OF_MEMORY;
}

static tlod_result run(tess* t) {
  tlod_result r = resolve_levels(t);
  if (r != TLOD_SUCCESS) return r;
  if ((r = number_vertices(t)) != TLOD_SUCCESS || (r = alloc_output(t, false)) != TLOD_SUCCESS)
    return r == TLOD_ERROR_UNSUPPORTED
               ? _tlod_fail(t->ctx, r, "tlod_cpu_tessellate: output would exceed 2^30 triangles")
               : _tlod_fail(t->ctx, r, "tlod_cpu_tessellate: out of memory for %u vertices", t->vertex_count);
  eval_corners(t);
  _tlod_parallel_for(t->ctx, eval_patches, t, t->m->face_count);
  if (stitch(t) != TLOD_SUCCESS || alloc_output(t, true) != TLOD_SUCCESS)
    return _tlod_fail(t->ctx, TLOD_ERROR_OUT_OF_MEMORY, "tlod_cpu_tessellate: out of memory for triangles");
  _tlod_parallel_for(t->ctx, emit_patches, t, t->m->face_count);
  if (t->strip_count) {
    memcpy(t->out->indices + 3 * (size_t)t->pattern_tris, t->strip_tris, sizeof(uint32_t) * 3 * t->strip_count);
    for (uint32_t k = 0; k < t->strip_count; k++)
      t->out->triangle_patch[t->pattern_tris + k] = UINT32_MAX;
  }
  return TLOD_SUCCESS;
}

tlod_result tlod_cpu_tessellate(tlod_context* ctx, const tlod_surface* surface, const tlod_patterns* patterns,
                                const tlod_cpu_tessellate_desc* desc, tlod_cpu_mesh** out) {
  if (!ctx) return TLOD_ERROR_INVALID_ARGUMENT;
  if (!out || !surface || !patterns || !desc)
    return _tlod_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "tlod_cpu_tessellate: NULL argument");
  *out = NULL;
  tess t = {.ctx = ctx, .s = surface, .m = surface->mesh, .pat = patterns, .d = *desc};
  t.lmax = tlod_patterns_max_level(patterns);
  t.n_grid = 1u << t.lmax;
  t.out = _tlod_calloc(ctx, 1, sizeof(tlod_cpu_mesh));
  if (!t.out) return _tlod_fail(ctx, TLOD_ERROR_OUT_OF_MEMORY, "tlod_cpu_tessellate: out of memory");
  tlod_result r = run(&t);
  tess_free(&t);
  if (r != TLOD_SUCCESS) {
    tlod_cpu_mesh_destroy(ctx, t.out);
    return r;
  }
  *out = t.out;
  return TLOD_SUCCESS;
}
