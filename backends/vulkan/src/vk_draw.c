/* tesslod::vulkan -- tlod_device_draw(): validates the draw's Vulkan
 * fields, begins the frame slot, makes the pipelines the items need,
 * stages every item exactly as the gl device (device_stage.h), writes
 * instances, strips, strip references and indices and one uniform block per item into
 * the slot's ring, writes the descriptor sets that changed and records, per
 * item in draw order (BLEND last, farthest first): its pattern draws
 * (indexed, instanced) or its tessellation batches, its strips, and with
 * wireframe its edges. Nothing is submitted or waited for. */
#include <string.h>

#include "vk_internal.h"

/* Where this draw's data sits in the ring (absolute offsets). */
typedef struct ring_view {
  VkBuffer buffer;
  char* mapped;
  VkDeviceSize uniforms, instances, strips, refs, indices;
  VkDeviceSize instance_bytes, strip_bytes;
} ring_view;

static tlod_result check_vk(vk_device* d, const tlod_draw_desc* fr) {
  const char* fn = "tlod_device_draw";
  if (!fr->vk.command_buffer)
    return tlod_context_fail(d->ctx, TLOD_ERROR_INVALID_ARGUMENT,
                             "%s: desc.vk.command_buffer is NULL (the vulkan device records into the engine's)", fn);
  if (fr->vk.frame_index >= d->frames.count)
    return tlod_context_fail(d->ctx, TLOD_ERROR_INVALID_ARGUMENT,
                             "%s: desc.vk.frame_index %u outside [0, %u) (desc.vk.frames_in_flight of device '%s')", fn,
                             fr->vk.frame_index, d->frames.count, d->label);
  if (fr->wireframe && !d->wireframe_ok)
    return tlod_context_fail(d->ctx, TLOD_ERROR_UNSUPPORTED,
                             "%s: wireframe needs the fillModeNonSolid feature, which the physical device of '%s' "
                             "lacks",
                             fn, d->label);
  return TLOD_SUCCESS;
}

/* As gl_device.c: PLAIN unless the item's fragments read a texture or (a
 * fragment hook) its mesh's attributes; MASK items their own. */
static int variant_of(const vk_device* d, const _tlod_draw_ref* it) {
  const vk_surface* vs = it->surface_state;
  return _tlod_stage_variant(d->pipelines.hook != NULL, vs->attribute_count, it->item);
}

/* CPU-mesh mode: the PLAIN items draw their CPU mesh (the others, and
 * hardware tessellation, evaluate on the GPU). */
static bool uses_mesh(const vk_device* d, const _tlod_draw_ref* it) {
  return d->cpu_mesh && variant_of(d, it) == VK_VARIANT_PLAIN;
}

/* Every pipeline the items need, before anything is recorded (a failure
 * leaves the command buffer untouched). */
static tlod_result prepare(vk_device* d, const tlod_draw_desc* fr, const _tlod_draw_ref* items) {
  for (uint32_t k = 0; k < fr->item_count; k++) {
    const vk_surface* vs = items[k].surface_state;
    int v = variant_of(d, &items[k]), k0 = d->hardware ? VK_KIND_TESS3 : VK_KIND_PATTERN;
    bool blend = items[k].item->blend == TLOD_BLEND_BLEND, mesh = uses_mesh(d, &items[k]);
    if (mesh) k0 = VK_KIND_MESH;
    for (int kind = k0; kind < k0 + (mesh ? 1 : 2); kind++) {
      for (int line = 0; line <= (int)fr->wireframe; line++) {
        VkPipeline p;
        tlod_result r = _tlod_vkb_pipeline(&d->pipelines, vs->type, v, kind, blend, line, &p);
        if (r != TLOD_SUCCESS) return r;
      }
    }
  }
  return TLOD_SUCCESS;
}

/* proj * view * model with Vulkan's depth range: z' = 0.5 z + 0.5 w (rows
 * x, y and w stay bitwise GL's). */
