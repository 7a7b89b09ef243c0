// The closed form a face had in its source file (plane, cylinder, cone, sphere or torus), kept
// beside its exact NURBS so that the renderer can intersect a pixel's ray with it in closed form.
// The NURBS stays what is edited and saved as geometry; an edit of the geometry drops the form.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>

namespace kw {

/// How one NURBS parameter s maps to one parameter of the analytic form. With
/// phi(s) = offset + scale * s:
/// - Linear: the analytic parameter is phi(s) (a plane's directions, a cylinder's or a cone's
///   height);
/// - HalfAngle: the direction is a circle written as rational quadratic arcs, one per knot span
///   (the way OpenCASCADE converts circles). At each distinct knot s_k the angle is phi(s_k);
///   inside a span [s_k, s_k+1], with t = (s - s_k) / (s_k+1 - s_k), d = phi(s_k+1) - phi(s_k)
///   and m = (phi(s_k) + phi(s_k+1)) / 2, the angle is m + 2 atan((2t - 1) tan(d / 4)); the
///   inverse is t = (1 + tan((angle - m) / 2) / tan(d / 4)) / 2.
struct AnalyticParamMap {
    enum class Kind : std::uint8_t { Linear, HalfAngle };
    Kind kind = Kind::Linear;
    double offset = 0.0;
    double scale = 1.0;
    bool operator==(const AnalyticParamMap&) const = default;
};

/// An analytic surface in OpenCASCADE's parametrisation (a, b), with the frame (origin; X, Y, Z),
/// which need not be right-handed:
/// - Plane:    P = O + a X + b Y;
/// - Cylinder: P = O + R (cos a X + sin a Y) + b Z;
/// - Cone:     P = O + (R + b sin(semiAngle)) (cos a X + sin a Y) + b cos(semiAngle) Z;
/// - Sphere:   P = O + R cos b (cos a X + sin a Y) + R sin b Z;
/// - Torus:    P = O + (R + r cos b) (cos a X + sin a Y) + r sin b Z, R = radius, r = minorRadius.
/// The NURBS's (u, v) give (a, b) through the maps: a = u.map(u), b = v.map(v), or, when
/// `swapped`, a from v and b from u. The form is kept only while S(u, v) of the NURBS equals
/// P(a, b) across the domain, to the import's tolerance; None otherwise.
struct AnalyticForm {
    enum class Kind : std::uint8_t { None, Plane, Cylinder, Cone, Sphere, Torus };
    Kind kind = Kind::None;
    glm::dvec3 origin{0.0};
    glm::dvec3 xAxis{1.0, 0.0, 0.0};
    glm::dvec3 yAxis{0.0, 1.0, 0.0};
    glm::dvec3 zAxis{0.0, 0.0, 1.0};
    double radius = 0.0;
    double minorRadius = 0.0;
    double semiAngle = 0.0;
    AnalyticParamMap u;
    AnalyticParamMap v;
    bool swapped = false;
    bool operator==(const AnalyticForm&) const = default;
};

} // namespace kw
