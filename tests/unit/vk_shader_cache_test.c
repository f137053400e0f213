/*
 * vk_shader_cache_test.c -- the Vulkan backend's GLSL -> SPIR-V module
 * (backends/vulkan/src/vk_shader.h, white-box; glslang only, no device):
 *   - every stage of every program variant the devices build (pattern and
 *     strip vertex stages, the hardware path's vertex / control /
 *     evaluation stages for 3 and 4 corners, the fragment stage; flat, Phong
 *     and PN; PLAIN, FULL and MASK; with and without a fragment hook)
 *     compiles for Vulkan to SPIR-V;
 *   - the disk cache: a first run compiles each distinct stage once (the
 *     test counts distinct source lists itself), a second run compiles
 *     nothing and loads every stage, bitwise equal; a truncated, corrupted,
 *     misnamed or hostile cache file is ignored and compiled again;
 *   - errors name the string and its line ("fragment_hook:3",
 *     "common.glsl:2"), and a failed compile leaves no cache file;
 *   - the SPIR-V's std140 / push constant member offsets (read from its
 *     OpMemberDecorate Offset) are those of the C mirrors tlod_vk_uniforms
 *     and tlod_vk_push in layout.h;
 *   - every allocation goes through the context, and is freed.
 */
#define _POSIX_C_SOURCE 200809L /* opendir, unlink, truncate */
#include <dirent.h>
#include <stddef.h>
#include <stdint.h>
#include <sys/stat.h>
#include <unistd.h>

#include "layout.h"
#include "shader_sources.h"
#include "test.h"
#include "test_context.h"
#include "vk_shader.h"

#ifndef TLOD_TEST_SCRATCH
#error "TLOD_TEST_SCRATCH (tests/CMakeLists.txt) names the test's scratch folder"
#endif
#define CACHE_DIR TLOD_TEST_SCRATCH "/cache/sub" /* a missing parent too: created on the first write */

static const char* const k_hook = "vec4 tlod_shade(tlod_fragment f) {\n"
                                  "  return f.base_color * f.attributes[1] + vec4(f.level == 0u ? 0.1 : 0.0);\n"
                                  "}\n";

/* ---- every stage of every variant ------------------------------------------ */

#define MAX_STAGES 256
typedef struct stage {
  glslang_stage_t kind;
  const char* src[_TLOD_SHADER_STAGE_SOURCES];
  const char* names[_TLOD_SHADER_STAGE_SOURCES];
  int count;
  char defines[_TLOD_SHADER_DEFINES_BYTES];
} stage;

typedef struct stage_list {
  stage s[MAX_STAGES];
  int n;
} stage_list;

/* Keeps one stage of the walk (the defines copied: they live only during it). */
static bool keep_stage(void* user, _tlod_shader_stage kind, const char* const* src, const char* const* names,
                       int count) {
  stage_list* l = user;
  if (l->n == MAX_STAGES) return false;
  stage* s = &l->s[l->n++];
  s->kind = _tlod_vk_stage(kind);
  s->count = count;
  snprintf(s->defines, sizeof(s->defines), "%s", src[0]);
  for (int i = 0; i < count; i++)
    s->src[i] = i == 0 ? s->defines : src[i], s->names[i] = names[i];
  return true;
}

/* The devices' variants: surface x PLAIN/FULL/MASK x hook, every stage. */
static void all_stages(stage_list* l, bool hooks) {
  l->n = 0;
  const tlod_surface_type types[3] = {TLOD_SURFACE_FLAT, TLOD_SURFACE_PHONG, TLOD_SURFACE_PN};
  for (int t = 0; t < 3; t++)
    for (int variant = 0; variant < 3; variant++)
      for (int hook = 0; hook < (hooks ? 2 : 1); hook++) {
        _tlod_shader_variant v = {.vulkan = true,
                                  .attribute_varyings = variant && hook ? TLOD_SHADER_MAX_ATTRIBUTES : 0,
                                  .texcoord = variant != 0,
                                  .mask = variant == 2};
        CHECK(_tlod_shader_each_stage(types[t], &v, hook ? k_hook : NULL, true, keep_stage, l));
      }
}

