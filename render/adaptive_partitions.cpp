// View-adaptive partitions: the cached choice per surface (see adaptive_partitions.h).
#include "render/adaptive_partitions.h"

#include <algorithm>
#include <cmath>
#include <iterator>

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
    sc.viewportPixels = glm::dvec2(std::max(camera.viewport.x, 1), std::max(camera.viewport.y, 1));
    return sc;
}

double viewMarginPixels(double tolerance) {
    return 2.0 * std::max(tolerance, 0.0) + 2.0;
}

PolygonCut cutInView(const PolygonCut& cut, const std::vector<SpanBound>& spans,
                     bool cellsInOneSub, const ScreenScale& scale, double marginPixels) {
    const std::vector<double>&bu = cut.breaksU, &bv = cut.breaksV;
    if (!scale.cullOutsideView || bu.size() < 2 || bv.size() < 2)
        return cut;
    // The frustum grown by the margin: |x| <= w (1 + 2 m / width) is |x'| <= w for
    // x' = x / (1 + 2 m / width), and likewise y.
    glm::dmat4 grow(1.0);
    grow[0][0] = 1.0 / (1.0 + 2.0 * marginPixels / scale.viewportPixels.x);
    grow[1][1] = 1.0 / (1.0 + 2.0 * marginPixels / scale.viewportPixels.y);
    const glm::dmat4 clip = grow * scale.viewProjection;
    // The (u, v) rectangle of the parts that may show (SpanBound::sideU / sideV).
    double u0 = 1e300, u1 = -1e300, v0 = 1e300, v1 = -1e300;
    const auto add = [&](double a0, double a1, double b0, double b1) {
        u0 = std::min(u0, a0), u1 = std::max(u1, a1);
        v0 = std::min(v0, b0), v1 = std::max(v1, b1);
    };
    for (const SpanBound& b : spans) {
        if (b.u1 <= bu.front() || b.u0 >= bu.back() || b.v1 <= bv.front() || b.v0 >= bv.back())
            continue;
        if (!cellsInOneSub) {
            // A cell may straddle this span's sub-rectangles: the span's bounds as one.
            glm::dvec3 lo(1e300), hi(-1e300);
            for (const SpanBound::Sub& sub : b.subs)
                lo = glm::min(lo, sub.lo), hi = glm::max(hi, sub.hi);
            if (!boxOutsideFrustum(clip, lo, hi))
                add(b.u0, b.u1, b.v0, b.v1);
            continue;
        }
        for (int j = 0; j < b.grid; ++j)
            for (int i = 0; i < b.grid; ++i) {
                const SpanBound::Sub& sub = b.subs[size_t(j * b.grid + i)];
                if (!boxOutsideFrustum(clip, sub.lo, sub.hi))
                    add(b.sideU(i), b.sideU(i + 1), b.sideV(j), b.sideV(j + 1));
            }
    }
    // Cells [first, last) along one direction: those meeting (t0, t1), or the first alone.
    const auto lanes = [](const std::vector<double>& br, double t0, double t1, int& first,
                          int& last) {
        const int cells = int(br.size()) - 1;
        first = int(std::upper_bound(br.begin(), br.end(), t0) - br.begin()) - 1;
        last = int(std::lower_bound(br.begin(), br.end(), t1) - br.begin());
        first = std::clamp(first, 0, cells - 1);
        last = std::clamp(last, first + 1, cells);
    };
    int iu0 = 0, iu1 = 1, iv0 = 0, iv1 = 1;
    if (u0 < u1 && v0 < v1) {
        lanes(bu, u0, u1, iu0, iu1);
        lanes(bv, v0, v1, iv0, iv1);
    }
    PolygonCut out;
    out.nu = cut.nu;
    out.nv = cut.nv;
    out.breaksU.assign(bu.begin() + iu0, bu.begin() + iu1 + 1);
    out.breaksV.assign(bv.begin() + iv0, bv.begin() + iv1 + 1);
    return out;
}

