// Kernel internals shared by the nurbs_*.cpp files: cheap shape checks and parameter clamping.
#pragma once

#include "model/nurbs/nurbs.h"

#include <cmath>
#include <cstdint>

namespace kw::detail {

/// O(1) consistency check that makes indexing safe (degrees, counts and array sizes agree).
/// It does not look at values; checkNurbsSurface does. Evaluation of a surface that fails
/// it returns zeros instead of reading out of bounds.
inline bool shapeOk(const NurbsSurface& s) {
    if (s.degreeU < 1 || s.degreeU > kMaxDegree || s.degreeV < 1 || s.degreeV > kMaxDegree)
        return false;
    if (s.countU < s.degreeU + 1 || s.countV < s.degreeV + 1)
        return false;
    const size_t n = size_t(s.countU) * size_t(s.countV);
    return s.knotsU.size() == size_t(s.countU) + size_t(s.degreeU) + 1 &&
           s.knotsV.size() == size_t(s.countV) + size_t(s.degreeV) + 1 && s.points.size() == n &&
           s.weights.size() == n;
}

/// Thresholds of the degenerate-normal rule (kw::surfaceFrame, mirrored by the GLSL port).
/// A first derivative is "tiny" when |Su| * widthU <= kTinyDerivativeRel * L, where widthU is
/// the width of the u domain and L the diagonal of the bounding box of the (degreeU+1) x
/// (degreeV+1) control points that act on the span containing (u, v). Both sides have the
/// units of length, so the test does not depend on the model's scale or parameterisation.
/// Likewise |Suv| * widthU * widthV <= kTinyDerivativeRel * L for the mixed derivative.
constexpr double kTinyDerivativeRel = 1e-8;
/// A cross product a x b is "degenerate" when |a x b| <= kParallelRel * |a| * |b|, i.e. the
/// sine of the angle between a and b is below kParallelRel.
constexpr double kParallelRel = 1e-10;
/// Step towards the domain centre, as a fraction of the domain width, for the last fallback.
constexpr double kInteriorStep = 1e-4;

/// Point operations (one combination of two homogeneous points for one line of the control
/// net) done by degree elevation on this thread so far. Lets the tests check that elevating by
/// t costs one pass, not t (the work is the answer's only witness that the tests can read).
std::uint64_t& elevationWork();

/// Derivatives to order 2 at a point plus the length scale of the span's control points.
struct LocalEval {
    SurfaceDerivatives d;
    double scale = 0.0; ///< diagonal of the bounds of the span's control points
};

/// A3.6 + A4.4 at (u, v). Preconditions: shapeOk(s); u, v inside the domain.
LocalEval evaluateLocal(const NurbsSurface& s, double u, double v);

/// surfaceFrame from an evaluation already made: e = evaluateLocal(s, u, v) with u, v clamped
/// to the domain (so a caller that needs the derivatives too evaluates once).
SurfaceFrame frameAt(const NurbsSurface& s, double u, double v, const LocalEval& e);

/// Step 1 of the normal rule: true when neither first partial is tiny (relative to e.scale and
/// the domain widths wu, wv) and Su x Sv is not degenerate, i.e. the plain normal is usable.
bool regularPoint(const LocalEval& e, double wu, double wv);

/// The parameter a step kInteriorStep * width towards the domain's centre (step 3 of the rule).
inline double towardsInterior(double t, const Interval& d) {
    const double c = 0.5 * (d.first + d.last);
    const double w = d.last - d.first;
    return t < c ? t + kInteriorStep * w : (t > c ? t - kInteriorStep * w : t);
}

inline bool shapeOk(const NurbsCurve2& c) {
    if (c.degree < 1 || c.degree > kMaxDegree || c.points.size() < size_t(c.degree + 1))
        return false;
    return c.knots.size() == c.points.size() + size_t(c.degree) + 1 &&
           c.weights.size() == c.points.size();
}

/// Clamps t to [d.first, d.last]; NaN maps to d.first.
inline double clampTo(double t, const Interval& d) {
    if (!(t > d.first))
        return d.first;
    return t < d.last ? t : d.last;
}

} // namespace kw::detail
