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

// The analytic parameter phi(s) of NURBS parameter s in the knot span `knots` (analytic.h's
// AnalyticParamMap), and its rate dphi/ds.
float kwMapForward(vec4 m, float s, vec2 knots) {
    if (m.x == 0.0)
        return m.y + m.z * s;
    float p0 = m.y + m.z * knots.x, p1 = m.y + m.z * knots.y;
    float t = (s - knots.x) / (knots.y - knots.x);
    return 0.5 * (p0 + p1) + 2.0 * atan((2.0 * t - 1.0) * tan(0.25 * (p1 - p0)));
}
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

// (a, b) of a point p on (or next to) the form, the angles taken nearest `near`.
vec2 kwFormParams(AnalyticFrame f, vec3 p, vec2 near) {
    if (f.kind == KW_FORM_PLANE)
        return p.xy;
    float a = atan(p.y, p.x), b;
    if (f.kind == KW_FORM_CYLINDER) {
        b = p.z;
    } else if (f.kind == KW_FORM_CONE) {
        b = p.z / f.cosA;
        if (f.R + b * f.sinA < 0.0) // the other nappe: the radius is negative there
            a += KW_PI;
    } else if (f.kind == KW_FORM_SPHERE) {
        b = atan(p.z, length(p.xy));
        if (length(p.xy) == 0.0)
            a = near.x; // a pole: every a is that point
    } else {
        // A spindle torus (r > R) has points where R + r cos b < 0, on the far side of the axis
        // from the direction a: the one of the two readings the point satisfies.
        float rho = length(p.xy);
        float outer = abs(length(vec2(rho - f.R, p.z)) - f.r);
        float across = abs(length(vec2(rho + f.R, p.z)) - f.r);
        if (across < outer) {
            a += KW_PI;
            rho = -rho;
        }
        b = atan(p.z, rho - f.R);
        b += 2.0 * KW_PI * round((near.y - b) / (2.0 * KW_PI));
    }
    a += 2.0 * KW_PI * round((near.x - a) / (2.0 * KW_PI));
    return vec2(a, b);
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
// double precision, each polished by two Newton steps on the quartic: their count.
int kwQuarticRoots(double c3, double c2, double c1, double c0, out vec4 result) {
    double s = c3 / 4.0;
    double p = c2 - 6.0 * s * s;
    double q = c1 - 2.0 * c2 * s + 8.0 * s * s * s;
    double r = c0 - c1 * s + c2 * s * s - 3.0 * s * s * s * s;
    // Resolvent m^3 + p m^2 + (p^2/4 - r) m - q^2/8 = 0: its largest root m >= 0.
    double a2 = p, a1 = 0.25 * p * p - r, a0 = -0.125 * q * q;
    double dp = a1 - a2 * a2 / 3.0;
    double dq = 2.0 * a2 * a2 * a2 / 27.0 - a2 * a1 / 3.0 + a0;
    double disc = dq * dq / 4.0 + dp * dp * dp / 27.0;
    double m;
    if (disc > 0.0) {
        double sd = sqrt(disc);
        double u = -dq / 2.0 + sd, v = -dq / 2.0 - sd;
        // Real cube roots (no double pow in GLSL): float, then a Newton step in double.
        double cu = double(sign(float(u)) * pow(abs(float(u)), 1.0 / 3.0));
        double cv = double(sign(float(v)) * pow(abs(float(v)), 1.0 / 3.0));
        if (cu != 0.0)
            cu -= (cu * cu * cu - u) / (3.0 * cu * cu);
        if (cv != 0.0)
            cv -= (cv * cv * cv - v) / (3.0 * cv * cv);
        m = cu + cv - a2 / 3.0;
    } else {
        float rho = sqrt(float(max(-dp / 3.0, 0.0)));
        float phi = rho > 0.0 ? acos(clamp(float(-dq / 2.0) / (rho * rho * rho), -1.0, 1.0)) : 0.0;
        m = double(2.0 * rho * cos(phi / 3.0)) - a2 / 3.0;
    }
    for (int k = 0; k < 2; ++k) { // polish the cubic's root
        double f = ((m + a2) * m + a1) * m + a0, df = (3.0 * m + 2.0 * a2) * m + a1;
        if (df != 0.0)
            m -= f / df;
    }
    m = max(m, 0.0);
    double roots[4];
    int n = 0;
    double w = sqrt(2.0 * m);
    if (w > 1e-12 * (1.0 + abs(p))) {
        for (int sgn = -1; sgn <= 1; sgn += 2) {
            // y^2 - sgn w y + p/2 + m + sgn q / (2 w) = 0
            double b = -double(sgn) * w, c = 0.5 * p + m + double(sgn) * q / (2.0 * w);
            double d = b * b - 4.0 * c;
            if (d >= 0.0) {
                double sd = sqrt(d);
                roots[n++] = 0.5 * (-b + sd) - s;
                roots[n++] = 0.5 * (-b - sd) - s;
            }
        }
    } else { // biquadratic: y^4 + p y^2 + r = 0
        double d = p * p - 4.0 * r;
        if (d >= 0.0) {
            double sd = sqrt(d);
            for (int k = 0; k < 2; ++k) {
                double y2 = 0.5 * (-p + (k == 0 ? sd : -sd));
                if (y2 >= 0.0) {
                    roots[n++] = sqrt(y2) - s;
                    roots[n++] = -sqrt(y2) - s;
                }
            }
        }
    }
    result = vec4(0.0);
    for (int k = 0; k < n; ++k) {
        double t = roots[k];
        for (int step = 0; step < 2; ++step) {
            double f = (((t + c3) * t + c2) * t + c1) * t + c0;
            double df = ((4.0 * t + 3.0 * c3) * t + 2.0 * c2) * t + c1;
            if (df != 0.0)
                t -= f / df;
        }
        result[k] = float(t);
    }
    return n;
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

// The point under the pixel on the face's analytic form, from the polygon's (u, v) `polyUv` in
// knot span `span`: the ray's first meeting with the face (in its domain, not trimmed away;
// where there is none, the meeting nearest the polygon's point, or where the ray misses, near a
// silhouette, its closest approach, put onto the form), its (u, v) clamped into the domain (the
// surface ends there, as the NURBS path clamps), `span` the span holding it, and the sample
// (with KW_SECOND_ORDER, the curvature of the NURBS at that (u, v)).
vec2 kwAnalyticPoint(vec2 polyUv, inout ivec2 span, float spanScale, out SurfaceSample s) {
    AnalyticFrame f = kwAnalyticFrame();
    bool swapped = f.mapU.w != 0.0;
    // The polygon's point on the form: where the root search starts.
    vec2 knotsU = spanKnotsU(span), knotsV = spanKnotsV(span);
    vec2 polyST = vec2(kwMapForward(f.mapU, polyUv.x, knotsU), kwMapForward(f.mapV, polyUv.y, knotsV));
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
    } else if (f.kind == KW_FORM_CYLINDER) {
        n = kwQuadraticRoots(dot(d.xy, d.xy), dot(o.xy, d.xy), dot(o.xy, o.xy) - f.R * f.R, roots);
    } else if (f.kind == KW_FORM_SPHERE) {
        n = kwQuadraticRoots(1.0, dot(o, d), dot(o, o) - f.R * f.R, roots);
    } else if (f.kind == KW_FORM_CONE) {
        // cos^2 (x^2 + y^2) = (R cos + z sin)^2
        float c2 = f.cosA * f.cosA, h = f.R * f.cosA + o.z * f.sinA;
        n = kwQuadraticRoots(c2 * dot(d.xy, d.xy) - f.sinA * f.sinA * d.z * d.z,
                             c2 * dot(o.xy, d.xy) - h * f.sinA * d.z,
                             c2 * dot(o.xy, o.xy) - h * h, roots);
    } else {
        // (|p|^2 + R^2 - r^2)^2 = 4 R^2 (x^2 + y^2), |d| = 1.
        dvec3 od = dvec3(o), dd = dvec3(d);
        double R2 = double(f.R) * double(f.R);
        double k = dot(od, od) + R2 - double(f.r) * double(f.r), b = dot(od, dd);
        double c3 = 4.0 * b;
        double c2 = 4.0 * b * b + 2.0 * k - 4.0 * R2 * dot(dd.xy, dd.xy);
        double c1 = 4.0 * b * k - 8.0 * R2 * dot(od.xy, dd.xy);
        double c0 = k * k - 4.0 * R2 * dot(od.xy, od.xy);
        n = kwQuarticRoots(c3, c2, c1, c0, roots);
        if (n == 0)
            n = -1; // missed: the polygon's point (roots.x = 0), put onto the form below
    }
    // Which meeting: the nearest to the eye whose (u, v) lies in the face's domain and is not
    // trimmed away, as a ray cast against the face alone would find (at a fold both meetings
    // are near the polygon's point, and the one in front is seen); where none is, the one
    // nearest the polygon's point, clamped onto the domain below. A loop over the roots in
    // order of depth: most pixels take the first.
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
    vec2 ab, uv;
    vec2 margin = 1e-6 * (uDomain.yw - uDomain.xz);
    for (int i = 0; i <= count; ++i) {
        int at = i < count ? i : chosen; // the last round: the fallback
        if (i < count && (n < 0 || !(t0 + roots[at] > 0.0)))
            continue;
        ab = kwFormParams(f, o + roots[at] * d, polyAb);
        vec2 period = vec2(f.kind == KW_FORM_PLANE ? 0.0 : 2.0 * KW_PI,
                           f.kind == KW_FORM_TORUS ? 2.0 * KW_PI : 0.0);
        vec2 st = swapped ? ab.yx : ab;
        period = swapped ? period.yx : period;
        st = vec2(kwIntoDomain(f.mapU, st.x, period.x, uDomain.x, uDomain.y),
                  kwIntoDomain(f.mapV, st.y, period.y, uDomain.z, uDomain.w));
        ab = swapped ? st.yx : st;
        vec2 lin = (st - vec2(f.mapU.y, f.mapV.y)) / vec2(f.mapU.z, f.mapV.z);
        ivec2 found = ivec2(kwAnalyticSpanU(lin.x, span.x), kwAnalyticSpanV(lin.y, span.y));
        knotsU = spanKnotsU(found);
        knotsV = spanKnotsV(found);
        uv = vec2(kwMapInverse(f.mapU, st.x, knotsU), kwMapInverse(f.mapV, st.y, knotsV));
        bool inDomain = all(greaterThanEqual(uv, uDomain.xz - margin)) &&
                        all(lessThanEqual(uv, uDomain.yw + margin));
#if defined(KW_TRIM) && !defined(KW_TRIM_AA)
        bool kept = inDomain && !trimmedAway(clamp(uv, uDomain.xz, uDomain.yw));
#else
        bool kept = inDomain;
#endif
        if (i == count || kept) {
            span = found;
            break;
        }
    }
    // Clamped into the domain and its span (the surface ends there, as the NURBS path clamps).
    vec2 inside = clamp(uv, max(uDomain.xz, vec2(knotsU.x, knotsV.x)),
                        min(uDomain.yw, vec2(knotsU.y, knotsV.y)));
    if (inside != uv) { // past the domain's edge: the edge's point, as the NURBS path shows
        uv = inside;
        vec2 st = vec2(kwMapForward(f.mapU, uv.x, knotsU), kwMapForward(f.mapV, uv.y, knotsV));
        ab = swapped ? st.yx : st;
    }
    vec3 p = kwFormPoint(f, ab, pa, pb);
    vec2 rate = vec2(kwMapRate(f.mapU, uv.x, knotsU), kwMapRate(f.mapV, uv.y, knotsV));
    // Su x Sv = rate.x rate.y (Pa x Pb), less when swapped (Su along Pb); a left-handed frame
    // turns the frame's cross product over.
    float side = sign(rate.x * rate.y) * (swapped ? -1.0 : 1.0) *
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
