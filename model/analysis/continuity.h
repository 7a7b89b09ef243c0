// Continuity of the edges where faces meet: G0 gap, G1 angle and G2 curvature jump, measured on
// the exact surfaces in double precision, with the edges from the import's record or found by
// matching boundaries (CATIA's Connect Checker, Rhino's EdgeContinuity).
#pragma once

#include "model/document/scene.h"
#include "model/document/seamgaps.h"
#include "model/error.h"

#include <QString>
#include <array>
#include <functional>
#include <glm/glm.hpp>
#include <vector>

namespace kw {

/// The tolerances a scene is judged by (Scene::continuity, saved with the project).
inline const ContinuityTolerances& continuityTolerances(const Scene& scene) {
    return scene.continuity;
}

/// ok() when every value is finite and > 0 and match >= g0, else an Error with the reason.
Status checkContinuityTolerances(const ContinuityTolerances& t);

enum class ContinuityClass { G2, G1, G0, Open };
/// "G2", "G1", "G0" or "open".
QString continuityClassName(ContinuityClass c);

/// An edge of a face's domain: the iso-boundary u = first, u = last, v = first or v = last.
enum class DomainEdge { None, U0, U1, V0, V1 };

/// One face's side of an edge: trim curve `curve` of loop `loop`, or (for an untrimmed face)
/// the domain edge `domainEdge`.
struct ContinuitySide {
    SurfaceId surface;
    TrimLoopId loop;
    int curve = -1;
    DomainEdge domainEdge = DomainEdge::None;
    auto operator<=>(const ContinuitySide&) const = default;
};

/// Two sides that are one edge. `recorded`: the SharedEdge's id when the import recorded it,
/// invalid when it was found by matching. `covers[k]`: side k lies wholly on the other side, so
/// its samples measure the edge; both for an edge of two equal sides, one when one side is a
/// part of a longer one (a T-junction).
struct ContinuityEdge {
    EdgeId recorded;
    double tolerance = 0.0; ///< the recorded edge's own (SharedEdge::tolerance), 0 if found
    std::array<ContinuitySide, 2> sides;
    std::array<bool, 2> covers{true, true};
};

/// The edges of a scene and the boundaries that meet nothing.
struct ContinuityTopology {
    std::vector<ContinuityEdge> edges; ///< the recorded ones in the record's order, then found
    std::vector<ContinuitySide> freeSides;
    /// Boundaries shorter than the G0 tolerance (a sphere's poles, a collapsed trim curve) and
    /// recorded edges with such a side: they have no across-direction, so they are neither
    /// measured nor free.
    std::vector<ContinuitySide> degenerateSides;
    /// Recorded sides naming a surface, loop or curve the scene lacks: neither measured nor free.
    int unresolvedSides = 0;
    /// Faces whose edges were found by matching boundaries: every face of a scene without a
    /// record, and the faces of a recorded scene that no recorded edge touches.
    int matchedFaces = 0;
};

/// The edges of `scene`: every SharedEdge of scene.topology, and, for the faces that no recorded
/// edge touches, their trim curves (or, untrimmed, the four edges of their domain) paired where
/// all samples of one lie within tolerances.match of the other. A face in the record has its
/// trim curves that are no side of a recorded edge as free sides. Cost: O(B log B) plus ~16
/// projections per candidate pair, B the boundaries of unrecorded faces.
ContinuityTopology continuityTopology(const Scene& scene, const ContinuityTolerances& tolerances);

/// The measure of one edge: the maxima over its samples and where they occur (points on the
/// side whose sample gave them).
struct EdgeContinuity {
    ContinuityEdge edge;
    double g0 = 0.0;        ///< largest distance between the sides (model units)
    double g1Degrees = 0.0; ///< largest angle between the normals, folded into [0, 90]
    double g2Percent = 0.0; ///< largest jump of normal curvature across the edge, % of larger
    glm::dvec3 g0At{0.0}, g1At{0.0}, g2At{0.0};
    int samples = 0;   ///< points measured (both directions)
    int g2Samples = 0; ///< of them, points where both sides had a curvature (no pole)
    ContinuityClass continuity = ContinuityClass::G2;
};

/// Least number of evenly spread points each covering side is measured at, besides its knots
/// (and for a domain edge, the surface's knots along it): 100 intervals, so the step is 1/100
/// of the side's parameter range, and never fewer than 64.
constexpr int kContinuitySamples = 101;

/// Curvatures below this, times the edges' size, count as flat for G2: their jump is measured
/// against it instead of against the larger curvature, so two planes (0 and 1e-15) are G2.
constexpr double kFlatCurvature = 1e-4;

/// Measures `edge` of `scene`. At every sample of a covering side: the foot of the perpendicular
/// on the other side's edge (model/document/seamgaps.h, nearestOnSeamSide) gives the gap; the unit
/// normals there give the angle; the normal curvatures of both faces in the direction normal to
/// the edge within each tangent plane (kn = II(d) / I(d), Do Carmo 3.2), the other's signed
/// against this side's normal, give the jump. Points where a surface has no plain normal (a
/// pole) count for G0 and G1 (limit normal, surfaceFrame) but not for G2. An edge whose side
/// the scene lacks gets an infinite gap (open).
EdgeContinuity measureEdgeContinuity(const Scene& scene, const ContinuityEdge& edge,
                                     const ContinuityTolerances& tolerances,
                                     int samples = kContinuitySamples);

/// The class of a measured edge under `tolerances`.
ContinuityClass classifyContinuity(const EdgeContinuity& e, const ContinuityTolerances& t);

/// Everything: the topology and every edge measured.
struct ContinuityReport {
    ContinuityTolerances tolerances;
    ContinuityTopology topology;
    std::vector<EdgeContinuity> edges; ///< topology.edges measured, in order
    int count(ContinuityClass c) const;
};

/// continuityTopology and measureEdgeContinuity of every edge (shared out over the cores when
/// there are many). Precondition: valid tolerances (checkContinuityTolerances).
ContinuityReport continuityReport(const Scene& scene, const ContinuityTolerances& tolerances);

/// Measures every edge of `report.topology` into `report.edges` (resized to match), in blocks
/// of a few hundred edges each shared out over the cores; between blocks, on the calling
/// thread, calls `progress(done, total)` (edges measured so far, of all), which returns false to
/// stop. Returns false when stopped (report.edges then partly measured), true when all are.
/// For a caller on a worker thread that shows progress and may be cancelled (the editor's
/// overlay on a large model). Precondition: report.tolerances valid.
bool measureContinuity(ContinuityReport& report, const Scene& scene,
                       const std::function<bool(size_t done, size_t total)>& progress);

/// The topology of `scene` with no edge measured yet (each edge's values zero, class G2): for
/// updateContinuity to measure only the edges of faces as they change, without the cost of
/// measuring every edge first (the status bar's check of a drag while the overlay is off).
/// Precondition: valid tolerances.
ContinuityReport continuityWatch(const Scene& scene, const ContinuityTolerances& tolerances);

/// Re-measures, in `report`, the edges that touch one of `faces` (ascending ids), after their
/// shape changed; the topology (which boundaries pair) stays as found, so an edge dragged apart
/// shows as open rather than as two free sides. Returns how many edges were measured. A drag
/// step costs this for the dragged face's edges.
int updateContinuity(ContinuityReport& report, const Scene& scene,
                     const std::vector<SurfaceId>& faces);

/// What an edit did to the seams of the faces it moved (for a status bar during a drag of a
/// point on a trimmed face, whose neighbours' edges no control point shares).
struct SeamOpening {
    int open = 0;            ///< edges touching the faces whose gap is above tolerance
    double largestGap = 0.0; ///< the largest of their gaps (model units)
};
/// Counts the open edges of `report` (re-measured: updateContinuity) that touch `faces`
/// (ascending ids).
SeamOpening seamsOpenAt(const ContinuityReport& report, const std::vector<SurfaceId>& faces);
/// "opens 2 seams, max gap 0.8", or empty when none is open; `unit` ("mm"), when given, follows
/// the gap.
QString seamOpeningText(const SeamOpening& opening, const QString& unit = {});

/// Every edge with a side on `surface`, as indices into `topology.edges`.
std::vector<size_t> edgesOfFace(const ContinuityTopology& topology, SurfaceId surface);

/// The boundaries of a face: its trim curves, or the four edges of its domain when untrimmed.
std::vector<ContinuitySide> continuityBoundaries(const Surface& surface);

/// The edge curve of a side (trim curve or domain edge) on its surface, sampled as
/// makeSeamSide does; nullopt when the scene lacks it. `surface` must outlive the result.
std::optional<SeamSide> continuitySideCurve(const Surface& surface, const ContinuitySide& side,
                                            int samples);

} // namespace kw
