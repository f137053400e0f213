/* tesslod::vulkan -- one shader stage from GLSL to SPIR-V: glslang's C
 * interface behind a content-addressed disk cache (vk_shader.h). */
#define _POSIX_C_SOURCE 200809L /* mkstemp, mkdir */
#include "vk_shader.h"

#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <glslang/Public/resource_limits_c.h>
#include <glslang/build_info.h>

#define SPIRV_MAGIC 0x07230203u
#define CACHE_MAGIC 0x56534C54u             /* "TLSV" */
#define CACHE_MAX_WORDS (16u * 1024 * 1024) /* 64 MiB: far above any stage of ours; bounds a hostile header */
#define ERROR_BYTES 1024

/* ---- hashing ---------------------------------------------------------------- */

/* Two FNV-1a lanes (different bases and primes) finished by murmur3's
 * fmix64 across both: a cache key, not a defence against forgery. */
typedef struct hash128 {
  uint64_t a, b;
} hash128;

static hash128 hash_begin(void) { return (hash128){0xcbf29ce484222325ull, 0x84222325cbf29ce4ull}; }

static void hash_bytes(hash128* h, const void* data, size_t n) {
  const unsigned char* p = data;
  for (size_t i = 0; i < n; i++) {
    h->a = (h->a ^ p[i]) * 0x100000001b3ull;
    h->b = (h->b ^ p[i]) * 0x9e3779b97f4a7c15ull;
  }
}

static uint64_t fmix64(uint64_t x) {
  x ^= x >> 33;
  x *= 0xff51afd7ed558ccdull;
  x ^= x >> 33;
  x *= 0xc4ceb9fe1a85ec53ull;
  return x ^ (x >> 33);
}

static hash128 hash_end(hash128 h) {
  uint64_t a = fmix64(h.a ^ (h.b << 31 | h.b >> 33));
  return (hash128){a, fmix64(h.b + a)};
}

/* Everything the SPIR-V depends on: the format, the compiler and its
 * options, the stage and every string with its length. */
static hash128 stage_key(glslang_stage_t stage, const char* const* sources, int count) {
  static const char options[] = "GLSL 450, Vulkan 1.2, SPIR-V 1.5, SPV+VULKAN rules, glslang " GLSLANG_VERSION_FLAVOR;
  const uint32_t fixed[5] = {TLOD_VK_SPIRV_CACHE_VERSION, GLSLANG_VERSION_MAJOR, GLSLANG_VERSION_MINOR,
                             GLSLANG_VERSION_PATCH, (uint32_t)stage};
  hash128 h = hash_begin();
  hash_bytes(&h, options, sizeof(options));
  hash_bytes(&h, fixed, sizeof(fixed));
  for (int i = 0; i < count; i++) {
    uint64_t n = strlen(sources[i]);
    hash_bytes(&h, &n, sizeof(n));
    hash_bytes(&h, sources[i], (size_t)n);
  }
  return hash_end(h);
}

void _tlod_vk_spirv_key(glslang_stage_t stage, const char* const* sources, int count, uint64_t key[2]) {
  hash128 h = stage_key(stage, sources, count);
  key[0] = h.a, key[1] = h.b;
}

static uint64_t words_checksum(const uint32_t* words, size_t count) {
  hash128 h = hash_begin();
  hash_bytes(&h, words, count * sizeof(uint32_t));
  return hash_end(h).a;
}

/* ---- the built-in table (TLOD_VK_PRECOMPILE) -------------------------------------- */

#if TLOD_VK_PRECOMPILED
extern const vk_spirv_builtin _tlod_vk_spirv_builtins[];
extern const int _tlod_vk_spirv_builtin_count;
#else
static const vk_spirv_builtin* const _tlod_vk_spirv_builtins = NULL;
static const int _tlod_vk_spirv_builtin_count = 0;
#endif

bool _tlod_vk_spirv_builtin_available(void) { return _tlod_vk_spirv_builtin_count > 0; }

/* A copy of the built-in words of key (the caller frees them), or NULL. */
static uint32_t* builtin_words(tlod_context* ctx, hash128 key, size_t* count) {
  for (int i = 0; i < _tlod_vk_spirv_builtin_count; i++) {
    const vk_spirv_builtin* b = &_tlod_vk_spirv_builtins[i];
    if (b->key[0] != key.a || b->key[1] != key.b) continue;
    uint32_t* words = tlod_context_alloc(ctx, sizeof(uint32_t) * b->word_count);
    if (words) memcpy(words, b->words, sizeof(uint32_t) * b->word_count), *count = b->word_count;
    return words;
  }
  return NULL;
}

/* ---- the disk cache ------------------------------------------------------------ */

