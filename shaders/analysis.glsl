// Surface analysis colouring from the exact per-fragment point, normal, curvature and (u, v)
// (docs/RENDERING.md, ## Analysis). KW_ANALYSIS selects the mode (kw::AnalysisMode values,
// injected by kw::analysisDefines): 1 Gaussian K, 2 mean H, 3 max |k|, 4 min radius 1/max |k|,
// 5 zebra, 6 isophotes, 7 environment map, 8 draft angle. KW_ISOCURVES overlays knot lines and
// iso-parameter lines on any mode, KW_DIRECTIONS principal-direction marks. KW_RAMP (an array of KW_RAMP_STOPS colours) is the colour
// scale of kw::colourRamp(), defined once in C++ (render/analysis.h) so the legend matches.
// Uniforms are set by kw::setAnalysisUniforms.

#ifdef KW_RAMP // a colour map: kw::isColourMap, from its mode's row (ExactVariant::defines)
uniform vec2 uAnalysisRange; // the scale's low and high value (model units: 1/length, 1/length^2 or length)
uniform int uAnalysisScale;  // kw::ColourScale: 0 linear, 1 symmetric about 0, 2 log

// The colour scale position in [0, 1] of value x (kw::colourScalePosition in C++).
float scalePosition(float x) {
    float lo = uAnalysisRange.x, hi = uAnalysisRange.y;
    if (uAnalysisScale == KW_SCALE_SYMMETRIC) { // symmetric: 0 in the middle, +-max(|lo|, |hi|) at the ends
        float m = max(max(abs(lo), abs(hi)), 1e-30);
        return clamp(0.5 + 0.5 * x / m, 0.0, 1.0);
    }
    if (uAnalysisScale == KW_SCALE_LOG) { // signed log: linear within m * 1e-3 of 0, logarithmic beyond
        float m = max(max(abs(lo), abs(hi)), 1e-30);
        float c = 1e-3 * m;
        return clamp(0.5 + 0.5 * sign(x) * log(1.0 + abs(x) / c) / log(1.0 + m / c), 0.0, 1.0);
    }
    return clamp((x - lo) / max(hi - lo, 1e-30), 0.0, 1.0);
}

vec3 rampColour(float t) {
    const vec3 ramp[KW_RAMP_STOPS] = KW_RAMP;
    float x = clamp(t, 0.0, 1.0) * float(KW_RAMP_STOPS - 1);
    int i = min(int(x), KW_RAMP_STOPS - 2);
    return mix(ramp[i], ramp[i + 1], x - float(i));
}

// The analysed quantity from (K, H, k1, k2), as kw::analysisValue.
float analysisValue(vec4 c) {
#if KW_ANALYSIS == KW_ANALYSIS_GAUSSIAN
    return c.x;
#elif KW_ANALYSIS == KW_ANALYSIS_MEAN
    return c.y;
#elif KW_ANALYSIS == KW_ANALYSIS_MAX_CURVATURE
    return max(abs(c.z), abs(c.w));
#elif KW_ANALYSIS == KW_ANALYSIS_MIN_RADIUS
    float kmax = max(abs(c.z), abs(c.w));
    return kmax > 0.0 ? 1.0 / kmax : 3.0e38; // a plane: infinite radius, the scale's top
#else
#error "a colour map's row with no value here"
#endif
}
#endif

#if KW_ANALYSIS == KW_ANALYSIS_ZEBRA
uniform float uStripeCount; // black and white stripe pairs per 180 degrees of reflection
uniform vec3 uStripeAxis;   // unit world direction the stripes run along (in the view plane)
#endif
#if KW_ANALYSIS == KW_ANALYSIS_ISOPHOTES
uniform float uIsophoteCount; // bands across N.L in [-1, 1]
uniform vec3 uIsophoteLight;  // unit world direction towards the light
#endif
#if KW_ANALYSIS == KW_ANALYSIS_ENVIRONMENT
uniform sampler2D uEnvironment; // equirectangular: longitude along x from -pi, latitude along y
#endif
#if KW_ANALYSIS == KW_ANALYSIS_DRAFT
uniform vec3 uPullDirection; // unit world vector
uniform float uDraftAngle;   // threshold in radians
#endif

