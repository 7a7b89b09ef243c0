// How far apart the two sides of each shared edge lie on the exact surfaces, and which recorded
// shells are therefore still closed: what an edit did to the seams of an imported solid.
#pragma once

#include "model/document/scene.h"

#include <functional>
#include <glm/glm.hpp>
#include <vector>

namespace kw {

/// The seam of one shared edge (SharedEdge) as the surfaces now have it.
struct SeamGap {
    EdgeId edge;
    SurfaceId faceA; ///< sides[0]'s surface
    SurfaceId faceB; ///< sides[1]'s surface (faceA again for a seam of one surface)
    /// The largest distance, in model units, from a point of either side's edge to the other
    /// side's edge (both ways, so a boundary moved along itself, shortened or lengthened counts).
    double gap = 0.0;
    glm::dvec3 where{0.0}; ///< the point of side `whereOn`'s edge where the gap is largest
    SurfaceId whereOn;
    double tolerance = 0.0; ///< the edge's (SharedEdge::tolerance)
    bool open() const { return gap > tolerance; }
};

/// Least number of points seamGaps samples each side's edge at, besides the trim curve's knots.
constexpr int kMinSeamSamples = 64;

/// One side of a seam: the curve C(t) = S(c(t)) of a 2D curve c in the (u, v) space of surface
/// S (a trim curve, or a straight line along an edge of the domain), with samples of it. The
/// continuity kernel (model/analysis/continuity.h) measures on the same sides.
struct SeamSide {
    const NurbsSurface* surface = nullptr; ///< not owned; must outlive the side
    NurbsCurve2 curve;
    Interval domain;
    std::vector<double> t;      ///< sample parameters, ascending
    std::vector<glm::dvec3> at; ///< C(t) at each
};

/// The side of `curve` on `surface`, sampled at `samples` (>= 2) parameters evenly spread over
/// the curve's domain, at each of its distinct interior knots and at each value of `extra`
/// inside the domain (e.g. a surface's knots along a boundary line). Preconditions: a valid
/// surface and curve.
SeamSide makeSeamSide(const NurbsSurface& surface, const NurbsCurve2& curve, int samples,
                      const std::vector<double>& extra = {});
/// C(t) of a side.
glm::dvec3 seamSidePoint(const SeamSide& side, double t);

/// The foot of the perpendicular from a point to a side: its parameter, its distance, and the
/// surface's point and derivatives there (so that a caller measuring more there need not
/// evaluate again).
struct SeamFoot {
    double t = 0.0;
    double distance = 0.0;
    glm::dvec2 uv{0.0};
    SurfaceDerivatives derivatives;
};
/// The point of `side` nearest to p: the nearest sample, refined on the chords next to it, then
/// Newton's iteration for the foot of the perpendicular (The NURBS Book, 6.1, eq. 6.3), clamped
/// to the domain. Every point visited lies on the side, so the distance is never below the true
/// one and never above the nearest sample's; the foot is the nearest point visited. About two
/// or three surface evaluations where the side passes close to p.
SeamFoot nearestOnSeamSide(const SeamSide& side, const glm::dvec3& p);

/// Runs `run(from, to)` over [0, count) in contiguous ranges, one per core, when there are at
/// least `perThread` items per range; else once on the calling thread. Each range is written
/// by one thread only, so results stored by index need no lock.
void forEachRange(size_t count, size_t perThread,
                  const std::function<void(size_t from, size_t to)>& run);

/// For every shared edge of scene.topology, in its order: a side's edge is the curve
/// S(c(t)) of its trim curve c on its surface S, in double precision (no tessellation). Each
/// side is sampled at `samples` (at least kMinSeamSamples) parameters evenly spread over its
/// curve's domain and at each of the curve's distinct knots; the distance from each sample to
/// the other side's edge is minimised over that edge's parameter (nearest of its own samples,
/// then Newton's iteration on (C(s) - p) . C'(s) = 0, The NURBS Book 6.1, clamped to the ends).
/// Precondition: a valid scene (kw::checkScene); an edge naming a surface, loop or curve the
/// scene does not have gets an infinite gap (open) rather than undefined behaviour. Cost ~ 2 x
/// samples x (samples + 5 surface derivative evaluations) per edge, about 0.3 ms for a bicubic
/// face's edge; more than 128 edges are shared out over the machine's cores (std::thread), with the
/// same result.
std::vector<SeamGap> seamGaps(const Scene& scene, int samples = kMinSeamSamples);

/// One recorded shell (Shell) as the surfaces now have it.
struct ShellState {
    ShellId shell;
    int solid = -1; ///< Shell::solid
    int faces = 0;
    /// The shell was recorded closed, no face or edge of it was removed since (Shell::closed),
    /// and no edge with a side on one of its faces is open (SeamGap::open).
    bool closed = false;
    int openEdges = 0;       ///< edges of the shell whose gap is above their tolerance
    double largestGap = 0.0; ///< the largest gap of its edges (model units)
};

/// Every shell of scene.topology, in its order, judged by `gaps` (seamGaps of the same scene).
std::vector<ShellState> closedShells(const Scene& scene, const std::vector<SeamGap>& gaps);

} // namespace kw