static void item_uniforms(const vk_device* d, const tlod_draw_desc* fr, const _tlod_draw_ref* it,
                          const float view[3][3], tlod_vk_uniforms* u) {
  const vk_surface* vs = it->surface_state;
  _tlod_item_shading sh;
  _tlod_item_shading_of(fr, it->item, &sh);
  memset(u, 0, sizeof(*u));
  memcpy(u->view_proj, sh.mvp, sizeof(u->view_proj));
  for (int c = 0; c < 4; c++)
    u->view_proj[c * 4 + 2] = 0.5f * sh.mvp[c * 4 + 2] + 0.5f * sh.mvp[c * 4 + 3];
  memcpy(u->model, sh.model, sizeof(u->model));
  for (int c = 0; c < 3; c++)
    memcpy(&u->normal_matrix[c * 4], &sh.normal_matrix[c * 3], sizeof(float[3]));
  memcpy(u->light_dir, view[0], sizeof(u->light_dir));
  memcpy(u->base_color, sh.color, sizeof(u->base_color));
  memcpy(u->eye, view[1], sizeof(u->eye));
  memcpy(u->forward, view[2], sizeof(u->forward));
  u->ortho = fr->proj[15] == 1.0f ? 1u : 0u;
  u->alpha_cutoff = it->item->has_alpha_cutoff ? it->item->alpha_cutoff : 0.5f;
  u->grid = 1u << d->lmax;
  u->max_level = d->lmax;
  u->texcoord = it->item->base_color_texture ? it->item->base_color_texcoord : TLOD_SHADER_MAX_ATTRIBUTES;
  u->attribute_count = vs->attribute_count;
}

/* The strip indices, each triangle rotated by one vertex (a b c -> c a
 * b: the same triangle and winding). Flat varyings come from a triangle's
 * first vertex in Vulkan and from its last in GL; a strip triangle spans
 * two levels (v_level), so without the rotation the levels view and a
 * hook reading f.level would colour strips differently from GL. */
static void write_indices(uint32_t* out, const uint32_t* indices, uint32_t count) {
  for (uint32_t t = 0; t + 2 < count; t += 3) {
    out[t] = indices[t + 2];
    out[t + 1] = indices[t];
    out[t + 2] = indices[t + 1];
  }
}

/* CPU-mesh mode: each mesh item's list evaluated (again only when it
 * changed), before the ring block is sized. */
static tlod_result evaluate_meshes(vk_device* d, const tlod_draw_desc* fr, const _tlod_draw_ref* items) {
  d->stats->mesh_evaluations = 0, d->stats->mesh_eval_ms = 0.0, d->stats->mesh_bytes = 0;
  if (!d->cpu_mesh) return TLOD_SUCCESS;
  if (!_tlod_device_grow(d->ctx, (void**)&d->mesh_at, &d->mesh_at_cap, fr->item_count, sizeof(VkDeviceSize[2])))
    return tlod_context_fail(d->ctx, TLOD_ERROR_OUT_OF_MEMORY, "vulkan device '%s': out of memory", d->label);
  for (uint32_t k = 0; k < fr->item_count; k++) {
    if (!uses_mesh(d, &items[k])) continue;
    double t0 = tlod_now_ms();
    bool evaluated = false;
    vk_surface* vs = items[k].surface_state;
    tlod_result r = _tlod_item_mesh_update(d->ctx, d->patterns, &items[k], &vs->mesh, &evaluated);
    if (r != TLOD_SUCCESS) return r;
    if (evaluated) d->stats->mesh_evaluations++, d->stats->mesh_eval_ms += tlod_now_ms() - t0;
  }
  return TLOD_SUCCESS;
}

/* A mesh's vertex (positions then normals) and index bytes. */
static void mesh_bytes(const tlod_cpu_mesh* c, VkDeviceSize* vb, VkDeviceSize* ib) {
  *vb = c ? 2 * sizeof(float[3]) * (VkDeviceSize)c->vertex_count : 0;
  *ib = c ? sizeof(uint32_t[3]) * (VkDeviceSize)c->triangle_count : 0;
}

