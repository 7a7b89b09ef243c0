// Exact NURBS constructors for common shapes (spheres, cylinders, tori, planes, trim circles).
#pragma once

#include "model/nurbs/nurbs.h"

namespace kw {

// All quadrics below are exact rational surfaces of revolution (The NURBS Book, A8.1 with the
// 9-point circle of Sec. 7.5 / Ex. 7.2): degree 2 and rational in u (around the axis), the
// profile in v. The axis is parallel to +z. u runs counter-clockwise seen from +z, v runs
// along the profile so that Su x Sv points outward. Domains are [0, 1] x [0, 1].
// Contract: lengths should be finite and > 0; other values still give a well-formed surface
// (degenerate or inside-out), and non-finite input is reported by checkNurbsSurface.

/// Sphere: u around the axis (9 x), v from the south pole (v = 0) to the north pole (v = 1)
/// along a 5-point half circle, so the v = 0 and v = 1 edges collapse to the poles.
/// 9 x 5 control points, degree 2 x 2.
NurbsSurface makeSphere(const glm::dvec3& center, double radius);

/// Open cylinder (no caps) of the given radius from baseCenter up to baseCenter + height * z.
/// v is degree 1 (a straight line from bottom to top). 9 x 2 control points, degree 2 x 1.
NurbsSurface makeCylinder(const glm::dvec3& baseCenter, double radius, double height);

/// Torus around the z axis through center: tube centre circle of radius majorRadius, tube of
/// radius minorRadius. v starts on the outer equator and runs upward. 9 x 9 control points.
NurbsSurface makeTorus(const glm::dvec3& center, double majorRadius, double minorRadius);

/// Planar parallelogram origin + u edgeU + v edgeV, (u, v) in [0, 1]^2: a degree 1 x 1 patch
/// with 2 x 2 control points and unit weights. Its normal is edgeU x edgeV.
NurbsSurface makePlane(const glm::dvec3& origin, const glm::dvec3& edgeU, const glm::dvec3& edgeV);

/// Bilinear patch through four corners: S(0,0) = p00, S(1,0) = p10, S(0,1) = p01, S(1,1) = p11.
NurbsSurface makeBilinear(const glm::dvec3& p00, const glm::dvec3& p10, const glm::dvec3& p01,
                          const glm::dvec3& p11);

/// Closed rational circle of degree 2 in the plane (9 control points, the first and last equal,
/// knots {0,0,0, 1/4,1/4, 1/2,1/2, 3/4,3/4, 1,1,1}, weights 1 and sqrt(2)/2 alternately). It
/// starts at center + (radius, 0) and runs counter-clockwise, or clockwise when `clockwise`
/// is true (the orientation trim code may use to tell holes from outer loops).
NurbsCurve2 makeCircle2(const glm::dvec2& center, double radius, bool clockwise = false);

/// Surface of revolution of a profile curve around the z axis through `center` (A8.1): the
/// profile point (x, y) of the 2D curve means distance x from the axis at height y. Profile
/// points with x < 0 are allowed (the surface then passes through the axis). u is the 9-point
/// circle around the axis, v the profile's own parameterisation.
NurbsSurface makeRevolution(const glm::dvec3& center, const NurbsCurve2& profile);

} // namespace kw
