// Exact pass (paper 3.4.1): evaluates the NURBS surface at the fragment's (u, v) and shades it.
// Variants: DEGREE_U/DEGREE_V (1..15), KW_AOV (write AOV targets), KW_EXACT_DEPTH (gl_FragDepth),
// KW_TRIM (discard where the surface's trim mask says trimmed; only used without the depth
// pre-pass, whose own KW_TRIM variant makes GL_EQUAL reject trimmed fragments here),
// KW_TRIM_AA (with KW_TRIM: keep only fragments the trims cover wholly, anti-aliasing),
// KW_TRIM_EDGE (with KW_TRIM_AA: the edge pass, which keeps the partly covered fragments and
// writes colour times coverage and the coverage, for kw::AntialiasTarget's accumulation),
// KW_ANALYSIS (an analysis colouring instead of Phong, analysis.glsl), KW_ISOCURVES (knot and
// iso-parameter lines over the colour), KW_DIRECTIONS (principal-direction marks; needs
// KW_SECOND_ORDER), KW_SECOND_ORDER (second derivatives and curvature,
// for the curvature modes and KW_AOV_CURVATURE: the K, H, k1, k2 target at
// KW_AOV_CURVATURE_OUTPUT and the principal direction of k1 at KW_AOV_DIRECTION_OUTPUT),
// KW_RAY_NEWTON (adaptive partitions: shade the point truly under the pixel, kwOntoRay), KW_SKIRT (the edge skirts: keep a fragment only
// where the pixel's ray meets the surface inside its domain and trims, kwSkirtPoint),
// KW_DEPTH_ONLY (with KW_RAY_NEWTON and KW_TRIM: the depth pre-pass of cells near a trim curve,
// which tests the trims at the point under the pixel and shades nothing), KW_SECTION (section
// planes cut the exact point; caps where a closed solid is seen from inside; section.glsl),
// KW_BACK_FILL (a closed solid's skipped side, drawn last where nothing nearer covered a pixel:
// kw::ExactSurfacePass::backFacePass), KW_ANALYTIC (with KW_RAY_NEWTON: the point under the
// pixel from the face's analytic form in closed form, analytic.glsl, instead of the Newton step),
// KW_COVER (with KW_ANALYTIC and KW_EXACT_DEPTH: a closed-form face's cover, whose boxes are no
// chords of it: the ray's first meeting with the face, or the fragment is discarded).
#include "nurbs_surface.glsl"
#include "phong.glsl"
#include "trim_sample.glsl"
#ifdef KW_SECTION
#include "section.glsl"
#endif
#ifndef KW_ANALYSIS
#define KW_ANALYSIS KW_ANALYSIS_PHONG
#endif

#ifdef KW_DEFERRED
// The deferred exact pass (kw::ExactSurfacePass, "deferred"): one triangle over the view per
// variant, routed by the stencil the pre-pass wrote; what the base polygon's fragment would
// have carried comes from the pre-pass's buffer (kwReadPrepass, at the top of main).
layout(binding = KW_PREPASS_UNIT) uniform usampler2D kwPrepass;
// The vertex pool (kw::BaseVertex: position 0-2, uv 3-4, span 5-6, span scale 7) four words a
// texel. A texture buffer, not a storage buffer: llvmpipe returns 0 from a storage-buffer load
// in a helper invocation, and llvmpipe clips this triangle to the view as two triangles, so the
// 2 x 2 quads along the view's diagonal got a helper with span 0 and a wrong point; every
// screen derivative there (the zebra's and isophotes' band filters, isocurve widths) drew a
// straight grey line across the image (surface_data.glsl says the same of the surface data).
layout(binding = KW_VERTEX_POOL_UNIT) uniform usamplerBuffer kwVertexPool;
uint kwVertexWord(uint word) {
    return texelFetch(kwVertexPool, int(word >> 2u))[word & 3u];
}
vec2 vUv;
ivec2 vSpan;
float vSpanScale;
int vSurface;
bool kwFrontFacing;
void kwReadPrepass() {
    uvec4 g = texelFetch(kwPrepass, ivec2(gl_FragCoord.xy), 0);
    vUv = uintBitsToFloat(g.xy);
    vSurface = int(g.z & 0x7fffffffu);
    kwFrontFacing = (g.z >> 31) != 0u;
    uint at = g.w * uint(KW_VERTEX_WORDS);
    uint span = at + uint(KW_VERTEX_SPAN_WORD);
    vSpan = ivec2(kwVertexWord(span), kwVertexWord(span + 1u));
    vSpanScale = uintBitsToFloat(kwVertexWord(at + uint(KW_VERTEX_SPAN_SCALE_WORD)));
}
#define KW_FRONT_FACING kwFrontFacing
#else
in vec2 vUv;
flat in ivec2 vSpan;
flat in float vSpanScale;
flat in int vSurface; // row of the surface table (surface_data.glsl)
#define KW_FRONT_FACING gl_FrontFacing
#endif