/* The ring bytes of the mesh items after `end`, each section aligned. */
static VkDeviceSize meshes_size(const vk_device* d, const tlod_draw_desc* fr, const _tlod_draw_ref* items,
                                VkDeviceSize end) {
  for (uint32_t k = 0; k < fr->item_count; k++) {
    if (!uses_mesh(d, &items[k])) continue;
    VkDeviceSize vb, ib;
    mesh_bytes(((const vk_surface*)items[k].surface_state)->mesh.cpu, &vb, &ib);
    end = _tlod_vkb_align(_tlod_vkb_align(end, d->ring_align) + vb, d->ring_align) + ib;
  }
  return end;
}

/* The mesh items' vertices and indices into the ring from `at` (every
 * draw: the ring is the slot's); where each went into d->mesh_at. */
static void write_meshes(vk_device* d, const tlod_draw_desc* fr, const _tlod_draw_ref* items, const ring_view* rv,
                         VkDeviceSize at) {
  for (uint32_t k = 0; k < fr->item_count; k++) {
    if (!uses_mesh(d, &items[k])) continue;
    const tlod_cpu_mesh* c = ((const vk_surface*)items[k].surface_state)->mesh.cpu;
    VkDeviceSize vb, ib;
    mesh_bytes(c, &vb, &ib);
    d->mesh_at[k][0] = _tlod_vkb_align(at, d->ring_align);
    d->mesh_at[k][1] = _tlod_vkb_align(d->mesh_at[k][0] + vb, d->ring_align);
    at = d->mesh_at[k][1] + ib;
    if (!c) continue;
    memcpy(rv->mapped + d->mesh_at[k][0], c->positions, (size_t)vb / 2);
    memcpy(rv->mapped + d->mesh_at[k][0] + vb / 2, c->normals, (size_t)vb / 2);
    memcpy(rv->mapped + d->mesh_at[k][1], c->indices, (size_t)ib);
    d->stats->mesh_bytes += vb + ib;
  }
}

/* The ring block of this draw: uniforms, instances, strips, references, strip indices, CPU meshes. */
static tlod_result upload(vk_device* d, const tlod_draw_desc* fr, const _tlod_draw_ref* items, ring_view* rv) {
  VkDeviceSize a = d->ring_align, n = fr->item_count;
  VkDeviceSize ib = sizeof(tlod_gl_instance) * (VkDeviceSize)d->st.instance_count;
  VkDeviceSize sb = sizeof(tlod_gl_strip) * (VkDeviceSize)d->st.strip_count;
  VkDeviceSize rb = sizeof(uint32_t[2]) * (VkDeviceSize)d->st.ref_count;
  rv->instance_bytes = ib ? ib : 16, rv->strip_bytes = sb ? sb : 16;
  VkDeviceSize i0 = _tlod_vkb_align(n * d->uniform_stride, a), s0 = _tlod_vkb_align(i0 + rv->instance_bytes, a);
  VkDeviceSize xb = sizeof(uint32_t) * (VkDeviceSize)d->st.index_count;
  VkDeviceSize r0 = _tlod_vkb_align(s0 + rv->strip_bytes, a), x0 = _tlod_vkb_align(r0 + (rb ? rb : 16), a);
  VkDeviceSize meshes_from = x0 + (xb ? xb : 16), total = meshes_size(d, fr, items, meshes_from), base = 0;
  VkResult r = _tlod_vkb_ring_take(&d->frames, total, a, &base, d->stats);
  if (r != VK_SUCCESS)
    return tlod_context_fail(d->ctx, r == VK_ERROR_OUT_OF_HOST_MEMORY ? TLOD_ERROR_OUT_OF_MEMORY : TLOD_ERROR_BACKEND,
                             "tlod_device_draw: device '%s': upload ring of %llu bytes: %s", d->label,
                             (unsigned long long)total, _tlod_vkb_result_name(r));
  const vk_slot* s = &d->frames.slots[d->frames.current];
  rv->buffer = s->ring.buffer;
  rv->mapped = s->ring.mem.mapped;
  rv->uniforms = base, rv->instances = base + i0, rv->strips = base + s0, rv->refs = base + r0, rv->indices = base + x0;
  float view[3][3];
  _tlod_view_vectors(fr, view[0], view[1], view[2]);
  for (uint32_t k = 0; k < fr->item_count; k++)
    item_uniforms(d, fr, &items[k], (const float(*)[3])view,
                  (tlod_vk_uniforms*)(rv->mapped + base + k * d->uniform_stride));
  memcpy(rv->mapped + rv->instances, d->st.instances, (size_t)ib);
  memcpy(rv->mapped + rv->strips, d->st.strips, (size_t)sb);
  memcpy(rv->mapped + rv->refs, d->st.refs, (size_t)rb);
  write_indices((uint32_t*)(rv->mapped + rv->indices), d->st.indices, d->st.index_count);
  write_meshes(d, fr, items, rv, base + meshes_from);
  d->stats->vk.upload_bytes = n * sizeof(tlod_vk_uniforms) + ib + sb + rb + xb;
  return TLOD_SUCCESS;
}