namespace {
/// The most sub-rectangles chooseCut bounds again near the eye (about 4 ms at ~1 us each).
constexpr std::int64_t kMaxFinerSubs = 4096;
} // namespace

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
    // Near the eye a sub-rectangle's control bounds can hold the eye's surroundings in view
    // though the surface keeps its distance: finer bounds of the same spans (re-extracted,
    // so tighter; their sides nest in the coarse ones, so a cell inside a fine one is inside a
    // coarse one too) let the tensor grid see that, at a bounded cost per view.
    const auto pastNear = [&] {
        for (const SpanBound& b : spans)
            for (const SpanBound::Sub& sub : b.subs)
                if (boxMinDepth(scale, sub.lo, sub.hi) < scale.nearDepth)
                    return true;
        return false;
    };
    if (!tensor.met && scale.cullOutsideView && !spans.empty() && pastNear()) {
        const int allSpans = surfaceSpanCount(s);
        for (int grid = spans.front().grid * 2;
             grid <= 16 && std::int64_t(allSpans) * grid * grid <= kMaxFinerSubs; grid *= 2) {
            std::vector<SpanBound> finer;
            for (SpanBound& b : surfaceSpanBounds(s, grid))
                if (b.u1 > box.u.first && b.u0 < box.u.last && b.v1 > box.v.first &&
                    b.v0 < box.v.last)
                    finer.push_back(std::move(b));
            PartitionChoice t = chooseBreaks(finer, box.u, box.v, scale, tolerance, minU, minV);
            if (t.met) {
                tensor = std::move(t);
                break;
            }
        }
    }
    const auto cells = [](const PartitionChoice& c) {
        return std::int64_t(c.breaksU.size() - 1) * std::int64_t(c.breaksV.size() - 1);
    };
    if (!tensor.met || (uniform.met && cells(uniform) <= cells(tensor)))
        return uniform;
    return tensor;
}

std::int64_t AdaptivePartitions::hostBytes() const {
    std::int64_t bytes = 0;
    for (const std::vector<SpanBound>* v : {&m_spans, &m_inBox})
        for (const SpanBound& b : *v)
            bytes += std::int64_t(sizeof(SpanBound) + b.subs.size() * sizeof(SpanBound::Sub));
    return bytes + std::int64_t((m_cut.breaksU.size() + m_cut.breaksV.size()) * sizeof(double));
}

int AdaptivePartitions::gridFor(int spans) {
    return spans <= 16 ? 4 : spans <= 64 ? 2 : 1;
}

const std::vector<SpanBound>& AdaptivePartitions::spans(const Surface& surface,
                                                         const Revisions& rev) {
    if (m_haveSpans && m_geometry.points == rev.points && m_geometry.knots == rev.knots)
        return m_spans;
    const NurbsSurface& g = surface.geometry;
    // The grid depends on the count of spans.
    m_spans = surfaceSpanBounds(g, gridFor(surfaceSpanCount(g)));
    m_geometry = rev;
    m_haveSpans = true;
    std::vector<SpanBound>().swap(m_inBox);
    m_allInBox = false;
    m_box = ParameterBox{{1.0, 0.0}, {1.0, 0.0}}; // forces choose's filter
    return m_spans;
}

const PartitionChoice& AdaptivePartitions::choose(const Surface& surface, const Revisions& rev,
                                                  const ParameterBox& box, const ScreenScale& scale,
                                                  std::uint64_t viewStamp, double tolerance,
                                                  int minU, int minV, bool* recomputed,
                                                  bool inView) {
    if (recomputed)
        *recomputed = false;
    const NurbsSurface& g = surface.geometry;
    bool stale = !m_haveChoice || m_viewStamp != viewStamp || m_minU != minU || m_minV != minV ||
                 m_inView != inView;
    if (!m_haveSpans || m_geometry.points != rev.points || m_geometry.knots != rev.knots) {
        spans(surface, rev);
        stale = true;
    }
    if (!(box == m_box)) {
        // Spans wholly outside the polygon's box carry no cell of it.
        const auto meets = [&box](const SpanBound& b) {
            return b.u1 > box.u.first && b.u0 < box.u.last && b.v1 > box.v.first &&
                   b.v0 < box.v.last;
        };
        std::vector<SpanBound>().swap(m_inBox);
        m_allInBox = std::all_of(m_spans.begin(), m_spans.end(), meets);
        if (!m_allInBox)
            std::copy_if(m_spans.begin(), m_spans.end(), std::back_inserter(m_inBox), meets);
        m_box = box;
        stale = true;
    }
    if (stale) {
        // The breaks are kept once, in the cut the polygon is built from.
        PartitionChoice c = chooseCut(g, inBox(), box, scale, tolerance, minU, minV);
        m_choiceCells = std::int64_t(std::max<std::size_t>(c.breaksU.size(), 1) - 1) *
                        std::int64_t(std::max<std::size_t>(c.breaksV.size(), 1) - 1);
        m_cut = PolygonCut{c.nu, c.nv, std::move(c.breaksU), std::move(c.breaksV)};
        // At a close-up most of a surface's cells lie off screen: only those that may reach
        // the view are kept, so the polygon's memory and build follow what is on screen.
        if (inView)
            m_cut = cutInView(m_cut, inBox(), c.cellsInOneSub, scale, viewMarginPixels(tolerance));
        c.breaksU.clear();
        c.breaksV.clear();
        m_choice = std::move(c);
        m_viewStamp = viewStamp;
        m_minU = minU;
        m_minV = minV;
        m_inView = inView;
        m_haveChoice = true;
        if (recomputed)
            *recomputed = true;
    }
    return m_choice;
}

} // namespace kw
