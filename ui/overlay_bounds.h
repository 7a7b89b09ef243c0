// OverlayBounds: a QPainter device that draws nothing and keeps the device-pixel bounds of
// what is painted on it, text included (a QPicture's bounding rectangle missed the axis
// indicator's labels: painted twice over a kept frame, tst_editor_analysis).
#pragma once

#include <QPaintDevice>
#include <QRect>
#include <memory>

namespace kw {

class OverlayBoundsEngine;

class OverlayBounds : public QPaintDevice {
public:
    /// Measures as `like` does (size, resolution, pixel ratio), so that what paints on it lays
    /// out as it would there.
    explicit OverlayBounds(const QPaintDevice& like);
    ~OverlayBounds() override;

    QPaintEngine* paintEngine() const override;
    /// What the painters drew, in the device's pixels (y down), widened by their pens and by a
    /// pixel for antialiased edges; null when nothing.
    QRect bounds() const;

protected:
    int metric(PaintDeviceMetric metric) const override;

private:
    std::unique_ptr<OverlayBoundsEngine> m_engine;
    int m_width, m_height, m_dpiX, m_dpiY, m_physicalDpiX, m_physicalDpiY, m_depth;
    qreal m_dpr;
};

} // namespace kw