/* What item `it`'s set holds (vk_set_key). */
static vk_set_key set_key(const vk_device* d, const _tlod_draw_ref* it, const ring_view* rv) {
  uint32_t slot = d->frames.current;
  const vk_surface* vs = it->surface_state;
  vk_set_key k;
  memset(&k, 0, sizeof(k));
  k.surface = vs, k.texture = it->texture_state ? it->texture_state : d->white;
  k.ring = rv->buffer, k.patches = vs->patches[slot].buffer, k.attrs = vs->attrs[slot].buffer;
  k.instance_bytes = rv->instance_bytes, k.strip_bytes = rv->strip_bytes;
  k.record_bytes = vs->record_bytes, k.attribute_bytes = vs->attribute_bytes;
  k.retired = d->frames.retired_serial;
  return k;
}

static void write_set(vk_device* d, VkDescriptorSet set, const _tlod_draw_ref* it, const ring_view* rv) {
  uint32_t slot = d->frames.current;
  const vk_surface* vs = it->surface_state;
  const vk_texture* t = it->texture_state ? it->texture_state : d->white;
  VkDescriptorBufferInfo b[6] = {{vs->patches[slot].buffer, 0, vs->record_bytes},
                                 {d->pattern_vertices.buffer, 0, VK_WHOLE_SIZE},
                                 {rv->buffer, 0, rv->instance_bytes},
                                 {rv->buffer, 0, rv->strip_bytes},
                                 {vs->attrs[slot].buffer, 0, vs->attribute_bytes},
                                 {rv->buffer, 0, sizeof(tlod_vk_uniforms)}};
  VkDescriptorImageInfo img = {t->sampler, t->view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  static const VkDescriptorType types[7] = {
      VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,         VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
      VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC,
      VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,         VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC,
      VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER};
  VkWriteDescriptorSet w[7];
  for (uint32_t i = 0; i < 7; i++)
    w[i] = (VkWriteDescriptorSet){.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
                                  .dstSet = set,
                                  .dstBinding = i,
                                  .descriptorCount = 1,
                                  .descriptorType = types[i],
                                  .pBufferInfo = i < 6 ? &b[i] : NULL,
                                  .pImageInfo = i == 6 ? &img : NULL};
  vkUpdateDescriptorSets(d->device, 7, w, 0, NULL);
}

/* The surfaces' copies of this slot, then one set per item from the
 * slot's cache, written only when what it holds changed (a static scene
 * writes none: the ring, sizes and surfaces stay). */
static tlod_result descriptors(vk_device* d, const tlod_draw_desc* fr, const _tlod_draw_ref* items,
                               const ring_view* rv) {
  uint32_t n = fr->item_count;
  VkResult r = VK_SUCCESS;
  for (uint32_t k = 0; k < n && r == VK_SUCCESS; k++)
    r = _tlod_vkb_surface_sync(d, items[k].surface_state, d->frames.current);
  vk_set_key* keys = NULL;
  if (r == VK_SUCCESS) r = _tlod_vkb_sets(&d->frames, n, &d->sets, &keys);
  if (r != VK_SUCCESS)
    return tlod_context_fail(d->ctx, r == VK_ERROR_OUT_OF_HOST_MEMORY ? TLOD_ERROR_OUT_OF_MEMORY : TLOD_ERROR_BACKEND,
                             "tlod_device_draw: device '%s': surface copies / descriptor sets: %s", d->label,
                             _tlod_vkb_result_name(r));
  d->stats->vk.descriptor_writes = 0;
  for (uint32_t k = 0; k < n; k++) {
    vk_set_key key = set_key(d, &items[k], rv);
    if (!memcmp(&key, &keys[k], sizeof(key))) continue;
    write_set(d, d->sets[k], &items[k], rv);
    keys[k] = key;
    d->stats->vk.descriptor_writes++;
  }
  d->stats->vk.descriptor_sets = n;
  return TLOD_SUCCESS;
}

/* ---- recording ------------------------------------------------------------------ */

typedef struct item_rec {
  VkCommandBuffer cmd;
  const vk_surface* vs;
  int variant;
  bool blend;
  const tlod_draw_list* dl;
  const _tlod_stage_range* range;
  const ring_view* rv;
  uint32_t k;
  bool mesh; /* uses_mesh */
} item_rec;

static void push(vk_device* d, VkCommandBuffer cmd, uint32_t first, uint32_t shape_base, uint32_t corners,
                 uint32_t debug) {
  tlod_vk_push p = {first, shape_base, corners, debug};
  vkCmdPushConstants(cmd, d->pipelines.layout, VK_SHADER_STAGE_ALL_GRAPHICS, 0, sizeof(p), &p);
}

static void bind(vk_device* d, const item_rec* ir, int kind, bool line) {
  VkPipeline p = d->pipelines.pipelines[ir->vs->type][ir->variant][kind][ir->blend][line];
  vkCmdBindPipeline(ir->cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p);
}

/* One instanced draw per refinement pattern, then the item's strips in one draw. */
static uint32_t issue_draws(vk_device* d, const item_rec* ir, bool line, uint32_t debug, uint64_t* vertices) {
  uint32_t calls = 0;
  bind(d, ir, VK_KIND_PATTERN, line);
  vkCmdBindIndexBuffer(ir->cmd, d->pattern_indices.buffer, 0, VK_INDEX_TYPE_UINT32);
  for (uint32_t k = 0; k < ir->dl->bucket_count; k++) {
    const tlod_draw_bucket* bk = &ir->dl->buckets[k];
    uint32_t sh = (uint32_t)bk->shape;
    push(d, ir->cmd, ir->range->instance_first + bk->first, d->shape_base[sh], 0, debug);
    vkCmdDrawIndexed(ir->cmd, d->index_count[sh][bk->level], bk->count, d->index_first[sh][bk->level], 0, 0);
    *vertices += (uint64_t)tlod_pattern_vertex_count(bk->shape, bk->level) * bk->count;
    calls++;
  }
  if (ir->range->index_count) {
    /* Indexed: each strip point is shaded once, not once per triangle. */
    bind(d, ir, VK_KIND_STRIP, line);
    push(d, ir->cmd, 0, 0, 0, debug);
    vkCmdBindVertexBuffers(ir->cmd, 0, 1, &ir->rv->buffer, &ir->rv->refs); /* a mesh item may have bound its own */
    vkCmdBindIndexBuffer(ir->cmd, ir->rv->buffer, ir->rv->indices, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexed(ir->cmd, ir->range->index_count, 1, ir->range->index_first, 0, 0);
    *vertices += ir->range->ref_count;
    calls++;
  }
  return calls;
}

/* Hardware path: per bucket, batches of whole patches under 65,536
 * tessellated vertices (_tlod_tess_batch), as gl_device.c. */
static uint32_t issue_tess_draws(vk_device* d, const item_rec* ir, bool line, uint32_t debug, uint64_t* vertices) {
  uint32_t calls = 0;
  for (uint32_t k = 0; k < ir->dl->bucket_count; k++) {
    const tlod_draw_bucket* bk = &ir->dl->buckets[k];
    uint32_t sh = (uint32_t)bk->shape, corners = sh ? 4u : 3u;
    bind(d, ir, sh ? VK_KIND_TESS4 : VK_KIND_TESS3, line);
    uint32_t end = ir->range->instance_first + bk->first + bk->count;
    for (uint32_t start = ir->range->instance_first + bk->first, next; start < end; start = next) {
      next = _tlod_tess_batch(d->st.instances, start, end, corners, vertices);
      push(d, ir->cmd, start, 0, corners, debug);
      vkCmdDraw(ir->cmd, (next - start) * corners, 1, 0, 0);
      calls++;
    }
  }
  return calls;
}

/* CPU-mesh mode: the item's mesh from the ring (write_meshes), one indexed draw. */
static uint32_t issue_mesh(vk_device* d, const item_rec* ir, bool line, uint32_t debug, uint64_t* vertices) {
  const tlod_cpu_mesh* c = ir->vs->mesh.cpu;
  if (!c || !c->triangle_count) return 0;
  bind(d, ir, VK_KIND_MESH, line);
  push(d, ir->cmd, 0, 0, 0, debug);
  const VkDeviceSize* at = d->mesh_at[ir->k];
  VkBuffer bufs[2] = {ir->rv->buffer, ir->rv->buffer};
  VkDeviceSize offs[2] = {at[0], at[0] + sizeof(float[3]) * (VkDeviceSize)c->vertex_count};
  vkCmdBindVertexBuffers(ir->cmd, 0, 2, bufs, offs);
  vkCmdBindIndexBuffer(ir->cmd, ir->rv->buffer, at[1], VK_INDEX_TYPE_UINT32);
  vkCmdDrawIndexed(ir->cmd, 3 * c->triangle_count, 1, 0, 0, 0);
  *vertices += c->vertex_count;
  return 1;
}

static uint32_t issue(vk_device* d, const item_rec* ir, bool line, uint32_t debug, uint64_t* vertices) {
  if (ir->mesh) return issue_mesh(d, ir, line, debug, vertices);
  return d->hardware ? issue_tess_draws(d, ir, line, debug, vertices) : issue_draws(d, ir, line, debug, vertices);
}

/* Item k: its state (culling, depth writes, its set), patterns and strips,
 * then (wireframe) its edges over them with the fill pushed back by a
 * depth bias (GL: polygon offset 1, 1). */
static void draw_item(vk_device* d, const tlod_draw_desc* fr, const _tlod_draw_ref* it, uint32_t k, const ring_view* rv,
                      tlod_draw_item_stats* st) {
  double t0 = tlod_now_ms();
  VkCommandBuffer cmd = fr->vk.command_buffer;
  item_rec ir = {.cmd = cmd,
                 .vs = it->surface_state,
                 .variant = variant_of(d, it),
                 .blend = it->item->blend == TLOD_BLEND_BLEND,
                 .dl = it->item->draw_list,
                 .range = &d->st.ranges[k],
                 .rv = rv,
                 .k = k,
                 .mesh = uses_mesh(d, it)};
  vkCmdSetCullMode(cmd, it->item->cull_back_faces ? VK_CULL_MODE_BACK_BIT : VK_CULL_MODE_NONE);
  vkCmdSetDepthWriteEnable(cmd, ir.blend ? VK_FALSE : VK_TRUE);
  vkCmdSetDepthBiasEnable(cmd, fr->wireframe ? VK_TRUE : VK_FALSE);
  uint32_t dyn[3] = {(uint32_t)rv->instances, (uint32_t)rv->strips, (uint32_t)(rv->uniforms + k * d->uniform_stride)};
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, d->pipelines.layout, 0, 1, &d->sets[k], 3, dyn);
  uint64_t vertices = 0, unused = 0;
  uint32_t calls = issue(d, &ir, false, (uint32_t)fr->debug, &vertices);
  if (fr->wireframe) {
    vkCmdSetDepthBiasEnable(cmd, VK_FALSE);
    calls += issue(d, &ir, true, 4u, &unused);
  }
  const tlod_cpu_mesh* c = ir.vs->mesh.cpu;
  st->triangles = ir.mesh       ? (c ? (uint64_t)c->triangle_count + c->folds_skipped : 0u)
                  : d->hardware ? ir.dl->pattern_triangles
                                : ir.dl->pattern_triangles + ir.range->index_count / 3;
  st->vertices = vertices;
  st->draw_calls = calls;
  st->cpu_ms += tlod_now_ms() - t0;
}

/* Viewport flipped (negative height: GL's y up, so the image and the
 * winding are GL's); origin at the framebuffer's top-left (Vulkan's). */
static void begin_state(const tlod_draw_desc* fr) {
  VkCommandBuffer cmd = fr->vk.command_buffer;
  const uint32_t* v = fr->viewport;
  VkViewport vp = {(float)v[0], (float)v[1] + (float)v[3], (float)v[2], -(float)v[3], 0.0f, 1.0f};
  VkRect2D sc = {{(int32_t)v[0], (int32_t)v[1]}, {v[2], v[3]}};
  vkCmdSetViewport(cmd, 0, 1, &vp);
  vkCmdSetScissor(cmd, 0, 1, &sc);
  vkCmdSetDepthBias(cmd, 1.0f, 0.0f, 1.0f);
}

/* The first draw of a frame is measured: timestamps around it and the
 * clipping invocations (read a slot-reuse later, vk_frame.c). */
static bool begin_queries(vk_device* d, VkCommandBuffer cmd) {
  vk_slot* s = &d->frames.slots[d->frames.current];
  if (!d->frames.queries || s->queried) return false;
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, s->timestamps, 0);
  if (s->statistics) vkCmdBeginQuery(cmd, s->statistics, 0, 0);
  s->queried = true;
  s->query_draw = d->stats->draws + 1; /* the dispatch counts this draw on success */
  return true;
}

