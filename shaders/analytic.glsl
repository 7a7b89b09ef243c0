// A face's analytic form (kw::AnalyticForm: plane, cylinder, cone, sphere, torus) met by the
// pixel's ray in closed form (KW_ANALYTIC, with KW_RAY_NEWTON): a quadratic for the quadrics, a
// quartic for the torus, solved from the polygon's point so that the root wanted is the small
// one. Its (a, b) go to the NURBS's (u, v) through the form's parameter maps (their inverse,
// model/nurbs/analytic.h), and the point, tangents and normal come from the form. Needs
// nurbs_surface.glsl (the span tables, SurfaceSample), window.glsl (uViewport), uEye
// (phong.glsl) and uViewProjection.
#ifndef KW_ANALYTIC_GLSL
#define KW_ANALYTIC_GLSL

// kw::AnalyticEntry, kAnalyticTexels texels per surface row (kw::AnalyticTable).
layout(binding = KW_ANALYTIC_UNIT) uniform samplerBuffer kwAnalytic;
#define KW_ANALYTIC_ROW(k) texelFetch(kwAnalytic, kwSurface * KW_ANALYTIC_TEXELS + (k))
#define KW_PI 3.14159265358979

struct AnalyticFrame {
    vec3 o, x, y, z; // the frame, o relative to uOrigin
    int kind;        // KW_FORM_*
    float R, r, sinA, cosA;
    vec4 mapU, mapV; // kind (0 linear, 1 half angle), offset, scale; mapU.w: swapped
};

AnalyticFrame kwAnalyticFrame() {
    AnalyticFrame f;
    vec4 t0 = KW_ANALYTIC_ROW(0), t1 = KW_ANALYTIC_ROW(1), t2 = KW_ANALYTIC_ROW(2);
    vec4 t3 = KW_ANALYTIC_ROW(3);
    f.o = t0.xyz;
    f.kind = int(t0.w);
    f.x = t1.xyz;
    f.R = t1.w;
    f.y = t2.xyz;
    f.r = t2.w;
    f.z = t3.xyz;
    f.sinA = t3.w;
    f.mapU = KW_ANALYTIC_ROW(4);
    f.mapV = KW_ANALYTIC_ROW(5);
    f.cosA = f.mapV.w;
    return f;
}

// The rate dphi/ds of the analytic parameter phi(s) of NURBS parameter s in the knot span `knots`
// (analytic.h's AnalyticParamMap: linear, or a half angle, 2 atan((2t - 1) tan(turn / 4)) about
// the span's middle angle).
float kwMapRate(vec4 m, float s, vec2 knots) {
    if (m.x == 0.0)
        return m.z;
    float p0 = m.y + m.z * knots.x, p1 = m.y + m.z * knots.y;
    float t = (s - knots.x) / (knots.y - knots.x);
    float q = tan(0.25 * (p1 - p0)), w = (2.0 * t - 1.0) * q;
    return 4.0 * q / ((1.0 + w * w) * (knots.y - knots.x));
}
// The inverse: s of phi in the span `knots` (which must hold it).
float kwMapInverse(vec4 m, float phi, vec2 knots) {
    if (m.x == 0.0)
        return (phi - m.y) / m.z;
    float p0 = m.y + m.z * knots.x, p1 = m.y + m.z * knots.y;
    float t = 0.5 * (1.0 + tan(0.5 * (phi - 0.5 * (p0 + p1))) / tan(0.25 * (p1 - p0)));
    return knots.x + t * (knots.y - knots.x);
}

// The knot span holding s (clamped into the domain), walked to from `span`: usually the same or
// the next (the point under the pixel lies within the pixel tolerance of the polygon's), but a
// meeting on the far side of a closed face lies across the domain, and OpenCASCADE's circles
// have double knots (empty spans between the arcs), so the walk may take up to
// KW_ANALYTIC_SPAN_STEPS spans. Where the maps are half angles, phi is linear at the knots, so
// the span holding the linear estimate of s holds s itself.
#define KW_ANALYTIC_SPAN_STEPS 64
#define KW_ANALYTIC_NEAR 0.1 // kwAnalyticPoint: the window of the meetings it takes
int kwAnalyticSpanU(float s, int span) {
    for (int k = 0; k < KW_ANALYTIC_SPAN_STEPS; ++k) {
        vec2 knots = spanKnotsU(ivec2(span, 0));
        if (s >= knots.y && knots.y < uDomain.y)
            ++span;
        else if (s < knots.x && knots.x > uDomain.x)
            --span;
        else
            break;
    }
    return span;
}
int kwAnalyticSpanV(float s, int span) {
    for (int k = 0; k < KW_ANALYTIC_SPAN_STEPS; ++k) {
        vec2 knots = spanKnotsV(ivec2(0, span));
        if (s >= knots.y && knots.y < uDomain.w)
            ++span;
        else if (s < knots.x && knots.x > uDomain.z)
            --span;
        else
            break;
    }
    return span;
}

