// Exact NURBS constructors: the 9-point rational circle and surfaces of revolution (A8.1).
#include "model/nurbs/nurbs_shapes.h"

#include <cmath>

namespace kw {
namespace {

const double kHalfSqrt2 = std::sqrt(0.5);

/// Knots of the 9-point circle (The NURBS Book, Ex. 7.2): four quarter arcs.
const std::vector<double>& circleKnots() {
    static const std::vector<double> k = {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1};
    return k;
}

/// Control points of the unit 9-point circle, counter-clockwise from (1, 0).
const glm::dvec2 kUnitSquare[9] = {{1, 0},   {1, 1},  {0, 1},  {-1, 1}, {-1, 0},
                                   {-1, -1}, {0, -1}, {1, -1}, {1, 0}};

double circleWeight(int i) {
    return i % 2 == 0 ? 1.0 : kHalfSqrt2;
}

} // namespace

NurbsCurve2 makeCircle2(const glm::dvec2& center, double radius, bool clockwise) {
    NurbsCurve2 c;
    c.degree = 2;
    c.knots = circleKnots();
    for (int i = 0; i < 9; ++i) {
        glm::dvec2 q = kUnitSquare[i];
        if (clockwise)
            q.y = -q.y;
        c.points.push_back(center + radius * q);
        c.weights.push_back(circleWeight(i));
    }
    return c;
}

NurbsSurface makeRevolution(const glm::dvec3& center, const NurbsCurve2& profile) {
    NurbsSurface s;
    s.degreeU = 2;
    s.degreeV = profile.degree;
    s.countU = 9;
    s.countV = int(profile.points.size());
    s.knotsU = circleKnots();
    s.knotsV = profile.knots;
    s.points.reserve(size_t(s.countU) * size_t(s.countV));
    s.weights.reserve(s.points.capacity());
    for (int j = 0; j < s.countV; ++j) {
        const glm::dvec2 pr = profile.points[size_t(j)];
        const double wp = j < int(profile.weights.size()) ? profile.weights[size_t(j)] : 1.0;
        for (int i = 0; i < 9; ++i) {
            const glm::dvec2 q = kUnitSquare[i];
            s.points.push_back(center + glm::dvec3(pr.x * q.x, pr.x * q.y, pr.y));
            s.weights.push_back(circleWeight(i) * wp);
        }
    }
    return s;
}

NurbsSurface makeSphere(const glm::dvec3& center, double radius) {
    // Half circle in the (distance, height) plane from the south to the north pole:
    // two quarter arcs, 5 points, knots {0,0,0, 1/2,1/2, 1,1,1}.
    NurbsCurve2 half;
    half.degree = 2;
    half.knots = {0, 0, 0, 0.5, 0.5, 1, 1, 1};
    const double r = radius;
    half.points = {{0, -r}, {r, -r}, {r, 0}, {r, r}, {0, r}};
    half.weights = {1, kHalfSqrt2, 1, kHalfSqrt2, 1};
    return makeRevolution(center, half);
}

NurbsSurface makeCylinder(const glm::dvec3& baseCenter, double radius, double height) {
    NurbsCurve2 line;
    line.degree = 1;
    line.knots = {0, 0, 1, 1};
    line.points = {{radius, 0}, {radius, height}};
    line.weights = {1, 1};
    return makeRevolution(baseCenter, line);
}

NurbsSurface makeTorus(const glm::dvec3& center, double majorRadius, double minorRadius) {
    // The tube's cross-section, counter-clockwise in the (distance, height) plane from the
    // outer equator, so that Su x Sv points away from the tube's centre circle.
    return makeRevolution(center, makeCircle2({majorRadius, 0.0}, minorRadius));
}

NurbsSurface makeBilinear(const glm::dvec3& p00, const glm::dvec3& p10, const glm::dvec3& p01,
                          const glm::dvec3& p11) {
    NurbsSurface s;
    s.degreeU = s.degreeV = 1;
    s.countU = s.countV = 2;
    s.knotsU = s.knotsV = {0, 0, 1, 1};
    s.points = {p00, p10, p01, p11}; // index(i, j) = j * 2 + i
    s.weights = {1, 1, 1, 1};
    return s;
}

NurbsSurface makePlane(const glm::dvec3& origin, const glm::dvec3& edgeU, const glm::dvec3& edgeV) {
    return makeBilinear(origin, origin + edgeU, origin + edgeV, origin + edgeU + edgeV);
}

} // namespace kw
