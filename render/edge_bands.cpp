// Edge Continuity overlay geometry from the kernel's report.
#include "render/edge_bands.h"

#include <QHash>

namespace kw {

glm::vec4 continuityColor(ContinuityClass c) {
    switch (c) {
    case ContinuityClass::G2:
        return {0.10f, 0.78f, 0.25f, 1.0f};
    case ContinuityClass::G1:
        return {0.15f, 0.50f, 1.00f, 1.0f};
    case ContinuityClass::G0:
        return {1.00f, 0.62f, 0.00f, 1.0f};
    case ContinuityClass::Open:
        break;
    }
    return {0.95f, 0.08f, 0.08f, 1.0f};
}

glm::vec4 freeEdgeColor() {
    return {0.90f, 0.15f, 0.90f, 1.0f};
}

std::vector<EdgeBandVertex> edgeBandLine(const Surface& surface, const ContinuitySide& side,
                                         const glm::vec4& color, int segments) {
    std::vector<EdgeBandVertex> out;
    const std::optional<SeamSide> curve = continuitySideCurve(surface, side, segments + 1);
    if (!curve)
        return out;
    for (size_t k = 1; k < curve->at.size(); ++k) {
        out.push_back({glm::vec3(curve->at[k - 1]), color});
        out.push_back({glm::vec3(curve->at[k]), color});
    }
    return out;
}

namespace {

void addSide(const QHash<SurfaceId, const Surface*>& surfaces, const ContinuitySide& side,
             const glm::vec4& color, int segments, std::vector<EdgeBandVertex>& out) {
    if (const Surface* s = surfaces.value(side.surface, nullptr)) {
        const std::vector<EdgeBandVertex> line = edgeBandLine(*s, side, color, segments);
        out.insert(out.end(), line.begin(), line.end());
    }
}

} // namespace

EdgeBands makeEdgeBands(const Scene& scene, const ContinuityReport& report, std::uint64_t revision,
                        int segments) {
    QHash<SurfaceId, const Surface*> surfaces;
    for (const Surface& s : scene.surfaces)
        if (!s.hidden)
            surfaces.insert(s.id, &s);
    EdgeBands bands;
    bands.revision = revision;
    for (const EdgeContinuity& e : report.edges)
        addSide(surfaces, e.edge.covers[0] ? e.edge.sides[0] : e.edge.sides[1],
                continuityColor(e.continuity), segments, bands.vertices);
    for (const ContinuitySide& side : report.topology.freeSides)
        addSide(surfaces, side, freeEdgeColor(), segments, bands.vertices);
    return bands;
}

} // namespace kw
