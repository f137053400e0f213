/* import_contract.h -- what tools/import/tlod_import.h promises about tlod_import_file(),
 * checked on every fuzz input (a broken promise abort()s: a finding). */
#ifndef TLOD_FUZZ_IMPORT_CONTRACT_H
#define TLOD_FUZZ_IMPORT_CONTRACT_H

#include "tlod_import.h"

/* res, r and error as tlod_import_file(path, ...) left them: a listed result code; on failure
 * no result and a message naming the file; on success an empty message and a result whose
 * positions are finite, indices below vertex_count, faces of 3 or 4 corners that use up the
 * indices, and parts inside the arrays. */
void fuzz_check_import(tlod_result res, const tlod_import_result* r, const char* error, const char* path);

/* tlod_import_file(path) with the default options, held to the contract above, freed. */
void fuzz_import_and_check(const char* path);

#endif
