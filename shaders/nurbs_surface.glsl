// Exact rational surface point, first partials and unit normal at (u, v) inside the knot span
// `span` (paper eqs. 3.1, 3.5-3.7; The NURBS Book A3.6 on homogeneous points, A4.4 quotient).
// Needs DEGREE_U and DEGREE_V; sums only the (p+1) x (q+1) non-zero terms. With
// KW_SECOND_ORDER also Suu, Suv, Svv and the curvature of kw::surfaceCurvature (K, H, k1, k2).

// The surface's control texels ((w (P - uOrigin), w) of point (i, j)), span tables
// (kw::packSpanTable, row = span - degree) and domain uDomain come from its row of the
// scene's surface table (surface_data.glsl).
#include "surface_data.glsl"

// Thresholds of the degenerate-normal rule of kw::surfaceFrame. The kernel's kTinyDerivativeRel
// (1e-8) and kParallelRel (1e-10) are below float resolution: a collapsed edge evaluates to
// |Su| ~ 1e-7 L of rounding noise here, so the GPU uses float-sized thresholds. Between the two
// the rules differ only where the limit normal and Su x Sv agree to ~1e-5 rad.
#define KW_TINY_REL 1e-5
#define KW_PARALLEL_REL 1e-6
#define KW_INTERIOR_STEP 1e-4

// Where the control texels and span-table rows come from: the per-cell flat inputs
// (cell_data.glsl) or the textures.
#ifdef KW_CELL_GATHER
#define KW_CELL_IO flat in
#include "cell_data.glsl"
#define CONTROL_TEXEL(first, i, j) vCellControl[(j) * (DEGREE_U + 1) + (i)]
#else
#define CONTROL_TEXEL(first, i, j) KW_CONTROL((first) + ivec2(i, j))
#endif

#ifdef KW_CELL_GATHER
#define SPAN_TEXEL_U(x, row) vCellSpanU[x]
#define SPAN_TEXEL_V(x, row) vCellSpanV[x]
#else
#define SPAN_TEXEL_U(x, row) KW_SPAN_U(x, row)
#define SPAN_TEXEL_V(x, row) KW_SPAN_V(x, row)
#endif

#define BASIS_FN basisU
#define BASIS_P DEGREE_U
#define BASIS_TEXEL(x, row) SPAN_TEXEL_U(x, row)
#include "basis.glsl"
#undef BASIS_FN
#undef BASIS_P
#undef BASIS_TEXEL
#define BASIS_FN basisV
#define BASIS_P DEGREE_V
#define BASIS_TEXEL(x, row) SPAN_TEXEL_V(x, row)
#include "basis.glsl"
#undef BASIS_FN
#undef BASIS_P
#undef BASIS_TEXEL

// The knots (U[k], U[k+1]) bounding knot span k = span.x (resp. V and span.y), read from the
// span-table rows: float 0 is U[k+1-1], float p is U[k+1] (kw::packSpanTable).
vec2 spanKnotsU(ivec2 span) {
    int row = span.x - DEGREE_U;
    return vec2(SPAN_TEXEL_U(0, row).x, SPAN_TEXEL_U(DEGREE_U / 4, row)[DEGREE_U % 4]);
}
vec2 spanKnotsV(ivec2 span) {
    int row = span.y - DEGREE_V;
    return vec2(SPAN_TEXEL_V(0, row).x, SPAN_TEXEL_V(DEGREE_V / 4, row)[DEGREE_V % 4]);
}

struct SurfaceSample {
    vec3 point;
    vec3 du;
    vec3 dv;
    vec3 normal; // unit; the limit normal at collapsed edges (see evaluateSurface)
#ifdef KW_SECOND_ORDER
    vec4 curvature; // K, H, k1, k2 with kw::surfaceCurvature's signs and collapsed-edge rule
    vec3 dir1;      // unit principal direction of k1 (world), tangent to `normal`; dir2 = n x dir1
#endif
};

struct SurfacePartials {
    vec3 s, su, sv, suv;
#ifdef KW_SECOND_ORDER
    vec3 suu, svv;
#endif
};