uniform mat4 uViewProjection;
uniform vec3 uForward;

#if KW_ANALYSIS != KW_ANALYSIS_PHONG || defined(KW_ISOCURVES) || defined(KW_DIRECTIONS)
#include "analysis.glsl"
#endif

#if (defined(KW_TRIM_EDGE) && !defined(KW_EXACT_DEPTH)) || defined(KW_BACK_FILL)
// The edge pass writes no depth: test it before shading, so fragments behind what the opaque
// passes drew (the surface's own inside among them: equal depth fails the strict nearer
// test) cost nothing. The back-face fill writes none either (a fragment its trims discard
// would write it all the same): with a discard in the shader llvmpipe tested the depth after
// it, so every fragment of the hidden side was shaded, 1.2x the frame.
layout(early_fragment_tests) in;
#endif

#ifdef KW_SKIRT
#include "window.glsl"

// The edge skirt and the silhouette fins (surface.vert KW_SKIRT, kw::buildFins): the (u, v)
// of this surface's point under the pixel centre, from the strip's (u, v), with S continued
// linearly past the domain; true when the solve comes within 0.002 px of the pixel centre at a
// point at most uSkirtReach px (on screen) outside the domain: a quarter pixel of overlap where
// faces meet, so that B-rep edges whose faces miss each other by a fraction of a pixel (within
// the model's tolerance) show no pinhole, and the depth test picks the face in front. The
// point shown is then the edge's (clamped into the domain). False where the ray misses the
// face: beyond its edge (unless it meets the face farther on, kwSkirtPoint), outside its
// silhouette, or when the solve makes no progress.
// The solve is Levenberg-Marquardt on project(S(u, v)) = pixel centre: the Newton step (2
// equations, 2 unknowns, the Jacobian is the projected tangents) while it brings the point
// nearer; where it does not (near a silhouette the Jacobian is nearly singular and the full
// step overshoots along the fold), back to the best point with the step damped 8 times more.
// Every start is solved: an early rejection of points further outside than twice their
// residual (on the reasoning that a step moves a point about its residual) left pinholes in
// seams, where near a fold a step moves the point much farther (docs/PERFORMANCE.md ## Edges,
// "Back faces of closed solids"), and saved no measurable time. The acceptance is tight because a pixel centre just
// outside a silhouette stalls the solve at its distance to it: at 0.02 px the fins drew 2 % of
// the pixels along a silhouette that the exact surface misses by less than that.
uniform float uSkirtReach;
// The knot span holding `uv` (inside the domain), from `span` a few spans away at most: the
// solve moves the point by about its residual, and a fin's (u, v) runs along an edge that may
// cross a knot, so the provoking vertex's span is only where the search starts. A span's
// polynomial continued past its knots is not the surface (it only matches it to the order of
// continuity there), and near a silhouette that difference moves the outline.
ivec2 kwSpanAt(vec2 uv, ivec2 span) {
    for (int k = 0; k < 4; ++k) {
        vec2 knots = spanKnotsU(span);
        if (uv.x >= knots.y && uv.x < uDomain.y)
            ++span.x;
        else if (uv.x < knots.x && uv.x > uDomain.x)
            --span.x;
        else
            break;
    }
    for (int k = 0; k < 4; ++k) {
        vec2 knots = spanKnotsV(span);
        if (uv.y >= knots.y && uv.y < uDomain.w)
            ++span.y;
        else if (uv.y < knots.x && uv.y > uDomain.z)
            --span.y;
        else
            break;
    }
    return span;
}
// The Levenberg-Marquardt solve above from `uv` in `span`, in at most `steps` evaluations:
// KW_SOLVE_FOUND where it ends within uSkirtReach of the domain (`uv` the point clamped into it),
// KW_SOLVE_BEYOND where it ends on the continuation farther out (`uv` the point outside),
// KW_SOLVE_MISSED where it ends nowhere. `span` ends at the clamped point, and `found` holds the
// surface's partials there (with KW_SOLVE_MISSED, those of the last point evaluated: with
// `steps` 1, the start clamped into the domain).
#define KW_SOLVE_MISSED 0
#define KW_SOLVE_FOUND 1
#define KW_SOLVE_BEYOND 2
int kwSkirtSolve(inout vec2 uv, inout ivec2 span, out SurfacePartials found, int steps) {
    ivec2 bestSpan = span;
    vec2 best = uv, trial = uv;
    mat2 bestJ = mat2(0.0);
    vec2 bestR = vec2(0.0);
    float bestResidual = 1e30, damping = 0.0;
    for (int k = 0; k < steps; ++k) {
        vec2 inside = clamp(trial, uDomain.xz, uDomain.yw);
        ivec2 at = kwSpanAt(inside, bestSpan);
        SurfacePartials d = surfacePartials(inside, at);
        found = d;
        vec3 p = d.s + d.su * (trial.x - inside.x) + d.sv * (trial.y - inside.y);
        vec4 clip = uViewProjection * vec4(p + uOrigin, 1.0);
        float residual = 1e30;
        bool improved = false;
        if (clip.w > 0.0) {
            vec2 r = kwWindow(clip) - gl_FragCoord.xy;
            mat2 j = mat2(kwWindowTangent(clip, d.su), kwWindowTangent(clip, d.sv));
            residual = length(r);
            if (residual < 0.002) {
                span = at;
                if (length(j * (trial - inside)) > uSkirtReach) { // on screen, past the edge
                    uv = trial;
                    return KW_SOLVE_BEYOND;
                }
                uv = inside;
                return KW_SOLVE_FOUND;
            }
            if (residual < bestResidual) {
                if (!(residual < 8.0))
                    return KW_SOLVE_MISSED;
                best = trial;
                bestSpan = at;
                bestJ = j;
                bestR = r;
                bestResidual = residual;
                damping *= 0.25;
                improved = true;
            }
        }
        if (!improved)
            damping = max(damping * 8.0, 1e-3);
        if (bestResidual == 1e30)
            return KW_SOLVE_MISSED; // the start is behind the eye
        mat2 a = transpose(bestJ) * bestJ;
        float scale = a[0][0] + a[1][1];
        mat2 m = a + mat2(damping * scale);
        float det = determinant(m);
        if (!(abs(det) > 1e-10 * scale * scale))
            return KW_SOLVE_MISSED; // no tangent plane on screen (edge on, or collapsed)
        trial = best - inverse(m) * (transpose(bestJ) * bestR);
    }
    return KW_SOLVE_MISSED;
}

