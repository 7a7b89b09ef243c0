// Edge Continuity overlay geometry from the kernel's report.
#include "render/edge_bands.h"

#include <QHash>
#include <algorithm>
#include <atomic>
#include <optional>

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

std::uint64_t nextEdgeBandRevision() {
    static std::atomic<std::uint64_t> counter{0};
    return ++counter;
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
                    line.front().position, line.front().position, out.revision};
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
    bands.revision = bands.layoutRevision = revision;
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

namespace {

/// `line`'s range at `first`, its bounds, stamped `revision`.
EdgeBandRange bandRange(const std::vector<EdgeBandVertex>& line, size_t first,
                        std::uint64_t revision) {
    EdgeBandRange r{std::uint32_t(first), std::uint32_t(line.size()), glm::vec3(0.0f),
                    glm::vec3(0.0f), revision};
    if (!line.empty())
        r.lo = r.hi = line.front().position;
    for (const EdgeBandVertex& v : line) {
        r.lo = glm::min(r.lo, v.position);
        r.hi = glm::max(r.hi, v.position);
    }
    return r;
}

} // namespace

std::shared_ptr<const EdgeBands> EdgeBandCache::update(const Scene& scene,
                                                       const ContinuityReport& report,
                                                       const std::vector<SurfaceId>& faces) {
    const size_t edges = report.edges.size(), free = report.topology.freeSides.size();
    const bool all = faces.empty() || !m_bands || m_edges != edges || m_free != free;
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
    // Line k: edge k, or free side k - edges; nullopt when untouched.
    const auto line = [&](size_t k) -> std::optional<std::vector<EdgeBandVertex>> {
        ContinuitySide side;
        glm::vec4 color;
        if (k < edges) {
            const EdgeContinuity& e = report.edges[k];
            // A class may change with the other side's edit: every edge of the faces is re-made.
            if (!touched(e.edge.sides[0]) && !touched(e.edge.sides[1]))
                return std::nullopt;
            side = e.edge.covers[0] ? e.edge.sides[0] : e.edge.sides[1];
            color = continuityColor(e.continuity);
        } else {
            side = report.topology.freeSides[k - edges];
            if (!touched(side))
                return std::nullopt;
            color = freeEdgeColor();
        }
        const Surface* s = surface(side.surface);
        return s && !s->hidden ? edgeBandLine(*s, side, color) : std::vector<EdgeBandVertex>{};
    };
    const std::uint64_t revision = nextEdgeBandRevision();
    std::vector<std::pair<size_t, std::vector<EdgeBandVertex>>> fresh;
    if (!all) {
        bool sameLengths = true;
        for (size_t k = 0; k < edges + free; ++k)
            if (std::optional<std::vector<EdgeBandVertex>> l = line(k)) {
                const std::int64_t r = m_rangeOf[k];
                sameLengths = sameLengths && l->size() == (r < 0 ? 0 : m_bands->ranges[r].count);
                fresh.emplace_back(k, std::move(*l));
            }
        if (sameLengths) {
            // A drag step: the re-made lines written over their old ones, nothing else copied.
            for (const auto& [k, l] : fresh)
                if (!l.empty()) {
                    EdgeBandRange& r = m_bands->ranges[size_t(m_rangeOf[k])];
                    std::copy(l.begin(), l.end(), m_bands->vertices.begin() + r.first);
                    r = bandRange(l, r.first, revision);
                }
            m_bands->revision = revision;
            return m_bands;
        }
    }
    // New bands: every line made (all), or the old ones spliced with the re-made ones.
    auto bands = std::make_shared<EdgeBands>();
    bands->revision = bands->layoutRevision = revision;
    std::vector<std::int64_t> rangeOf(edges + free, -1);
    size_t next = 0;
    for (size_t k = 0; k < edges + free; ++k) {
        const std::vector<EdgeBandVertex>* l = nullptr;
        std::optional<std::vector<EdgeBandVertex>> made;
        if (all) {
            made = line(k);
            l = &*made;
        } else if (next < fresh.size() && fresh[next].first == k) {
            l = &fresh[next++].second;
        }
        if (l) {
            if (l->empty())
                continue;
            rangeOf[k] = std::int64_t(bands->ranges.size());
            bands->ranges.push_back(bandRange(*l, bands->vertices.size(), revision));
            bands->vertices.insert(bands->vertices.end(), l->begin(), l->end());
        } else if (m_rangeOf[k] >= 0) {
            EdgeBandRange r = m_bands->ranges[size_t(m_rangeOf[k])];
            const auto from = m_bands->vertices.begin() + r.first;
            r.first = std::uint32_t(bands->vertices.size());
            r.revision = revision;
            rangeOf[k] = std::int64_t(bands->ranges.size());
            bands->ranges.push_back(r);
            bands->vertices.insert(bands->vertices.end(), from, from + r.count);
        }
    }
    m_bands = std::move(bands);
    m_rangeOf = std::move(rangeOf);
    m_edges = edges;
    m_free = free;
    return m_bands;
}

std::span<const EdgeBandVertex> EdgeBandCache::edgeLine(size_t k) const {
    if (k >= m_edges || m_rangeOf[k] < 0)
        return {};
    const EdgeBandRange& r = m_bands->ranges[size_t(m_rangeOf[k])];
    return {m_bands->vertices.data() + r.first, r.count};
}

void EdgeBandCache::clear() {
    m_bands.reset();
    m_rangeOf.clear();
    m_edges = m_free = 0;
}

} // namespace kw