typedef struct cache_header {
  uint32_t magic, version;
  uint64_t key[2];
  uint32_t word_count, reserved;
  uint64_t checksum;
} cache_header;
_Static_assert(sizeof(cache_header) == 40, "the cache file header (docs/shaders.md)");

#define TMP_SUFFIX ".tmp.XXXXXX" /* mkstemp's template after the final name */

/* "<dir>/<32 hex>.spv"; NULL without memory. */
static char* cache_path(tlod_context* ctx, const char* dir, hash128 key) {
  size_t n = strlen(dir) + sizeof("/0123456789abcdef0123456789abcdef.spv");
  char* path = tlod_context_alloc(ctx, n);
  if (path) snprintf(path, n, "%s/%016llx%016llx.spv", dir, (unsigned long long)key.a, (unsigned long long)key.b);
  return path;
}

static const char* check_header(const cache_header* h, hash128 key) {
  if (h->magic != CACHE_MAGIC) return "not a tesslod SPIR-V cache file";
  if (h->version != TLOD_VK_SPIRV_CACHE_VERSION) return "another format version";
  if (h->key[0] != key.a || h->key[1] != key.b) return "key does not match its name";
  if (h->word_count < 5 || h->word_count > CACHE_MAX_WORDS) return "word count out of range";
  return NULL;
}

/* The checked words of path, or NULL (*why says what failed; NULL: no file). */
static uint32_t* read_words(tlod_context* ctx, FILE* f, hash128 key, size_t* count, const char** why) {
  cache_header h;
  if (fread(&h, sizeof(h), 1, f) != 1) return *why = "truncated header", NULL;
  if ((*why = check_header(&h, key))) return NULL;
  uint32_t* words = tlod_context_alloc(ctx, sizeof(uint32_t) * h.word_count);
  if (!words) return *why = "out of memory", NULL;
  if (fread(words, sizeof(uint32_t), h.word_count, f) != h.word_count)
    *why = "truncated words";
  else if (fgetc(f) != EOF)
    *why = "longer than its header says";
  else if (words_checksum(words, h.word_count) != h.checksum)
    *why = "checksum mismatch";
  else if (words[0] != SPIRV_MAGIC)
    *why = "not SPIR-V";
  if (*why) {
    tlod_context_free(ctx, words);
    return NULL;
  }
  *count = h.word_count;
  return words;
}

static uint32_t* cache_load(tlod_context* ctx, const char* path, hash128 key, size_t* count) {
  FILE* f = fopen(path, "rb");
  if (!f) {
    if (errno != ENOENT) tlod_context_log(ctx, TLOD_LOG_WARNING, "vulkan shader cache: %s: %s", path, strerror(errno));
    return NULL;
  }
  const char* why = NULL;
  uint32_t* words = read_words(ctx, f, key, count, &why);
  fclose(f);
  if (!words) tlod_context_log(ctx, TLOD_LOG_WARNING, "vulkan shader cache: %s: %s: compiled again", path, why);
  return words;
}

/* mkdir -p: every missing folder of dir (an existing one is fine). */
static bool make_dirs(char* dir) {
  for (char* p = dir + 1; *p; p++) {
    if (*p != '/') continue;
    *p = '\0';
    bool ok = mkdir(dir, 0777) == 0 || errno == EEXIST;
    *p = '/';
    if (!ok) return false;
  }
  return mkdir(dir, 0777) == 0 || errno == EEXIST;
}

static bool write_file(FILE* f, const cache_header* h, const uint32_t* words) {
  bool ok = fwrite(h, sizeof(*h), 1, f) == 1 && fwrite(words, sizeof(uint32_t), h->word_count, f) == h->word_count;
  return fclose(f) == 0 && ok;
}

/* Writes a unique temporary in the folder, then renames it to path: a
 * reader sees the old file, the new one or none, never a partial one. */
static bool store_file(tlod_context* ctx, const char* path, const cache_header* h, const uint32_t* words) {
  size_t n = strlen(path);
  char* tmp = tlod_context_alloc(ctx, n + sizeof(TMP_SUFFIX));
  if (!tmp) return false;
  memcpy(tmp, path, n);
  memcpy(tmp + n, TMP_SUFFIX, sizeof(TMP_SUFFIX));
  char* slash = strrchr(tmp, '/');
  *slash = '\0';
  bool ok = make_dirs(tmp);
  *slash = '/';
  int fd = ok ? mkstemp(tmp) : -1;
  FILE* f = fd >= 0 ? fdopen(fd, "wb") : NULL;
  if (fd >= 0 && !f) close(fd);
  ok = f && write_file(f, h, words) && rename(tmp, path) == 0;
  int err = errno;
  if (fd >= 0 && !ok) unlink(tmp);
  tlod_context_free(ctx, tmp);
  errno = err;
  return ok;
}

