/*
 * tesslod/vulkan.h -- the "vulkan" device (module tesslod::vulkan): what it
 * makes on an engine's Vulkan device and what it records into the engine's
 * command buffers. The API is tesslod/backend.h (tlod_device_create with
 * .backend = "vulkan" and the desc's .vk, tlod_device_draw with the draw
 * desc's .vk); this header holds the Vulkan facts. Design notes (memory,
 * rings, synchronisation): docs/vulkan.md.
 *
 * WHAT IT DOES
 *   Draws everything the "gl" device draws, the same way (the same GLSL,
 *   backends/shaders, compiled at run time by glslang with an optional
 *   SPIR-V disk cache; the same staging, draw order, variants, hardware
 *   batches, wireframe and debug views): each patch an instance of its
 *   level's refinement pattern, connection strips, geomorphs, attributes,
 *   textures, materials and blend modes, strips drawn indexed, and the
 *   CPU-mesh mode (desc.vk.gpu_eval, as tesslod/gl.h; AUTO is OFF on a
 *   VK_PHYSICAL_DEVICE_TYPE_CPU device or one named llvmpipe / lavapipe:
 *   the mesh is evaluated again only when its list changed and copied into
 *   the frame's ring every draw). It records into the command buffer
 *   the draw names, inside the engine's rendering (a render pass instance of
 *   desc.vk.render_pass / subpass, or dynamic rendering with the device's
 *   colour and depth formats). The image is GL's: the device multiplies
 *   proj by the clip correction z' = 0.5 z + 0.5 w on the CPU (rows x, y, w
 *   stay bitwise GL's) and flips y with a negative-height viewport, so the
 *   winding (front face counter-clockwise) and the picture equal GL's.
 *
 * DOES NOT
 *   - submit, present, wait for fences or the queue, or call
 *     vkDeviceWaitIdle in a draw: tlod_device_draw() only records;
 *   - begin or end rendering, clear, or transition the engine's images;
 *   - read the image back (tlod_device_read_image: TLOD_ERROR_UNSUPPORTED;
 *     platform/ reads its own images);
 *   - destroy any handle of the desc (instance, devices, queue, render pass);
 *   - restore command buffer state: after a draw the bound pipeline,
 *     descriptor set 0, push constants, vertex and index buffers, viewport,
 *     scissor, cull mode, depth write enable, depth bias enable and depth
 *     bias are tesslod's (below); the engine rebinds what it draws next.
 *
 * STEP BY STEP
 *   1. create the VkDevice with Vulkan 1.3 and the features below enabled;
 *   2. tlod_device_create(ctx, &(tlod_device_desc){ .backend = "vulkan",
 *      .patterns = p, .vk = { .instance, .physical_device, .device, .queue,
 *      .queue_family, .color_format, .depth_format, .host_query_reset = true,
 *      .shader_cache_dir = "..." } }, &dev): checks the features and
 *      formats, uploads the pattern buffers (one submit on desc.vk.queue and
 *      a fence wait), compiles the PLAIN shader stages of every surface type
 *      in desc.vk.surface_types (0 == flat, phong, pn, quadratic: 2 vertex
 *      stages each, 6 more with hardware_tessellation, + 1 fragment);
 *   3. per object tlod_device_create_surface(); per image
 *      tlod_device_create_texture() (one upload submit + fence wait each);
 *   4. per frame: wait for the frame slot's fence (the engine's), begin the
 *      command buffer and the rendering, then tlod_device_draw() with
 *      .vk = { .command_buffer, .frame_index } (one or more draws per
 *      frame, all with the frame's index), end the rendering, submit;
 *   5. tlod_device_destroy(): waits for the device to be idle
 *      (vkDeviceWaitIdle: frames the engine submitted may still read what
 *      it destroys; the engine must not use the device's queues meanwhile),
 *      then destroys every object it made.
 *
 * FRAME-INDEX CONTRACT
 *   desc.vk.frame_index < frames_in_flight (0 == 2) names the upload ring a
 *   draw writes. The engine guarantees that the GPU has finished the last
 *   submitted frame that drew with this index when it draws with it again
 *   (it waited for that frame's fence, as every frames-in-flight loop does).
 *   A frame slot begins a new frame at the first draw naming its index after
 *   a draw naming another index; draws of one frame share the index and
 *   append to the ring. So with frames_in_flight 1 each draw is its own
 *   frame (one draw per frame). Within the contract no buffer the GPU may
 *   still read is written and no object it may still use is destroyed:
 *   tlod_device_destroy_surface / _texture and a ring that grew are retired
 *   and destroyed once every frame slot has begun a frame after that.
 *   tlod_device_update_surface between two draws of one frame: both draws
 *   read the updated surface (the slot's copy is refreshed once per frame).
 *   Undefined: a draw breaking the contract (the ring of a frame in flight
 *   would be overwritten).
 *
 * REQUIRED
 *   Vulkan 1.3 (vkCmdSetCullMode, vkCmdSetDepthWriteEnable,
 *   vkCmdSetDepthBiasEnable; dynamicRendering enabled when render_pass is
 *   0); refused at creation naming what is missing:
 *     - apiVersion of the physical device below 1.3 (UNSUPPORTED);
 *     - hardware_tessellation without the tessellationShader feature;
 *     - color_format without COLOR_ATTACHMENT_BLEND in optimal tiling,
 *       depth_format without DEPTH_STENCIL_ATTACHMENT (the desc field and
 *       the VkFormat number named);
 *     - samples not a power of two up to 64 (INVALID_ARGUMENT) or not in
 *       the device's colour and depth sample counts (UNSUPPORTED);
 *     - a shader that does not compile (TLOD_ERROR_BACKEND; the message
 *       names the shader file and line, "fragment_hook:LINE" for a hook).
 *   At draw time: wireframe without the fillModeNonSolid feature fails the
 *   draw (UNSUPPORTED, naming the feature). The features are read from the
 *   physical device: the engine enables on its VkDevice those it supports
 *   among tessellationShader (with hardware_tessellation), fillModeNonSolid
 *   (wireframe) and pipelineStatisticsQuery (vk.primitives), and
 *   hostQueryReset when it sets host_query_reset.
 *   With host_query_reset: a timestamp query pool (2) and, with
 *   pipelineStatisticsQuery, a clipping-invocations pool (1) per frame slot;
 *   the first draw of a frame is measured. Results are read (without
 *   VK_QUERY_RESULT_WAIT_BIT) by tlod_device_query_stats(), never by a
 *   draw: the latest measured draw whose frame has run gives stats.gpu_ms,
 *   gpu_draw and vk.primitives; a reading nobody asked for before its slot
 *   begins its next frame is dropped (the queries are reset then). Note:
 *   lavapipe waits for the device to be idle inside vkGetQueryPoolResults,
 *   so there tlod_device_query_stats() waits for the frames in flight.
 *   Without host_query_reset gpu_ms stays < 0.
 *
 * VULKAN OBJECTS
 *   Every object is created with VkAllocationCallbacks that route Vulkan's
 *   host allocations through the tlod_context's allocator (aligned).
 *   Per device: a transient command pool + one command buffer + one fence
 *     (uploads at create / create_texture only); the descriptor set layout
 *     (below), a pipeline layout (set 0 + 16 bytes of push constants, all
 *     graphics stages), an in-memory VkPipelineCache; shader modules per
 *     surface type and variant (PLAIN at creation; FULL, MASK at the first
 *     item needing them, as the gl device: tesslod/gl.h) and one fragment
 *     module per variant; graphics pipelines per (surface type, variant,
 *     kind: pattern / strip / tessellated triangles / quads, blend on/off,
 *     fill/line), made at the first draw needing them (stats.vk.pipelines);
 *     the pattern vertex (storage) and index buffers, device-local, uploaded
 *     once through a staging buffer; a 1x1 white texture (the binding of
 *     untextured items).
 *   Per frame slot: one host-visible, persistently mapped ring buffer
 *     (storage + uniform + vertex use; 256 KiB, doubled when a draw needs
 *     more), descriptor pools of 256 sets (reset at the slot's new frame,
 *     one more when a frame needs more), the query pools above.
 *   Per device surface: its patch records and attributes on the CPU, and a
 *     host-visible storage buffer of each per frame slot.
 *   Per texture: a VkImage R8G8B8A8_UNORM (SRGB with desc.srgb), optimal
 *     tiling, the full mip chain made with vkCmdBlitImage (linear) unless
 *     mipmaps_off, left in SHADER_READ_ONLY_OPTIMAL; an image view; a
 *     sampler with the desc's wrap modes and filters (minification with
 *     mipmaps: LINEAR -> linear mipmaps, NEAREST -> nearest mipmap).
 *   Device memory: a few 16 MiB VkDeviceMemory blocks per memory type,
 *     suballocated (requests past 4 MiB get their own allocation):
 *     stats.vk.memory_blocks / memory_bytes.
 *
 * COMMANDS RECORDED BY tlod_device_draw()
 *   vkCmdSetViewport (x, y + height, width, -height; the draw's viewport
 *   with its origin at the framebuffer's TOP-left, Vulkan's), vkCmdSetScissor
 *   (the viewport's rectangle), vkCmdSetDepthBias (1, 0, 1),
 *   vkCmdBindIndexBuffer (the pattern indices), vkCmdBindVertexBuffers
 *   (binding 0: the strip references in the ring); with queries
 *   vkCmdWriteTimestamp + vkCmdBeginQuery around the items; then per item in
 *   draw order (non-BLEND in item order, BLEND farthest first):
 *   vkCmdSetCullMode (BACK with cull_back_faces, else NONE),
 *   vkCmdSetDepthWriteEnable (off for BLEND), vkCmdSetDepthBiasEnable (on
 *   with wireframe: GL's polygon offset 1, 1 on the fill),
 *   vkCmdBindDescriptorSets (set 0, three dynamic offsets), and per draw
 *   call vkCmdBindPipeline, vkCmdPushConstants (tlod_vk_push:
 *   first_instance, shape_base, corners, debug), vkCmdDrawIndexed (one per
 *   pattern bucket, instanced) and vkCmdDraw (strips; tessellation
 *   batches under 65,536 tessellated vertices). Wireframe draws every item
 *   again with the line pipelines. Pipelines: depth test LESS, front face
 *   counter-clockwise, straight alpha blending (SRC_ALPHA,
 *   ONE_MINUS_SRC_ALPHA; ONE, ONE_MINUS_SRC_ALPHA; ADD) for BLEND items,
 *   rasterization samples of desc.vk.samples.
 *
 * THREADING AND ALLOCATION
 *   As tesslod/backend.h: the device belongs to its context's thread; the
 *   command buffer of a draw is recorded on the calling thread. The engine
 *   must not use desc.vk.queue concurrently with tlod_device_create and
 *   tlod_device_create_texture (each submits once and waits for its fence).
 *   A steady frame allocates nothing on the host (staging and sets grown,
 *   never shrunk) and no device memory (rings grown, never shrunk).
 *
 * BINDINGS (descriptor set 0; the values of backends/shaders/layout.h)
 */
