// Trim loops in a surface's (u, v) space: tessellation, point classification and trimmed area.
#pragma once

#include "model/document/scene.h"

#include <QStringList>
#include <glm/glm.hpp>
#include <vector>

namespace kw {

/// A loop flattened to a closed polyline in (u, v); the last point is not repeated.
using TrimPolygon = std::vector<glm::dvec2>;

/// The piece of a curve between parameters first < last inside its domain, exactly: knots are
/// inserted (Boehm, The NURBS Book A5.1, on homogeneous points) to multiplicity `degree` at
/// both ends and the clamped piece is cut out; its parameters stay those of the source.
/// Precondition: a valid curve and curveDomain(c).first <= first < last <= curveDomain(c).last.
NurbsCurve2 trimCurveSegment(NurbsCurve2 curve, double first, double last);
/// The same curve run backwards: C'(t) = C(-t) over the domain [-b, -a] of a curve C over
/// [a, b]. Exact (negated knots), so the result is valid whenever the curve is.
NurbsCurve2 trimCurveReversed(const NurbsCurve2& curve);

/// Flattens one trim curve: samples the curve at its knots and bisects every piece until the
/// midpoint of each chord is within `tolerance` (in parameter units) of the curve, or the
/// depth limit is reached. The depth limit (at most 18) shrinks with the number of knot spans
/// so that a curve gives at most max(2^14, 4 x spans) + 1 points, whatever its scale. Returns the
/// points from start to end inclusive. Precondition: a valid curve (checkNurbsCurve passes)
/// and tolerance > 0.
std::vector<glm::dvec2> tessellateTrimCurve(const NurbsCurve2& curve, double tolerance);

/// Flattens a whole loop (curves in order) to a closed polygon within `tolerance`. Consecutive
/// duplicate points are dropped. An empty loop gives an empty polygon.
TrimPolygon tessellateTrimLoop(const TrimLoop& loop, double tolerance);

/// All loops of a surface, flattened, with their bounding boxes for quick rejection.
struct TrimRegion {
    std::vector<TrimPolygon> loops;
    std::vector<glm::dvec2> lo; ///< per loop
    std::vector<glm::dvec2> hi; ///< per loop
    bool empty() const { return loops.empty(); }
};

/// Flattens every loop of `trims`; tolerance as in tessellateTrimLoop. Messy input is made
/// usable and, when `warnings` is given, reported there (one line per problem, naming the loop):
/// - a curve that is not valid (checkNurbsCurve) is left out of its loop;
/// - a gap wider than `tolerance` between consecutive curves, or between the last curve's end
///   and the first curve's start, is bridged by a straight segment (the polygon is closed);
/// - a loop that flattens to fewer than 3 distinct points or encloses no area (|signed area|
///   below tolerance^2) is dropped: it would change no point's parity anyway.
/// Orientation is irrelevant: classification is by parity. Tolerance must be > 0.
TrimRegion makeTrimRegion(const std::vector<TrimLoop>& trims, double tolerance,
                          QStringList* warnings = nullptr);

/// Makes a loop closed in the sense of kw::checkTrimLoop (what the .knot reader demands), the
/// way makeTrimRegion would draw it: a gap between consecutive curves (and between the last
/// curve's end and the first curve's start) no wider than `snap` moves the later curve's first
/// control point onto the earlier curve's end (its start, for a curve with a clamped start);
/// any other gap gets a straight degree-1 curve across it. Returns one line per gap closed
/// ("gap of G before curve K snapped" / "... bridged by a straight segment"), empty when the
/// loop was already closed. `newIndex`, when given, gets the index each curve has after the
/// bridges were inserted (curve k is now curve (*newIndex)[k]). Precondition: every curve valid
/// (checkNurbsCurve).
QStringList closeTrimLoop(TrimLoop& loop, double snap, std::vector<int>* newIndex = nullptr);

/// closeTrimLoop for every loop of `scene` at trimTolerance of its surface (the topology's sides
/// renumbered with the curves they name), as an import ends
/// (CAD and OBJ readers): returns one line per gap closed, "surface 'NAME', trim loop ID:
/// <closeTrimLoop's line>". A loop with an invalid curve (checkNurbsCurve) is left as it
/// is, for kw::checkScene to name.
QStringList closeSceneTrimLoops(Scene& scene);

/// The trim points that must move with `hit` so that its loop stays closed (Document refuses a
/// move that opens a loop): `hit` first, then, when it is the first or last point of its curve,
/// every curve end of the same loop within trimLoopClosureTolerance of it (the neighbouring
/// curve's end; a single closed curve's other end). An interior point, or a ref naming no point of
/// `surface`, gives {hit} alone. The UV editor's drag, its exact-position fields and the
/// benchmarks' trim drags all move this set.
std::vector<TrimPointRef> trimPointWithCoincidentEnds(const Surface& surface,
                                                      const TrimPointRef& hit);

/// The warnings makeTrimRegion reports for a surface's trims at trimTolerance(surface).
QStringList trimWarnings(const Surface& surface);

/// Distance in (u, v) from `uv` to the nearest edge of the region's polygons (closing edges
/// included); +infinity for a region without loops.
double trimRegionDistance(const TrimRegion& region, glm::dvec2 uv);

/// A tolerance suited to a surface's domain: `relative` times the diagonal of its (u, v) domain.
double trimTolerance(const NurbsSurface& surface, double relative = 1e-5);

/// Parity rule (even-odd, as the trim mask does): true when `uv` lies inside an odd number of
/// loops. A region without loops contains every point (an untrimmed surface).
bool trimRegionContains(const TrimRegion& region, glm::dvec2 uv);

/// trimRegionContains(region, (u, v[k])) for k in [0, count), into inside[k]: the same answers,
/// with one walk of each loop's edges per column instead of per point (the crossings of the line
/// u = const are found once and each v counts those above it). For grids of samples.
void trimRegionContainsColumn(const TrimRegion& region, double u, const double* v, int count,
                              bool* inside);

/// The parameter intervals of the vertical line u = const that lie inside the region by the
/// parity rule, clipped to [v0, v1], sorted and disjoint. Without loops: {[v0, v1]}.
std::vector<Interval> trimRegionSpans(const TrimRegion& region, double u, double v0, double v1);

} // namespace kw