static void cache_store(tlod_context* ctx, const char* path, hash128 key, const uint32_t* words, size_t count) {
  cache_header h = {CACHE_MAGIC, TLOD_VK_SPIRV_CACHE_VERSION, {key.a, key.b}, (uint32_t)count,
                    0,           words_checksum(words, count)};
  if (count > CACHE_MAX_WORDS || !store_file(ctx, path, &h, words))
    tlod_context_log(ctx, TLOD_LOG_WARNING, "vulkan shader cache: cannot write %s: %s", path, strerror(errno));
}

/* ---- compiling ------------------------------------------------------------------- */

/* The strings joined (each ending in a newline) and the concatenation's
 * line of each string's first line. */
typedef struct joined {
  char* text;
  int* first_line;
} joined;

static bool join(tlod_context* ctx, const char* const* sources, int count, joined* j) {
  size_t bytes = 1;
  for (int i = 0; i < count; i++)
    bytes += strlen(sources[i]) + 1;
  j->text = tlod_context_alloc(ctx, bytes);
  j->first_line = tlod_context_alloc(ctx, sizeof(int) * (size_t)count);
  if (!j->text || !j->first_line) return false;
  size_t o = 0;
  int line = 1;
  for (int i = 0; i < count; i++) {
    j->first_line[i] = line;
    for (const char* p = sources[i]; *p; p++)
      line += (j->text[o++] = *p) == '\n';
    if (o == 0 || j->text[o - 1] != '\n') j->text[o++] = '\n', line++;
  }
  j->text[o] = '\0';
  return true;
}

/* "ERROR: 0:LINE: message" -> "name:line: error: message"; other lines of
 * the log (link errors) are kept, the closing error count dropped. */
static size_t name_line(const char* line, size_t len, const joined* j, const char* const* names, int count, char* out,
                        size_t size) {
  const char* kind = strncmp(line, "ERROR: ", 7) == 0 ? "error" : strncmp(line, "WARNING: ", 9) == 0 ? "warning" : NULL;
  const char* p = kind ? line + (kind[0] == 'e' ? 7 : 9) : line;
  char* end = NULL;
  if (kind) strtoul(p, &end, 10);
  long at = end && end > p && *end == ':' ? strtol(end + 1, &end, 10) : 0;
  if (kind && at > 0 && *end == ':') {
    int s = count - 1;
    while (s > 0 && j->first_line[s] > at)
      s--;
    int n = snprintf(out, size, "%s:%ld: %s:%.*s\n", names[s], at - j->first_line[s] + 1, kind,
                     (int)(len - (size_t)(end + 1 - line)), end + 1);
    return n < 0 ? 0 : (size_t)n;
  }
  const char* tail = "compilation errors.  No code generated.";
  if (kind && len >= strlen(tail) && strncmp(line + len - strlen(tail), tail, strlen(tail)) == 0) return 0;
  int n = snprintf(out, size, "%.*s\n", (int)len, line);
  return n < 0 ? 0 : (size_t)n;
}

static void name_log(const char* log, const joined* j, const char* const* names, int count, char* out, size_t size) {
  size_t o = 0;
  out[0] = '\0';
  for (const char* p = log; *p && o + 1 < size;) {
    const char* nl = strchr(p, '\n');
    size_t len = nl ? (size_t)(nl - p) : strlen(p);
    if (len) o += name_line(p, len, j, names, count, out + o, size - o);
    p += len + (nl != NULL);
  }
  while (o > 0 && o < size && (out[o - 1] == '\n' || out[o - 1] == ' '))
    out[--o] = '\0';
}

static const char* stage_name(glslang_stage_t stage) {
  switch (stage) {
  case GLSLANG_STAGE_VERTEX:
    return "vertex";
  case GLSLANG_STAGE_TESSCONTROL:
    return "tessellation control";
  case GLSLANG_STAGE_TESSEVALUATION:
    return "tessellation evaluation";
  case GLSLANG_STAGE_FRAGMENT:
    return "fragment";
  default:
    return "other";
  }
}

glslang_stage_t _tlod_vk_stage(_tlod_shader_stage stage) {
  return stage == _TLOD_SHADER_FRAGMENT          ? GLSLANG_STAGE_FRAGMENT
         : stage == _TLOD_SHADER_TESS_CONTROL    ? GLSLANG_STAGE_TESSCONTROL
         : stage == _TLOD_SHADER_TESS_EVALUATION ? GLSLANG_STAGE_TESSEVALUATION
                                                 : GLSLANG_STAGE_VERTEX;
}

