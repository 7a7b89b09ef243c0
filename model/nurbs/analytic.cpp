// Closed forms of analytic faces: points, normals, parameter maps and ray intersections.
#include "model/nurbs/analytic_eval.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace kw {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTwoPi = 2.0 * std::numbers::pi;

using Kind = AnalyticForm::Kind;

bool finite(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// +1 for a right-handed frame (X x Y = Z), -1 for an indirect one.
double handedness(const AnalyticForm& f) {
    return glm::dot(glm::cross(f.xAxis, f.yAxis), f.zAxis) < 0.0 ? -1.0 : 1.0;
}

double phi(const AnalyticParamMap& m, double s) {
    return m.offset + m.scale * s;
}

// The analytic parameter of NURBS parameter s (the header's AnalyticParamMap). A HalfAngle
// span is a rational quadratic arc in standard form, whose angle runs as the half-angle
// (stereographic) parametrisation: tan((angle - m) / 2) is linear in t (The NURBS Book, 7.3).
double mapForward(const AnalyticParamMap& m, const std::vector<double>& knots, double s) {
    if (m.kind == AnalyticParamMap::Kind::Linear || knots.size() < 2)
        return phi(m, s);
    s = std::clamp(s, knots.front(), knots.back());
    const size_t k = std::min<size_t>(
        size_t(std::upper_bound(knots.begin(), knots.end(), s) - knots.begin()), knots.size() - 1);
    const double s0 = knots[k - 1], s1 = knots[k];
    const double a0 = phi(m, s0), a1 = phi(m, s1);
    const double t = (s - s0) / (s1 - s0);
    const double d = a1 - a0, mid = 0.5 * (a0 + a1);
    return mid + 2.0 * std::atan((2.0 * t - 1.0) * std::tan(0.25 * d));
}

// The NURBS parameter of analytic parameter x (angles modulo 2 pi for HalfAngle maps); nullopt
// when x is outside the direction's range by more than `slack`.
std::optional<double> mapInverse(const AnalyticParamMap& m, const std::vector<double>& knots,
                                 double x, double slack) {
    const double s0 = knots.front(), s1 = knots.back();
    const double lo = std::min(phi(m, s0), phi(m, s1)), hi = std::max(phi(m, s0), phi(m, s1));
    const double angleSlack = slack * (hi - lo);
    if (m.kind == AnalyticParamMap::Kind::Linear) {
        const double s = (x - m.offset) / m.scale;
        const double tol = slack * (s1 - s0);
        if (!(s >= s0 - tol && s <= s1 + tol))
            return std::nullopt;
        return std::clamp(s, s0, s1);
    }
    // The turn of x that lies in [lo, hi] (the first, when the range spans more than one).
    const double base = lo - angleSlack;
    double y = x - kTwoPi * std::floor((x - base) / kTwoPi);
    if (y > hi + angleSlack)
        return std::nullopt;
    y = std::clamp(y, lo, hi);
    for (size_t k = 1; k < knots.size(); ++k) {
        const double a0 = phi(m, knots[k - 1]), a1 = phi(m, knots[k]);
        if (y < std::min(a0, a1) || y > std::max(a0, a1))
            continue;
        const double d = a1 - a0, mid = 0.5 * (a0 + a1);
        const double t = 0.5 * (1.0 + std::tan(0.5 * (y - mid)) / std::tan(0.25 * d));
        return knots[k - 1] + std::clamp(t, 0.0, 1.0) * (knots[k] - knots[k - 1]);
    }
    return std::clamp((x - m.offset) / m.scale, s0, s1);
}

double sign(double x) {
    return x < 0.0 ? -1.0 : 1.0;
}

void push(AnalyticRayHits& hits, double t) {
    if (hits.count < 4)
        hits.t[hits.count++] = t;
}

// Roots of a x^2 + b x + c = 0 appended to `hits`, without the cancellation of the textbook
// formula (Numerical Recipes, 5.6).
void quadraticRoots(double a, double b, double c, AnalyticRayHits& hits) {
    if (a == 0.0) {
        if (b != 0.0)
            push(hits, -c / b);
        return;
    }
    const double disc = b * b - 4.0 * a * c;
    if (disc < 0.0)
        return;
    const double q = -0.5 * (b + sign(b) * std::sqrt(disc));
    if (q == 0.0) { // b == 0 and c == 0: a double root at 0
        push(hits, 0.0);
        return;
    }
    push(hits, q / a);
    push(hits, c / q);
}

// The largest real root of the monic cubic x^3 + a x^2 + b x + c (Numerical Recipes, 5.6:
// Viete's trigonometric form for three real roots, Cardano's otherwise), polished by Newton.
double largestCubicRoot(double a, double b, double c) {
    const double q = (a * a - 3.0 * b) / 9.0;
    const double r = (2.0 * a * a * a - 9.0 * a * b + 27.0 * c) / 54.0;
    double x;
    if (r * r < q * q * q) {
        const double theta = std::acos(std::clamp(r / std::sqrt(q * q * q), -1.0, 1.0));
        x = -2.0 * std::sqrt(q) * std::cos((theta - kTwoPi) / 3.0) - a / 3.0;
    } else {
        const double A = -sign(r) * std::cbrt(std::abs(r) + std::sqrt(r * r - q * q * q));
        const double B = A == 0.0 ? 0.0 : q / A;
        x = A + B - a / 3.0;
    }
    for (int i = 0; i < 4; ++i) {
        const double f = ((x + a) * x + b) * x + c;
        const double df = (3.0 * x + 2.0 * a) * x + b;
        if (df == 0.0)
            break;
        const double step = f / df;
        x -= step;
        if (std::abs(step) <= 1e-16 * std::max(1.0, std::abs(x)))
            break;
    }
    return x;
}

// Real roots of the monic quartic x^4 + a x^3 + b x^2 + c x + d by Ferrari's method: with
// x = y - a/4, y^4 + p y^2 + q y + r = (y^2 + p/2 + m)^2 - 2m (y - q / 4m)^2 for the root m > 0
// of the resolvent 8m^3 + 8p m^2 + (2p^2 - 8r) m - q^2; two quadratics follow. Each root is
// then polished by Newton steps on the quartic itself, which the resolvent's rounding
// otherwise leaves a few digits short near tangent rays.
void quarticRoots(double a, double b, double c, double d, AnalyticRayHits& hits) {
    const double a2 = a * a;
    const double p = b - 3.0 * a2 / 8.0;
    const double q = c - a * b / 2.0 + a2 * a / 8.0;
    const double r = d - a * c / 4.0 + a2 * b / 16.0 - 3.0 * a2 * a2 / 256.0;
    AnalyticRayHits y;
    const double scale = std::max({std::abs(p), std::sqrt(std::abs(r)), 1e-300});
    if (std::abs(q) <= 1e-14 * scale * std::sqrt(scale)) {
        // Biquadratic: y^2 = z with z^2 + p z + r = 0.
        AnalyticRayHits z;
        quadraticRoots(1.0, p, r, z);
        for (int i = 0; i < z.count; ++i)
            if (z.t[i] >= 0.0) {
                const double s = std::sqrt(z.t[i]);
                push(y, s);
                if (s != 0.0)
                    push(y, -s);
            }
    } else {
        const double m = largestCubicRoot(p, p * p / 4.0 - r, -q * q / 8.0);
        if (!(m > 0.0))
            return;
        const double s = std::sqrt(2.0 * m);
        quadraticRoots(1.0, -s, p / 2.0 + m + q / (2.0 * s), y);
        quadraticRoots(1.0, s, p / 2.0 + m - q / (2.0 * s), y);
    }
    for (int i = 0; i < y.count; ++i) {
        double x = y.t[i] - a / 4.0;
        for (int it = 0; it < 3; ++it) {
            const double f = (((x + a) * x + b) * x + c) * x + d;
            const double df = ((4.0 * x + 3.0 * a) * x + 2.0 * b) * x + c;
            if (df == 0.0)
                break;
            const double step = f / df;
            // A step larger than the root's scale means a near-double root: keep the estimate.
            if (!std::isfinite(step) || std::abs(step) > 1e-3 * std::max(1.0, std::abs(x)))
                break;
            x -= step;
        }
        push(hits, x);
    }
}

// The ray in the form's frame: coordinates along X, Y, Z from the origin.
struct LocalRay {
    glm::dvec3 o, d;
};
LocalRay toLocal(const AnalyticForm& f, const glm::dvec3& origin, const glm::dvec3& dir) {
    const glm::dvec3 o = origin - f.origin;
    return {{glm::dot(o, f.xAxis), glm::dot(o, f.yAxis), glm::dot(o, f.zAxis)},
            {glm::dot(dir, f.xAxis), glm::dot(dir, f.yAxis), glm::dot(dir, f.zAxis)}};
}

} // namespace

