// ControlPointPicker: CPU projection of control points, nearest-within-radius and rubber band.
#include "ui/controlpointpicker.h"

#include <algorithm>
#include <cmath>

namespace kw {

void ControlPointPicker::update(const Document& doc, const ViewProjection& view,
                                const std::vector<SurfaceId>* only) {
    m_points.clear();
    for (const Surface& s : doc.scene().surfaces) {
        if (only && std::find(only->begin(), only->end(), s.id) == only->end())
            continue;
        const NurbsSurface& g = s.geometry;
        for (int j = 0; j < g.countV; ++j)
            for (int i = 0; i < g.countU; ++i) {
                const glm::dvec3& p = g.points[size_t(g.index(i, j))];
                const double depth = view.depth(p);
                if (depth <= 0.0)
                    continue;
                if (const std::optional<QPointF> px = view.project(p))
                    m_points.push_back({ControlPointRef{s.id, i, j}, *px, depth});
            }
    }
}

std::optional<ControlPointRef> ControlPointPicker::nearest(QPointF pixel, double radius) const {
    const Projected* best = nullptr;
    double bestDistance = 0.0;
    for (const Projected& p : m_points) {
        const double d = std::hypot(p.pixel.x() - pixel.x(), p.pixel.y() - pixel.y());
        if (d > radius)
            continue;
        // Points closer than half a pixel to each other count as equally near; then the
        // front one wins (a point hidden exactly behind another cannot be reached otherwise).
        if (!best || d < bestDistance - 0.5 ||
            (std::abs(d - bestDistance) <= 0.5 && p.depth < best->depth)) {
            best = &p;
            bestDistance = d;
        }
    }
    if (!best)
        return std::nullopt;
    return best->ref;
}

std::vector<ControlPointRef> ControlPointPicker::inRect(const QRectF& rect) const {
    const QRectF r = rect.normalized();
    std::vector<ControlPointRef> out;
    for (const Projected& p : m_points)
        if (r.contains(p.pixel))
            out.push_back(p.ref);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

std::optional<QPointF> ControlPointPicker::pixelOf(const ControlPointRef& ref) const {
    for (const Projected& p : m_points)
        if (p.ref == ref)
            return p.pixel;
    return std::nullopt;
}

} // namespace kw