#ifdef KW_SECOND_ORDER
// A collapsed edge of the cell (a sphere's pole, a cone's apex): an outer row or column of its
// control texels whose points coincide, to a few float ulps of their size. Near it |Su| (or
// |Sv|) shrinks like the parameter distance h to the edge, while the sums of surfacePartials
// add O(1) homogeneous terms that cancel: float leaves O(1e-7) absolute noise in Su, Suu and
// L = Suu.n (itself O(h^2)), so K and H drifted by 1e-7 / h^2 (2e-3 at the pixel next to a
// pole). Summed about the collapsed point instead, that row's terms are exactly 0 and every
// other term carries a basis factor O(h): the rounding shrinks with the derivatives. Returns
// false when no outer row or column is collapsed; `which` tells which one (x: 0 column, 1 row;
// y: its index in the cell).
bool collapsedPoint(ivec2 first, out vec3 p, out ivec2 which) {
    p = vec3(0.0);
    which = ivec2(-1);
    for (int side = 0; side < 4; ++side) {
        bool isRow = side >= 2;
        int at = (side & 1) == 0 ? 0 : (isRow ? DEGREE_V : DEGREE_U);
        int count = isRow ? DEGREE_U : DEGREE_V;
        vec4 c0 = isRow ? CONTROL_TEXEL(first, 0, at) : CONTROL_TEXEL(first, at, 0);
        vec3 q = c0.xyz / c0.w;
        bool same = true;
        for (int k = 1; k <= count; ++k) {
            vec4 c = isRow ? CONTROL_TEXEL(first, k, at) : CONTROL_TEXEL(first, at, k);
            same = same && length(c.xyz - c.w * q) <= 1e-6 * (length(c.xyz) + abs(c.w) * length(q));
        }
        if (same) {
            p = q;
            which = ivec2(isRow ? 1 : 0, at);
            return true;
        }
    }
    return false;
}
#endif

SurfacePartials surfacePartials(vec2 uv, ivec2 span) {
    float Nu[DEGREE_U + 1], dNu[DEGREE_U + 1];
    float Nv[DEGREE_V + 1], dNv[DEGREE_V + 1];
#ifdef KW_SECOND_ORDER
    float d2Nu[DEGREE_U + 1], d2Nv[DEGREE_V + 1];
    basisU(span.x - DEGREE_U, uv.x, Nu, dNu, d2Nu);
    basisV(span.y - DEGREE_V, uv.y, Nv, dNv, d2Nv);
    vec4 Auu = vec4(0.0), Avv = vec4(0.0);
#else
    basisU(span.x - DEGREE_U, uv.x, Nu, dNu);
    basisV(span.y - DEGREE_V, uv.y, Nv, dNv);
#endif
    vec4 A = vec4(0.0), Au = vec4(0.0), Av = vec4(0.0), Auv = vec4(0.0);
    ivec2 first = span - ivec2(DEGREE_U, DEGREE_V);
#ifdef KW_SECOND_ORDER
    // The sums run about `base`: a collapsed edge's point, else the surface's origin (0).
    vec3 base;
    ivec2 which;
    collapsedPoint(first, base, which);
#endif
    for (int j = 0; j <= DEGREE_V; ++j) {
        vec4 row = vec4(0.0), rowU = vec4(0.0);
#ifdef KW_SECOND_ORDER
        vec4 rowUU = vec4(0.0);
#endif
        for (int i = 0; i <= DEGREE_U; ++i) {
            vec4 c = CONTROL_TEXEL(first, i, j);
#ifdef KW_SECOND_ORDER
            bool onEdge = which.x == 1 ? j == which.y : (which.x == 0 && i == which.y);
            c.xyz = onEdge ? vec3(0.0) : c.xyz - c.w * base;
#endif
            row += Nu[i] * c;
            rowU += dNu[i] * c;
#ifdef KW_SECOND_ORDER
            rowUU += d2Nu[i] * c;
#endif
        }
        A += Nv[j] * row;
        Av += dNv[j] * row;
        Au += Nv[j] * rowU;
        Auv += dNv[j] * rowU;
#ifdef KW_SECOND_ORDER
        Auu += Nv[j] * rowUU;
        Avv += d2Nv[j] * row;
#endif
    }
    // A4.4 to first order: S = A/w, Su = (Au - wu S)/w, Suv = (Auv - wu Sv - wv Su - wuv S)/w.
    float invW = 1.0 / A.w;
    SurfacePartials d;
    d.s = A.xyz * invW; // relative to base while the derivatives are formed
    d.su = (Au.xyz - Au.w * d.s) * invW;
    d.sv = (Av.xyz - Av.w * d.s) * invW;
    d.suv = (Auv.xyz - Au.w * d.sv - Av.w * d.su - Auv.w * d.s) * invW;
#ifdef KW_SECOND_ORDER
    // A4.4 to second order: Suu = (Auu - 2 wu Su - wuu S)/w, likewise Svv.
    d.suu = (Auu.xyz - 2.0 * Au.w * d.su - Auu.w * d.s) * invW;
    d.svv = (Avv.xyz - 2.0 * Av.w * d.sv - Avv.w * d.s) * invW;
    d.s += base;
#endif
    return d;
}