static bool same_stage(const stage* a, const stage* b) {
  if (a->kind != b->kind || a->count != b->count) return false;
  for (int i = 0; i < a->count; i++) {
    if (strcmp(a->src[i], b->src[i]) != 0) return false;
  }
  return true;
}

/* Stages whose sources no earlier stage has: what a cold cache compiles. */
static int distinct_stages(const stage_list* l) {
  int n = 0;
  for (int i = 0; i < l->n; i++) {
    int j = 0;
    while (j < i && !same_stage(&l->s[i], &l->s[j]))
      j++;
    n += j == i;
  }
  return n;
}

/* ---- scratch folder ------------------------------------------------------------- */

static void remove_files(const char* dir) {
  DIR* d = opendir(dir);
  if (!d) return;
  for (struct dirent* e; (e = readdir(d));) {
    char path[1024];
    snprintf(path, sizeof(path), "%s/%s", dir, e->d_name);
    if (e->d_name[0] != '.') unlink(path);
  }
  closedir(d);
}

/* The cache files (names ending in .spv) in CACHE_DIR; paths[i] when not NULL. */
static int cache_files(char paths[][1024], int max) {
  DIR* d = opendir(CACHE_DIR);
  int n = 0;
  for (struct dirent* e; d && (e = readdir(d));) {
    size_t len = strlen(e->d_name);
    if (len < 4 || strcmp(e->d_name + len - 4, ".spv") != 0) continue;
    if (paths && n < max) snprintf(paths[n], 1024, "%s/%s", CACHE_DIR, e->d_name);
    n++;
  }
  if (d) closedir(d);
  return n;
}

/* ---- runs --------------------------------------------------------------------------- */

typedef struct spirv {
  uint32_t* words[MAX_STAGES];
  size_t count[MAX_STAGES];
} spirv;

/* Through the folder only: the built-in table (TLOD_VK_PRECOMPILE builds)
 * has its own test. */
static tlod_result compile_one(tlod_context* ctx, vk_shader_cache* cache, const stage* s, uint32_t** words,
                               size_t* count) {
  cache->skip_builtins = true;
  return _tlod_vk_spirv(ctx, cache, s->kind, s->src, s->names, s->count, words, count);
}

/* Compiles every stage of l; out keeps the words (free_spirv). */
static void run_all(tlod_context* ctx, vk_shader_cache* cache, const stage_list* l, spirv* out) {
  for (int i = 0; i < l->n; i++) {
    tlod_result r = compile_one(ctx, cache, &l->s[i], &out->words[i], &out->count[i]);
    CHECK_MSG(r == TLOD_SUCCESS, "stage %d (%s ...): %s", i, l->s[i].names[l->s[i].count - 1],
              tlod_context_last_error(ctx));
    CHECK_MSG(out->count[i] > 5 && out->words[i][0] == 0x07230203u, "stage %d: not SPIR-V", i);
  }
}

static void free_spirv(tlod_context* ctx, spirv* s, int n) {
  for (int i = 0; i < n; i++)
    tlod_context_free(ctx, s->words[i]);
  memset(s, 0, sizeof(*s));
}

static stage_list g_stages;
static spirv g_first, g_second;

