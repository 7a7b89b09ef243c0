// ControlPointPicker: control points projected to pixels on the CPU; the nearest one within a
// few pixels of a click, or all inside a rubber band.
#pragma once

#include "model/document/document.h"
#include "ui/cameracontroller.h"

#include <QPointF>
#include <QRectF>
#include <optional>
#include <vector>

namespace kw {

class ControlPointPicker {
public:
    static constexpr double kDefaultRadius = 6.0; ///< pixels

    /// Projects every control point of every surface of `doc` (points behind the eye are
    /// skipped), or of the surfaces listed in `only` when given. Call again after the camera,
    /// the widget size or the points change.
    void update(const Document& doc, const ViewProjection& view,
                const std::vector<SurfaceId>* only = nullptr);

    /// The control point whose projection is nearest to `pixel` and at most `radius` pixels
    /// away; among equally near ones, the one closest to the eye. nullopt when none.
    std::optional<ControlPointRef> nearest(QPointF pixel, double radius = kDefaultRadius) const;
    /// Every control point projected inside `rect` (normalised first), sorted.
    std::vector<ControlPointRef> inRect(const QRectF& rect) const;
    /// Pixel position of a control point from the last update; nullopt if not projected.
    std::optional<QPointF> pixelOf(const ControlPointRef& ref) const;

    struct Projected {
        ControlPointRef ref;
        QPointF pixel;
        double depth = 0.0;
    };
    const std::vector<Projected>& projected() const { return m_points; }

private:
    std::vector<Projected> m_points;
};

} // namespace kw