// The form's point and partials at (a, b), in its frame's coordinates (analytic.h's formulas).
vec3 kwFormPoint(AnalyticFrame f, vec2 ab, out vec3 pa, out vec3 pb) {
    float ca = cos(ab.x), sa = sin(ab.x), cb = cos(ab.y), sb = sin(ab.y);
    vec3 around = vec3(-sa, ca, 0.0), radial = vec3(ca, sa, 0.0);
    if (f.kind == KW_FORM_PLANE) {
        pa = vec3(1.0, 0.0, 0.0);
        pb = vec3(0.0, 1.0, 0.0);
        return vec3(ab, 0.0);
    }
    if (f.kind == KW_FORM_CYLINDER) {
        pa = f.R * around;
        pb = vec3(0.0, 0.0, 1.0);
        return vec3(f.R * radial.xy, ab.y);
    }
    if (f.kind == KW_FORM_CONE) {
        float rho = f.R + ab.y * f.sinA;
        pa = rho * around;
        pb = vec3(f.sinA * radial.xy, f.cosA);
        return vec3(rho * radial.xy, ab.y * f.cosA);
    }
    if (f.kind == KW_FORM_SPHERE) {
        pa = f.R * cb * around;
        pb = f.R * vec3(-sb * radial.xy, cb);
        return f.R * vec3(cb * radial.xy, sb);
    }
    float rho = f.R + f.r * cb; // torus
    pa = rho * around;
    pb = f.r * vec3(-sb * radial.xy, cb);
    return vec3(rho * radial.xy, f.r * sb);
}

// The unit normal along Pa x Pb (frame coordinates), defined at the sphere's poles and a cone's
// apex too.
vec3 kwFormNormal(AnalyticFrame f, vec2 ab) {
    float ca = cos(ab.x), sa = sin(ab.x), cb = cos(ab.y), sb = sin(ab.y);
    if (f.kind == KW_FORM_PLANE)
        return vec3(0.0, 0.0, 1.0);
    if (f.kind == KW_FORM_CYLINDER)
        return vec3(ca, sa, 0.0);
    if (f.kind == KW_FORM_CONE)
        return (f.R + ab.y * f.sinA < 0.0 ? -1.0 : 1.0) * vec3(f.cosA * ca, f.cosA * sa, -f.sinA);
    vec3 n = vec3(cb * ca, cb * sa, sb);
    return f.kind == KW_FORM_TORUS && f.R + f.r * cb < 0.0 ? -n : n;
}

// (a, b) of a point p on (or next to) the form, the angles taken nearest `near`. Written without
// branches on the kind and with one atan for b (the sphere's and the torus's): llvmpipe runs
// every branch of a divergent `if` under a mask, so each kind's atan cost every pixel.
vec2 kwFormParams(AnalyticFrame f, vec3 p, vec2 near) {
    float rho = length(p.xy);
    bool torus = f.kind == KW_FORM_TORUS, cone = f.kind == KW_FORM_CONE;
    // A spindle torus (r > R) has points where R + r cos b < 0, on the far side of the axis
    // from the direction a, and a cone's other nappe has a negative radius: the one of the two
    // readings the point satisfies.
    float outer = abs(length(vec2(rho - f.R, p.z)) - f.r);
    float across = abs(length(vec2(rho + f.R, p.z)) - f.r);
    float coneB = p.z / f.cosA;
    bool flip = torus ? across < outer : cone && f.R + coneB * f.sinA < 0.0;
    float a = atan(p.y, p.x) + (flip ? KW_PI : 0.0);
    if (f.kind == KW_FORM_SPHERE && rho == 0.0)
        a = near.x; // a pole: every a is that point
    a += 2.0 * KW_PI * round((near.x - a) / (2.0 * KW_PI));
    float b = atan(p.z, torus ? (flip ? -rho : rho) - f.R : rho); // sphere, torus
    b += torus ? 2.0 * KW_PI * round((near.y - b) / (2.0 * KW_PI)) : 0.0;
    b = f.kind == KW_FORM_CYLINDER ? p.z : cone ? coneB : b;
    return f.kind == KW_FORM_PLANE ? p.xy : vec2(a, b);
}