// Near a fold (a silhouette) the pixel's ray meets the surface twice, on the sheet in front and
// on the hidden one behind it, and the solve may end on either; the one behind, lit as if seen
// (phong turns the normal to the eye), showed as black specks along silhouettes. Which sheet a
// point is on follows from the normal curvature along the ray's direction t in the tangent
// plane: the ray's curve through the fold bends towards its centre of curvature, and on the
// front sheet the normal pointing to that centre points away from the eye (the surface curves
// away behind its outline). So with n the unit normal, r the unit ray, c = n . r and II =
// S_tt . n (estimated from S_t two pixels along t), the point is in front (`front`) when
// II c > 0. The ray's curve is a parabola about the fold: in the plane of n and t the surface
// rises II s^2 / 2 over the tangent at arc length s, the ray rises c / |r - c n| per unit of
// s, so the ray meets it again at s = 2 c / (II |r - c n|) (`other`; where the ray runs
// nearly along the surface that is far from the first point, and the old estimate without
// the 1 / |r - c n| started the solve short of it). `uv` may lie outside the domain (a
// solve that ended on the continuation, KW_SOLVE_BEYOND): the point and the tangent plane are
// then the continuation's, the curvature the edge's. False where the ray has no fold here
// (looking straight at the surface, edge on, or flat along t): `front` is then true.
bool kwRayCurve(vec2 uv, ivec2 span, SurfacePartials d, out bool front, out vec2 other) {
    front = true;
    other = uv;
    vec2 inside = clamp(uv, uDomain.xz, uDomain.yw);
    vec3 p = d.s + d.su * (uv.x - inside.x) + d.sv * (uv.y - inside.y) + uOrigin;
    vec3 n = cross(d.su, d.sv);
    vec3 r = p - uEye;
    float ln = length(n), lr = length(r);
    if (!(ln > 0.0) || !(lr > 0.0))
        return false;
    n /= ln;
    r /= lr;
    float c = dot(n, r);
    vec3 t = r - c * n, b = cross(n, t);
    float lt = length(t);
    if (!(lt > 1e-6))
        return false; // looking straight at it: no fold
    t /= lt;
    b /= lt;
    // The (u, v) directions of unit steps along t and b (least squares through the tangents).
    float e = dot(d.su, d.su), f = dot(d.su, d.sv), g = dot(d.sv, d.sv);
    float det = e * g - f * f;
    if (!(det > 0.0))
        return false;
    vec2 wt = vec2(g * dot(d.su, t) - f * dot(d.sv, t), e * dot(d.sv, t) - f * dot(d.su, t)) / det;
    vec2 wb = vec2(g * dot(d.su, b) - f * dot(d.sv, b), e * dot(d.sv, b) - f * dot(d.su, b)) / det;
    // Two pixels of length, from the screen rate along b (square to the ray, not foreshortened).
    vec4 clip = uViewProjection * vec4(p, 1.0);
    float rate = length(kwWindowTangent(clip, d.su * wb.x + d.sv * wb.y));
    if (!(rate > 0.0))
        return false;
    float h = 2.0 / rate;
    vec2 there = inside + h * wt;
    if (any(lessThan(there, uDomain.xz)) || any(greaterThan(there, uDomain.yw)))
        h = -h, there = inside + h * wt;
    there = clamp(there, uDomain.xz, uDomain.yw);
    if (there == inside)
        return false;
    SurfacePartials d2 = surfacePartials(there, kwSpanAt(there, span));
    float second = dot((d2.su - d.su) * wt.x + (d2.sv - d.sv) * wt.y, n) / h;
    if (!(abs(second) > 1e-6 / lr))
        return false;
    front = second * c > 0.0;
    other = uv + 2.0 * c / (second * lt) * wt;
    return true;
}

