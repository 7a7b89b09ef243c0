// 2D curve evaluation: rational derivatives to order 2 (The NURBS Book, A3.2 + A4.2).
#include "model/nurbs/nurbs_internal.h"

namespace kw {

Interval curveDomain(const NurbsCurve2& c) {
    return knotDomain(c.knots, c.degree);
}

// The NURBS Book, A3.2 (CurveDerivsAlg1) on homogeneous points Pw = (w P, w), then A4.2
// (RatCurveDerivs): C' = (A' - w' C) / w and C'' = (A'' - 2 w' C' - w'' C) / w.
CurveDerivatives2 curveDerivatives(const NurbsCurve2& c, double t) {
    if (!detail::shapeOk(c))
        return {};
    const int p = c.degree;
    t = detail::clampTo(t, curveDomain(c));
    const int span = findSpan(p, c.knots, t);
    double n[3 * (kMaxDegree + 1)];
    basisFunctionDerivatives(span, t, p, 2, c.knots, n);
    glm::dvec3 a[3] = {};
    for (int j = 0; j <= p; ++j) {
        const size_t idx = size_t(span - p + j);
        const double w = c.weights[idx];
        const glm::dvec3 pw(c.points[idx] * w, w);
        for (int k = 0; k < 3; ++k)
            a[k] += n[k * (p + 1) + j] * pw;
    }
    CurveDerivatives2 out;
    const double w0 = a[0].z;
    out.point = glm::dvec2(a[0]) / w0;
    out.d1 = (glm::dvec2(a[1]) - a[1].z * out.point) / w0;
    out.d2 = (glm::dvec2(a[2]) - 2.0 * a[1].z * out.d1 - a[2].z * out.point) / w0;
    return out;
}

// The point alone: A2.2 (BasisFuns) gives the same basis values as row 0 of A2.3 (the same
// recurrence, the same operations), so this equals curveDerivatives(c, t).point bit for bit
// without the derivative rows, which cost most of the time when flattening trim loops (perf of
// fuzz_trim: 60 % of its time in basisFunctionDerivatives under curvePoint).
glm::dvec2 curvePoint(const NurbsCurve2& c, double t) {
    if (!detail::shapeOk(c))
        return {};
    const int p = c.degree;
    t = detail::clampTo(t, curveDomain(c));
    const int span = findSpan(p, c.knots, t);
    double n[kMaxDegree + 1];
    basisFunctions(span, t, p, c.knots, n);
    glm::dvec3 a(0.0);
    for (int j = 0; j <= p; ++j) {
        const size_t idx = size_t(span - p + j);
        const double w = c.weights[idx];
        const glm::dvec3 pw(c.points[idx] * w, w);
        a += n[j] * pw;
    }
    return glm::dvec2(a) / a.z;
}

} // namespace kw