// An angle `phi` (period `period`, 0: not an angle) of the map `m` turned by whole turns so that
// its linear estimate of the NURBS parameter falls in [lo, hi] (to 1e-6 of it, as the domain
// test) where a turn can bring it there:
// taken next to the polygon's, a meeting on the far side of a closed face came out a turn off.
float kwIntoDomain(vec4 m, float phi, float period, float lo, float hi) {
    if (period > 0.0) {
        float lin = (phi - m.y) / m.z, turn = period / abs(m.z), margin = 1e-6 * (hi - lo);
        if (lin < lo - margin)
            phi += sign(m.z) * period * max(1.0, ceil((lo - lin) / turn - 1e-4));
        else if (lin > hi + margin)
            phi -= sign(m.z) * period * max(1.0, ceil((lin - hi) / turn - 1e-4));
    }
    return phi;
}

// The map parameters (phi_u, phi_v) of a point p on (or next to) the form: its (a, b) taken next
// to the polygon's `near`, ordered as the maps (`swapped`), each angle (`period`) turned into
// the domain.
vec2 kwAnalyticST(AnalyticFrame f, vec3 p, vec2 near, bool swapped, vec2 period) {
    vec2 ab = kwFormParams(f, p, near);
    vec2 st = swapped ? ab.yx : ab;
    return vec2(kwIntoDomain(f.mapU, st.x, period.x, uDomain.x, uDomain.y),
                kwIntoDomain(f.mapV, st.y, period.y, uDomain.z, uDomain.w));
}

// The roots of A t^2 + 2 B t + C = 0 (t from the polygon's point, so the one wanted is small),
// in the forms that lose no digits (Numerical Recipes 5.6): their count, or -1 where the ray
// misses (near a silhouette), roots.x then its closest approach to the quadric.
int kwQuadraticRoots(float A, float B, float C, out vec4 roots) {
    roots = vec4(0.0);
    float disc = B * B - A * C;
    if (!(disc >= 0.0)) {
        roots.x = abs(A) > 0.0 ? -B / A : 0.0;
        return -1;
    }
    float q = -(B + (B < 0.0 ? -1.0 : 1.0) * sqrt(disc));
    if (q == 0.0) { // B = 0 and C = 0 (or A C = 0 with disc 0): the root 0 (twice)
        return 1;
    }
    roots.x = C / q; // the smaller one
    if (A == 0.0)
        return 1;
    roots.y = q / A;
    return 2;
}

