/* Private to tesslod::vulkan: GLSL to SPIR-V with glslang's C interface,
 * through an optional on-disk cache.
 *
 * WHAT IT DOES: compiles one stage from several source strings (the same
 * strings the gl device hands glShaderSource, concatenated in order; a
 * string that does not end in a newline gets one), for Vulkan 1.2 / SPIR-V
 * 1.5, GLSL 450; errors name the string and its line: "pattern.vert:12:
 * error: 'x' : undeclared identifier" (the hook's string named
 * "fragment_hook" gives "fragment_hook:LINE"). The sources must not use
 * #line (the mapping from the concatenation's lines is by counting).
 *
 * THE CACHE (cache->dir not NULL): the SPIR-V of a stage is kept in
 * <dir>/<32 hex digits>.spv, the digits a 128-bit hash of the stage, every
 * source string (with its length), glslang's version and the file format's
 * version, so a changed source, define, compiler or format gives a new
 * name. A file starts with a header (magic, format version, the key, the
 * word count, a 64-bit checksum of the words); it is used only when every
 * field checks out, its size is exactly header + words and the words start
 * with the SPIR-V magic number; any other file (truncated, corrupt,
 * hostile, another version) is ignored and replaced by a fresh compile, so
 * nothing unchecked reaches the driver. The checksum catches corruption,
 * not an attacker who can write the folder. Files are written to a unique
 * temporary name in the folder and renamed over the final one (readers see
 * a whole file or none; two processes writing one key both succeed). The
 * folder is created (with its parents) on the first write; a cache that
 * cannot be read or written is logged as a warning and the compile result
 * used, never an error.
 *
 * DOES NOT: call glslang_initialize_process / glslang_finalize_process
 * (process-global, reference counted: the device does, around its life);
 * validate the SPIR-V beyond its header (glslang's output is trusted).
 *
 * ALLOCATION: the returned words and every buffer here through the
 * context's allocator; glslang allocates internally with its own (C++).
 * THREADING: as the context; glslang's process state is its own.
 */
#ifndef TESSLOD_VK_SHADER_H
#define TESSLOD_VK_SHADER_H

#include <stddef.h>
#include <stdint.h>

#include <glslang/Include/glslang_c_interface.h>

#include "tesslod/core.h"

/* Format version of the cache files (part of the key and of the header). */
#define TLOD_VK_SPIRV_CACHE_VERSION 1u

/* The cache folder and what went through it; counters only grow. */
typedef struct vk_shader_cache {
  const char* dir;   /* NULL: no disk cache (every call compiles) */
  uint32_t compiles; /* stages compiled by glslang */
  uint32_t hits;     /* stages loaded from dir */
  double ms;         /* wall time in compiles and loads (tlod_now_ms) */
} vk_shader_cache;

/* Compiles (or loads from the cache) one stage; sources[i] named names[i]
 * for error messages ("pattern.vert:12: error: ..."; the hook's lines as
 * "fragment_hook:LINE"). count >= 1, sources[0] starts with #version.
 * On success *words (allocated through ctx, tlod_context_free) holds
 * *word_count SPIR-V words. On failure *words is NULL and the context's
 * error is "vulkan shader: <stage> stage: <name>:<line>: error: ..."
 * (TLOD_ERROR_BACKEND), or TLOD_ERROR_OUT_OF_MEMORY. */
tlod_result _tlod_vk_spirv(tlod_context* ctx, vk_shader_cache* cache, glslang_stage_t stage, const char* const* sources,
                           const char* const* names, int count, uint32_t** words, size_t* word_count);

#endif
