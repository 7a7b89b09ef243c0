// Trim classification for the surface passes. With KW_TRIM the fragment's (u, v) is classified
// and the fragment discarded where trimmed; without it KW_DISCARD_TRIMMED is empty, so
// untrimmed surfaces pay nothing. KW_TRIM_EXACT (RenderOptions::TrimMode::Exact, the default):
// exactly, by the surface's hybrid trim grid (trim_exact.glsl); else by the paper's
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

#ifdef KW_TRIM_AA
// What trimCoverage answers for a pixel kept wholly with no trim curve in reach: more than 1,
// so that the edge pass drops it at once (its opaque fragment is already drawn) while a
// coverage of exactly 1 next to a curve, which the pre-pass computed in another program, is
// still drawn there if the pre-pass found it a hair below 1 (no pixel can fall between).
#define KW_WHOLLY 2.0

// The box filter's coverage of a pixel (side 1, centred on the fragment) by the inside of a
// straight edge with unit screen normal n, the pixel's centre at signed distance sd from it
// (> 0: inside): P(n . x < sd) for x uniform over the pixel, whose n . x is the sum of two
// uniform variables of widths |n.x| and |n.y|, so the answer is their trapezoid's integral.
float kwEdgeCoverage(float sd, vec2 n) {
    float a = max(abs(n.x), abs(n.y)), b = min(abs(n.x), abs(n.y));
    float w = sd + 0.5 * (a + b); // from the trapezoid's left end
    if (w <= 0.0)
        return 0.0;
    if (w >= a + b)
        return 1.0;
    if (b < 1e-4)
        return clamp(w / a, 0.0, 1.0);
    if (w < b)
        return w * w / (2.0 * a * b);
    if (w <= a)
        return (w - 0.5 * b) / a;
    float r = a + b - w;
    return 1.0 - r * r / (2.0 * a * b);
}
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
#ifdef KW_TRIM_AA
// The box filter's coverage of the pixel by the surface's domain as its base polygon spans it,
// from the nearest side of the (u, v) rectangle. MSAA already leaves out the samples past the
// polygon's edge, so a trim curve on (or next to) the domain's boundary, as CAD faces' outer
// loops often are, must not cut them again: trimCoverage divides by this.
float kwDomainCoverage(vec2 uv, mat2 jacobian) {
    vec4 d = uDomain;
    vec2 gu = vec2(jacobian[0].x, jacobian[1].x), gv = vec2(jacobian[0].y, jacobian[1].y);
    float lu = length(gu), lv = length(gv);
    float best = 1e30;
    vec2 normal = vec2(1.0, 0.0);
    if (lu > 0.0) {
        float a = (uv.x - d.x) / lu, b = (d.y - uv.x) / lu;
        if (a < best)
            best = a, normal = gu / lu;
        if (b < best)
            best = b, normal = gu / lu;
    }
    if (lv > 0.0) {
        float a = (uv.y - d.z) / lv, b = (d.w - uv.y) / lv;
        if (a < best)
            best = a, normal = gv / lv;
        if (b < best)
            best = b, normal = gv / lv;
    }
    return best > 1.0 ? 1.0 : kwEdgeCoverage(best, normal);
}

// The fraction of the fragment's pixel kept by the trims, or KW_WHOLLY, for
// the anti-aliased passes (kw::ExactSurfacePass): opaque passes keep only fragments covered
// wholly, the edge pass sums the rest by this coverage. Call it from main() before any
// discard: it takes screen derivatives.
float trimCoverageOfPixel(vec2 uv, mat2 jacobian);
float trimCoverage(vec2 uv) {
    mat2 jacobian = mat2(dFdx(uv), dFdy(uv));
    float coverage = trimCoverageOfPixel(uv, jacobian);
    if (!(coverage > 0.0 && coverage <= 1.0))
        return coverage;
    float domain = kwDomainCoverage(uv, jacobian);
    return domain > 0.0 ? min(coverage / domain, 1.0) : coverage;
}
float trimCoverageOfPixel(vec2 uv, mat2 jacobian) {
#ifdef KW_TRIM_EXACT
    vec2 unit = (uv - uTrimRect.xz) / (uTrimRect.yw - uTrimRect.xz);
    bool inside = !trimmedAway(uv);
    float coverage = kwTrimCoverageExact(uv, unit, jacobian, inside);
    if (coverage >= 0.0)
        return coverage;
    // A corner or a sliver in the pixel: the fraction of 55 points over it that the exact
    // classification keeps, a Fibonacci lattice (point i at (i, 34 i mod 55) / 55), whose even
    // spread counts thin slivers to a few hundredths.
    int kept = 0;
    for (int i = 0; i < 55; ++i) {
        vec2 at = (vec2(float(i), float((34 * i) % 55)) + 0.5) / 55.0 - 0.5;
        kept += trimmedAway(uv + jacobian * at) ? 0 : 1;
    }
    return float(kept) / 55.0;
#else
    // The paper's mask: its bilinear value's 0.5 level is the edge, and the value's screen
    // gradient turns the distance to it into pixels.
    vec2 unit = (uv - uTrimRect.xz) / (uTrimRect.yw - uTrimRect.xz);
    vec2 texel = clamp(unit * uTrimSize, vec2(0.5), uTrimSize - vec2(0.5));
    float m = texture(uTrimMask, vec3(texel * uTrimLayerScale, uTrimLayer)).r;
    vec2 gradient = vec2(dFdx(m), dFdy(m));
    if (any(lessThan(unit, vec2(0.0))) || any(greaterThan(unit, vec2(1.0))))
        return 0.0;
    float g = length(gradient);
    if (!(g > 0.0))
        return m < 0.5 ? 0.0 : KW_WHOLLY;
    return kwEdgeCoverage((m - 0.5) / g, gradient / g);
#endif
}
// Opaque passes: whatever is not wholly kept is left to the edge pass.
#define KW_DISCARD_TRIMMED(uv)                                                                     \
    if (trimCoverage(uv) < 1.0)                                                                    \
    discard
#else
#define KW_DISCARD_TRIMMED(uv)                                                                     \
    if (trimmedAway(uv))                                                                           \
    discard
#endif
#else
#define KW_DISCARD_TRIMMED(uv)
#endif
