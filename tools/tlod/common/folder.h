/* Folders the tools make: run folders (play), the shader cache (vulkan). */
#ifndef TLOD_TOOLS_COMMON_FOLDER_H
#define TLOD_TOOLS_COMMON_FOLDER_H

#include <stdbool.h>
#include <stddef.h>

/* mkdir -p; true when path is a folder afterwards (errno set otherwise). */
bool tool_mkdir_p(const char* path);
/* A file can be made in folder path (a temporary is created and removed:
 * permission bits alone do not say it, e.g. for root or read-only mounts). */
bool tool_folder_writable(const char* path);

/* --shader-cache: option NULL == the default folder, $XDG_CACHE_HOME/tesslod
 * or $HOME/.cache/tesslod, made when missing; when it cannot be made or
 * written, *dir is NULL (no disk cache) and warning holds why. "off": *dir
 * NULL. A folder given: made when missing; false with the reason in error
 * when it cannot be made or written (asked for: never ignored). *dir points
 * at option or at buf. */
bool tool_shader_cache_dir(const char* option, char* buf, size_t size, const char** dir, char* warning,
                           size_t warning_size, char* error, size_t error_size);

#endif