// The point under the pixel on the sheet in front. Where kwRayCurve finds the solve's point
// on the hidden sheet, the solve starts again from its estimate of the other meeting, and the
// nearer of the two points is kept: the criterion holds at folds, but away from one (a saddle's
// inside, where a skirt fills a seam) the normal curvature along the ray has either sign, so
// it only says where to look, and the depth decides. The restarts begin at the strip's own
// span and look the knot span up again as they go.
// Where the solve ends on the continuation past the edge (KW_SOLVE_BEYOND), the ray may still
// meet the face itself near the edge: looking into a bore past its rim, the ray meets the
// bore's continuation first and the far wall second (Axis_of_bearing (457, 775) at 1024²
// fitted, a pinhole in a seam). The solve starts again from the other meeting when that lies
// in the domain, and keeps the point only when it lies near the strip's depth: the strip is
// drawn at its polygon's depth, pushed back kSkirtDepthPixels, so a point farther behind it
// (uSkirtDepthScale once more) would be drawn in front of faces that hide it.
uniform float uSkirtDepthScale;
// The attempts, one solve each: the strip's own (u, v); the other meeting past the edge; the
// estimate of the sheet in front; the first point mirrored about the strip's (u, v); and last,
// for a point with no plain normal, the evaluation of the nearby interior point that the
// normal rule asks for (surfaceSampleRound). One loop, not a sequence of calls in `if`s: SIMD
// lanes (llvmpipe's, a GPU's) run an `if` body under a mask for the whole group, so each
// attempt's first evaluation cost every skirt fragment; a loop's later rounds run only in the
// groups where some fragment needs them. `s` is the sample of the point found, from the
// solve's own partials there (evaluateSurface's first round would evaluate them again).
#define KW_TRY_STRIP 0
#define KW_TRY_BEYOND 1
#define KW_TRY_ESTIMATE 2
#define KW_TRY_MIRRORED 3
#define KW_TRY_INTERIOR 4
bool kwSkirtPoint(inout vec2 uv, out ivec2 span, out SurfaceSample s) {
    bool limitNormal;
    beginSurfaceSample(s, limitNormal);
    vec2 start = uv, restart = uv, first = uv, interior = uv;
    ivec2 startSpan = vSpan, firstSpan = vSpan;
    SurfacePartials d, firstD;
    float firstDistance = 0.0;
    int attempt = KW_TRY_STRIP;
    for (int round = 0; round < 4; ++round) {
        vec2 tried = start;
        span = startSpan;
        int solved = kwSkirtSolve(tried, span, d, attempt == KW_TRY_INTERIOR ? 1 : 12);
        if (attempt == KW_TRY_INTERIOR) {
            surfaceSampleRound(d, 1, uv, vSpanScale, s, limitNormal, interior);
            return true;
        }
        if (attempt == KW_TRY_STRIP) {
            if (solved == KW_SOLVE_MISSED)
                return false;
            bool front;
            bool fold = kwRayCurve(tried, span, d, front, restart);
            if (solved == KW_SOLVE_BEYOND) {
                if (!fold || any(lessThan(restart, uDomain.xz)) ||
                    any(greaterThan(restart, uDomain.yw)))
                    return false;
                attempt = KW_TRY_BEYOND; // from the same span
                start = restart;
                startSpan = span;
                continue;
            }
            if (!front) {
                first = tried;
                firstSpan = span;
                firstD = d;
                firstDistance = distance(d.s + uOrigin, uEye);
                // From the estimate, then from the first point mirrored about the strip's own
                // (u, v) (on the polygon's edge, near the fold) where that fails.
                attempt = KW_TRY_ESTIMATE;
                start = restart;
                startSpan = vSpan;
                continue;
            }
        } else if (attempt == KW_TRY_BEYOND) {
            if (solved != KW_SOLVE_FOUND)
                return false;
            vec4 clip = uViewProjection * vec4(d.s + uOrigin, 1.0);
            if (!(clip.w > 0.0 &&
                  clip.z / clip.w >= gl_FragCoord.z * uSkirtDepthScale * uSkirtDepthScale))
                return false;
        } else if (solved == KW_SOLVE_FOUND && distance(d.s + uOrigin, uEye) < firstDistance) {
            // a restart found the nearer point
        } else if (attempt == KW_TRY_ESTIMATE) {
            attempt = KW_TRY_MIRRORED;
            start = 2.0 * vUv - first;
            startSpan = vSpan;
            continue;
        } else { // neither restart found a nearer point: the first one
            tried = first;
            span = firstSpan;
            d = firstD;
        }
        // Accepted: the point and its sample.
        uv = tried;
        if (surfaceSampleRound(d, 0, uv, vSpanScale, s, limitNormal, interior))
            return true;
        attempt = KW_TRY_INTERIOR;
        start = interior;
        startSpan = span;
    }
    return true;
}
#endif

