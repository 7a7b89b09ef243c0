// Edge Continuity overlay geometry from the kernel's report.
#include "render/edge_bands.h"

#include <QHash>
#include <algorithm>

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

std::shared_ptr<const EdgeBands> EdgeBandCache::update(const Scene& scene,
                                                       const ContinuityReport& report,
                                                       const std::vector<SurfaceId>& faces) {
    const bool all = faces.empty() || m_edgeLines.size() != report.edges.size() ||
                     m_freeLines.size() != report.topology.freeSides.size();
    const auto touched = [&](const ContinuitySide& side) {
        return all || std::find(faces.begin(), faces.end(), side.surface) != faces.end();
    };
    // Every surface once when all lines are made; a drag step looks up only its edges' faces.
    QHash<SurfaceId, const Surface*> index;
    if (all)
        for (const Surface& s : scene.surfaces)
            index.insert(s.id, &s);
    const auto surface = [&](SurfaceId id) -> const Surface* {
        if (all)
            return index.value(id, nullptr);
        const auto it = std::find_if(scene.surfaces.begin(), scene.surfaces.end(),
                                     [&](const Surface& s) { return s.id == id; });
        return it == scene.surfaces.end() ? nullptr : &*it;
    };
    const auto line = [&](const ContinuitySide& side, const glm::vec4& color) {
        const Surface* s = surface(side.surface);
        return s && !s->hidden ? edgeBandLine(*s, side, color) : std::vector<EdgeBandVertex>{};
    };
    m_edgeLines.resize(report.edges.size());
    m_freeLines.resize(report.topology.freeSides.size());
    for (size_t k = 0; k < report.edges.size(); ++k) {
        const EdgeContinuity& e = report.edges[k];
        // A class may change with the other side's edit: every edge of the faces is re-made.
        if (touched(e.edge.sides[0]) || touched(e.edge.sides[1]))
            m_edgeLines[k] = line(e.edge.covers[0] ? e.edge.sides[0] : e.edge.sides[1],
                                  continuityColor(e.continuity));
    }
    for (size_t k = 0; k < report.topology.freeSides.size(); ++k)
        if (touched(report.topology.freeSides[k]))
            m_freeLines[k] = line(report.topology.freeSides[k], freeEdgeColor());
    auto bands = std::make_shared<EdgeBands>();
    bands->revision = ++m_revision;
    size_t count = 0;
    for (const auto* lines : {&m_edgeLines, &m_freeLines})
        for (const std::vector<EdgeBandVertex>& l : *lines)
            count += l.size();
    bands->vertices.reserve(count);
    for (const auto* lines : {&m_edgeLines, &m_freeLines})
        for (const std::vector<EdgeBandVertex>& l : *lines)
            bands->vertices.insert(bands->vertices.end(), l.begin(), l.end());
    return bands;
}

void EdgeBandCache::clear() {
    m_edgeLines.clear();
    m_freeLines.clear();
}

} // namespace kw