#ifdef KW_SECOND_ORDER
// Any unit vector perpendicular to the unit vector n (kw::surfaceCurvature's anyPerpendicular:
// branch on the components so the cross product is never degenerate).
vec3 anyPerpendicular(vec3 n) {
    vec3 a = abs(n.x) < 0.6 ? vec3(1.0, 0.0, 0.0)
                            : (abs(n.y) < 0.6 ? vec3(0.0, 1.0, 0.0) : vec3(0.0, 0.0, 1.0));
    return normalize(cross(n, a));
}

// K, H, k1 >= k2 and k1's unit direction from the fundamental forms, as kw::surfaceCurvature
// (model/nurbs/nurbs_curvature.cpp, Do Carmo 3.3): positive where the surface bends away from the unit
// normal n, which must be Su x Sv or its opposite. The shape operator is the symmetric 2x2
// matrix [[a, b], [b, c]] in the orthonormal tangent basis e1 = Su/|Su|, e2 = n x e1: with
// Sv = alpha e1 + beta e2, (u, v) = J (x, y), J = [[1/|Su|, -alpha/(|Su| beta)], [0, 1/beta]],
// and the operator is -J^T II J. Its eigenvalues (a + c)/2 +- hypot((a - c)/2, b) have no
// cancellation at umbilics, and k1's eigenvector is at angle atan2(b, (a - c)/2)/2 from e1.
vec4 curvatureFrom(SurfacePartials d, vec3 n, out vec3 dir1) {
    float L = dot(d.suu, n), M = dot(d.suv, n), N = dot(d.svv, n);
    float lsu = length(d.su);
    vec3 e1 = d.su / lsu;
    vec3 e2 = cross(n, e1);
    float alpha = dot(d.sv, e1);
    float beta = dot(d.sv, e2); // +-|Su x Sv| / |Su|, not 0 at a regular point
    float j11 = 1.0 / lsu, j12 = -alpha / (lsu * beta), j22 = 1.0 / beta;
    float a = -(L * j11 * j11);
    float b = -(L * j11 * j12 + M * j11 * j22);
    float c = -(L * j12 * j12 + 2.0 * M * j12 * j22 + N * j22 * j22);
    float half_ = 0.5 * (a - c);
    float r = length(vec2(half_, b));
    float H = 0.5 * (a + c);
    vec4 k = vec4(a * c - b * b, H, H + r, H - r);
    // atan(0, 0) is undefined in GLSL; the kernel's atan2 gives 0 there (any direction at an
    // umbilic), so e1.
    float theta = (half_ == 0.0 && b == 0.0) ? 0.0 : 0.5 * atan(b, half_);
    dir1 = cos(theta) * e1 + sin(theta) * e2;
    // Never NaN or infinite (float overflow on extreme inputs): the zero answer, as the kernel.
    bool bad = any(isnan(k)) || any(isinf(k)) || any(isnan(dir1)) || any(isinf(dir1));
    if (bad)
        dir1 = anyPerpendicular(n);
    return bad ? vec4(0.0) : k;
}

#endif

// Step 1 of the rule: the plain normal Su x Sv, when neither partial is tiny and they are not
// parallel. tinyU/tinyV report the tiny tests for step 2.
bool plainNormal(SurfacePartials d, float tinyLen, out vec3 n, out bool tinyU, out bool tinyV) {
    vec2 width = vec2(uDomain.y - uDomain.x, uDomain.w - uDomain.z);
    // Both are tiny when the span's control points coincide (L = 0, so tinyLen = 0).
    bool collapsed = !(tinyLen > 0.0);
    tinyU = collapsed || !(length(d.su) * width.x > tinyLen);
    tinyV = collapsed || !(length(d.sv) * width.y > tinyLen);
    n = cross(d.su, d.sv);
    float ln = length(n);
    if (tinyU || tinyV || !(ln > KW_PARALLEL_REL * length(d.su) * length(d.sv)))
        return false;
    n /= ln;
    return true;
}

