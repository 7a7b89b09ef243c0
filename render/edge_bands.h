// The Edge Continuity overlay's geometry, built on the CPU from the continuity kernel's report
// (no GL): coloured line segments along every measured edge and every free edge.
#pragma once

#include "model/analysis/continuity.h"

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <span>
#include <vector>

namespace kw {

/// One end of a band segment. Matches shaders/edge_bands.vert (kAttrPosition, kAttrBandColour).
struct EdgeBandVertex {
    glm::vec3 position;
    glm::vec4 color;
};
static_assert(sizeof(EdgeBandVertex) == 7 * sizeof(float), "tightly packed for the VBO");

/// One edge's (or free side's) band within EdgeBands::vertices, with its bounds, so that the
/// pass can leave out the bands wholly off screen (a close-up of a large model).
struct EdgeBandRange {
    std::uint32_t first = 0, count = 0; ///< vertices [first, first + count)
    glm::vec3 lo{0.0f}, hi{0.0f};       ///< bounds of those vertices' positions
    /// The EdgeBands::revision at which these vertices last changed.
    std::uint64_t revision = 0;
};

/// Line segments (pairs of vertices, GL_LINES) to draw as bands `widthPixels` wide over the
/// surfaces. `revision` changes whenever the vertices do, so the pass uploads only then.
/// `ranges`, when not empty, cover every vertex in order, one per band.
struct EdgeBands {
    std::vector<EdgeBandVertex> vertices;
    std::vector<EdgeBandRange> ranges;
    std::uint64_t revision = 0;
    /// The revision at which the ranges last changed in number, order or length. A pass that
    /// holds an upload of a revision at or after it (and before `revision`) need upload only the
    /// ranges whose own revision is newer than its upload: a drag step's few edges, not all.
    std::uint64_t layoutRevision = 0;
    float widthPixels = 4.0f;
};

/// A fresh band revision, process-wide: bands made by different caches (the overlay's and a
/// background run's) never share one, so a pass never mistakes new bands for those it holds.
std::uint64_t nextEdgeBandRevision();

/// The overlay's colours: G2 green, G1 blue, G0 (within tolerance, at an angle) orange, open
/// red; free edges magenta. The legend and the gl test read them from here.
glm::vec4 continuityColor(ContinuityClass c);
glm::vec4 freeEdgeColor();

/// The segments (vertex pairs) of a polyline of `segments` pieces along `side` of `surface`;
/// empty when the surface lacks it.
std::vector<EdgeBandVertex> edgeBandLine(const Surface& surface, const ContinuitySide& side,
                                         const glm::vec4& color, int segments = 48);

/// Runs of EdgeBands::vertices to draw (GL_LINES first / count), adjacent bands merged.
struct EdgeBandRuns {
    std::vector<std::int32_t> first, count;
};

/// The bands of `bands` not wholly outside one side plane of the frustum of `viewProjection`
/// (an OpenGL clip transform), its sides pushed out by `margin` (a fraction of the half-size,
/// for the band's pixels beside its line): a conservative test on each range's bounds, so a
/// band that shows is never left out. Every vertex as one run when `bands.ranges` is empty.
EdgeBandRuns visibleEdgeBands(const EdgeBands& bands, const glm::mat4& viewProjection,
                              float margin);

/// The overlay's bands kept between edits, so that an edit re-makes only the lines of the
/// faces it changed (a drag step: the dragged face's edges) and the rest stay as they are. The
/// editor's overlay and the bench's drag step both use it.
class EdgeBandCache {
public:
    /// Re-makes the lines of the edges and free sides of `report` with a side on one of `faces`
    /// (every line when `faces` is empty or the report's edges changed in number): an edge's
    /// colour follows its class, its curve the side that covers it. Hidden surfaces (and
    /// surfaces `scene` lacks) get no line. Returns all lines as bands with a new revision.
    /// When no re-made line changed its length (a drag step), that is the object the last call
    /// returned, updated in place: only the re-made ranges are written and stamped with the new
    /// revision, nothing else is copied, and a pass uploads just those ranges. So the bands must
    /// be read on the thread that updates them (the GUI thread, in the editor).
    std::shared_ptr<const EdgeBands> update(const Scene& scene, const ContinuityReport& report,
                                            const std::vector<SurfaceId>& faces = {});
    void clear();
    /// The segments of report.edges[k]'s line (empty for a hidden face, or past the end).
    std::span<const EdgeBandVertex> edgeLine(size_t k) const;
    /// How many edges' lines are kept (report.edges.size() after update).
    size_t edgeCount() const { return m_edges; }

private:
    std::shared_ptr<EdgeBands> m_bands;
    /// Per edge, then per free side: its index in m_bands->ranges, -1 when its line is empty.
    std::vector<std::int64_t> m_rangeOf;
    size_t m_edges = 0, m_free = 0;
};

/// Polylines of `segments` pieces along each edge of `report` (its first side's curve),
/// coloured by class, and along each free side. `revision` is stored as is.
EdgeBands makeEdgeBands(const Scene& scene, const ContinuityReport& report, std::uint64_t revision,
                        int segments = 48);

} // namespace kw
