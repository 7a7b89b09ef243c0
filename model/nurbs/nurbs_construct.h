// NURBS constructions for modeling: 3D curves, patches, cones, revolution, extrusion, loft
// (skinning) and knot removal (algorithms from Piegl & Tiller, The NURBS Book, 2nd ed.).
#pragma once

#include "model/error.h"
#include "model/nurbs/nurbs.h"

#include <string>
#include <vector>

namespace kw {

/// A NURBS curve in 3D: profiles and sections of the surfaces built below, and iso-curves or
/// boundaries of existing surfaces. Same conventions as NurbsCurve2 (Cartesian points, weights
/// > 0, points.size() + degree + 1 knots).
struct NurbsCurve3 {
    int degree = 1;
    std::vector<double> knots;
    std::vector<glm::dvec3> points;
    std::vector<double> weights;

    bool operator==(const NurbsCurve3&) const = default;
};

/// ok() when valid, else the reason (checkKnotVector, finite points, weights > 0).
Status checkNurbsCurve3(const NurbsCurve3& c);
/// A3.2/A4.1 on homogeneous points; t is clamped to the domain. Precondition: a valid curve.
glm::dvec3 curve3Point(const NurbsCurve3& c, double t);

/// Clamped uniform knot vector on [0, 1]: degree + 1 zeros, count - degree - 1 evenly spaced
/// interior knots, degree + 1 ones. Precondition: 1 <= degree < count.
std::vector<double> clampedUniformKnots(int degree, int count);

/// A flat, non-rational patch of countU x countV control points (clamped uniform knots) filling
/// the sizeU x sizeV rectangle centred on `center` in the plane spanned by x and y, control
/// points evenly spaced. Contract: 1 <= degree < count for each direction, sizes finite.
NurbsSurface makePatch(const glm::dvec3& center, int degreeU, int degreeV, int countU, int countV,
                       double sizeU, double sizeV);

/// Exact cone frustum around +z: radius baseRadius at baseCenter, topRadius (0 for a pointed
/// cone, whose apex edge collapses) at baseCenter + height z. A makeRevolution of a line:
/// 9 x 2 control points, degree 2 x 1, normals outward.
NurbsSurface makeCone(const glm::dvec3& baseCenter, double baseRadius, double height,
                      double topRadius = 0.0);

/// Full surface of revolution (A8.1 with the 9-point circle) of a 3D profile about the axis
/// through axisPoint along axisDirection (need not be unit; must be non-zero). u runs around
/// the axis (degree 2, rational), v along the profile. Exact for rational profiles too.
NurbsSurface makeRevolution3(const NurbsCurve3& profile, const glm::dvec3& axisPoint,
                             const glm::dvec3& axisDirection);

/// General cylinder (The NURBS Book Sec. 8.3): the curve swept along `direction`. u is the
/// curve, v a straight line (degree 1) from the curve (v = 0) to curve + direction (v = 1).
NurbsSurface makeExtrusion(const NurbsCurve3& curve, const glm::dvec3& direction);

/// Skinned (lofted) surface through two or more section curves (Sec. 10.3). The sections are
/// made compatible first: each is reparameterised to [0, 1], raised to the highest degree
/// (degree elevation) and given the union of all knot vectors (knot insertion), which leaves
/// every section unchanged as a curve. v then interpolates the sections' homogeneous control
/// points (A9.1: averaged chord-length parameters, averaged knots, Eq. 9.8)
/// with degree min(maxDegreeV, sections - 1), so S(u, v_k) is section k exactly.
/// Returns an error when the sections are invalid, fewer than two, coincide, or the
/// interpolation gives non-positive weights. *sectionParameters (if given) receives the v_k.
Expected<NurbsSurface> makeLoft(std::vector<NurbsCurve3> sections, int maxDegreeV = 3,
                                std::vector<double>* sectionParameters = nullptr);

/// Global curve interpolation (The NURBS Book A9.1): the non-rational curve of degree
/// min(maxDegree, n - 1) through the n >= 2 points, parameters by chord length (Eq. 9.5) on
/// [0, 1], knots by averaging (Eq. 9.8), so C(t_k) = Q_k. Returns an error when there are
/// fewer than two points, a point is not finite or two consecutive points coincide.
/// *parameters (if given) receives the t_k.
Expected<NurbsCurve3> interpolateCurve3(const std::vector<glm::dvec3>& points, int maxDegree = 3,
                                        std::vector<double>* parameters = nullptr);
/// The non-rational clamped uniform B-spline of degree min(maxDegree, n - 1) with the n >= 2
/// points as its control polygon (empty for fewer points).
NurbsCurve3 controlPointCurve3(const std::vector<glm::dvec3>& points, int maxDegree = 3);

/// The iso-curve S(u, v0) (alongU true: the curve runs in u at fixed v = v0) or S(u0, v)
/// (alongU false, at u = v0), exact: knot insertion up to full multiplicity at the parameter
/// makes one row of the net the curve's control polygon (A5.3). The parameter is clamped to
/// the domain. Precondition: a valid surface.
NurbsCurve3 surfaceIsoCurve(const NurbsSurface& s, bool alongU, double parameter);

/// A5.8 (RemoveCurveKnot) applied to every row of the net in one direction: removes interior
/// knots one at a time while the surface moves by at most `tolerance` (model units; the
/// homogeneous bound of Eq. 5.30 is used, and the removals share one error budget, so their sum
/// stays within it). Repeats until no knot can be removed. Returns the new surface and sets
/// *removed to the count removed (0: the input comes back unchanged). Invalid input or tolerance <
/// 0 removes nothing.
NurbsSurface surfaceRemoveKnots(const NurbsSurface& s, bool alongU, double tolerance,
                                int* removed = nullptr);

/// A trim curve with one more control point and the same shape: knot t inserted once (A5.1).
/// Returns the input when t is not inside the open domain or its multiplicity is the degree.
NurbsCurve2 curve2InsertKnot(const NurbsCurve2& c, double t);
/// The trim curve without control point `index` (an interior one: 0 < index < count - 1, so
/// the ends, shared with the neighbouring curves of a loop, stay). One interior knot goes too,
/// the one nearest the removed point's Greville abscissa, and the degree drops when too few
/// points remain for it. Returns the input for an invalid index or a curve of two points.
NurbsCurve2 curve2RemovePoint(const NurbsCurve2& c, int index);

} // namespace kw
