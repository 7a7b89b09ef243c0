// View-adaptive partitions: the cached choice per surface (see adaptive_partitions.h).
#include "render/adaptive_partitions.h"

#include <algorithm>
#include <cmath>

namespace kw {

ScreenScale frameScreenScale(const FrameCamera& camera) {
    ScreenScale sc;
    sc.eye = glm::dvec3(camera.eye);
    sc.forward = glm::dvec3(camera.forward);
    // A perspective projection's [0][0] and [1][1] are 1 / tan of the half angles.
    const double tanHalfX = 1.0 / double(camera.projection[0][0]);
    const double tanHalfY = 1.0 / double(camera.projection[1][1]);
    sc.focalPixels = 0.5 * double(std::max(camera.viewport.y, 1)) / tanHalfY;
    sc.tanHalfDiagonal = std::sqrt(tanHalfX * tanHalfX + tanHalfY * tanHalfY);
    sc.nearDepth = std::max(double(camera.nearPlane), 1e-300);
    sc.cullOutsideView = true;
    sc.viewProjection = glm::dmat4(camera.viewProjection);
    return sc;
}

PartitionChoice chooseCut(const NurbsSurface& s, const std::vector<SpanBound>& spans,
                          const ParameterBox& box, const ScreenScale& scale, double tolerance,
                          int minU, int minV) {
    PartitionChoice uniform = choosePartitions(spans, box.u, box.v, scale, tolerance, minU, minV);
    uniform.breaksU = cellBreaks(s.knotsU, uniform.nu, box.u);
    uniform.breaksV = cellBreaks(s.knotsV, uniform.nv, box.v);
    // Both meet the tolerance; the tensor grid leaves coarse what needs little or is not
    // seen. Its coarser cells put the polygon's silhouettes nearer the full tolerance inside
    // the exact ones: the silhouette fins (kw::buildFins) cover the pixel centres there.
    PartitionChoice tensor = chooseBreaks(spans, box.u, box.v, scale, tolerance, minU, minV);
    const auto cells = [](const PartitionChoice& c) {
        return std::int64_t(c.breaksU.size() - 1) * std::int64_t(c.breaksV.size() - 1);
    };
    if (!tensor.met || (uniform.met && cells(uniform) <= cells(tensor)))
        return uniform;
    return tensor;
}

int AdaptivePartitions::gridFor(int spans) {
    return spans <= 16 ? 4 : spans <= 64 ? 2 : 1;
}

const std::vector<SpanBound>& AdaptivePartitions::spans(const Surface& surface,
                                                         const Revisions& rev) {
    if (m_haveSpans && m_geometry.points == rev.points && m_geometry.knots == rev.knots)
        return m_spans;
    const NurbsSurface& g = surface.geometry;
    // Count the spans first: the grid depends on them.
    int spans = 0;
    for (int ku = g.degreeU; ku < g.countU; ++ku)
        for (int kv = g.degreeV; kv < g.countV; ++kv)
            spans += g.knotsU[size_t(ku)] < g.knotsU[size_t(ku + 1)] &&
                     g.knotsV[size_t(kv)] < g.knotsV[size_t(kv + 1)];
    m_spans = surfaceSpanBounds(g, gridFor(spans));
    m_geometry = rev;
    m_haveSpans = true;
    m_inBox.clear();
    m_box = ParameterBox{{1.0, 0.0}, {1.0, 0.0}}; // forces choose's filter
    return m_spans;
}

const PartitionChoice& AdaptivePartitions::choose(const Surface& surface, const Revisions& rev,
                                                  const ParameterBox& box, const ScreenScale& scale,
                                                  std::uint64_t viewStamp, double tolerance,
                                                  int minU, int minV, bool* recomputed) {
    if (recomputed)
        *recomputed = false;
    const NurbsSurface& g = surface.geometry;
    bool stale = !m_haveChoice || m_viewStamp != viewStamp || m_minU != minU || m_minV != minV;
    if (!m_haveSpans || m_geometry.points != rev.points || m_geometry.knots != rev.knots) {
        spans(surface, rev);
        stale = true;
    }
    if (!(box == m_box)) {
        // Spans wholly outside the polygon's box carry no cell of it.
        m_inBox.clear();
        for (const SpanBound& b : m_spans)
            if (b.u1 > box.u.first && b.u0 < box.u.last && b.v1 > box.v.first && b.v0 < box.v.last)
                m_inBox.push_back(b);
        m_box = box;
        stale = true;
    }
    if (stale) {
        // The breaks are kept once, in the cut the polygon is built from.
        PartitionChoice c = chooseCut(g, m_inBox, box, scale, tolerance, minU, minV);
        m_cut = PolygonCut{c.nu, c.nv, std::move(c.breaksU), std::move(c.breaksV)};
        c.breaksU.clear();
        c.breaksV.clear();
        m_choice = std::move(c);
        m_viewStamp = viewStamp;
        m_minU = minU;
        m_minV = minV;
        m_haveChoice = true;
        if (recomputed)
            *recomputed = true;
    }
    return m_choice;
}

} // namespace kw