static glslang_input_t stage_input(glslang_stage_t stage, const char* code) {
  return (glslang_input_t){.language = GLSLANG_SOURCE_GLSL,
                           .stage = stage,
                           .client = GLSLANG_CLIENT_VULKAN,
                           .client_version = GLSLANG_TARGET_VULKAN_1_2,
                           .target_language = GLSLANG_TARGET_SPV,
                           .target_language_version = GLSLANG_TARGET_SPV_1_5,
                           .code = code,
                           .default_version = 450,
                           .default_profile = GLSLANG_NO_PROFILE,
                           .messages = GLSLANG_MSG_DEFAULT_BIT,
                           .resource = glslang_default_resource()};
}

/* The linked program's SPIR-V, copied into the context's memory. */
static tlod_result take_spirv(tlod_context* ctx, glslang_program_t* prog, glslang_stage_t stage, uint32_t** words,
                              size_t* count) {
  glslang_program_SPIRV_generate(prog, stage);
  size_t n = glslang_program_SPIRV_get_size(prog);
  if (n == 0)
    return tlod_context_fail(ctx, TLOD_ERROR_BACKEND, "vulkan shader: %s stage: no SPIR-V", stage_name(stage));
  *words = tlod_context_alloc(ctx, sizeof(uint32_t) * n);
  if (!*words) return tlod_context_fail(ctx, TLOD_ERROR_OUT_OF_MEMORY, "vulkan shader: out of memory for SPIR-V");
  glslang_program_SPIRV_get(prog, *words);
  *count = n;
  return TLOD_SUCCESS;
}

static tlod_result compile(tlod_context* ctx, glslang_stage_t stage, const joined* j, const char* const* names,
                           int count, uint32_t** words, size_t* word_count) {
  glslang_input_t in = stage_input(stage, j->text);
  glslang_shader_t* sh = glslang_shader_create(&in);
  glslang_program_t* prog = sh ? glslang_program_create() : NULL;
  if (!prog) {
    glslang_shader_delete(sh);
    return tlod_context_fail(ctx, TLOD_ERROR_OUT_OF_MEMORY, "vulkan shader: glslang could not start");
  }
  const char* log = NULL;
  if (!glslang_shader_preprocess(sh, &in) || !glslang_shader_parse(sh, &in)) log = glslang_shader_get_info_log(sh);
  glslang_program_add_shader(prog, sh);
  if (!log && !glslang_program_link(prog, GLSLANG_MSG_SPV_RULES_BIT | GLSLANG_MSG_VULKAN_RULES_BIT))
    log = glslang_program_get_info_log(prog);
  tlod_result r = TLOD_SUCCESS;
  if (log) {
    char named[ERROR_BYTES];
    name_log(log, j, names, count, named, sizeof(named));
    r = tlod_context_fail(ctx, TLOD_ERROR_BACKEND, "vulkan shader: %s stage: %s", stage_name(stage), named);
  } else {
    r = take_spirv(ctx, prog, stage, words, word_count);
  }
  glslang_program_delete(prog);
  glslang_shader_delete(sh);
  return r;
}

/* Compiles the joined strings; the cache (path not NULL) gets the result. */
static tlod_result compile_stage(tlod_context* ctx, vk_shader_cache* cache, glslang_stage_t stage,
                                 const char* const* sources, const char* const* names, int count, uint32_t** words,
                                 size_t* word_count) {
  joined j = {0};
  tlod_result r = join(ctx, sources, count, &j)
                      ? compile(ctx, stage, &j, names, count, words, word_count)
                      : tlod_context_fail(ctx, TLOD_ERROR_OUT_OF_MEMORY, "vulkan shader: out of memory for sources");
  cache->compiles++;
  tlod_context_free(ctx, j.text);
  tlod_context_free(ctx, j.first_line);
  return r;
}

tlod_result _tlod_vk_spirv(tlod_context* ctx, vk_shader_cache* cache, glslang_stage_t stage, const char* const* sources,
                           const char* const* names, int count, uint32_t** words, size_t* word_count) {
  double t0 = tlod_now_ms();
  *words = NULL;
  *word_count = 0;
  hash128 key = stage_key(stage, sources, count);
  char* path = cache->dir && cache->dir[0] ? cache_path(ctx, cache->dir, key) : NULL;
  tlod_result r = TLOD_SUCCESS;
  if (!cache->skip_builtins && (*words = builtin_words(ctx, key, word_count))) {
    cache->builtins++;
  } else if (path && (*words = cache_load(ctx, path, key, word_count))) {
    cache->hits++;
  } else {
    r = compile_stage(ctx, cache, stage, sources, names, count, words, word_count);
    if (r == TLOD_SUCCESS && path) cache_store(ctx, path, key, *words, *word_count);
  }
  tlod_context_free(ctx, path);
  cache->ms += tlod_now_ms() - t0;
  return r;
}