#ifndef TESSLOD_VULKAN_H
#define TESSLOD_VULKAN_H

#include "tesslod/core.h" /* tlod_patch_record: the layout at TLOD_VK_BINDING_PATCHES */

#define TLOD_VK_BINDING_PATCHES 0    /* STORAGE_BUFFER: tlod_patch_record per patch */
#define TLOD_VK_BINDING_PATTERNS 1   /* STORAGE_BUFFER: pattern vertices of both shapes */
#define TLOD_VK_BINDING_INSTANCES 2  /* STORAGE_BUFFER_DYNAMIC (frame ring): per visible patch */
#define TLOD_VK_BINDING_STRIPS 3     /* STORAGE_BUFFER_DYNAMIC (frame ring): per connection strip */
#define TLOD_VK_BINDING_ATTRIBUTES 4 /* STORAGE_BUFFER: vec4 mesh attributes per patch corner */
#define TLOD_VK_BINDING_UNIFORMS 5   /* UNIFORM_BUFFER_DYNAMIC (frame ring): 256 bytes per item (std140) */
#define TLOD_VK_BINDING_BASE_COLOR 6 /* COMBINED_IMAGE_SAMPLER: the item's base colour texture */

/* Largest desc.vk.frames_in_flight. */
#define TLOD_VK_MAX_FRAMES_IN_FLIGHT 8

#endif