#ifdef KW_RAY_NEWTON
#include "window.glsl"

// The (u, v) of the surface point under this pixel's centre, from the base polygon's (u, v).
// In adaptive mode the polygon lies within the pixel tolerance of the exact surface on screen,
// so S(uv) projects up to that far from the pixel centre and the normal shown would be the
// exact normal of a point up to 0.5 px away (an error of the curvature times the offset, 0.3
// degrees p99 on the teapot). One Newton step on project(S(u, v)) = pixel centre (2 equations,
// 2 unknowns, Jacobian = the projected tangents) moves it onto the pixel's ray; convergence is
// quadratic, so the residual falls from <= 0.5 px to the order of (0.5 px)^2 times the
// projection's curvature. No step where the start is farther than KW_NEWTON_REACH px (not the
// adaptive polygon's neighbourhood) or where the projected tangents are nearly parallel (the
// silhouette, where the ray may miss the surface): the polygon's (u, v) is kept there.
// `residual` is the start's distance to the pixel centre in pixels.
#define KW_NEWTON_REACH 4.0
vec2 kwOntoRay(vec2 uv, out float residual) {
    SurfacePartials d = surfacePartials(uv, vSpan);
    vec4 clip = uViewProjection * vec4(d.s + uOrigin, 1.0);
    vec2 r = kwWindow(clip) - gl_FragCoord.xy;
    residual = length(r);
    mat2 j = mat2(kwWindowTangent(clip, d.su), kwWindowTangent(clip, d.sv));
    float det = determinant(j);
    if (!(residual <= KW_NEWTON_REACH) ||
        !(abs(det) > 1e-3 * length(j[0]) * length(j[1])))
        return uv;
    vec2 step = -(inverse(j) * r);
    return clamp(uv + step, uDomain.xz, uDomain.yw);
}

#ifdef KW_ANALYTIC
#include "analytic.glsl"
#endif
#endif

