// Trim classification for the surface passes. With KW_TRIM the fragment's (u, v) is classified
// and the fragment discarded where trimmed; without it KW_DISCARD_TRIMMED is empty, so
// untrimmed surfaces pay nothing. KW_TRIM_EXACT (RenderOptions::TrimMode::Exact, the default):
// exactly, by the surface's hybrid trim grid (trim_exact.glsl, issue 11); else by the paper's
// FBO mask (3.4.2): a lookup in the surface's layer of the mask array.
// Uniforms match kw::TrimMaskPass::setUniforms; the exact pass's shaders (surface_data.glsl
// included first) read the per-surface values from the surface's table row instead.
#ifdef KW_TRIM
#ifndef KW_SURFACE_DATA
uniform vec4 uTrimRect;           // (u first, u last, v first, v last) the mask or grid spans;
                                  // outside it no point is inside a loop
uniform vec2 uTrimSize;           // mask or grid width and height in texels
#ifdef KW_TRIM_EXACT
uniform uint uTrimBlock;          // the grid's first word
#else
uniform float uTrimLayer;
#endif
#endif

#ifdef KW_TRIM_EXACT
#include "trim_exact.glsl"
#else
uniform sampler2DArray uTrimMask; // R8, 1 = kept; the surface's mask in texels [0, size) of its layer
uniform vec2 uTrimLayerScale;     // 1 / (array width, array height)
#endif

bool trimmedAway(vec2 uv) {
    vec2 unit = (uv - uTrimRect.xz) / (uTrimRect.yw - uTrimRect.xz);
    if (any(lessThan(unit, vec2(0.0))) || any(greaterThan(unit, vec2(1.0))))
        return true;
#ifdef KW_TRIM_EXACT
    return kwTrimmedAwayExact(uv, unit);
#else
    // Bilinear between texel centres, kept inside the mask's own rectangle of the layer.
    vec2 texel = clamp(unit * uTrimSize, vec2(0.5), uTrimSize - vec2(0.5));
    return texture(uTrimMask, vec3(texel * uTrimLayerScale, uTrimLayer)).r < 0.5;
#endif
}
#define KW_DISCARD_TRIMMED(uv)                                                                     \
    if (trimmedAway(uv))                                                                           \
    discard
#else
#define KW_DISCARD_TRIMMED(uv)
#endif