TEST(every_variant_compiles_then_loads_from_the_cache) {
  counting_allocator counter = {.fail_at = -1};
  tlod_context* ctx = new_context(1, &counter, NULL);
  remove_files(CACHE_DIR);
  CALL(all_stages(&g_stages, true));
  int distinct = distinct_stages(&g_stages);
  vk_shader_cache cold = {.dir = CACHE_DIR};
  CALL(run_all(ctx, &cold, &g_stages, &g_first));
  printf("  %d stages, %d distinct: %u compiles, %u hits, %.0f ms\n", g_stages.n, distinct, cold.compiles, cold.hits,
         cold.ms);
  CHECK_MSG(cold.compiles == (uint32_t)distinct && cold.hits == (uint32_t)(g_stages.n - distinct), "%u %u",
            cold.compiles, cold.hits);
  CHECK_MSG(cache_files(NULL, 0) == distinct, "%d cache files", cache_files(NULL, 0));
  vk_shader_cache warm = {.dir = CACHE_DIR};
  CALL(run_all(ctx, &warm, &g_stages, &g_second));
  printf("  second start: %u compiles, %u hits, %.1f ms\n", warm.compiles, warm.hits, warm.ms);
  CHECK_MSG(warm.compiles == 0 && warm.hits == (uint32_t)g_stages.n, "%u %u", warm.compiles, warm.hits);
  for (int i = 0; i < g_stages.n; i++)
    CHECK_MSG(g_first.count[i] == g_second.count[i] &&
                  memcmp(g_first.words[i], g_second.words[i], sizeof(uint32_t) * g_first.count[i]) == 0,
              "stage %d differs after the cache", i);
  free_spirv(ctx, &g_first, g_stages.n);
  free_spirv(ctx, &g_second, g_stages.n);
  tlod_context_destroy(ctx);
  CHECK_MSG(counter.allocs == counter.frees, "%ld allocations, %ld frees", counter.allocs, counter.frees);
}

/* Writes bytes over the file (or truncates it to size when bytes is NULL). */
static void damage(const char* path, long offset, const void* bytes, size_t n, long size) {
  if (!bytes) {
    CHECK(truncate(path, size) == 0);
    return;
  }
  FILE* f = fopen(path, "r+b");
  CHECK(f);
  fseek(f, offset, SEEK_SET);
  fwrite(bytes, 1, n, f);
  fclose(f);
}

/* One stage through a fresh cache struct: compiled (true) or loaded. */
static bool compiled_again(tlod_context* ctx, const stage* s) {
  vk_shader_cache c = {.dir = CACHE_DIR};
  uint32_t* words = NULL;
  size_t count = 0;
  tlod_result r = compile_one(ctx, &c, s, &words, &count);
  bool ok = r == TLOD_SUCCESS && count > 5 && words[0] == 0x07230203u && c.compiles + c.hits == 1;
  tlod_context_free(ctx, words);
  return ok ? c.compiles == 1 : (fprintf(stderr, "compile failed: %s\n", tlod_context_last_error(ctx)), false);
}

/* The largest allocation asked of the context: a hostile header must not
 * make the loader allocate what it says. */
static size_t g_largest;
static void* sizing_alloc(size_t size, void* user_data) {
  (void)user_data;
  g_largest = size > g_largest ? size : g_largest;
  return malloc(size ? size : 1);
}
static void sizing_free(void* ptr, void* user_data) {
  (void)user_data;
  free(ptr);
}