std::vector<double> distinctKnots(const std::vector<double>& knots, int degree) {
    const Interval d = knotDomain(knots, degree);
    std::vector<double> out;
    for (double k : knots)
        if (k >= d.first && k <= d.last && (out.empty() || k > out.back()))
            out.push_back(k);
    return out;
}

const char* analyticKindName(AnalyticForm::Kind kind) {
    switch (kind) {
    case Kind::None:
        break;
    case Kind::Plane:
        return "plane";
    case Kind::Cylinder:
        return "cylinder";
    case Kind::Cone:
        return "cone";
    case Kind::Sphere:
        return "sphere";
    case Kind::Torus:
        return "torus";
    }
    return "none";
}

std::optional<AnalyticForm::Kind> analyticKindNamed(const std::string& name) {
    for (Kind k : {Kind::None, Kind::Plane, Kind::Cylinder, Kind::Cone, Kind::Sphere, Kind::Torus})
        if (name == analyticKindName(k))
            return k;
    return std::nullopt;
}

namespace {

/// checkAnalyticForm's rules, the reason as plain text.
std::string analyticFormProblem(const AnalyticForm& f, const NurbsSurface& geometry) {
    if (f.kind == Kind::None)
        return {};
    if (!finite(f.origin) || !finite(f.xAxis) || !finite(f.yAxis) || !finite(f.zAxis))
        return "the frame is not finite";
    for (const glm::dvec3& axis : {f.xAxis, f.yAxis, f.zAxis})
        if (std::abs(glm::length(axis) - 1.0) > 1e-9)
            return "an axis of the frame is not of unit length";
    if (std::abs(glm::dot(f.xAxis, f.yAxis)) > 1e-9 ||
        std::abs(glm::dot(f.yAxis, f.zAxis)) > 1e-9 || std::abs(glm::dot(f.zAxis, f.xAxis)) > 1e-9)
        return "the axes of the frame are not orthogonal";
    if (!std::isfinite(f.radius) || !std::isfinite(f.minorRadius) || !std::isfinite(f.semiAngle))
        return "a radius or the semi-angle is not finite";
    switch (f.kind) {
    case Kind::None:
    case Kind::Plane:
        break;
    case Kind::Cone:
        if (!(f.radius >= 0.0))
            return "a cone's radius must be >= 0";
        if (!(std::abs(f.semiAngle) > 0.0 && std::abs(f.semiAngle) < kPi / 2))
            return "a cone's semi-angle must lie strictly between 0 and pi/2 in magnitude";
        break;
    case Kind::Torus:
        if (!(f.minorRadius > 0.0))
            return "a torus's minor radius must be > 0";
        [[fallthrough]];
    case Kind::Cylinder:
    case Kind::Sphere:
        if (!(f.radius > 0.0))
            return "the radius must be > 0";
        break;
    }
    for (const AnalyticParamMap* m : {&f.u, &f.v}) {
        if (!std::isfinite(m->offset) || !std::isfinite(m->scale) || m->scale == 0.0)
            return "a parameter map's offset and scale must be finite, the scale non-zero";
        if (m->kind != AnalyticParamMap::Kind::HalfAngle)
            continue;
        const bool alongU = m == &f.u;
        if (checkNurbsSurface(geometry).has_value()) {
            if ((alongU ? geometry.degreeU : geometry.degreeV) != 2)
                return "a half-angle map needs a direction of degree 2";
            const std::vector<double> k =
                alongU ? distinctKnots(geometry.knotsU, 2) : distinctKnots(geometry.knotsV, 2);
            for (size_t i = 1; i < k.size(); ++i)
                if (!(std::abs(m->scale * (k[i] - k[i - 1])) < kPi))
                    return "a half-angle map turns by pi or more in one knot span";
        }
    }
    return {};
}

} // namespace

