// Probe refinement onto the pixel's ray and the texts of probe values and measurements.
#include "model/analysis/probe.h"

#include "model/nurbs/nurbs_curvature.h"

#include <QStringList>
#include <algorithm>
#include <cmath>
#include <limits>

namespace kw {
namespace {

/// The component of v across the ray, in the orthonormal basis (e1, e2) of the plane
/// perpendicular to the ray's direction.
glm::dvec2 across(const glm::dvec3& v, const glm::dvec3& e1, const glm::dvec3& e2) {
    return {glm::dot(v, e1), glm::dot(v, e2)};
}

QString num(double v, int digits) {
    if (std::isinf(v))
        return QStringLiteral("∞");
    return QString::number(v, 'g', digits);
}

QString vecText(const glm::dvec3& v, int digits) {
    return QStringLiteral("%1, %2, %3").arg(num(v.x, digits), num(v.y, digits), num(v.z, digits));
}

} // namespace

double curvatureRadius(double k) {
    return k == 0.0 ? std::numeric_limits<double>::infinity() : 1.0 / std::abs(k);
}

std::optional<ProbePoint> probeOnRay(const Surface& surface, glm::dvec2 uvGuess,
                                     const glm::dvec3& origin, const glm::dvec3& direction) {
    const NurbsSurface& g = surface.geometry;
    if (!checkNurbsSurface(g) || !std::isfinite(uvGuess.x) || !std::isfinite(uvGuess.y) ||
        !(glm::length(direction) > 0.0))
        return std::nullopt;
    const glm::dvec3 d = glm::normalize(direction);
    // Any two unit vectors across the ray.
    const glm::dvec3 helper =
        std::abs(d.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, std::abs(d.y) < 0.6 ? 1 : 0, 1);
    const glm::dvec3 e1 = glm::normalize(glm::cross(d, helper));
    const glm::dvec3 e2 = glm::cross(d, e1);
    const Interval du = surfaceDomainU(g), dv = surfaceDomainV(g);
    const auto clampUv = [&](glm::dvec2 uv) {
        return glm::dvec2(std::clamp(uv.x, du.first, du.last), std::clamp(uv.y, dv.first, dv.last));
    };

    glm::dvec2 uv = clampUv(uvGuess);
    SurfaceDerivatives s = surfaceDerivatives(g, uv.x, uv.y);
    glm::dvec2 f = across(s.s - origin, e1, e2);
    double dist = glm::length(f);
    ProbePoint p;
    for (int k = 0; k < 30 && dist > 0.0; ++k) {
        // Newton: J step = -f, J = the partials seen across the ray.
        const glm::dvec2 a = across(s.su, e1, e2), b = across(s.sv, e1, e2);
        const double det = a.x * b.y - a.y * b.x;
        if (!(std::abs(det) > 0.0))
            break;
        glm::dvec2 step(-(b.y * f.x - b.x * f.y) / det, -(a.x * f.y - a.y * f.x) / det);
        bool improved = false;
        for (int halve = 0; halve < 20; ++halve, step *= 0.5) {
            const glm::dvec2 next = clampUv(uv + step);
            if (next == uv)
                break;
            const SurfaceDerivatives t = surfaceDerivatives(g, next.x, next.y);
            const glm::dvec2 ft = across(t.s - origin, e1, e2);
            if (glm::length(ft) < dist) {
                uv = next, s = t, f = ft, dist = glm::length(ft);
                improved = true;
                break;
            }
        }
        p.iterations = k + 1;
        if (!improved)
            break;
    }
    const SurfaceCurvature c = surfaceCurvature(g, uv.x, uv.y);
    p.surface = surface.id;
    p.name = surface.name;
    p.uv = uv;
    p.point = s.s;
    p.normal = c.normal;
    p.gaussian = c.gaussian;
    p.mean = c.mean;
    p.k1 = c.k1;
    p.k2 = c.k2;
    p.rayDistance = dist;
    return p;
}

namespace {

/// " mm", or nothing without a unit.
QString after(const QString& unit, const char* power = "") {
    return unit.isEmpty() ? QString() : QStringLiteral(" %1%2").arg(unit, QString::fromUtf8(power));
}

} // namespace

QString probeText(const ProbePoint& p, const QString& unit) {
    constexpr int d = 10;
    const QString length = after(unit);
    const QString perLength = unit.isEmpty() ? QString() : QStringLiteral(" 1/%1").arg(unit);
    // Concatenated: arg() would read "%1²" as a two-digit placeholder.
    const QString perArea = unit.isEmpty() ? QString() : QStringLiteral(" 1/") + unit + u'²';
    QStringList lines;
    lines << QStringLiteral("surface: %1 (id %2)").arg(p.name).arg(p.surface.value)
          << QStringLiteral("u, v: %1, %2").arg(num(p.uv.x, 12), num(p.uv.y, 12))
          << QStringLiteral("x, y, z: %1%2").arg(vecText(p.point, d), length)
          << QStringLiteral("normal: %1").arg(vecText(p.normal, d))
          << QStringLiteral("K: %1%2").arg(num(p.gaussian, d), perArea)
          << QStringLiteral("H: %1%2").arg(num(p.mean, d), perLength)
          << QStringLiteral("k1, k2: %1, %2%3").arg(num(p.k1, d), num(p.k2, d), perLength)
          << QStringLiteral("radii: %1, %2%3")
                 .arg(num(curvatureRadius(p.k1), d), num(curvatureRadius(p.k2), d), length);
    return lines.join(QLatin1Char('\n'));
}

double measurementValue(const Measurement& m) {
    switch (m.kind) {
    case Measurement::Kind::Distance:
        return glm::distance(m.a.point, m.b.point);
    case Measurement::Kind::Angle:
        // atan2 of |cross| and dot keeps full precision near 0 and 180 degrees.
        return glm::degrees(std::atan2(glm::length(glm::cross(m.a.normal, m.b.normal)),
                                       glm::dot(m.a.normal, m.b.normal)));
    case Measurement::Kind::Radius:
        return curvatureRadius(std::max(std::abs(m.a.k1), std::abs(m.a.k2)));
    }
    return 0.0;
}

QString measurementText(const Measurement& m, int digits, const QString& unit) {
    const double value = measurementValue(m);
    const QString u = after(unit);
    switch (m.kind) {
    case Measurement::Kind::Distance: {
        const glm::dvec3 d = m.b.point - m.a.point;
        return QStringLiteral("distance %1%5 (dx %2%5, dy %3%5, dz %4%5)")
            .arg(num(value, digits), num(d.x, digits), num(d.y, digits), num(d.z, digits), u);
    }
    case Measurement::Kind::Angle:
        return m.betweenPlanes
                   ? QStringLiteral("angle %1° between plane faces").arg(num(value, digits))
                   : QStringLiteral("angle %1° between normals").arg(num(value, digits));
    case Measurement::Kind::Radius:
        return QStringLiteral("radius %1%4 (principal radii %2, %3%4)")
            .arg(num(value, digits), num(curvatureRadius(m.a.k1), digits),
                 num(curvatureRadius(m.a.k2), digits), u);
    }
    return QString();
}

} // namespace kw