TEST(damaged_cache_files_are_compiled_again) {
  tlod_context* ctx = NULL;
  tlod_context_desc desc = {.thread_count = 1, .allocator = {sizing_alloc, sizing_free, NULL}};
  CHECK(tlod_context_create(&desc, &ctx) == TLOD_SUCCESS);
  remove_files(CACHE_DIR);
  const stage* s = &g_stages.s[0];
  CHECK(compiled_again(ctx, s));
  CHECK_MSG(!compiled_again(ctx, s), "an intact file is loaded");
  char paths[2][1024];
  CHECK(cache_files(paths, 2) == 1);
  struct stat st;
  CHECK(stat(paths[0], &st) == 0);
  const uint32_t zero = 0, huge = 0xFFFFFFFFu;
  struct {
    const char* what;
    long offset;
    const void* bytes;
    long size;
  } cases[] = {
      {"truncated inside the words", 0, NULL, (long)st.st_size / 2},
      {"truncated inside the header", 0, NULL, 10},
      {"empty", 0, NULL, 0},
      {"a word flipped", (long)st.st_size - 8, &huge, 0},
      {"longer than its header says", (long)st.st_size, &zero, 0},
      {"hostile word count", 24, &huge, 0},
      {"zero word count", 24, &zero, 0},
      {"bad magic", 0, &zero, 0},
  };
  for (size_t i = 0; i < sizeof(cases) / sizeof(cases[0]); i++) {
    CALL(damage(paths[0], cases[i].offset, cases[i].bytes, 4, cases[i].size));
    g_largest = 0;
    CHECK_MSG(compiled_again(ctx, s), "%s: not compiled again", cases[i].what);
    CHECK_MSG(g_largest < (1u << 20), "%s: allocated %zu bytes", cases[i].what, g_largest);
    CHECK_MSG(!compiled_again(ctx, s), "%s: the new file is not loaded", cases[i].what);
  }
  /* One stage's valid file under another stage's name: its key does not match. */
  CHECK(compiled_again(ctx, &g_stages.s[1]));
  CHECK(cache_files(paths, 2) == 2);
  size_t size0 = 0;
  char* first = test_read_file(paths[0], &size0);
  CHECK(first);
  FILE* f = fopen(paths[1], "wb");
  fwrite(first, 1, size0, f);
  fclose(f);
  free(first);
  int again = compiled_again(ctx, &g_stages.s[0]) + compiled_again(ctx, &g_stages.s[1]);
  CHECK_MSG(again == 1, "the stage whose file has the other's contents is compiled again (%d)", again);
  again = compiled_again(ctx, &g_stages.s[0]) + compiled_again(ctx, &g_stages.s[1]);
  CHECK_MSG(again == 0, "then both load (%d)", again);
  tlod_context_destroy(ctx);
}

static void expect_error(tlod_context* ctx, const stage* s, const char* want, const char* token) {
  vk_shader_cache c = {.dir = CACHE_DIR};
  uint32_t* words = (uint32_t*)&c;
  size_t count = 1;
  int files = cache_files(NULL, 0);
  tlod_result r = compile_one(ctx, &c, s, &words, &count);
  const char* e = tlod_context_last_error(ctx);
  CHECK_MSG(r == TLOD_ERROR_BACKEND && !words && count == 0, "result %d", (int)r);
  CHECK_MSG(strstr(e, want) && strstr(e, token) && strstr(e, ": error:"), "error: %s", e);
  CHECK_MSG(!strstr(e, "compilation errors"), "the closing count is dropped: %s", e);
  CHECK_MSG(cache_files(NULL, 0) == files, "a failed compile wrote a cache file");
}

TEST(errors_name_the_string_and_its_line) {
  counting_allocator counter = {.fail_at = -1};
  tlod_context* ctx = new_context(1, &counter, NULL);
  stage s;
  _tlod_shader_variant v = {.vulkan = true, .attribute_varyings = TLOD_SHADER_MAX_ATTRIBUTES, .texcoord = true};
  _tlod_shader_defines(&v, s.defines);
  const char* bad_hook =
      "vec4 tlod_shade(tlod_fragment f) {\n  vec4 c = f.base_color;\n  return c * no_such_colour;\n}";
  s.kind = GLSLANG_STAGE_FRAGMENT;
  s.count = _tlod_shader_fragment(s.src, s.defines, NULL, bad_hook);
  _tlod_shader_names(s.src, s.count, bad_hook, s.names);
  CALL(expect_error(ctx, &s, "vulkan shader: fragment stage: fragment_hook:3: error:", "no_such_colour"));
  /* An error in a string in the middle: common.glsl with a bad line 2. */
  size_t n = strlen(_tlod_shader_common);
  char* common = malloc(n + 64);
  CHECK(common);
  snprintf(common, n + 64, "// line 1\nconst float bad = undeclared_thing;\n%s", _tlod_shader_common);
  s.kind = GLSLANG_STAGE_VERTEX;
  s.count = _tlod_shader_vertex_side(s.src, s.defines, NULL, _tlod_shader_pn, true, _tlod_shader_pattern_vert);
  _tlod_shader_names(s.src, s.count, NULL, s.names);
  s.src[3] = common; /* defines, layout.h, uniforms.glsl, common.glsl */
  s.names[3] = "common.glsl";
  expect_error(ctx, &s, "vulkan shader: vertex stage: common.glsl:2: error:", "undeclared_thing");
  free(common);
  tlod_context_destroy(ctx);
  CHECK_MSG(counter.allocs == counter.frees, "%ld allocations, %ld frees", counter.allocs, counter.frees);
}