// Black and white bands of the periodic coordinate `phase` (a band per 0.5), anti-aliased over
// one pixel of width w (the phase's screen derivative, fwidth); unresolvable bands fade to grey.
float bands(float phase, float w) {
    float f = fract(phase);
    float edge = min(abs(f - 0.5), min(f, 1.0 - f)); // distance to the nearest band edge
    float cover = clamp(edge / max(w, 1e-12) + 0.5, 0.0, 1.0);
    float inside = f < 0.5 ? 1.0 : 0.0;
    float value = mix(0.5, inside, cover);
    return w > 0.5 ? 0.5 : value;
}

// Diffuse headlight factor so colour maps keep the shape readable.
float headlight(vec3 normal, vec3 V) {
    return 0.35 + 0.65 * abs(dot(normal, V));
}

vec3 analysisColour(vec3 point, vec3 normal, vec4 curvature) {
    vec3 V = normalize(uEye - point);
    vec3 N = dot(normal, V) < 0.0 ? -normal : normal; // two-sided, as phong()
#ifdef KW_RAMP
    return rampColour(scalePosition(analysisValue(curvature))) * headlight(normal, V);
#elif KW_ANALYSIS == KW_ANALYSIS_ZEBRA
    // Zebra: infinitely long light tubes parallel to the stripe axis A (in the view plane),
    // evenly spread around it: a reflected view ray R sees the tube of its angle about A,
    // measured from the direction back to the viewer. That angle is a ratio of R's components,
    // so on a cylinder parallel to A it does not depend on the height (straight stripes, also
    // in perspective). Where R runs along A the bands meet, as real tubes meet at their
    // vanishing point.
    vec3 R = reflect(-V, N);
    vec3 C = -uForward;
    vec3 B = normalize(cross(uStripeAxis, C));
    float phi = atan(dot(R, B), dot(R, C));
    // phi jumps by 2 pi where R, turned away from the viewer, crosses the plane of A and C
    // (atan's branch cut). The bands are continuous there (uStripeCount is a whole number of
    // halves: kw::setAnalysisUniforms), but fwidth(phi) is not: it saw the 2 pi jump, widened
    // the filter past half a band and drew a grey line along the cut. The screen derivatives
    // of the angle itself, wrapped into (-pi, pi], have no cut.
    vec2 d = vec2(dFdx(phi), dFdy(phi));
    d -= 6.28318530717959 * round(d / 6.28318530717959);
    float k = uStripeCount / 3.14159265358979;
    return vec3(bands(phi * k, (abs(d.x) + abs(d.y)) * k));
#elif KW_ANALYSIS == KW_ANALYSIS_ISOPHOTES
    float phase = 0.5 * (dot(N, uIsophoteLight) + 1.0) * uIsophoteCount;
    return vec3(bands(phase, fwidth(phase)));
#elif KW_ANALYSIS == KW_ANALYSIS_ENVIRONMENT
    vec3 R = reflect(-V, N);
    vec2 uvEnv = vec2(atan(R.y, R.x) / 6.28318530717959 + 0.5,
                      0.5 - asin(clamp(R.z, -1.0, 1.0)) / 3.14159265358979);
    return texture(uEnvironment, uvEnv).rgb;
#elif KW_ANALYSIS == KW_ANALYSIS_DRAFT
    // Draft angle of the oriented normal (Su x Sv side) against the pull direction: green at
    // or beyond +threshold, red at or beyond -threshold, yellow in between (insufficient);
    // the colours are kw::draftColours(), which the editor's legend shows.
    float a = asin(clamp(dot(normal, uPullDirection), -1.0, 1.0));
    vec3 c = a >= uDraftAngle ? KW_DRAFT_OK
                              : (a <= -uDraftAngle ? KW_DRAFT_UNDERCUT : KW_DRAFT_INSUFFICIENT);
    return c * headlight(normal, V);
#else
    return vec3(0.0);
#endif
}

#ifdef KW_ISOCURVES
uniform vec2 uIsoCount;    // iso-parameter lines per direction (lines at i / (n + 1) of the domain)
uniform float uIsoWidth;   // line width in pixels
uniform vec3 uIsoColour;   // iso-parameter lines
uniform vec3 uKnotColour;  // knot lines (span boundaries, including the domain's edges)

// Coverage of a line of `width` pixels at the integers of the coordinate f whose screen
// gradient has length g (per pixel), anti-aliased by a one-pixel box filter: constant screen
// width whatever the parameterisation.
float lineCover(float f, float g, float width) {
    float d = abs(f - round(f)) / max(g, 1e-20); // pixels to the nearest line
    return clamp(0.5 * width + 0.5 - d, 0.0, 1.0);
}

