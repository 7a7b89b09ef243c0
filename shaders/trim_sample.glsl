// Trim mask lookup (paper 3.4.2) for the surface passes. With KW_TRIM the fragment's (u, v) is
// looked up in the surface's layer of the mask array and the fragment is discarded where the
// mask says trimmed; without it KW_DISCARD_TRIMMED is empty, so untrimmed surfaces pay nothing.
// Uniforms match kw::TrimMaskPass::setUniforms; the exact pass's shaders (surface_data.glsl
// included first) read the per-surface values from the surface's table row instead.
#ifdef KW_TRIM
uniform sampler2DArray uTrimMask; // R8, 1 = kept; the surface's mask in texels [0, size) of its layer
uniform vec2 uTrimLayerScale;     // 1 / (array width, array height)
#ifndef KW_SURFACE_DATA
uniform vec4 uTrimRect;           // (u first, u last, v first, v last) the mask spans; outside
                                  // it no point is inside a loop
uniform vec2 uTrimSize;           // mask width and height in texels
uniform float uTrimLayer;
#endif

bool trimmedAway(vec2 uv) {
    vec2 unit = (uv - uTrimRect.xz) / (uTrimRect.yw - uTrimRect.xz);
    if (any(lessThan(unit, vec2(0.0))) || any(greaterThan(unit, vec2(1.0))))
        return true;
    // Bilinear between texel centres, kept inside the mask's own rectangle of the layer.
    vec2 texel = clamp(unit * uTrimSize, vec2(0.5), uTrimSize - vec2(0.5));
    return texture(uTrimMask, vec3(texel * uTrimLayerScale, uTrimLayer)).r < 0.5;
}
#define KW_DISCARD_TRIMMED(uv)                                                                     \
    if (trimmedAway(uv))                                                                           \
    discard
#else
#define KW_DISCARD_TRIMMED(uv)
#endif