// The real roots of the monic quartic t^4 + c3 t^3 + c2 t^2 + c1 t + c0 (Ferrari: the depressed
// quartic factored into two quadratics through the largest root of its resolvent cubic), in
// float: estimates for kwTorusRoots's polish. Their count.
int kwQuarticRoots(float c3, float c2, float c1, float c0, out vec4 roots) {
    float s = 0.25 * c3;
    float p = c2 - 6.0 * s * s;
    float q = c1 - 2.0 * c2 * s + 8.0 * s * s * s;
    float r = c0 - c1 * s + c2 * s * s - 3.0 * s * s * s * s;
    // Resolvent m^3 + p m^2 + (p^2/4 - r) m - q^2/8 = 0: its largest root m >= 0.
    float a2 = p, a1 = 0.25 * p * p - r, a0 = -0.125 * q * q;
    float dp = a1 - a2 * a2 / 3.0;
    float dq = 2.0 * a2 * a2 * a2 / 27.0 - a2 * a1 / 3.0 + a0;
    float disc = 0.25 * dq * dq + dp * dp * dp / 27.0;
    float m;
    if (disc > 0.0) {
        float sd = sqrt(disc);
        float u = -0.5 * dq + sd, v = -0.5 * dq - sd;
        m = sign(u) * pow(abs(u), 1.0 / 3.0) + sign(v) * pow(abs(v), 1.0 / 3.0) - a2 / 3.0;
    } else {
        float rho = sqrt(max(-dp / 3.0, 0.0));
        float phi = rho > 0.0 ? acos(clamp(-0.5 * dq / (rho * rho * rho), -1.0, 1.0)) : 0.0;
        m = 2.0 * rho * cos(phi / 3.0) - a2 / 3.0;
    }
    for (int k = 0; k < 2; ++k) { // polish the cubic's root
        float f = ((m + a2) * m + a1) * m + a0, df = (3.0 * m + 2.0 * a2) * m + a1;
        m -= df != 0.0 ? f / df : 0.0;
    }
    m = max(m, 0.0);
    roots = vec4(0.0);
    int n = 0;
    float w = sqrt(2.0 * m);
    if (w > 1e-6 * (1.0 + abs(p))) {
        for (int sgn = -1; sgn <= 1; sgn += 2) {
            // y^2 - sgn w y + p/2 + m + sgn q / (2 w) = 0
            float b = -float(sgn) * w, c = 0.5 * p + m + float(sgn) * q / (2.0 * w);
            float d = b * b - 4.0 * c;
            if (d >= 0.0) {
                float sd = sqrt(d);
                roots[n++] = 0.5 * (-b + sd) - s;
                roots[n++] = 0.5 * (-b - sd) - s;
            }
        }
    } else { // biquadratic: y^4 + p y^2 + r = 0
        float d = p * p - 4.0 * r;
        if (d >= 0.0) {
            float sd = sqrt(d);
            for (int k = 0; k < 2; ++k) {
                float y2 = 0.5 * (-p + (k == 0 ? sd : -sd));
                if (y2 >= 0.0) {
                    roots[n++] = sqrt(y2) - s;
                    roots[n++] = -sqrt(y2) - s;
                }
            }
        }
    }
    return n;
}

// The torus (|p|^2 + R^2 - r^2)^2 = 4 R^2 (x^2 + y^2) met by the ray o + t d (|d| = 1, o next
// to the face): float throughout. G factors into the squared distances' differences to the
// tube circle and to its mirror across the axis, ((rho - R)^2 + z^2 - r^2) ((rho + R)^2 + z^2 -
// r^2), and each factor is computed as (q - r)(q + r) with q that distance: its error is then
// float's on the coordinates, not on their fourth powers, as in the quadrics. The constant term
// is G(o) in that form; the root taken is polished by two Newton steps on G at its point in the
// same form (kwTorusPolish; the double-precision Ferrari cost 15-20 ms of a 1024^2 frame on
// llvmpipe, which runs every kind's branch under a mask). Their count.
float kwTorusG(vec3 p, float R, float r) {
    float rho = length(p.xy);
    float outer = length(vec2(rho - R, p.z)), across = length(vec2(rho + R, p.z));
    return (outer - r) * (outer + r) * ((across - r) * (across + r));
}
int kwTorusRoots(vec3 o, vec3 d, float R, float r, out vec4 roots) {
    float R2 = R * R, k = dot(o, o) + R2 - r * r, b = dot(o, d);
    float c3 = 4.0 * b;
    float c2 = 4.0 * b * b + 2.0 * k - 4.0 * R2 * dot(d.xy, d.xy);
    float c1 = 4.0 * b * k - 8.0 * R2 * dot(o.xy, d.xy);
    return kwQuarticRoots(c3, c2, c1, kwTorusG(o, R, r), roots);
}
float kwTorusPolish(vec3 o, vec3 d, float R, float r, float t) {
    for (int step = 0; step < 2; ++step) {
        vec3 p = o + t * d;
        float dg = 4.0 * (dot(p, p) + R * R - r * r) * dot(p, d) - 8.0 * R * R * dot(p.xy, d.xy);
        t -= dg != 0.0 ? kwTorusG(p, R, r) / dg : 0.0;
    }
    return t;
}