static void end_queries(vk_device* d, VkCommandBuffer cmd) {
  vk_slot* s = &d->frames.slots[d->frames.current];
  if (s->statistics) vkCmdEndQuery(cmd, s->statistics, 0);
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, s->timestamps, 1);
}

static const float* vk_surface_center(const void* surface_state) { return ((const vk_surface*)surface_state)->center; }

tlod_result _tlod_vkb_draw(void* state, const tlod_draw_desc* fr, const _tlod_draw_ref* items,
                           tlod_draw_item_stats* item_stats) {
  vk_device* d = state;
  tlod_result r = check_vk(d, fr);
  if (r != TLOD_SUCCESS) return r;
  _tlod_vkb_frames_begin(&d->frames, fr->vk.frame_index);
  r = prepare(d, fr, items);
  _tlod_vkb_shader_stats(d);
  bool restaged; /* the ring is the slot's: it is written every draw, from the staged arrays */
  if (r == TLOD_SUCCESS)
    r = _tlod_stage_items(d->ctx, &d->st, d->patterns, "vulkan device", fr, items, item_stats, &restaged);
  if (r == TLOD_SUCCESS) r = _tlod_stage_order(d->ctx, &d->st, "vulkan device", fr, items, vk_surface_center);
  ring_view rv;
  if (r == TLOD_SUCCESS) r = evaluate_meshes(d, fr, items);
  if (r == TLOD_SUCCESS) r = upload(d, fr, items, &rv);
  if (r == TLOD_SUCCESS) r = descriptors(d, fr, items, &rv);
  if (r != TLOD_SUCCESS) return r;
  VkCommandBuffer cmd = fr->vk.command_buffer;
  begin_state(fr);
  bool timed = begin_queries(d, cmd);
  for (uint32_t j = 0; j < fr->item_count; j++) {
    uint32_t k = d->st.order[j];
    draw_item(d, fr, &items[k], k, &rv, &item_stats[k]);
  }
  if (timed) end_queries(d, cmd);
  return TLOD_SUCCESS;
}