vec3 overlayIsocurves(vec3 colour, vec2 uv, vec2 knotsU, vec2 knotsV) {
    // Gradients of u and v themselves: they are continuous across cells and spans (a gradient
    // of a per-span coordinate would jump where the 2x2 quad straddles a knot).
    vec2 gu = vec2(length(vec2(dFdx(uv.x), dFdy(uv.x))), length(vec2(dFdx(uv.y), dFdy(uv.y))));
    vec2 width = vec2(uDomain.y - uDomain.x, uDomain.w - uDomain.z);
    vec2 scale = (uIsoCount + 1.0) / width;
    vec2 f = (uv - uDomain.xz) * scale;
    float iso = max(uIsoCount.x > 0.0 ? lineCover(f.x, gu.x * scale.x, uIsoWidth) : 0.0,
                    uIsoCount.y > 0.0 ? lineCover(f.y, gu.y * scale.y, uIsoWidth) : 0.0);
    // Knot lines: the span's own bounds, as a coordinate with the span's ends at 0 and 1.
    vec2 spanW = vec2(knotsU.y - knotsU.x, knotsV.y - knotsV.x);
    float ku = lineCover((uv.x - knotsU.x) / spanW.x, gu.x / spanW.x, uIsoWidth);
    float kv = lineCover((uv.y - knotsV.x) / spanW.y, gu.y / spanW.y, uIsoWidth);
    colour = mix(colour, uIsoColour, iso);
    return mix(colour, uKnotColour, max(ku, kv));
}
#endif

#ifdef KW_DIRECTIONS
uniform float uDirSpacing; // pixels between the marks' centres
#include "window.glsl"

// Coverage of a mark: a segment of length 0.8 spacing and width 1.5 px through the grid cell's
// centre along the unit screen direction s, anti-aliased by a one-pixel box filter.
float markCover(vec2 r, vec2 s) {
    float along = abs(dot(r, s));
    float across = abs(dot(r, vec2(-s.y, s.x)));
    return clamp(1.25 - across, 0.0, 1.0) * clamp(0.4 * uDirSpacing + 0.5 - along, 0.0, 1.0);
}

// Principal-direction marks (a cross per grid cell: k1's direction dark red, k2's dark blue).
// Every fragment of a cell draws the directions of the same point, the cell centre's: its
// (u, v) extrapolated from the fragment's with the screen derivatives of (u, v), evaluated in
// the fragment's knot span (the span's polynomial, continued a few pixels past its knots when
// the centre lies in a neighbouring span), and projected at that point, so each mark is a
// straight segment along the projection of the centre's direction. No marks at (near)
// umbilics, where the directions are undefined (k1 - k2 <= 1e-3 max |k|), nor where the
// centre's point is degenerate.
vec3 overlayDirections(vec3 colour, vec3 normal, vec2 uv, ivec2 span) {
    vec2 ux = dFdx(uv), uy = dFdy(uv);
    vec2 cell = (floor(gl_FragCoord.xy / uDirSpacing) + 0.5) * uDirSpacing;
    vec2 r = gl_FragCoord.xy - cell;
    vec2 uvc = clamp(uv - r.x * ux - r.y * uy, uDomain.xz, uDomain.yw);
    SurfacePartials d = surfacePartials(uvc, span);
    vec3 n = cross(d.su, d.sv);
    float ln = length(n);
    if (!(ln > KW_PARALLEL_REL * length(d.su) * length(d.sv)))
        return colour;
    n = dot(n, normal) < 0.0 ? -n / ln : n / ln;
    vec3 dir1;
    vec4 k = curvatureFrom(d, n, dir1);
    float kmax = max(abs(k.z), abs(k.w));
    if (!(k.z - k.w > 1e-3 * kmax))
        return colour;
    vec3 p = d.s + uOrigin;
    vec4 clip = uViewProjection * vec4(p, 1.0);
    vec2 s1 = kwWindowTangent(clip, dir1), s2 = kwWindowTangent(clip, cross(n, dir1));
    float c1 = length(s1) > 0.0 ? markCover(r, normalize(s1)) : 0.0;
    float c2 = length(s2) > 0.0 ? markCover(r, normalize(s2)) : 0.0;
    colour = mix(colour, vec3(0.1, 0.2, 0.85), c2);
    return mix(colour, vec3(0.85, 0.1, 0.1), c1);
}
#endif
