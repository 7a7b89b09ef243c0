// NURBS validation: explains in plain English why a knot vector, surface or curve is unusable.
#include "model/nurbs/nurbs.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

namespace kw {
namespace {

/// Shortest decimal text that reads back as the same double ("0.2", "nan", "-inf").
std::string num(double x) {
    char buf[64];
    const auto res = std::to_chars(buf, buf + sizeof buf, x);
    return std::string(buf, res.ptr);
}

std::string num(std::int64_t x) {
    return std::to_string(x);
}

/// Checks one knot vector. `dir` is "" for a curve and "U" / "V" for a surface direction;
/// it names the vector in the message ("knot vector U has ...", "U: degree 0 is below 1").
std::string knotError(const std::vector<double>& knots, int degree, int count,
                      std::string_view dir) {
    const std::string prefix = dir.empty() ? std::string() : std::string(dir) + ": ";
    const std::string name = dir.empty() ? "knot vector" : "knot vector " + std::string(dir);
    if (degree < 1)
        return prefix + "degree " + num(std::int64_t(degree)) + " is below 1";
    if (degree > kMaxDegree)
        return prefix + "degree " + num(std::int64_t(degree)) + " is above the maximum " +
               num(std::int64_t(kMaxDegree));
    if (count < degree + 1)
        return prefix + num(std::int64_t(count)) + " control points are too few for degree " +
               num(std::int64_t(degree)) +
               " (need at least degree + 1 = " + num(std::int64_t(degree + 1)) + ")";
    const std::int64_t expected = std::int64_t(count) + degree + 1;
    if (std::int64_t(knots.size()) != expected)
        return name + " has " + num(std::int64_t(knots.size())) + " knots, expected " +
               num(expected) + " (count " + num(std::int64_t(count)) + " + degree " +
               num(std::int64_t(degree)) + " + 1)";
    for (size_t k = 0; k < knots.size(); ++k) {
        if (!std::isfinite(knots[k]))
            return prefix + "knot " + num(std::int64_t(k)) + " (" + num(knots[k]) +
                   ") is not finite";
    }
    for (size_t k = 1; k < knots.size(); ++k) {
        if (knots[k] < knots[k - 1])
            return prefix + "knot " + num(std::int64_t(k)) + " (" + num(knots[k]) +
                   ") is less than knot " + num(std::int64_t(k - 1)) + " (" + num(knots[k - 1]) +
                   ")";
    }
    for (size_t k = 0; k < knots.size();) {
        size_t e = k;
        while (e + 1 < knots.size() && knots[e + 1] == knots[k])
            ++e;
        const std::int64_t mult = std::int64_t(e - k + 1);
        if (mult > degree + 1)
            return prefix + "knot " + num(knots[k]) + " has multiplicity " + num(mult) +
                   ", above degree + 1 = " + num(std::int64_t(degree + 1));
        k = e + 1;
    }
    const double first = knots[size_t(degree)];
    const double last = knots[size_t(count)];
    if (!(first < last))
        return prefix + "the domain [" + num(first) + ", " + num(last) + "] (knots " +
               num(std::int64_t(degree)) + " and " + num(std::int64_t(count)) + ") is empty";
    return {};
}

bool finite3(const glm::dvec3& p) {
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

std::string text(const glm::dvec3& p) {
    return "(" + num(p.x) + ", " + num(p.y) + ", " + num(p.z) + ")";
}

std::string text(const glm::dvec2& p) {
    return "(" + num(p.x) + ", " + num(p.y) + ")";
}

std::string surfaceProblem(const NurbsSurface& s) {
    if (std::string e = knotError(s.knotsU, s.degreeU, s.countU, "U"); !e.empty())
        return e;
    if (std::string e = knotError(s.knotsV, s.degreeV, s.countV, "V"); !e.empty())
        return e;
    const std::int64_t n = std::int64_t(s.countU) * s.countV;
    const std::string grid = " (countU " + num(std::int64_t(s.countU)) + " x countV " +
                             num(std::int64_t(s.countV)) + ")";
    if (std::int64_t(s.points.size()) != n)
        return "surface has " + num(std::int64_t(s.points.size())) + " control points, expected " +
               num(n) + grid;
    if (std::int64_t(s.weights.size()) != n)
        return "surface has " + num(std::int64_t(s.weights.size())) + " weights, expected " +
               num(n) + grid;
    // The place is spelt out only for an error: building it for every point made validation
    // of a 5000-point net cost 15000 string allocations (the document validates every edit).
    const auto where = [](int i, int j) {
        return "control point (" + num(std::int64_t(i)) + ", " + num(std::int64_t(j)) + ")";
    };
    for (int j = 0; j < s.countV; ++j) {
        for (int i = 0; i < s.countU; ++i) {
            const glm::dvec3& p = s.points[size_t(s.index(i, j))];
            if (!finite3(p))
                return where(i, j) + " has a non-finite coordinate " + text(p);
            const double w = s.weights[size_t(s.index(i, j))];
            if (!(std::isfinite(w) && w > 0.0))
                return "weight of " + where(i, j) + " is " + num(w) + ", must be finite and > 0";
        }
    }
    return {};
}

std::string curveProblem(const NurbsCurve2& c) {
    if (c.points.size() > size_t(INT32_MAX))
        return "curve has too many control points";
    const int count = int(c.points.size());
    if (std::string e = knotError(c.knots, c.degree, count, ""); !e.empty())
        return e;
    if (c.weights.size() != c.points.size())
        return "curve has " + num(std::int64_t(c.weights.size())) + " weights, expected " +
               num(std::int64_t(count)) + " (one per control point)";
    for (int i = 0; i < count; ++i) {
        const glm::dvec2& p = c.points[size_t(i)];
        if (!(std::isfinite(p.x) && std::isfinite(p.y)))
            return "control point " + num(std::int64_t(i)) + " has a non-finite coordinate " +
                   text(p);
        const double w = c.weights[size_t(i)];
        if (!(std::isfinite(w) && w > 0.0))
            return "weight of control point " + num(std::int64_t(i)) + " is " + num(w) +
                   ", must be finite and > 0";
    }
    return {};
}

/// The reason as the kernel's result: the messages are built as std::string by the checks
/// above (std::to_chars gives the shortest text that reads back as the same double).
Status reasonStatus(const std::string& why) {
    if (why.empty())
        return ok();
    return Error(QString::fromStdString(why));
}

} // namespace

Status checkKnotVector(const std::vector<double>& knots, int degree, int count) {
    return reasonStatus(knotError(knots, degree, count, ""));
}

Status checkNurbsSurface(const NurbsSurface& s) {
    return reasonStatus(surfaceProblem(s));
}

Status checkNurbsCurve(const NurbsCurve2& c) {
    return reasonStatus(curveProblem(c));
}

} // namespace kw