TEST(without_a_folder_every_call_compiles) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  vk_shader_cache c = {0};
  for (int i = 0; i < 2; i++) {
    uint32_t* words = NULL;
    size_t count = 0;
    CHECK(compile_one(ctx, &c, &g_stages.s[0], &words, &count) == TLOD_SUCCESS);
    tlod_context_free(ctx, words);
  }
  CHECK_MSG(c.compiles == 2 && c.hits == 0, "%u %u", c.compiles, c.hits);
  tlod_context_destroy(ctx);
}

/* A cache folder that cannot be made (a file is in the way): compiled, used, a warning. */
TEST(an_unwritable_folder_is_not_an_error) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  mkdir(TLOD_TEST_SCRATCH, 0777);
  FILE* f = fopen(TLOD_TEST_SCRATCH "/file", "w");
  CHECK(f);
  fclose(f);
  vk_shader_cache c = {.dir = TLOD_TEST_SCRATCH "/file/cache"};
  uint32_t* words = NULL;
  size_t count = 0;
  CHECK(compile_one(ctx, &c, &g_stages.s[0], &words, &count) == TLOD_SUCCESS && count > 5);
  CHECK(c.compiles == 1);
  tlod_context_free(ctx, words);
  tlod_context_destroy(ctx);
}

/* ---- the block layouts against the C mirrors ------------------------------------------ */

/* The id OpName gives name, or 0. */
static uint32_t named_id(const uint32_t* w, size_t n, const char* name) {
  for (size_t i = 5; i < n; i += w[i] >> 16) {
    if ((w[i] & 0xFFFFu) == 5 && strcmp((const char*)&w[i + 2], name) == 0) return w[i + 1];
    if (w[i] >> 16 == 0) break;
  }
  return 0;
}

/* The Offset decoration of the member called member of struct id, or -1. */
static long member_offset(const uint32_t* w, size_t n, uint32_t id, const char* member) {
  long index = -1;
  for (size_t i = 5; i < n && w[i] >> 16; i += w[i] >> 16) {
    if ((w[i] & 0xFFFFu) == 6 && w[i + 1] == id && strcmp((const char*)&w[i + 3], member) == 0) index = w[i + 2];
  }
  for (size_t i = 5; i < n && w[i] >> 16; i += w[i] >> 16) {
    if ((w[i] & 0xFFFFu) == 72 && w[i + 1] == id && (long)w[i + 2] == index && w[i + 3] == 35) return w[i + 4];
  }
  return -1;
}

