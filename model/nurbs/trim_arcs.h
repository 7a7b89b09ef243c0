// Trim loops as monotone rational Bezier arcs: the exact trim geometry that the hybrid trim
// mask (render/trim_grid.h) classifies against, without flattening.
#pragma once

#include "model/document/scene.h"

#include <QStringList>
#include <glm/glm.hpp>
#include <vector>

namespace kw {

/// One rational Bezier arc of a trim curve over the local parameter t in [0, 1], monotone in u
/// and in v (Schollmeyer & Froehlich 2009, "Direct trimming of NURBS surfaces on the GPU": a
/// monotone arc meets any line u = const or v = const at most once, so bisection finds the
/// meeting and the arc's bounding box is the box of its end points).
struct TrimArc {
    int degree = 1;
    std::vector<glm::dvec3> hw; ///< degree + 1 homogeneous control points (w u, w v, w), w > 0
    /// C(0) and C(1). Consecutive arcs of a loop share them bit for bit (the parity argument of
    /// render/trim_grid.h relies on it); they equal hw's end points up to rounding.
    glm::dvec2 start{0.0}, end{0.0};
    int loop = 0; ///< index of the arc's loop among the loops kept (TrimArcs::loops)
};

/// Every loop of a surface as a closed chain of monotone arcs.
struct TrimArcs {
    std::vector<TrimArc> arcs;
    int loops = 0;
    glm::dvec2 lo{0.0}, hi{0.0}; ///< bounds of every arc (end points: the arcs are monotone)
    bool empty() const { return arcs.empty(); }
};

/// The point at local parameter t in [0, 1] (de Casteljau on the homogeneous points, The NURBS
/// Book A1.5, then the rational quotient).
glm::dvec2 trimArcPoint(const TrimArc& arc, double t);

/// The t in [t0, t1] where coordinate `axis` (0 = u, 1 = v) of the arc equals `value`, by
/// bisection; the coordinate must be monotone on [t0, t1] (true for a TrimArc). A value outside
/// the coordinate's range there gives the nearer end.
double trimArcSolve(const TrimArc& arc, int axis, double value, double t0, double t1);

/// The parameters in (0, 1) where u' or v' of the rational Bezier curve with homogeneous control
/// points `hw` changes sign, sorted. The numerator X'W - XW' of the derivative is a polynomial
/// of degree 2p - 1 whose Bernstein coefficients follow from the product rule for Bernstein
/// polynomials; its roots are isolated by de Casteljau subdivision (variation diminishing: no
/// sign change among the coefficients, no root) and refined by bisection.
std::vector<double> trimArcTurningPoints(const std::vector<glm::dvec3>& hw);

/// Splits a valid curve (checkNurbsCurve passes, degree <= kMaxDegree, rational allowed)
/// into monotone arcs: one rational Bezier per knot span (knot insertion, A5.1), each cut at its
/// turning points. The arcs run from the curve's start to its end, sharing end points.
std::vector<TrimArc> monotoneTrimArcs(const NurbsCurve2& curve);

/// The loops of a surface as arcs, repaired exactly as makeTrimRegion repairs them
/// (model/nurbs/trim.h), so both describe the same region: invalid curves and curves whose
/// evaluation overflows are left out, a gap between consecutive curves (or at the loop's closure)
/// is bridged by a straight arc, and a loop makeTrimRegion calls degenerate at `tolerance` is
/// dropped. Warnings are makeTrimRegion's, when asked for.
TrimArcs makeTrimArcs(const std::vector<TrimLoop>& trims, double tolerance,
                      QStringList* warnings = nullptr);

/// Even-odd classification against the exact curves, by the same rule as trimRegionContains:
/// crossings of the ray from uv towards +v, half-open in u. No loops: every point is inside.
bool trimArcsContain(const TrimArcs& arcs, glm::dvec2 uv);

} // namespace kw
