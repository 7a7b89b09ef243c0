// NURBS kernel: plain data and free functions (algorithms from Piegl & Tiller, The NURBS Book, 2nd
// ed.).
#pragma once

#include "model/error.h"

#include <glm/glm.hpp>
#include <vector>

namespace kw {

/// Highest degree the kernel, the file format and the GPU shader accept.
constexpr int kMaxDegree = 15;

/// A tensor-product NURBS surface. Control point (i, j), i along u and j along v, is stored at
/// index(i, j) = j * countU + i in `points` and `weights`. Knot vectors have count + degree + 1
/// entries. Points are Cartesian; the kernel lifts them to homogeneous (w*P, w) internally.
struct NurbsSurface {
    int degreeU = 1;
    int degreeV = 1;
    int countU = 0;
    int countV = 0;
    std::vector<double> knotsU;
    std::vector<double> knotsV;
    std::vector<glm::dvec3> points;
    std::vector<double> weights;

    int index(int i, int j) const { return j * countU + i; }
    bool operator==(const NurbsSurface&) const = default;
};

/// A planar NURBS curve, used for trim curves in a surface's (u, v) parameter space.
struct NurbsCurve2 {
    int degree = 1;
    std::vector<double> knots; ///< points.size() + degree + 1 entries
    std::vector<glm::dvec2> points;
    std::vector<double> weights;

    bool operator==(const NurbsCurve2&) const = default;
};

/// Parameter interval [first, last] of a knot vector of the given degree.
struct Interval {
    double first = 0.0;
    double last = 1.0;
    bool operator==(const Interval&) const = default;
};

// ---- Validation: each returns ok() when valid, else an Error whose message is the reason in
// plain English.

/// Degree in [1, kMaxDegree], knots.size() == count + degree + 1, finite non-decreasing knots,
/// interior multiplicity <= degree + 1 (ends too), and a non-empty domain.
Status checkKnotVector(const std::vector<double>& knots, int degree, int count);
/// Knot vectors as above; points and weights sized countU*countV; coordinates finite; weights
/// finite and > 0.
Status checkNurbsSurface(const NurbsSurface& s);
Status checkNurbsCurve(const NurbsCurve2& c);

// ---- Basis functions. Preconditions: a valid knot vector for `degree` (see checkKnotVector).

/// A2.1: the knot span index k with knots[k] <= u < knots[k+1], clamped to the valid range
/// [degree, n] so that u == last knot maps to the last non-empty span.
int findSpan(int degree, const std::vector<double>& knots, double u);
/// The non-empty knot spans of the domain, [knots[k], knots[k+1]) with knots[k] < knots[k+1]
/// for k in [degree, n]: the spans findSpan can return. 0 for a knot vector too short for
/// `degree`.
int nonEmptySpanCount(int degree, const std::vector<double>& knots);
/// A2.2: the degree+1 non-zero basis functions N[span-degree .. span] at u, written to out.
void basisFunctions(int span, double u, int degree, const std::vector<double>& knots, double* out);
/// A2.3: derivatives 0..order of the non-zero basis functions; out[k*(degree+1) + j] is the
/// k-th derivative of N[span-degree+j]. Derivatives above the degree are zero.
void basisFunctionDerivatives(int span, double u, int degree, int order,
                              const std::vector<double>& knots, double* out);

Interval knotDomain(const std::vector<double>& knots, int degree);
/// The Greville abscissa of control point i (degree >= 1, knots valid for it): the average of
/// knots i + 1 .. i + degree, where the point has most influence; B-splines reproduce linear
/// functions through them (sum of xi_i N_i(u) = u).
double grevilleAbscissa(const std::vector<double>& knots, int degree, int i);

// ---- Surface evaluation. Preconditions: a valid surface; (u, v) is clamped to the domain.

struct SurfaceDerivatives {
    glm::dvec3 s{0.0};
    glm::dvec3 su{0.0};
    glm::dvec3 sv{0.0};
    glm::dvec3 suu{0.0};
    glm::dvec3 suv{0.0};
    glm::dvec3 svv{0.0};
};

struct SurfaceFrame {
    glm::dvec3 point{0.0};
    glm::dvec3 du{0.0};
    glm::dvec3 dv{0.0};
    glm::dvec3 normal{0.0, 0.0, 1.0}; ///< unit length, never NaN
};

Interval surfaceDomainU(const NurbsSurface& s);
Interval surfaceDomainV(const NurbsSurface& s);
/// A3.6 on homogeneous points, then A4.4 for the rational quotient: S and derivatives to order 2.
SurfaceDerivatives surfaceDerivatives(const NurbsSurface& s, double u, double v);
glm::dvec3 surfacePoint(const NurbsSurface& s, double u, double v);
/// Point, first partials and unit normal Su x Sv. Where Su x Sv vanishes (a collapsed edge
/// such as a sphere pole or the teapot lid) the limit normal is used: Suv x Sv (or Su x Suv)
/// with the sign of the approach from the domain's interior; if that vanishes too, the normal
/// of a nearby interior point. The GPU shader implements the same rule.
SurfaceFrame surfaceFrame(const NurbsSurface& s, double u, double v);
/// Axis-aligned bounds of the control points (the surface lies inside by the convex hull
/// property, weights > 0).
void surfaceControlBounds(const NurbsSurface& s, glm::dvec3& lo, glm::dvec3& hi);
/// The non-empty spans (rectangles of one polynomial piece) of the surface's domain: the
/// product of nonEmptySpanCount along u and along v.
int surfaceSpanCount(const NurbsSurface& s);

// ---- Curve evaluation (2D). Preconditions: a valid curve; t is clamped to the domain.

struct CurveDerivatives2 {
    glm::dvec2 point{0.0};
    glm::dvec2 d1{0.0};
    glm::dvec2 d2{0.0};
};

Interval curveDomain(const NurbsCurve2& c);
/// A3.2 on homogeneous points, then A4.2 for the rational quotient, to order 2.
CurveDerivatives2 curveDerivatives(const NurbsCurve2& c, double t);
glm::dvec2 curvePoint(const NurbsCurve2& c, double t);

// ---- Modifying operations return new values; the input is unchanged.

/// A5.3: insert knot u `times` times in the u (or v) direction. The surface does not move.
/// Returns the input unchanged when u is outside the open domain or the multiplicity would
/// exceed the degree.
NurbsSurface surfaceInsertKnotU(const NurbsSurface& s, double u, int times = 1);
NurbsSurface surfaceInsertKnotV(const NurbsSurface& s, double v, int times = 1);
/// A5.9: raise the degree in u (or v) by t. The surface does not move. Returns the input
/// unchanged when the new degree would exceed kMaxDegree.
NurbsSurface surfaceElevateDegreeU(const NurbsSurface& s, int t = 1);
NurbsSurface surfaceElevateDegreeV(const NurbsSurface& s, int t = 1);

} // namespace kw
