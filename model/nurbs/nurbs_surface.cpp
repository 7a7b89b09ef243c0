// Surface evaluation: rational derivatives (A3.6 + A4.4), frames with the degenerate-normal
// rule shared with the GPU shader, and control-point bounds.
#include "model/nurbs/nurbs_internal.h"

#include <algorithm>

namespace kw {
namespace {

using detail::kInteriorStep;
using detail::kParallelRel;
using detail::kTinyDerivativeRel;
using detail::LocalEval;

constexpr double kBinom[3][3] = {{1, 0, 0}, {1, 1, 0}, {1, 2, 1}};

// The NURBS Book, A3.6 (SurfaceDerivsAlg1) on homogeneous points Pw = (w P, w), to order 2,
// followed by A4.4 (RatSurfaceDerivs) for the derivatives of the rational quotient.
// The points are lifted relative to the span's corner control point nearest (u, v), O:
// (w (P - O), w), and O is added to S at the end (derivatives do not change under a
// translation). At a collapsed edge (a sphere's pole, a cone's apex) O is the collapsed point,
// its row lifts to exact zeros, and Su there is exactly zero as the normal rule expects; lifted
// about the model's origin, the rounding of w P times derivative basis functions of size
// 1 / (span width) gave Su a spurious size of ~1e-16 |P| / (span width), which after a knot
// inserted 1e-6 of the domain from another was above the rule's thresholds and turned the
// pole's normal. Elsewhere the rounding becomes relative to the span's size, not to |P|.
// Preconditions: detail::shapeOk(s); u, v inside the domain.
LocalEval evaluateSpan(const NurbsSurface& s, double u, double v) {
    const int pu = s.degreeU;
    const int pv = s.degreeV;
    const int spanU = findSpan(pu, s.knotsU, u);
    const int spanV = findSpan(pv, s.knotsV, v);
    double nu[3 * (kMaxDegree + 1)];
    double nv[3 * (kMaxDegree + 1)];
    basisFunctionDerivatives(spanU, u, pu, 2, s.knotsU, nu);
    basisFunctionDerivatives(spanV, v, pv, 2, s.knotsV, nv);
    const size_t su = size_t(spanU), sv = size_t(spanV);
    const int cornerU = u - s.knotsU[su] <= s.knotsU[su + 1] - u ? spanU - pu : spanU;
    const int cornerV = v - s.knotsV[sv] <= s.knotsV[sv + 1] - v ? spanV - pv : spanV;
    const glm::dvec3 origin = s.points[size_t(s.index(cornerU, cornerV))];

    glm::dvec4 a[3][3] = {}; // a[k][l]: d^(k+l) / du^k dv^l of the homogeneous surface
    glm::dvec3 lo(0.0), hi(0.0);
    for (int l = 0; l <= pv; ++l) {
        glm::dvec4 temp[3] = {};
        const int j = spanV - pv + l;
        for (int r = 0; r <= pu; ++r) {
            const size_t idx = size_t(s.index(spanU - pu + r, j));
            const glm::dvec3& p = s.points[idx];
            const double w = s.weights[idx];
            const glm::dvec4 pw((p - origin) * w, w);
            for (int k = 0; k < 3; ++k)
                temp[k] += nu[k * (pu + 1) + r] * pw;
            lo = (l == 0 && r == 0) ? p : glm::min(lo, p);
            hi = (l == 0 && r == 0) ? p : glm::max(hi, p);
        }
        for (int k = 0; k < 3; ++k)
            for (int m = 0; m <= 2 - k; ++m)
                a[k][m] += nv[m * (pv + 1) + l] * temp[k];
    }

    glm::dvec3 skl[3][3];
    for (int k = 0; k < 3; ++k) {
        for (int l = 0; l <= 2 - k; ++l) {
            glm::dvec3 x = glm::dvec3(a[k][l]);
            for (int j = 1; j <= l; ++j)
                x -= kBinom[l][j] * a[0][j].w * skl[k][l - j];
            for (int i = 1; i <= k; ++i) {
                x -= kBinom[k][i] * a[i][0].w * skl[k - i][l];
                glm::dvec3 x2(0.0);
                for (int j = 1; j <= l; ++j)
                    x2 += kBinom[l][j] * a[i][j].w * skl[k - i][l - j];
                x -= kBinom[k][i] * x2;
            }
            skl[k][l] = x / a[0][0].w;
        }
    }
    LocalEval out;
    out.d.s = origin + skl[0][0];
    out.d.su = skl[1][0];
    out.d.sv = skl[0][1];
    out.d.suu = skl[2][0];
    out.d.suv = skl[1][1];
    out.d.svv = skl[0][2];
    out.scale = glm::length(hi - lo);
    return out;
}

bool degenerateCross(const glm::dvec3& c, const glm::dvec3& a, const glm::dvec3& b) {
    const double lc = glm::length(c);
    return !(lc > kParallelRel * glm::length(a) * glm::length(b)) || !std::isfinite(lc);
}

} // namespace

namespace detail {
LocalEval evaluateLocal(const NurbsSurface& s, double u, double v) {
    return evaluateSpan(s, u, v);
}

bool regularPoint(const LocalEval& e, double wu, double wv) {
    const double tinyLen = kTinyDerivativeRel * e.scale;
    return e.scale > 0.0 && glm::length(e.d.su) * wu > tinyLen &&
           glm::length(e.d.sv) * wv > tinyLen &&
           !degenerateCross(glm::cross(e.d.su, e.d.sv), e.d.su, e.d.sv);
}
} // namespace detail

Interval surfaceDomainU(const NurbsSurface& s) {
    return knotDomain(s.knotsU, s.degreeU);
}
Interval surfaceDomainV(const NurbsSurface& s) {
    return knotDomain(s.knotsV, s.degreeV);
}

SurfaceDerivatives surfaceDerivatives(const NurbsSurface& s, double u, double v) {
    if (!detail::shapeOk(s))
        return {};
    return evaluateSpan(s, detail::clampTo(u, surfaceDomainU(s)),
                        detail::clampTo(v, surfaceDomainV(s)))
        .d;
}

glm::dvec3 surfacePoint(const NurbsSurface& s, double u, double v) {
    return surfaceDerivatives(s, u, v).s;
}

// The normal rule, exactly as the GLSL port implements it. Notation: (u, v) clamped to the
// domain [u0, u1] x [v0, v1]; wu = u1 - u0, wv = v1 - v0; L = diagonal of the axis-aligned
// bounds of the (pu+1)(pv+1) control points of the span containing (u, v); Su, Sv, Suv the
// rational partial derivatives there.
//  1. n = Su x Sv. "tinyU" := |Su| wu <= kTinyDerivativeRel L; "tinyV" := |Sv| wv <= same;
//     both are true when L = 0 (the span's control points coincide).
//     If neither is tiny and |n| > kParallelRel |Su| |Sv|, the normal is n / |n|.
//  2. If exactly one of tinyU, tinyV holds: if tinyU, m = sign * (Suv x Sv) with sign = +1
//     if v < (v0 + v1) / 2 else -1; if tinyV, m = sign * (Su x Suv) with sign = +1 if
//     u < (u0 + u1) / 2 else -1. The sign makes m the limit of n approached from the
//     domain's interior. m is accepted, as m / |m|, when |Suv| wu wv > kTinyDerivativeRel L
//     and |m| > kParallelRel |Suv| |Sv| (resp. |Su| |Suv|).
//  3. Otherwise step to (u', v') = (u + kInteriorStep wu sgn(uc - u), v + kInteriorStep wv
//     sgn(vc - v)) with (uc, vc) the domain centre and sgn(0) = 0, evaluate there (its own L)
//     and use n' = Su' x Sv' if it passes the test of step 1 (with L' > 0).
//  4. Otherwise (0, 0, 1). A non-finite result at any step counts as degenerate.
SurfaceFrame surfaceFrame(const NurbsSurface& s, double u, double v) {
    if (!detail::shapeOk(s))
        return {};
    u = detail::clampTo(u, surfaceDomainU(s));
    v = detail::clampTo(v, surfaceDomainV(s));
    return detail::frameAt(s, u, v, evaluateSpan(s, u, v));
}

namespace detail {
SurfaceFrame frameAt(const NurbsSurface& s, double u, double v, const LocalEval& e) {
    SurfaceFrame f;
    const Interval du = surfaceDomainU(s);
    const Interval dv = surfaceDomainV(s);
    const double wu = du.last - du.first;
    const double wv = dv.last - dv.first;
    f.point = e.d.s;
    f.du = e.d.su;
    f.dv = e.d.sv;

    const double tinyLen = kTinyDerivativeRel * e.scale;
    const double lu = glm::length(e.d.su) * wu;
    const double lv = glm::length(e.d.sv) * wv;
    const bool collapsed = !(e.scale > 0.0);
    const bool tinyU = collapsed || !(lu > tinyLen);
    const bool tinyV = collapsed || !(lv > tinyLen);
    const glm::dvec3 n = glm::cross(e.d.su, e.d.sv);
    if (!tinyU && !tinyV && !degenerateCross(n, e.d.su, e.d.sv)) { // step 1
        f.normal = n / glm::length(n);
        return f;
    }
    if (tinyU != tinyV) { // step 2
        const bool suvOk = glm::length(e.d.suv) * wu * wv > tinyLen;
        glm::dvec3 m;
        glm::dvec3 other;
        if (tinyU) {
            const double sign = v < 0.5 * (dv.first + dv.last) ? 1.0 : -1.0;
            m = sign * glm::cross(e.d.suv, e.d.sv);
            other = e.d.sv;
        } else {
            const double sign = u < 0.5 * (du.first + du.last) ? 1.0 : -1.0;
            m = sign * glm::cross(e.d.su, e.d.suv);
            other = e.d.su;
        }
        if (suvOk && !degenerateCross(m, e.d.suv, other)) {
            f.normal = m / glm::length(m);
            return f;
        }
    }
    // Step 3: the plain normal of a nearby interior point.
    const LocalEval e2 =
        evaluateSpan(s, detail::towardsInterior(u, du), detail::towardsInterior(v, dv));
    if (detail::regularPoint(e2, wu, wv)) {
        const glm::dvec3 n2 = glm::cross(e2.d.su, e2.d.sv);
        f.normal = n2 / glm::length(n2);
        return f;
    }
    f.normal = glm::dvec3(0.0, 0.0, 1.0); // step 4
    return f;
}
} // namespace detail

void surfaceControlBounds(const NurbsSurface& s, glm::dvec3& lo, glm::dvec3& hi) {
    if (s.points.empty()) {
        lo = hi = glm::dvec3(0.0);
        return;
    }
    lo = hi = s.points.front();
    for (const glm::dvec3& p : s.points) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
}

} // namespace kw