Status checkAnalyticForm(const AnalyticForm& f, const NurbsSurface& geometry) {
    if (const std::string why = analyticFormProblem(f, geometry); !why.empty())
        return Error(QString::fromStdString(why));
    return ok();
}

glm::dvec3 analyticPoint(const AnalyticForm& f, double a, double b) {
    const glm::dvec3 radial = std::cos(a) * f.xAxis + std::sin(a) * f.yAxis;
    switch (f.kind) {
    case Kind::None:
        break;
    case Kind::Plane:
        return f.origin + a * f.xAxis + b * f.yAxis;
    case Kind::Cylinder:
        return f.origin + f.radius * radial + b * f.zAxis;
    case Kind::Cone:
        return f.origin + (f.radius + b * std::sin(f.semiAngle)) * radial +
               b * std::cos(f.semiAngle) * f.zAxis;
    case Kind::Sphere:
        return f.origin + f.radius * std::cos(b) * radial + f.radius * std::sin(b) * f.zAxis;
    case Kind::Torus:
        return f.origin + (f.radius + f.minorRadius * std::cos(b)) * radial +
               f.minorRadius * std::sin(b) * f.zAxis;
    }
    return f.origin;
}

// Pa x Pb in closed form, with h the frame's handedness (X x Z = -h Y, Y x Z = h X):
// plane h Z; cylinder h D (D = cos a X + sin a Y); cone h (R + b sin) (cos D - sin Z); sphere
// h R^2 cos b (cos b D + sin b Z); torus h r (R + r cos b) (cos b D + sin b Z). The NURBS's
// Su x Sv is that times (da/du)(db/dv), whose signs are the maps' scales', negated when
// swapped (Su x Sv is then a multiple of Pb x Pa).
glm::dvec3 analyticNormal(const AnalyticForm& f, double a, double b) {
    const double h = handedness(f) * sign(f.u.scale) * sign(f.v.scale) * (f.swapped ? -1.0 : 1.0);
    const glm::dvec3 radial = std::cos(a) * f.xAxis + std::sin(a) * f.yAxis;
    glm::dvec3 n(0.0);
    switch (f.kind) {
    case Kind::None:
        return glm::dvec3(0.0, 0.0, 1.0);
    case Kind::Plane:
        n = f.zAxis;
        break;
    case Kind::Cylinder:
        n = radial;
        break;
    case Kind::Cone: {
        const double rho = f.radius + b * std::sin(f.semiAngle);
        n = sign(rho) * (std::cos(f.semiAngle) * radial - std::sin(f.semiAngle) * f.zAxis);
        break;
    }
    case Kind::Sphere:
        n = std::cos(b) * radial + std::sin(b) * f.zAxis; // cos b >= 0 on [-pi/2, pi/2]
        n *= sign(std::cos(b));
        break;
    case Kind::Torus:
        n = sign(f.radius + f.minorRadius * std::cos(b)) *
            (std::cos(b) * radial + std::sin(b) * f.zAxis);
        break;
    }
    return h * glm::normalize(n);
}

