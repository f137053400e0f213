/* JSON of scheduler figures, shared by tlod tessellate --stats and the play traces. */
#ifndef TLOD_TOOLS_LOD_JSON_H
#define TLOD_TOOLS_LOD_JSON_H

#include "json_writer.h"

/* key: [count patch counts, level 0 first]. */
void json_level_histogram(json_writer* w, const char* key, const uint32_t* histogram, uint32_t count);
/* key: {"silhouette": ms, "metric": ..., one per scheduler stage}. */
void json_stage_ms(json_writer* w, const char* key, const double* ms);

#endif