#ifdef KW_GBUFFER
layout(location = KW_PREPASS_OUTPUT) out uvec4 kwPrepassOut; // the deferred pass's input (depth_only.frag)
flat in int vVertex;
vec4 fragColor; // not written: the pre-pass returns before shading
#else
layout(location = KW_COLOUR_OUTPUT) out vec4 fragColor;
#endif
#ifdef KW_AOV
layout(location = KW_AOV_ID_UV_DEPTH_OUTPUT) out vec4 aovIdUvDepth; // surface id, u, v, eye-space depth
layout(location = KW_AOV_POSITION_OUTPUT) out vec4 aovPosition; // exact point, w = 1
layout(location = KW_AOV_NORMAL_OUTPUT) out vec4 aovNormal; // unit normal (Su x Sv side, not flipped), w = 0
#endif
#ifdef KW_AOV_CURVATURE
layout(location = KW_AOV_CURVATURE_OUTPUT) out vec4 aovCurvature; // K, H, k1, k2 (kw::surfaceCurvature)
layout(location = KW_AOV_DIRECTION_OUTPUT) out vec4 aovDirection; // unit principal direction of k1 (world), w = 0
#endif

void main() {
#ifdef KW_DEFERRED
    kwReadPrepass();
#endif
    kwSurface = vSurface;
#ifdef KW_SKIRT
    vec2 skirtUv = vUv;
    ivec2 span; // where the solve ended: a fin's (u, v) may cross a knot
    SurfaceSample s;
    if (!kwSkirtPoint(skirtUv, span, s))
        discard;
    KW_DISCARD_TRIMMED(skirtUv);
    vec2 uv = skirtUv;
#else
    ivec2 span = vSpan;
#ifdef KW_TRIM_EDGE
    float coverage = trimCoverage(vUv);
    if (coverage <= 0.0 || coverage > 1.0)
        discard; // nothing here, or the opaque passes drew it
#elif !defined(KW_RAY_NEWTON) || defined(KW_TRIM_AA)
    KW_DISCARD_TRIMMED(vUv); // anti-aliased: the coverage's derivatives need the polygon's
#endif
    // The interpolated (u, v) can leave the domain by ~1e-5 at grazing pixels on the boundary
    // (float barycentrics of thin triangles); the surface ends at its domain, so clamp there,
    // as kw::surfacePoint does, instead of extrapolating the boundary span's polynomial.
    vec2 uv = clamp(vUv, uDomain.xz, uDomain.yw);
#ifdef KW_RAY_NEWTON
#ifdef KW_ANALYTIC
    SurfaceSample s;
    bool away; // the trim test at the meeting taken, made there
    vec2 onto = kwAnalyticPoint(uv, span, vSpanScale, s, away);
#else
    float before;
    vec2 onto = kwOntoRay(uv, before);
#endif
#ifndef KW_TRIM_AA
    // The trims are tested at the point under the pixel, as the depth pre-pass does
    // (KW_DEPTH_ONLY): at the polygon's (u, v), up to the tolerance away, a pixel centre just
    // inside a trimmed edge was dropped and the face behind showed through.
#ifndef KW_ANALYTIC
    KW_DISCARD_TRIMMED(onto);
#elif defined(KW_TRIM)
    if (away)
        discard;
#endif
#endif
#ifdef KW_DEPTH_ONLY
#ifdef KW_GBUFFER
    kwPrepassOut = kwPrepassWords(vUv, vSurface, gl_FrontFacing, vVertex);
#else
    fragColor = vec4(0.0);
#endif
    return; // the pre-pass of cells near a trim curve: the rasteriser writes the depth
#endif
    // A step that did not bring the point nearer the pixel centre (a strongly curved
    // projection near a silhouette) is undone: a second round evaluates the polygon's (u, v)
    // for those fragments. A loop, not an `if`: SIMD lanes (llvmpipe's, a GPU's) run an `if`
    // body under a mask for the whole group, but leave a loop once no lane is left in it, so
    // the rare undo costs an evaluation only where some fragment of the block needs it.
#ifdef KW_ANALYTIC
    uv = onto; // on the ray already, in closed form
#else
    SurfaceSample s;
    vec2 at = onto;
    for (int round = 0; round < 2; ++round) {
        s = evaluateSurface(at, vSpan, vSpanScale);
        if (round == 1 || at == uv ||
            length(kwWindow(uViewProjection * vec4(s.point, 1.0)) - gl_FragCoord.xy) < before)
            break;
        at = uv;
    }
    uv = at;
#endif
    // Near a fold (a silhouette) the polygon's triangle in front can span, in (u, v), past the
    // fold onto the hidden sheet behind it, and the point found is then the ray's far meeting
    // with the surface; lit with its normal turned to the eye (phong), it showed as a black
    // speck along the outline. The sheet a triangle stands for has the triangle's winding on
    // screen, so a point that faces the eye the other way than its triangle is on the other
    // sheet. The ray's near meeting mirrors it about the fold: the ray's curve there is a
    // parabola about the fold, symmetric along the ray, so the near point's normal is this
    // one with its component along the ray reversed (its depth differs by a fraction of the
    // pixel's footprint along the ray).
#ifndef KW_ANALYTIC // the closed form found the meeting in front (kwAnalyticPoint)
    vec3 ray = normalize(s.point - uEye);
    if ((dot(s.normal, ray) < 0.0) != KW_FRONT_FACING)
        s.normal -= 2.0 * dot(s.normal, ray) * ray;
#endif
#else
    SurfaceSample s = evaluateSurface(uv, vSpan, vSpanScale);
#endif
#endif // KW_SKIRT
#ifdef KW_EXACT_DEPTH
    vec4 clip = uViewProjection * vec4(s.point, 1.0);
    gl_FragDepth = clamp(clip.z / clip.w, 0.0, 1.0); // zero-to-one clip range, reversed
#endif
#ifdef KW_SECTION
    // Cut by the exact point; a kept face of a closed solid seen from inside shows the cap in
    // front of it instead: the plane's point and normal. The depth stays the face's, so that a
    // kept surface in front of the face (outside the solid's cut) still hides the cap.
#ifdef KW_DEFERRED
    // The deferred pass shades only cells every plane keeps, farther than the line's width
    // (kw::sectionCellClasses, conservative): no cut to test, and no line (its screen
    // derivatives jump between the surfaces of a 2 x 2 block there). Only the caps remain.
    float sectionLine = 0.0;
#else
    float sectionLine = kwSectionLine(s.point);
    if (kwSectionCut(s.point))
        discard;
#endif
    vec3 capPoint;
    int capPlane = uSolidSide == 0 ? -1 : kwSectionCap(s.point, s.normal * float(uSolidSide), capPoint);
    if (capPlane >= 0) {
        s.point = capPoint;
        s.normal = uSectionPlanes[capPlane].xyz;
    }
#endif
#ifdef KW_SECOND_ORDER
    vec4 curvature = s.curvature;
#else
    vec4 curvature = vec4(0.0);
#endif
#if KW_ANALYSIS != KW_ANALYSIS_PHONG
    vec3 colour = analysisColour(s.point, s.normal, curvature);
#else
    vec3 colour = phong(s.point, s.normal);
#endif
#ifdef KW_SECTION
    if (capPlane >= 0) {
#if KW_ANALYSIS != KW_ANALYSIS_PHONG
        colour = kwCapColour(phong(s.point, s.normal));
#else
        colour = kwCapColour(colour); // lit at the cap already (s is the cap's point)
#endif
        curvature = vec4(0.0); // a plane
    } else {
#endif
#ifdef KW_ISOCURVES
    colour = overlayIsocurves(colour, uv, spanKnotsU(span), spanKnotsV(span));
#endif
#ifdef KW_DIRECTIONS
    colour = overlayDirections(colour, s.normal, vUv, span);
#endif
#ifdef KW_SECTION
        colour = kwSectionLineColour(colour, sectionLine);
    }
#endif
#ifdef KW_TRIM_EDGE
    fragColor = vec4(colour * coverage, coverage); // premultiplied, summed by the blend
#else
    fragColor = vec4(colour, 1.0);
#endif
#ifdef KW_AOV
    aovIdUvDepth = vec4(uSurfaceId, uv, dot(s.point - uEye, uForward));
#ifdef KW_SECTION
    if (capPlane >= 0)
        aovIdUvDepth = vec4(float(KW_SECTION_CAP_ID), 0.0, 0.0, dot(s.point - uEye, uForward));
#endif
    aovPosition = vec4(s.point, 1.0);
    aovNormal = vec4(s.normal, 0.0);
#endif
#ifdef KW_AOV_CURVATURE
    aovCurvature = curvature;
    aovDirection = vec4(s.dir1, 0.0);
#endif
}