TEST(block_offsets_are_the_c_mirrors) {
  static const struct {
    const char* block;
    const char* member;
    size_t offset;
  } k[] = {
      {"TlodUniforms", "u_view_proj", offsetof(tlod_vk_uniforms, view_proj)},
      {"TlodUniforms", "u_model", offsetof(tlod_vk_uniforms, model)},
      {"TlodUniforms", "u_normal_matrix", offsetof(tlod_vk_uniforms, normal_matrix)},
      {"TlodUniforms", "u_light_dir", offsetof(tlod_vk_uniforms, light_dir)},
      {"TlodUniforms", "u_base_color", offsetof(tlod_vk_uniforms, base_color)},
      {"TlodUniforms", "u_eye", offsetof(tlod_vk_uniforms, eye)},
      {"TlodUniforms", "u_ortho", offsetof(tlod_vk_uniforms, ortho)},
      {"TlodUniforms", "u_forward", offsetof(tlod_vk_uniforms, forward)},
      {"TlodUniforms", "u_alpha_cutoff", offsetof(tlod_vk_uniforms, alpha_cutoff)},
      {"TlodUniforms", "u_grid", offsetof(tlod_vk_uniforms, grid)},
      {"TlodUniforms", "u_max_level", offsetof(tlod_vk_uniforms, max_level)},
      {"TlodUniforms", "u_texcoord", offsetof(tlod_vk_uniforms, texcoord)},
      {"TlodUniforms", "u_attribute_count", offsetof(tlod_vk_uniforms, attribute_count)},
      {"TlodPush", "u_first_instance", offsetof(tlod_vk_push, first_instance)},
      {"TlodPush", "u_shape_base", offsetof(tlod_vk_push, shape_base)},
      {"TlodPush", "u_corners", offsetof(tlod_vk_push, corners)},
      {"TlodPush", "u_debug", offsetof(tlod_vk_push, debug)},
  };
  tlod_context* ctx = new_context(1, NULL, NULL);
  vk_shader_cache c = {.skip_builtins = true};
  uint32_t* w = NULL;
  size_t n = 0;
  const stage* frag = &g_stages.s[2]; /* flat, PLAIN, no hook: the fragment stage */
  CHECK(frag->kind == GLSLANG_STAGE_FRAGMENT && compile_one(ctx, &c, frag, &w, &n) == TLOD_SUCCESS);
  for (size_t i = 0; i < sizeof(k) / sizeof(k[0]); i++) {
    long got = member_offset(w, n, named_id(w, n, k[i].block), k[i].member);
    CHECK_MSG(got == (long)k[i].offset, "%s.%s at %ld, C mirror at %zu", k[i].block, k[i].member, got, k[i].offset);
  }
  tlod_context_free(ctx, w);
  tlod_context_destroy(ctx);
}

/* TLOD_VK_PRECOMPILE: every default stage (no hook) comes from the table,
 * bitwise what the run-time compile gives. */
TEST(built_in_stages_equal_a_fresh_compile) {
  if (!_tlod_vk_spirv_builtin_available()) {
    printf("  this build has no built-in SPIR-V (TLOD_VK_PRECOMPILE OFF): checked that none is used\n");
  }
  static stage_list defaults;
  CALL(all_stages(&defaults, false));
  tlod_context* ctx = new_context(1, NULL, NULL);
  vk_shader_cache table = {0}, fresh = {.skip_builtins = true};
  for (int i = 0; i < defaults.n; i++) {
    const stage* s = &defaults.s[i];
    uint32_t *a = NULL, *b = NULL;
    size_t na = 0, nb = 0;
    CHECK(_tlod_vk_spirv(ctx, &table, s->kind, s->src, s->names, s->count, &a, &na) == TLOD_SUCCESS);
    CHECK(_tlod_vk_spirv(ctx, &fresh, s->kind, s->src, s->names, s->count, &b, &nb) == TLOD_SUCCESS);
    bool same = na == nb && memcmp(a, b, sizeof(uint32_t) * na) == 0;
    tlod_context_free(ctx, a);
    tlod_context_free(ctx, b);
    CHECK_MSG(same, "stage %d: the built-in words differ from a compile", i);
  }
  bool builtin = _tlod_vk_spirv_builtin_available();
  printf("  %d default stages: %u built in, %u compiled\n", defaults.n, table.builtins, table.compiles);
  CHECK_MSG(builtin ? table.builtins == (uint32_t)defaults.n && table.compiles == 0
                    : table.builtins == 0 && table.compiles == (uint32_t)defaults.n,
            "%u built in, %u compiled", table.builtins, table.compiles);
  CHECK(fresh.builtins == 0 && fresh.compiles == (uint32_t)defaults.n);
  tlod_context_destroy(ctx);
}

int main(void) {
  glslang_initialize_process();
  RUN(every_variant_compiles_then_loads_from_the_cache);
  RUN(damaged_cache_files_are_compiled_again);
  RUN(block_offsets_are_the_c_mirrors);
  RUN(built_in_stages_equal_a_fresh_compile);
  RUN(errors_name_the_string_and_its_line);
  RUN(without_a_folder_every_call_compiles);
  RUN(an_unwritable_folder_is_not_an_error);
  glslang_finalize_process();
  TEST_END();
}
