// Kernel internals shared by the nurbs_*.cpp files: cheap shape checks and parameter clamping.
#pragma once

#include "model/nurbs.h"

#include <cmath>

namespace kw::detail {

/// O(1) consistency check that makes indexing safe (degrees, counts and array sizes agree).
/// It does not look at values; surfaceValidationError does. Evaluation of a surface that fails
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
