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
             const glm::vec4& color, int segments, EdgeBands& out) {
    const Surface* s = surfaces.value(side.surface, nullptr);
    if (!s)
        return;
    const std::vector<EdgeBandVertex> line = edgeBandLine(*s, side, color, segments);
    if (line.empty())
        return;
    EdgeBandRange r{std::uint32_t(out.vertices.size()), std::uint32_t(line.size()),
                    line.front().position, line.front().position};
    for (const EdgeBandVertex& v : line) {
        r.lo = glm::min(r.lo, v.position);
        r.hi = glm::max(r.hi, v.position);
    }
    out.ranges.push_back(r);
    out.vertices.insert(out.vertices.end(), line.begin(), line.end());
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
                continuityColor(e.continuity), segments, bands);
    for (const ContinuitySide& side : report.topology.freeSides)
        addSide(surfaces, side, freeEdgeColor(), segments, bands);
    return bands;
}

EdgeBandRuns visibleEdgeBands(const EdgeBands& bands, const glm::mat4& viewProjection,
                              float margin) {
    EdgeBandRuns runs;
    if (bands.ranges.empty()) {
        if (!bands.vertices.empty()) {
            runs.first.push_back(0);
            runs.count.push_back(std::int32_t(bands.vertices.size()));
        }
        return runs;
    }
    // The side planes of the frustum from the rows of the clip transform (Gribb and Hartmann,
    // "Fast extraction of viewing frustum planes", 2001): -w <= x, y <= w, widened by margin.
    const auto row = [&](int i) {
        return glm::vec4(viewProjection[0][i], viewProjection[1][i], viewProjection[2][i],
                         viewProjection[3][i]);
    };
    const glm::vec4 w = (1.0f + margin) * row(3);
    const glm::vec4 planes[4] = {w + row(0), w - row(0), w + row(1), w - row(1)};
    for (const EdgeBandRange& r : bands.ranges) {
        bool inside = true;
        for (const glm::vec4& p : planes) {
            // The corner of the box farthest along the plane's normal.
            const glm::vec3 far(p.x > 0.0f ? r.hi.x : r.lo.x, p.y > 0.0f ? r.hi.y : r.lo.y,
                                p.z > 0.0f ? r.hi.z : r.lo.z);
            if (glm::dot(glm::vec3(p), far) + p.w < 0.0f) {
                inside = false;
                break;
            }
        }
        if (!inside)
            continue;
        if (!runs.first.empty() && runs.first.back() + runs.count.back() == std::int32_t(r.first)) {
            runs.count.back() += std::int32_t(r.count);
        } else {
            runs.first.push_back(std::int32_t(r.first));
            runs.count.push_back(std::int32_t(r.count));
        }
    }
    return runs;
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
    const auto bounds = [](const std::vector<EdgeBandVertex>& l) {
        std::pair<glm::vec3, glm::vec3> b{glm::vec3(0.0f), glm::vec3(0.0f)};
        if (!l.empty())
            b = {l.front().position, l.front().position};
        for (const EdgeBandVertex& v : l) {
            b.first = glm::min(b.first, v.position);
            b.second = glm::max(b.second, v.position);
        }
        return b;
    };
    m_edgeLines.resize(report.edges.size());
    m_edgeBounds.resize(report.edges.size());
    m_freeLines.resize(report.topology.freeSides.size());
    m_freeBounds.resize(report.topology.freeSides.size());
    for (size_t k = 0; k < report.edges.size(); ++k) {
        const EdgeContinuity& e = report.edges[k];
        // A class may change with the other side's edit: every edge of the faces is re-made.
        if (touched(e.edge.sides[0]) || touched(e.edge.sides[1])) {
            m_edgeLines[k] = line(e.edge.covers[0] ? e.edge.sides[0] : e.edge.sides[1],
                                  continuityColor(e.continuity));
            m_edgeBounds[k] = bounds(m_edgeLines[k]);
        }
    }
    for (size_t k = 0; k < report.topology.freeSides.size(); ++k)
        if (touched(report.topology.freeSides[k])) {
            m_freeLines[k] = line(report.topology.freeSides[k], freeEdgeColor());
            m_freeBounds[k] = bounds(m_freeLines[k]);
        }
    auto bands = std::make_shared<EdgeBands>();
    bands->revision = ++m_revision;
    size_t count = 0, lines = 0;
    for (const auto* all : {&m_edgeLines, &m_freeLines})
        for (const std::vector<EdgeBandVertex>& l : *all) {
            count += l.size();
            lines += !l.empty();
        }
    bands->vertices.reserve(count);
    bands->ranges.reserve(lines);
    for (const auto& [all, box] :
         {std::pair{&m_edgeLines, &m_edgeBounds}, std::pair{&m_freeLines, &m_freeBounds}})
        for (size_t k = 0; k < all->size(); ++k) {
            const std::vector<EdgeBandVertex>& l = (*all)[k];
            if (l.empty())
                continue;
            bands->ranges.push_back({std::uint32_t(bands->vertices.size()), std::uint32_t(l.size()),
                                     (*box)[k].first, (*box)[k].second});
            bands->vertices.insert(bands->vertices.end(), l.begin(), l.end());
        }
    return bands;
}

void EdgeBandCache::clear() {
    m_edgeLines.clear();
    m_freeLines.clear();
    m_edgeBounds.clear();
    m_freeBounds.clear();
}

} // namespace kw