glm::dvec2 analyticParameters(const AnalyticForm& f, const NurbsSurface& g, double u, double v) {
    const Interval du = surfaceDomainU(g), dv = surfaceDomainV(g);
    u = std::clamp(u, du.first, du.last);
    v = std::clamp(v, dv.first, dv.last);
    const double x = mapForward(f.u, distinctKnots(g.knotsU, g.degreeU), u);
    const double y = mapForward(f.v, distinctKnots(g.knotsV, g.degreeV), v);
    return f.swapped ? glm::dvec2(y, x) : glm::dvec2(x, y);
}

std::optional<glm::dvec2> nurbsParameters(const AnalyticForm& f, const NurbsSurface& g, double a,
                                          double b) {
    const double x = f.swapped ? b : a, y = f.swapped ? a : b;
    const std::optional<double> u = mapInverse(f.u, distinctKnots(g.knotsU, g.degreeU), x, 1e-9);
    const std::optional<double> v = mapInverse(f.v, distinctKnots(g.knotsV, g.degreeV), y, 1e-9);
    if (!u || !v)
        return std::nullopt;
    return glm::dvec2(*u, *v);
}

glm::dvec2 analyticProject(const AnalyticForm& f, const glm::dvec3& point) {
    const glm::dvec3 p = point - f.origin;
    const double x = glm::dot(p, f.xAxis), y = glm::dot(p, f.yAxis), z = glm::dot(p, f.zAxis);
    const double angle = std::atan2(y, x), rho = std::hypot(x, y);
    switch (f.kind) {
    case Kind::None:
    case Kind::Plane:
        return {x, y};
    case Kind::Cylinder:
        return {angle, z};
    case Kind::Cone: {
        const double b = z / std::cos(f.semiAngle);
        // The other nappe (radius R + b sin < 0) has its points at angle a + pi.
        if (f.radius + b * std::sin(f.semiAngle) < 0.0)
            return {std::atan2(-y, -x), b};
        return {angle, b};
    }
    case Kind::Sphere:
        return {angle, std::atan2(z, rho)};
    case Kind::Torus:
        // A spindle torus (r > R) has points where R + r cos b < 0: those lie at angle a + pi.
        // Of the two meridians through the point, the one whose tube circle it is on.
        if (std::abs(std::hypot(rho + f.radius, z) - f.minorRadius) <
            std::abs(std::hypot(rho - f.radius, z) - f.minorRadius))
            return {std::atan2(-y, -x), std::atan2(z, -rho - f.radius)};
        return {angle, std::atan2(z, rho - f.radius)};
    }
    return {x, y};
}