// The world direction of this pixel's ray from the eye: the line where the clip x and y of a
// point are its w times the pixel's normalised device coordinates (two planes through the eye).
vec3 kwPixelRay() {
    vec2 ndc = (gl_FragCoord.xy - uViewport.xy) / uViewport.zw * 2.0 - 1.0;
    vec3 rx = vec3(uViewProjection[0][0], uViewProjection[1][0], uViewProjection[2][0]);
    vec3 ry = vec3(uViewProjection[0][1], uViewProjection[1][1], uViewProjection[2][1]);
    vec3 rw = vec3(uViewProjection[0][3], uViewProjection[1][3], uViewProjection[2][3]);
    vec3 d = cross(rx - ndc.x * rw, ry - ndc.y * rw);
    return normalize(dot(rw, d) < 0.0 ? -d : d);
}

#ifdef KW_COVER
// A cover's meeting must lie beyond the near plane (the polygon there is clipped; a box is
// not the face): at `t` along the pixel's ray `w` (world, unit) from the eye, clip z within
// w (depth 1 at the near plane, reversed).
bool kwBeyondNear(float t, vec3 w) {
    vec4 clip = uViewProjection * vec4(uEye + t * w, 1.0);
    return t > 0.0 && clip.w > 0.0 && clip.z <= clip.w;
}
#define KW_ANALYTIC_IN_FRONT(t) kwBeyondNear(t, w)
// The skirts' overlap past a face's edge, on screen (kw::ExactSurfacePass::kSkirtReachPixels):
// a polygon's skirt keeps a pixel whose ray meets the face's continuation that close to its
// edge (B-rep faces meet within the model's tolerance, not exactly), and the cover does too.
uniform float uSkirtReach;
#else
#define KW_ANALYTIC_IN_FRONT(t) ((t) > 0.0)
#endif

// Whether a meeting `p` (frame coordinates; map parameters `st`, their linear estimate `lin`)
// counts as in the face's domain: within 1e-6 of it (`margin`), or, for a cover, past its edge
// by at most uSkirtReach on screen from the edge's point (the clamped one the caller shows).
bool kwInDomain(AnalyticFrame f, bool swapped, vec3 p, vec2 st, vec2 lin, vec2 margin) {
    if (all(greaterThanEqual(lin, uDomain.xz - margin)) &&
        all(lessThanEqual(lin, uDomain.yw + margin)))
        return true;
#ifdef KW_COVER
    vec2 inside = clamp(lin, uDomain.xz, uDomain.yw);
    vec2 edgeSt = mix(st, vec2(f.mapU.y, f.mapV.y) + vec2(f.mapU.z, f.mapV.z) * inside,
                      notEqual(inside, lin));
    vec3 pa, pb;
    vec3 edge = kwFormPoint(f, swapped ? edgeSt.yx : edgeSt, pa, pb);
    mat3 frame = mat3(f.x, f.y, f.z);
    vec4 clip = uViewProjection * vec4(frame * edge + f.o + uOrigin, 1.0);
    return clip.w > 0.0 && length(kwWindowTangent(clip, frame * (p - edge))) <= uSkirtReach;
#else
    return false;
#endif
}

