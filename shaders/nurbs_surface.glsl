// Exact rational surface point, first partials and unit normal at (u, v) inside the knot span
// `span` (paper eqs. 3.1, 3.5-3.7; The NURBS Book A3.6 on homogeneous points, A4.4 quotient).
// Needs DEGREE_U and DEGREE_V; sums only the (p+1) x (q+1) non-zero terms.

uniform sampler2D uControl; // RGBA32F, texel (i, j) = (w P, w) of control point (i, j)
uniform sampler2D uSpansU;  // span tables (kw::packSpanTable), row = span - degree
uniform sampler2D uSpansV;
uniform vec4 uDomain;       // (u first, u last, v first, v last) of the surface

// Thresholds of the degenerate-normal rule; the CPU kernel uses the same values.
#define KW_DEGENERATE_EPS 1e-7
#define KW_INTERIOR_STEP 1e-4

#define BASIS_FN basisU
#define BASIS_P DEGREE_U
#define BASIS_TABLE uSpansU
#include "basis.glsl"
#undef BASIS_FN
#undef BASIS_P
#undef BASIS_TABLE
#define BASIS_FN basisV
#define BASIS_P DEGREE_V
#define BASIS_TABLE uSpansV
#include "basis.glsl"
#undef BASIS_FN
#undef BASIS_P
#undef BASIS_TABLE

struct SurfaceSample {
    vec3 point;
    vec3 du;
    vec3 dv;
    vec3 normal; // unit; the limit normal at collapsed edges (see normalAt)
};

struct SurfacePartials {
    vec3 s, su, sv, suv;
};

SurfacePartials surfacePartials(vec2 uv, ivec2 span) {
    float Nu[DEGREE_U + 1], dNu[DEGREE_U + 1];
    float Nv[DEGREE_V + 1], dNv[DEGREE_V + 1];
    basisU(span.x - DEGREE_U, uv.x, Nu, dNu);
    basisV(span.y - DEGREE_V, uv.y, Nv, dNv);
    vec4 A = vec4(0.0), Au = vec4(0.0), Av = vec4(0.0), Auv = vec4(0.0);
    ivec2 first = span - ivec2(DEGREE_U, DEGREE_V);
    for (int j = 0; j <= DEGREE_V; ++j) {
        vec4 row = vec4(0.0), rowU = vec4(0.0);
        for (int i = 0; i <= DEGREE_U; ++i) {
            vec4 c = texelFetch(uControl, first + ivec2(i, j), 0);
            row += Nu[i] * c;
            rowU += dNu[i] * c;
        }
        A += Nv[j] * row;
        Av += dNv[j] * row;
        Au += Nv[j] * rowU;
        Auv += dNv[j] * rowU;
    }
    // A4.4 to first order: S = A/w, Su = (Au - wu S)/w, Suv = (Auv - wu Sv - wv Su - wuv S)/w.
    float invW = 1.0 / A.w;
    SurfacePartials d;
    d.s = A.xyz * invW;
    d.su = (Au.xyz - Au.w * d.s) * invW;
    d.sv = (Av.xyz - Av.w * d.s) * invW;
    d.suv = (Auv.xyz - Au.w * d.sv - Av.w * d.su - Auv.w * d.s) * invW;
    return d;
}

// The normal rule of kw::surfaceFrame (model/nurbs.h). Returns false when even the limit
// normal vanishes; n is then undefined.
bool normalAt(vec2 uv, SurfacePartials d, out vec3 n) {
    n = cross(d.su, d.sv);
    float su2 = dot(d.su, d.su), sv2 = dot(d.sv, d.sv);
    if (dot(n, n) > KW_DEGENERATE_EPS * KW_DEGENERATE_EPS * su2 * sv2 && su2 > 0.0 && sv2 > 0.0) {
        n = normalize(n);
        return true;
    }
    // Collapsed edge: near v = v0 with Su = 0, Su(v0 + h) ~ h Suv, so N ~ h (Suv x Sv); the
    // sign of h is that of the direction towards the domain's interior. Likewise for Sv = 0.
    if (su2 <= sv2) {
        float h = (uv.y - uDomain.z) <= (uDomain.w - uv.y) ? 1.0 : -1.0;
        n = h * cross(d.suv, d.sv);
    } else {
        float h = (uv.x - uDomain.x) <= (uDomain.y - uv.x) ? 1.0 : -1.0;
        n = h * cross(d.su, d.suv);
    }
    float ref = max(dot(d.suv, d.suv), 1e-30) * max(su2, sv2);
    if (dot(n, n) > KW_DEGENERATE_EPS * KW_DEGENERATE_EPS * ref && dot(n, n) > 0.0) {
        n = normalize(n);
        return true;
    }
    return false;
}

SurfaceSample evaluateSurface(vec2 uv, ivec2 span) {
    SurfacePartials d = surfacePartials(uv, span);
    SurfaceSample s;
    s.point = d.s;
    s.du = d.su;
    s.dv = d.sv;
    if (!normalAt(uv, d, s.normal)) {
        // Both vanish: the normal of a nearby interior point, stepped towards the domain centre.
        vec2 centre = 0.5 * vec2(uDomain.x + uDomain.y, uDomain.z + uDomain.w);
        vec2 size = vec2(uDomain.y - uDomain.x, uDomain.w - uDomain.z);
        vec2 inner = uv + sign(centre - uv) * KW_INTERIOR_STEP * size;
        SurfacePartials e = surfacePartials(inner, span);
        if (!normalAt(inner, e, s.normal))
            s.normal = vec3(0.0, 0.0, 1.0);
    }
    return s;
}