// The normal rule of kw::surfaceFrame, steps 1-4 (comment above it in model/nurbs/nurbs_surface.cpp);
// thresholds are scaled for float arithmetic (KW_TINY_REL, KW_PARALLEL_REL). It takes one or two
// rounds: round 0 with the partials at uv, round 1 (where that gives no plain normal, or with
// KW_SECOND_ORDER no curvature) with those of a nearby interior point. beginSurfaceSample sets
// up, and surfaceSampleRound takes round `round`'s partials `d`: true when the sample is
// complete, else `at` is where round 1 evaluates (in the same span: the step is tiny). Split so
// that a caller which already holds round 0's partials (the skirts' solve) does not evaluate
// them again.
void beginSurfaceSample(out SurfaceSample s, out bool limitNormal) {
    s.point = vec3(0.0);
    s.du = vec3(0.0);
    s.dv = vec3(0.0);
    s.normal = vec3(0.0, 0.0, 1.0);
#ifdef KW_SECOND_ORDER
    s.curvature = vec4(0.0); // step 4: no regular point nearby
    s.dir1 = vec3(1.0, 0.0, 0.0);
#endif
    limitNormal = false; // step 2 gave the normal; the curvature still needs step 3
}
bool surfaceSampleRound(SurfacePartials d, int round, vec2 uv, float spanScale,
                        inout SurfaceSample s, inout bool limitNormal, out vec2 at) {
    vec2 width = vec2(uDomain.y - uDomain.x, uDomain.w - uDomain.z);
    vec2 centre = 0.5 * vec2(uDomain.x + uDomain.y, uDomain.z + uDomain.w);
    float tinyLen = KW_TINY_REL * spanScale;
    at = uv;
    if (round == 0) {
        s.point = d.s + uOrigin;
        s.du = d.su;
        s.dv = d.sv;
    }
    bool tinyU, tinyV;
    vec3 n;
    if (plainNormal(d, tinyLen, n, tinyU, tinyV)) {
        if (!limitNormal)
            s.normal = n;
#ifdef KW_SECOND_ORDER
        s.curvature = curvatureFrom(d, dot(n, s.normal) < 0.0 ? -n : n, s.dir1);
        // At a collapsed edge: tangent to the reported (limit) normal, as the kernel.
        if (round == 1)
            s.dir1 = normalize(s.dir1 - dot(s.dir1, s.normal) * s.normal);
#endif
        return true;
    }
    if (round == 1) {
        if (!limitNormal)
            s.normal = vec3(0.0, 0.0, 1.0); // step 4
#ifdef KW_SECOND_ORDER
        s.dir1 = anyPerpendicular(s.normal);
#endif
        return true;
    }
    if (tinyU != tinyV) { // step 2: the limit normal, approached from the domain's interior
        vec3 other = tinyU ? d.sv : d.su;
        vec3 m = tinyU ? (uv.y < centre.y ? 1.0 : -1.0) * cross(d.suv, d.sv)
                       : (uv.x < centre.x ? 1.0 : -1.0) * cross(d.su, d.suv);
        float lm = length(m);
        if (length(d.suv) * width.x * width.y > tinyLen &&
            lm > KW_PARALLEL_REL * length(d.suv) * length(other)) {
            s.normal = m / lm;
            limitNormal = true;
#ifndef KW_SECOND_ORDER
            return true;
#endif
        }
    }
    // Step 3: the plain normal (and the curvature) of a nearby interior point.
    at = uv + sign(centre - uv) * KW_INTERIOR_STEP * width;
    return false;
}
SurfaceSample evaluateSurface(vec2 uv, ivec2 span, float spanScale) {
    SurfaceSample s;
    bool limitNormal;
    beginSurfaceSample(s, limitNormal);
    // One evaluation site for both rounds: the second runs only for fragments (SIMD lanes) that
    // need it, and the code is not duplicated.
    vec2 at = uv;
    for (int round = 0; round < 2; ++round)
        if (surfaceSampleRound(surfacePartials(at, span), round, uv, spanScale, s, limitNormal,
                               at))
            break;
    return s;
}
