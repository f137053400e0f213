/* tlod -- JSON of scheduler figures. */
#include "lod_json.h"

#include "tool_names.h"

void json_level_histogram(json_writer* w, const char* key, const uint32_t* histogram, uint32_t count) {
  json_array_begin(w, key);
  for (uint32_t l = 0; l < count; l++)
    json_uint(w, NULL, histogram[l]);
  json_array_end(w);
}

void json_stage_ms(json_writer* w, const char* key, const double* ms) {
  json_object_begin(w, key);
  for (int s = 0; s < TLOD_STAGE_NUM; s++)
    json_number(w, tool_stage_name(s), ms[s]);
  json_object_end(w);
}