AnalyticRayHits analyticRayHits(const AnalyticForm& f, const glm::dvec3& origin,
                                const glm::dvec3& dir) {
    AnalyticRayHits hits;
    const double len = glm::length(dir);
    if (f.kind == Kind::None || !(len > 0.0) || !std::isfinite(len))
        return hits;
    // Solve along the unit direction from the ray's point nearest the frame's origin: the
    // coefficients then stay of the surface's size whatever the origin's distance (a camera far
    // away would otherwise cancel most digits of the torus's quartic).
    const LocalRay raw = toLocal(f, origin, dir / len);
    const double t0 = -glm::dot(raw.o, raw.d);
    const glm::dvec3 o = raw.o + t0 * raw.d, d = raw.d;
    switch (f.kind) {
    case Kind::None:
        break;
    case Kind::Plane:
        if (d.z != 0.0)
            push(hits, -o.z / d.z);
        break;
    case Kind::Cylinder:
        quadraticRoots(d.x * d.x + d.y * d.y, 2.0 * (o.x * d.x + o.y * d.y),
                       o.x * o.x + o.y * o.y - f.radius * f.radius, hits);
        break;
    case Kind::Cone: {
        // x^2 + y^2 = (R + z tan)^2: b = z / cos, radius R + b sin.
        const double k = std::tan(f.semiAngle);
        const double rz = f.radius + o.z * k;
        quadraticRoots(d.x * d.x + d.y * d.y - d.z * d.z * k * k,
                       2.0 * (o.x * d.x + o.y * d.y - rz * d.z * k),
                       o.x * o.x + o.y * o.y - rz * rz, hits);
        break;
    }
    case Kind::Sphere:
        quadraticRoots(1.0, 2.0 * glm::dot(o, d), glm::dot(o, o) - f.radius * f.radius, hits);
        break;
    case Kind::Torus: {
        // (|p|^2 + R^2 - r^2)^2 = 4 R^2 (x^2 + y^2) with p = o + s d, |d| = 1:
        // |p|^2 = s^2 + 2 (o.d) s + |o|^2 = s^2 + e s + g (e = 0 after the shift above, kept for
        // exactness), x^2 + y^2 = A s^2 + B s + C.
        const double R2 = f.radius * f.radius, r2 = f.minorRadius * f.minorRadius;
        const double e = 2.0 * glm::dot(o, d), g = glm::dot(o, o) + R2 - r2;
        const double A = d.x * d.x + d.y * d.y, B = 2.0 * (o.x * d.x + o.y * d.y),
                     C = o.x * o.x + o.y * o.y;
        // (s^2 + e s + g)^2 - 4 R^2 (A s^2 + B s + C)
        quarticRoots(2.0 * e, e * e + 2.0 * g - 4.0 * R2 * A, 2.0 * e * g - 4.0 * R2 * B,
                     g * g - 4.0 * R2 * C, hits);
        break;
    }
    }
    int kept = 0;
    for (int i = 0; i < hits.count; ++i)
        if (std::isfinite(hits.t[i]))
            hits.t[kept++] = (hits.t[i] + t0) / len;
    hits.count = std::min(kept, 4);
    // Insertion sort of at most four (std::sort's threshold of 16 draws a false -Warray-bounds).
    for (int i = 1; i < hits.count; ++i)
        for (int j = i; j > 0 && hits.t[j] < hits.t[j - 1]; --j)
            std::swap(hits.t[j], hits.t[j - 1]);
    return hits;
}

