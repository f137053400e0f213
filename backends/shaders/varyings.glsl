// The attribute varyings of the device's last vertex stages (pattern.vert,
// strip.vert, tess.tese), after attributes.glsl.
// Varyings: every attribute only for a fragment hook
// (TLOD_ATTRIBUTE_VARYINGS 8; the built-in material reads none), and the
// base colour texture's coordinates (u_texcoord; >= 8: none), both only in
// the programs of items that read them (TLOD_TEXCOORD 1, the FULL and MASK
// variants). Each varying costs interpolation per fragment (llvmpipe:
// measurably), and the PLAIN variant reads no attribute at all.
#if TLOD_TEXCOORD
layout(location = TLOD_LOCATION_TEXCOORD) out vec2 v_texcoord;
#endif
#if TLOD_ATTRIBUTE_VARYINGS > 0
layout(location = TLOD_LOCATION_ATTRIBUTES) out vec4 v_attr[TLOD_SHADER_MAX_ATTRIBUTES];
#endif
void write_varyings(uint patch_id, Patch P, uint kind, uint num, vec2 uv) {
#if TLOD_TEXCOORD
  v_texcoord = point_attribute(patch_id, P, kind, num, uv, u_texcoord).xy;
#endif
#if TLOD_ATTRIBUTE_VARYINGS > 0
  point_attributes(patch_id, P, kind, num, uv, v_attr);
#endif
}
