/* export_merge.h -- the OBJ/PLY side of a scene export (private to
 * tools/import/): every instance of every part in world space, one mesh. */
#ifndef TESSLOD_TOOLS_EXPORT_MERGE_H
#define TESSLOD_TOOLS_EXPORT_MERGE_H

#include "export_internal.h"

typedef struct _exp_merged {
  tlod_export_mesh mesh;
  tlod_export_attribute attributes[2]; /* TEXCOORD_0, COLOR_0: what OBJ and PLY write */
  float *positions, *normals, *uv, *color;
  uint32_t* indices;
} _exp_merged;

/* Parts placed at every node instancing their mesh (flattened sources: as
 * they are); the written attributes kept. On failure out holds nothing. */
tlod_result _exp_merge(_exp_job* job, const tlod_export_scene_desc* d, _exp_merged* out);
void _exp_merged_free(_exp_merged* m);

#endif