// The point under the pixel on the face's analytic form, from the polygon's (u, v) `polyUv` in
// knot span `span`: the ray's first meeting with the face (in its domain, not trimmed away;
// where there is none, the meeting nearest the polygon's point, or where the ray misses, near a
// silhouette, its closest approach, put onto the form), its (u, v) clamped into the domain (the
// surface ends there, as the NURBS path clamps), `span` the span holding it, and the sample
// (with KW_SECOND_ORDER, the curvature of the NURBS at that (u, v)). `away`: that point is
// trimmed away (tested here for each meeting, so the caller need not test it again).
vec2 kwAnalyticPoint(vec2 polyUv, inout ivec2 span, float spanScale, out SurfaceSample s,
                     out bool away) {
    AnalyticFrame f = kwAnalyticFrame();
    bool swapped = f.mapU.w != 0.0;
    // The polygon's point on the form: where the root search starts.
    vec2 knotsU, knotsV;
    // Its linear estimate (phi = offset + scale s, exact at the knots, a few degrees off within a
    // quarter arc) serves: the start only has to be near the face, for the shift below and to
    // take the angles next to it (the forward maps' atan and tan cost every pixel).
    vec2 polyST = vec2(f.mapU.y, f.mapV.y) + vec2(f.mapU.z, f.mapV.z) * polyUv;
    vec2 polyAb = swapped ? polyST.yx : polyST;
    vec3 pa, pb;
    vec3 start = kwFormPoint(f, polyAb, pa, pb);
    vec3 rel = uEye - uOrigin - f.o;
    vec3 eye = vec3(dot(rel, f.x), dot(rel, f.y), dot(rel, f.z));
    vec3 w = kwPixelRay();
    vec3 d = normalize(vec3(dot(w, f.x), dot(w, f.y), dot(w, f.z)));
    // Shifted to the polygon's point along the ray: the root wanted is then near 0 and the
    // constant term small, so float keeps its digits.
    float t0 = max(dot(start - eye, d), 0.0);
    vec3 o = eye + t0 * d;
    vec4 roots;
    int n;
    if (f.kind == KW_FORM_PLANE) {
        roots = vec4(abs(d.z) > 0.0 ? -o.z / d.z : 0.0, 0.0, 0.0, 0.0);
        n = abs(d.z) > 0.0 ? 1 : -1;
    } else if (f.kind != KW_FORM_TORUS) {
        // The quadrics as one: cos^2 (x^2 + y^2) = (R cos + z sin)^2 for the cone, with
        // (cos, sin) = (1, 0) the cylinder; the sphere adds z^2 (one solve: every branch costs).
        bool cone = f.kind == KW_FORM_CONE, sphere = f.kind == KW_FORM_SPHERE;
        float c = cone ? f.cosA : 1.0, sn = cone ? f.sinA : 0.0, zz = sphere ? 1.0 : 0.0;
        float c2 = c * c, h = f.R * c + o.z * sn;
        n = kwQuadraticRoots(c2 * dot(d.xy, d.xy) + (zz - sn * sn) * d.z * d.z,
                             c2 * dot(o.xy, d.xy) + (zz * o.z - h * sn) * d.z,
                             c2 * dot(o.xy, o.xy) + zz * o.z * o.z - h * h, roots);
    } else {
        n = kwTorusRoots(o, d, f.R, f.r, roots);
        if (n == 0)
            n = -1; // missed: the polygon's point (roots.x = 0), put onto the form below
    }
    // Which meeting: the nearest to the eye whose (u, v) lies in the face's domain and is not
    // trimmed away, as a ray cast against the face alone would find (at a fold both meetings
    // are near the polygon's point, and the one in front is seen); where none is, the one
    // nearest the polygon's point, clamped onto the domain below. The roots in order of depth.
    int count = max(n, 1);
    for (int i = 1; i < count; ++i) // insertion sort of at most 4
        for (int j = i; j > 0 && roots[j] < roots[j - 1]; --j) {
            float t = roots[j];
            roots[j] = roots[j - 1];
            roots[j - 1] = t;
        }
    int chosen = 0;
    for (int i = 1; i < count; ++i)
        if (abs(roots[i]) < abs(roots[chosen]))
            chosen = i;
    // The first of them in the face's domain, read in the maps' linear estimate of (u, v), which
    // is exact at the knots and so at the domain's ends (the maps are monotone): no span walk,
    // no tan and no trim test for the meetings a pixel passes over. `count`: none. Only a
    // meeting near the polygon's (u, v) (KW_ANALYTIC_NEAR of the domain: a fold's two meetings
    // are) counts: one across the face is another part of it, which its own polygon draws at
    // its own depth; taken here it was drawn at this polygon's depth, in front of the face that
    // hides it (Axis_of_bearing: 55 edge-band pixels showed a face behind the reference's, 36
    // with the window, 38 by the Newton step).
    vec2 period = vec2(f.kind == KW_FORM_PLANE ? 0.0 : 2.0 * KW_PI,
                       f.kind == KW_FORM_TORUS ? 2.0 * KW_PI : 0.0);
    period = swapped ? period.yx : period;
    vec2 offset = vec2(f.mapU.y, f.mapV.y), scale = vec2(f.mapU.z, f.mapV.z);
    vec2 margin = 1e-6 * (uDomain.yw - uDomain.xz);
    int first = count;
    vec2 turn = period / abs(scale); // a whole turn in (u, v); 0: not an angle
    for (int i = 0; i < count; ++i) {
        vec2 st = kwAnalyticST(f, o + roots[i] * d, polyAb, swapped, period);
        vec2 lin = (st - offset) / scale;
        vec2 apart = lin - polyUv; // across a closed face's seam: the short way
        apart = abs(apart - mix(vec2(0.0), turn * round(apart / turn), greaterThan(turn, vec2(0.0))));
#ifdef KW_COVER
        // A cover draws the face's first meeting wherever it lies, at its own exact depth.
        apart = vec2(0.0);
#endif
        if (n >= 0 && KW_ANALYTIC_IN_FRONT(t0 + roots[i]) &&
            all(lessThanEqual(apart, KW_ANALYTIC_NEAR * (uDomain.yw - uDomain.xz))) &&
            kwInDomain(f, swapped, o + roots[i] * d, st, lin, margin)) {
            first = i;
            break;
        }
    }
    // From there, the nearest not trimmed away; none: the fallback (round `count`). The trim
    // test is the costly part (made for every meeting in turn it cost a third of Pump_Nut's
    // frame), and nearly every pixel keeps its first meeting in the domain: one round, as a
    // loop leaves once no pixel of the SIMD group needs another.
    ivec2 from = span;
    vec2 st, uv;
    away = false;
    for (int i = first; i <= count; ++i) {
#ifdef KW_COVER
        if (i == count)
            discard; // no meeting in the domain (or all trimmed away): the box, not the face
#endif
        int at = i < count ? i : chosen;
        if (f.kind == KW_FORM_TORUS && n > 0)
            roots[at] = kwTorusPolish(o, d, f.R, f.r, roots[at]);
        st = kwAnalyticST(f, o + roots[at] * d, polyAb, swapped, period);
        vec2 lin = (st - offset) / scale;
        if (i < count && (n < 0 || !KW_ANALYTIC_IN_FRONT(t0 + roots[at]) ||
                          !kwInDomain(f, swapped, o + roots[at] * d, st, lin, margin)))
            continue;
        span = ivec2(kwAnalyticSpanU(lin.x, from.x), kwAnalyticSpanV(lin.y, from.y));
        knotsU = spanKnotsU(span);
        knotsV = spanKnotsV(span);
        uv = vec2(kwMapInverse(f.mapU, st.x, knotsU), kwMapInverse(f.mapV, st.y, knotsV));
#if defined(KW_TRIM) && !defined(KW_TRIM_AA)
        away = trimmedAway(clamp(uv, uDomain.xz, uDomain.yw));
#endif
        if (i == count || !away)
            break;
    }
    // Clamped into the domain and its span (the surface ends there, as the NURBS path clamps).
    vec2 inside = clamp(uv, max(uDomain.xz, vec2(knotsU.x, knotsV.x)),
                        min(uDomain.yw, vec2(knotsU.y, knotsV.y)));
    // Past the domain's edge: the edge's point, as the NURBS path shows. The clamped parameter
    // is a knot, where the map is linear (no forward map's atan and tan).
    st = mix(st, offset + scale * inside, notEqual(inside, uv));
    vec2 ab = swapped ? st.yx : st;
    uv = inside;
    vec3 p = kwFormPoint(f, ab, pa, pb);
    vec2 rate = vec2(kwMapRate(f.mapU, uv.x, knotsU), kwMapRate(f.mapV, uv.y, knotsV));
    // Su x Sv = rate.x rate.y (Pa x Pb), less when swapped (Su along Pb); a left-handed frame
    // turns the frame's cross product over. The rates have their scales' signs (a half-angle
    // span turns less than a half turn), so the rates' tan is paid only where S_u, S_v are used.
    float side = sign(f.mapU.z * f.mapV.z) * (swapped ? -1.0 : 1.0) *
                 sign(dot(cross(f.x, f.y), f.z));
    vec3 normal = kwFormNormal(f, ab) * side;
    mat3 frame = mat3(f.x, f.y, f.z);
#ifdef KW_SECOND_ORDER
    s = evaluateSurface(uv, span, spanScale); // the curvature of the NURBS at the exact (u, v)
#endif
    s.point = frame * p + f.o + uOrigin;
    s.du = frame * (swapped ? pb : pa) * rate.x;
    s.dv = frame * (swapped ? pa : pb) * rate.y;
    s.normal = normalize(frame * normal);
    return uv;
}

#endif // KW_ANALYTIC_GLSL
