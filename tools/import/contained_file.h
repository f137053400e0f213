/* contained_file.h -- the project's rule for files a model names (private to tools/import/).
 * Owned by the import/export layer. docs/security.md states the rule; this is its one implementation,
 * used for glTF buffer URIs and OBJ mtllib (images are never opened).
 *
 * A reference is read only if, in this order:
 *   1. it percent-decodes cleanly (no "%" without two hex digits, no NUL byte);
 *   2. it is relative: not absolute ("/x") and without a scheme ("file:", "http:");
 *   3. realpath(folder/ref), symlinks resolved, lies inside realpath(folder);
 *   4. opened O_RDONLY|O_NONBLOCK|O_NOCTTY|O_CLOEXEC, fstat says a regular file
 *      (never a FIFO, device, socket or folder: nothing that can block or never end);
 *   5. its size is at most max_bytes (the import's remaining memory budget).
 * A refusal names only the reference as written, never the size or any byte of
 * what it resolved to. */
#ifndef TESSLOD_TOOLS_IMPORT_CONTAINED_FILE_H
#define TESSLOD_TOOLS_IMPORT_CONTAINED_FILE_H

#include <stdbool.h>
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum _tlod_contained_status {
  _TLOD_CONTAINED_OK = 0,
  _TLOD_CONTAINED_BAD_ESCAPE,   /* malformed percent-encoding or an encoded NUL */
  _TLOD_CONTAINED_ABSOLUTE,     /* "/x", "file:...", "http://..." */
  _TLOD_CONTAINED_OUTSIDE,      /* resolves outside the model's folder (.. or a symlink) */
  _TLOD_CONTAINED_NOT_FOUND,    /* does not exist or cannot be opened */
  _TLOD_CONTAINED_NOT_REGULAR,  /* FIFO, device, socket, folder */
  _TLOD_CONTAINED_TOO_LARGE,    /* larger than max_bytes */
  _TLOD_CONTAINED_READ_ERROR,   /* read failed or the file changed size */
  _TLOD_CONTAINED_OUT_OF_MEMORY /* malloc failed */
} _tlod_contained_status;

/* Decodes %XX escapes of ref into out (out_size bytes, terminated).
 * Returns false on a malformed escape, an encoded NUL or no room. */
bool _tlod_percent_decode(const char* ref, char* out, size_t out_size);

/* Reads folder/ref under the rule above into malloc memory (*data, *size;
 * one zero byte past the end). folder "" is the current folder. ref is the
 * reference as written in the file (still percent-encoded). On failure *data is NULL. */
_tlod_contained_status _tlod_contained_read(const char* folder, const char* ref, size_t max_bytes, unsigned char** data,
                                            size_t* size);

/* The tlod_result a refusal gives: TLOD_ERROR_OUT_OF_MEMORY (too large, out of memory),
 * TLOD_ERROR_PARSE (bad escape), else TLOD_ERROR_IO. Returned as int (tlod_result) so this
 * header needs no core header. */
int _tlod_contained_result(_tlod_contained_status status);

/* A short phrase for a status, for "<file>: <element> '<ref>': <phrase>". */
const char* _tlod_contained_message(_tlod_contained_status status);

#ifdef __cplusplus
}
#endif
#endif