double analyticDeviation(const AnalyticForm& f, const NurbsSurface& g, int samples) {
    if (f.kind == Kind::None || !checkNurbsSurface(g) || samples < 1)
        return std::numeric_limits<double>::infinity();
    const Interval du = surfaceDomainU(g), dv = surfaceDomainV(g);
    std::vector<double> us, vs;
    for (int i = 0; i <= samples; ++i) {
        us.push_back(du.first + (du.last - du.first) * i / samples);
        vs.push_back(dv.first + (dv.last - dv.first) * i / samples);
    }
    // Span midpoints: where a wrong HalfAngle map (a linear one, a shifted knot) strays most.
    const std::vector<double> ku = distinctKnots(g.knotsU, g.degreeU),
                              kv = distinctKnots(g.knotsV, g.degreeV);
    for (size_t k = 1; k < ku.size(); ++k)
        us.push_back(0.5 * (ku[k - 1] + ku[k]));
    for (size_t k = 1; k < kv.size(); ++k)
        vs.push_back(0.5 * (kv[k - 1] + kv[k]));
    double worst = 0.0;
    for (double u : us)
        for (double v : vs) {
            const glm::dvec2 ab = analyticParameters(f, g, u, v);
            const double dist = glm::length(surfacePoint(g, u, v) - analyticPoint(f, ab.x, ab.y));
            if (!std::isfinite(dist))
                return std::numeric_limits<double>::infinity();
            worst = std::max(worst, dist);
        }
    return worst;
}

double analyticMatchLimit(const NurbsSurface& g) {
    glm::dvec3 lo, hi;
    surfaceControlBounds(g, lo, hi);
    return 1e-6 * glm::length(hi - lo);
}

