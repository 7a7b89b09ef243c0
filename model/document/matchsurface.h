// Match Surface (Rhino's MatchSrf): move the rows of control points along one edge of a face so
// that it meets a neighbour's edge with G0, G1 or G2 continuity.
#pragma once

#include "model/analysis/continuity.h"
#include "model/error.h"

#include <QString>
#include <optional>

namespace kw {

enum class MatchContinuity { G0, G1, G2 };

/// Match domain edge `edge` of untrimmed surface `surface` to side `target` of another face (a
/// domain edge of an untrimmed face, or a trim curve).
struct MatchRequest {
    SurfaceId surface;
    DomainEdge edge = DomainEdge::V0;
    ContinuitySide target;
    MatchContinuity continuity = MatchContinuity::G1;
};

struct MatchResult {
    NurbsSurface geometry;   ///< the surface's new geometry
    EdgeContinuity measured; ///< the continuity kernel's measure of the matched edge
    bool exact = false;      ///< the method is exact (an untrimmed target edge)
    bool reached = false;    ///< the measured class is at least the one asked for
    QString summary;         ///< one line: what was reached, or why not and the deviation
};

/// Computes the match; the scene is not changed. Exact for a target that is a domain edge of an
/// untrimmed face: the along-edge bases are made equal (degree elevation A5.9 and knot insertion
/// A5.3 on copies, so neither shape moves), then, on homogeneous points (so rational faces match
/// too), the boundary row is copied and the next rows are set so that near the edge the surface
/// is the target's continued across it, A(t, s) = B(t, -beta s), with beta keeping the surface's
/// own mean tangent length: equal cross derivatives to first (G1) and second (G2) order.
/// Needs degree >= 2 across for G2 and enough rows that the opposite edge stays where it is
/// (knots are inserted across otherwise). For a trim-curve target (an edge inside the
/// neighbour's domain) it fits the boundary row by least squares to the edge and turns the next
/// row into the neighbour's tangent planes, which is approximate: the summary then says whether
/// the tolerance was reached and with what deviation. Returns an error when the request names
/// no such surface or side, the surface is trimmed, the two are the same side, or an edge is
/// not clamped.
Expected<MatchResult> matchSurface(const Scene& scene, const MatchRequest& request,
                                   const ContinuityTolerances& tolerances);

/// The side of `target` nearest to edge `edge` of `surface` (by the distance between their
/// samples' mean points), for a dialog's default; nullopt when the target has none.
std::optional<ContinuitySide> nearestSide(const Scene& scene, SurfaceId surface, DomainEdge edge,
                                          SurfaceId target);

/// "U0", "U1", "V0", "V1" (or "" for None).
QString domainEdgeName(DomainEdge edge);

} // namespace kw
