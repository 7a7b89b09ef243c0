// Helpers for the kernel tests: seeded random knot vectors, surfaces and curves, tolerances.
#pragma once

#include "model/nurbs/nurbs.h"
#include "model/nurbs/nurbs_shapes.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace kwtest {

/// A valid knot vector for `degree` and `count` control points on [0, 1]-ish ranges: distinct
/// knot values separated by gaps within a factor 3 of each other (so finite differences stay
/// well conditioned), interior multiplicities drawn up to maxInteriorMult, clamped ends unless
/// `unclamped`.
inline std::vector<double> randomKnotsOnce(std::mt19937& rng, int degree, int count,
                                           int maxInteriorMult, bool unclamped) {
    std::uniform_real_distribution<double> gap(0.5, 1.5);
    std::uniform_int_distribution<int> multDist(1, std::max(1, maxInteriorMult));
    const int total = count + degree + 1;
    const int ends = unclamped ? 1 : degree + 1;
    // Interior knots: total - 2 * ends slots, filled with runs of random multiplicity.
    std::vector<int> mults;
    int left = total - 2 * ends;
    while (left > 0) {
        const int m = std::min(left, multDist(rng));
        mults.push_back(m);
        left -= m;
    }
    std::vector<double> knots;
    double x = std::uniform_real_distribution<double>(-1.0, 1.0)(rng);
    knots.insert(knots.end(), size_t(ends), x);
    for (int m : mults) {
        x += gap(rng);
        knots.insert(knots.end(), size_t(m), x);
    }
    x += gap(rng);
    knots.insert(knots.end(), size_t(ends), x);
    return knots;
}

/// As randomKnotsOnce, redrawn until valid (an unclamped draw can have an empty domain).
inline std::vector<double> randomKnots(std::mt19937& rng, int degree, int count,
                                       int maxInteriorMult, bool unclamped = false) {
    for (;;) {
        std::vector<double> k = randomKnotsOnce(rng, degree, count, maxInteriorMult, unclamped);
        if (kw::checkKnotVector(k, degree, count).has_value())
            return k;
    }
}

inline kw::NurbsSurface randomSurface(std::mt19937& rng, int degreeU, int degreeV, int countU,
                                      int countV, bool rational, int maxInteriorMult = 1,
                                      bool unclamped = false) {
    std::uniform_real_distribution<double> coord(-1.0, 1.0);
    std::uniform_real_distribution<double> weight(0.5, 2.0);
    kw::NurbsSurface s;
    s.degreeU = degreeU;
    s.degreeV = degreeV;
    s.countU = countU;
    s.countV = countV;
    s.knotsU = randomKnots(rng, degreeU, countU, maxInteriorMult, unclamped);
    s.knotsV = randomKnots(rng, degreeV, countV, maxInteriorMult, unclamped);
    for (int k = 0; k < countU * countV; ++k) {
        s.points.emplace_back(coord(rng), coord(rng), coord(rng));
        s.weights.push_back(rational ? weight(rng) : 1.0);
    }
    return s;
}

inline kw::NurbsCurve2 randomCurve(std::mt19937& rng, int degree, int count, bool rational,
                                   int maxInteriorMult = 1) {
    std::uniform_real_distribution<double> coord(-1.0, 1.0);
    std::uniform_real_distribution<double> weight(0.5, 2.0);
    kw::NurbsCurve2 c;
    c.degree = degree;
    c.knots = randomKnots(rng, degree, count, maxInteriorMult);
    for (int k = 0; k < count; ++k) {
        c.points.emplace_back(coord(rng), coord(rng));
        c.weights.push_back(rational ? weight(rng) : 1.0);
    }
    return c;
}

/// A parameter inside a random non-empty span, at least `margin` (fraction of the span) away
/// from its ends; span bounds are returned so callers can size finite-difference steps.
inline double randomInSpan(std::mt19937& rng, const std::vector<double>& knots, int degree,
                           double margin, double& spanWidth) {
    std::vector<int> spans;
    for (int k = degree; k + 1 < int(knots.size()) - degree; ++k)
        if (knots[size_t(k)] < knots[size_t(k + 1)])
            spans.push_back(k);
    const int k = spans[std::uniform_int_distribution<size_t>(0, spans.size() - 1)(rng)];
    const double a = knots[size_t(k)];
    const double b = knots[size_t(k + 1)];
    spanWidth = b - a;
    return a + (b - a) * std::uniform_real_distribution<double>(margin, 1.0 - margin)(rng);
}

/// The plane makePlane(origin, edgeU, edgeV) elevated to degree 3 x 2 and refined at u = 0.2,
/// 0.7 and v = 0.3, as the editor's commands do: the same plane with 6 x 4 control points on
/// uneven knots (an affine surface of higher degree, kw::surfaceIsAffine).
inline kw::NurbsSurface refinedPlane(const glm::dvec3& origin, const glm::dvec3& edgeU,
                                     const glm::dvec3& edgeV) {
    using namespace kw;
    NurbsSurface s =
        surfaceElevateDegreeV(surfaceElevateDegreeU(makePlane(origin, edgeU, edgeV), 2), 1);
    s = surfaceInsertKnotU(surfaceInsertKnotU(s, 0.2), 0.7);
    return surfaceInsertKnotV(s, 0.3);
}

/// Diagonal of the control-point bounds: the length scale for relative tolerances.
inline double controlScale(const kw::NurbsSurface& s) {
    glm::dvec3 lo, hi;
    kw::surfaceControlBounds(s, lo, hi);
    return glm::length(hi - lo);
}

} // namespace kwtest