AnalyticForm analyticTransformed(const AnalyticForm& f, const glm::dmat3& m, const glm::dvec3& t) {
    AnalyticForm out = f;
    if (f.kind == Kind::None)
        return out;
    const double s = std::cbrt(std::abs(glm::determinant(m)));
    out.origin = m * f.origin + t;
    out.xAxis = glm::normalize(m * f.xAxis);
    out.yAxis = glm::normalize(m * f.yAxis);
    out.zAxis = glm::normalize(m * f.zAxis);
    out.radius = f.radius * s;
    out.minorRadius = f.minorRadius * s;
    for (AnalyticParamMap* p : {&out.u, &out.v})
        if (p->kind == AnalyticParamMap::Kind::Linear) {
            p->offset *= s;
            p->scale *= s;
        }
    return out;
}

std::optional<AnalyticForm> analyticFollow(const AnalyticForm& form, const NurbsSurface& from,
                                           const NurbsSurface& to) {
    if (form.kind == Kind::None || from.degreeU != to.degreeU || from.degreeV != to.degreeV ||
        from.countU != to.countU || from.countV != to.countV || from.knotsU != to.knotsU ||
        from.knotsV != to.knotsV || from.weights != to.weights ||
        from.points.size() != to.points.size() || from.points.empty())
        return std::nullopt;
    const std::vector<glm::dvec3>& p = from.points;
    const std::vector<glm::dvec3>& q = to.points;
    // Three points of `from` spanning a triangle as large as the net allows: the first, the
    // one farthest from it, and the one farthest from the line through both.
    size_t ib = 0, ic = 0;
    double far = 0.0, area = 0.0;
    for (size_t i = 0; i < p.size(); ++i)
        if (const double d = glm::length(p[i] - p[0]); d > far)
            far = d, ib = i;
    const glm::dvec3 e1 = p[ib] - p[0];
    for (size_t i = 0; i < p.size(); ++i)
        if (const double a = glm::length(glm::cross(e1, p[i] - p[0])); a > area)
            area = a, ic = i;
    if (!(far > 0.0) || !(area > 1e-9 * far * far))
        return std::nullopt;
    const glm::dvec3 e2 = p[ic] - p[0], e3 = glm::cross(e1, e2);
    const glm::dvec3 f1 = q[ib] - q[0], f2 = q[ic] - q[0];
    const double s = glm::length(f1) / glm::length(e1);
    if (!(s > 0.0) || !std::isfinite(s))
        return std::nullopt;
    glm::dvec3 lo = q[0], hi = q[0];
    double reach = 0.0;
    for (const glm::dvec3& x : q) {
        lo = glm::min(lo, x), hi = glm::max(hi, x);
        reach = std::max({reach, std::abs(x.x), std::abs(x.y), std::abs(x.z)});
    }
    // A few hundred ulps of the coordinates: what a transform computed in double leaves, while
    // any edit a user makes is far larger.
    const double tol = 1e-13 * (glm::length(hi - lo) + reach);
    const glm::dmat3 inv = glm::inverse(glm::dmat3(e1, e2, e3));
    // A rotation maps e1 x e2 to f1 x f2 / s, a reflection to its opposite: for a planar net
    // both fit (and describe the same surface); otherwise the points decide.
    for (double side : {1.0, -1.0}) {
        const glm::dmat3 m = glm::dmat3(f1, f2, side * glm::cross(f1, f2) / s) * inv;
        const glm::dmat3 mtm = glm::transpose(m) * m;
        bool similar = true;
        for (int c = 0; c < 3 && similar; ++c)
            for (int r = 0; r < 3 && similar; ++r)
                similar = std::abs(mtm[c][r] - (c == r ? s * s : 0.0)) <= 1e-9 * s * s;
        const glm::dvec3 t = q[0] - m * p[0];
        for (size_t i = 0; i < p.size() && similar; ++i)
            similar = glm::length(m * p[i] + t - q[i]) <= tol;
        if (similar)
            return analyticTransformed(form, m, t);
    }
    return std::nullopt;
}

} // namespace kw
