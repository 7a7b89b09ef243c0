// Section classes of base-polygon cells (see section_cells.h).
#include "render/section_cells.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace kw {

std::vector<CellBox> polygonCellBoxes(const NurbsSurface& surface, const BasePolygon& polygon,
                                      const std::vector<SpanBound>& spans) {
    std::map<std::pair<int, int>, const SpanBound*> bySpan;
    for (const SpanBound& s : spans)
        bySpan[{s.spanU, s.spanV}] = &s;
    const int cu = polygon.cellsU(), cv = polygon.cellsV();
    std::vector<CellBox> boxes(size_t(cu) * size_t(cv));
    // The polygon's nodes: exact surface points at the breaks.
    const int nu = polygon.nodesU();
    std::vector<glm::dvec3> nodes(size_t(nu) * polygon.breaksV.size());
    for (size_t j = 0; j < polygon.breaksV.size(); ++j)
        for (int i = 0; i < nu; ++i)
            nodes[j * size_t(nu) + size_t(i)] =
                surfacePoint(surface, polygon.breaksU[size_t(i)], polygon.breaksV[j]);
    // The sub-rectangles [first, last] of a span's grid that the interval [a, b] overlaps.
    const auto subRange = [](double a, double b, double s0, double s1, int grid) {
        const double scale = double(grid) / (s1 - s0);
        const int first = std::clamp(int(std::floor((a - s0) * scale)), 0, grid - 1);
        const int last = std::clamp(int(std::ceil((b - s0) * scale)) - 1, first, grid - 1);
        return std::pair<int, int>(first, last);
    };
    for (int j = 0; j < cv; ++j)
        for (int i = 0; i < cu; ++i) {
            const auto it = bySpan.find({polygon.spanU[size_t(i)], polygon.spanV[size_t(j)]});
            if (it == bySpan.end())
                return {};
            const SpanBound& s = *it->second;
            const auto [a0, a1] = subRange(polygon.breaksU[size_t(i)],
                                           polygon.breaksU[size_t(i + 1)], s.u0, s.u1, s.grid);
            const auto [b0, b1] = subRange(polygon.breaksV[size_t(j)],
                                           polygon.breaksV[size_t(j + 1)], s.v0, s.v1, s.grid);
            CellBox box{glm::dvec3(std::numeric_limits<double>::max()),
                        glm::dvec3(-std::numeric_limits<double>::max())};
            SecondDerivativeBound m;
            for (int b = b0; b <= b1; ++b)
                for (int a = a0; a <= a1; ++a) {
                    const SpanBound::Sub& sub = s.subs[size_t(b * s.grid + a)];
                    box.lo = glm::min(box.lo, sub.lo);
                    box.hi = glm::max(box.hi, sub.hi);
                    m.uu = std::max(m.uu, sub.m.uu);
                    m.uv = std::max(m.uv, sub.m.uv);
                    m.vv = std::max(m.vv, sub.m.vv);
                }
            const double deviation =
                cellDeviationBound(m, polygon.breaksU[size_t(i + 1)] - polygon.breaksU[size_t(i)],
                                   polygon.breaksV[size_t(j + 1)] - polygon.breaksV[size_t(j)]);
            glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-lo);
            for (int c = 0; c < 4; ++c) {
                const glm::dvec3& p =
                    nodes[size_t(j + (c >> 1)) * size_t(nu) + size_t(i + (c & 1))];
                lo = glm::min(lo, p);
                hi = glm::max(hi, p);
            }
            box.lo = glm::max(box.lo, lo - deviation);
            box.hi = glm::min(box.hi, hi + deviation);
            boxes[size_t(j) * size_t(cu) + size_t(i)] = box;
        }
    return boxes;
}

CellSection boxSection(const glm::dvec3& lo, const glm::dvec3& hi,
                       const std::vector<SectionPlane>& planes, double margin) {
    bool crossed = false;
    for (const SectionPlane& plane : planes) {
        const glm::dvec3 n = plane.removedSide();
        if (n == glm::dvec3(0.0))
            continue;
        // The box's extent along n about its centre: its corners' distances to the plane lie
        // within centre +- radius.
        const glm::dvec3 c = 0.5 * (lo + hi), h = 0.5 * (hi - lo);
        const double centre = glm::dot(n, c - plane.position);
        const double radius = std::abs(n.x) * h.x + std::abs(n.y) * h.y + std::abs(n.z) * h.z;
        if (centre - radius > margin)
            return CellSection::Removed;
        crossed = crossed || centre + radius > -margin;
    }
    return crossed ? CellSection::Crossed : CellSection::Kept;
}

std::vector<CellSection> sectionCellClasses(const BasePolygon& polygon,
                                            const std::vector<CellBox>& boxes,
                                            const std::vector<SectionPlane>& planes,
                                            const ScreenScale& scale, double marginPixels) {
    const int cu = polygon.cellsU(), cv = polygon.cellsV();
    if (boxes.size() != size_t(cu) * size_t(cv))
        return {};
    // The 3 x 3 ring's union, separably: along u, then along v.
    std::vector<CellBox> alongU(boxes.size());
    for (int j = 0; j < cv; ++j)
        for (int i = 0; i < cu; ++i) {
            CellBox b = boxes[size_t(j) * size_t(cu) + size_t(i)];
            for (int k = std::max(i - 1, 0); k <= std::min(i + 1, cu - 1); ++k) {
                const CellBox& o = boxes[size_t(j) * size_t(cu) + size_t(k)];
                b.lo = glm::min(b.lo, o.lo);
                b.hi = glm::max(b.hi, o.hi);
            }
            alongU[size_t(j) * size_t(cu) + size_t(i)] = b;
        }
    double planeScale = 0.0;
    for (const SectionPlane& p : planes)
        planeScale = std::max(planeScale, glm::length(p.position));
    // A pixel's footprint at depth z is at most z (1 + t^2) / f (t: the frustum's half
    // diagonal's tangent; the ray is longer and slanted there).
    const double perDepth =
        marginPixels * (1.0 + scale.tanHalfDiagonal * scale.tanHalfDiagonal) /
        std::max(scale.focalPixels, 1e-300);
    std::vector<CellSection> classes(boxes.size(), CellSection::Crossed);
    for (int j = 0; j < cv; ++j)
        for (int i = 0; i < cu; ++i) {
            CellBox b = alongU[size_t(j) * size_t(cu) + size_t(i)];
            for (int k = std::max(j - 1, 0); k <= std::min(j + 1, cv - 1); ++k) {
                const CellBox& o = alongU[size_t(k) * size_t(cu) + size_t(i)];
                b.lo = glm::min(b.lo, o.lo);
                b.hi = glm::max(b.hi, o.hi);
            }
            double far = scale.nearDepth;
            for (int c = 0; c < 8; ++c) {
                const glm::dvec3 p(c & 1 ? b.hi.x : b.lo.x, c & 2 ? b.hi.y : b.lo.y,
                                   c & 4 ? b.hi.z : b.lo.z);
                far = std::max(far, glm::dot(p - scale.eye, scale.forward));
            }
            // The shader compares float distances: the float resolution of the coordinates.
            const double rounding = 1e-5 * (glm::length(b.hi - b.lo) + glm::length(b.hi) +
                                            glm::length(b.lo) + planeScale);
            classes[size_t(j) * size_t(cu) + size_t(i)] =
                boxSection(b.lo, b.hi, planes, far * perDepth + rounding);
        }
    return classes;
}

} // namespace kw
