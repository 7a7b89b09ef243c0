// Functions of kw::AnalyticForm (model/nurbs/analytic.h): points, normals, the parameter maps,
// closed-form ray intersections; the CPU reference for the renderer's closed-form pass and the
// probe.
#pragma once

#include "model/nurbs/analytic.h"
#include "model/nurbs/nurbs.h"

#include <optional>
#include <string>
#include <vector>

namespace kw {

// `form` must be valid (checkAnalyticForm passes) and not Kind::None unless stated. The maps:
// the map named `u` always takes the NURBS's u (when `swapped`, it gives b, and `v` gives a).

/// "none", "plane", "cylinder", "cone", "sphere" or "torus" (the .knot file's and the JSON's
/// names); analyticKindNamed is the inverse (nullopt for any other text).
const char* analyticKindName(AnalyticForm::Kind kind);
std::optional<AnalyticForm::Kind> analyticKindNamed(const std::string& name);

/// Why `form` cannot be used, or ok(): a frame of finite, unit (1e-9), mutually orthogonal
/// (1e-9) axes; finite values; radius > 0 (cylinder, sphere, torus; cone: >= 0);
/// 0 < minorRadius (torus); |semiAngle| in (0, pi/2) (cone); map scales finite and non-zero.
/// Kind::None is always valid. `geometry` checks the maps against the NURBS: a HalfAngle map
/// needs a degree 2 direction whose spans each turn by less than pi.
Status checkAnalyticForm(const AnalyticForm& form, const NurbsSurface& geometry);

/// The distinct knots of a clamped direction's domain [knots[p], knots[n]], ascending: the
/// span ends the parameter maps work between.
std::vector<double> distinctKnots(const std::vector<double>& knots, int degree);

/// P(a, b) of the form (analytic.h gives the formulas).
glm::dvec3 analyticPoint(const AnalyticForm& form, double a, double b);
/// The unit normal at (a, b), pointing the way the NURBS's Su x Sv points (the maps' directions
/// and `swapped` taken into account, an indirect frame too). At a sphere's pole or on a
/// torus's or cone's axis, the limit from the side the parameters give.
glm::dvec3 analyticNormal(const AnalyticForm& form, double a, double b);

/// (a, b) of the NURBS's (u, v) through the maps (u, v clamped to the NURBS's domain).
glm::dvec2 analyticParameters(const AnalyticForm& form, const NurbsSurface& geometry, double u,
                              double v);
/// The inverse: the (u, v) whose (a, b) are the given ones, angles taken modulo 2 pi (a
/// HalfAngle map's range decides which turn); nullopt when (a, b) lies outside the NURBS's
/// domain by more than 1e-9 of its size (slightly outside: clamped onto it).
std::optional<glm::dvec2> nurbsParameters(const AnalyticForm& form, const NurbsSurface& geometry,
                                          double a, double b);
/// (a, b) of a point on (or near) the form's surface: the closed-form inverse of analyticPoint,
/// angles in (-pi, pi] (on a cone's other nappe and where a spindle torus (minorRadius > radius)
/// has R + r cos b < 0, a is the point's own angle plus pi). Undefined on the axis of a
/// cylinder, cone, sphere or torus.
glm::dvec2 analyticProject(const AnalyticForm& form, const glm::dvec3& point);

/// The ray parameters t (origin + t dir, dir non-zero, any length) where the ray meets the whole
/// analytic surface (unbounded plane, cylinder and cone, both nappes of a cone), ascending,
/// negative ones included: a quadratic for plane (linear), cylinder, cone and sphere, a quartic
/// for the torus (Ferrari's resolvent, each root polished by Newton steps). Tangent rays may
/// give a double root once or not at all.
struct AnalyticRayHits {
    int count = 0;
    double t[4] = {0.0, 0.0, 0.0, 0.0};
};
AnalyticRayHits analyticRayHits(const AnalyticForm& form, const glm::dvec3& origin,
                                const glm::dvec3& dir);

/// The largest distance between S(u, v) of `geometry` and P(a(u), b(v)) of `form` over a
/// (samples + 1)^2 grid of the domain plus every knot span's midpoints (the import's check:
/// the form is kept only where this is within its tolerance). Infinity for Kind::None.
double analyticDeviation(const AnalyticForm& form, const NurbsSurface& geometry, int samples = 16);

/// The most a kept form may lie from its NURBS (analyticDeviation): a millionth of the control
/// net's diagonal. The importer keeps a form only within the face's tolerance and this; the
/// .knot reader refuses a form beyond it (a NURBS edited by hand, a form copied to another face).
double analyticMatchLimit(const NurbsSurface& geometry);

/// `form` moved by the similarity x -> m x + t (m: a rotation, or a reflection, times a uniform
/// scale s > 0): origin and axes mapped, lengths (radii, Linear maps of lengths) times s.
AnalyticForm analyticTransformed(const AnalyticForm& form, const glm::dmat3& m,
                                 const glm::dvec3& t);

/// The form of `to` when `to` is `from` moved by a similarity (the same degrees, knots and
/// weights, and every control point mapped by one rotation or reflection, uniform scale and
/// translation, within 1e-13 of the net's size plus its distance from the origin: the rounding
/// of a transform computed in double, far below any edit): `form` (which describes `from`)
/// transformed as analyticTransformed; nullopt otherwise, and when `from`'s points are collinear.
std::optional<AnalyticForm> analyticFollow(const AnalyticForm& form, const NurbsSurface& from,
                                           const NurbsSurface& to);

} // namespace kw
