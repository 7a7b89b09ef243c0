// OverlayBounds: every primitive QPainter hands its engine, mapped by the painter's transform
// and widened by its pen, joins one rectangle.
#include "ui/overlay_bounds.h"

#include <QFontMetricsF>
#include <QPaintEngine>
#include <QPainterPath>
#include <QPixmap>
#include <QPolygonF>
#include <QTextItem>
#include <cmath>

namespace kw {

class OverlayBoundsEngine : public QPaintEngine {
public:
    OverlayBoundsEngine() : QPaintEngine(AllFeatures) {}

    bool begin(QPaintDevice*) override { return true; }
    bool end() override { return true; }
    Type type() const override { return User; }

    void updateState(const QPaintEngineState& state) override {
        if (state.state() & DirtyTransform)
            m_transform = state.transform();
        if (state.state() & DirtyPen)
            m_pen = state.pen();
    }

    void drawPath(const QPainterPath& path) override { add(path.controlPointRect(), true); }
    void drawPolygon(const QPointF* points, int count, PolygonDrawMode) override {
        if (count > 0)
            add(QPolygonF(QList<QPointF>(points, points + count)).boundingRect(), true);
    }
    void drawLines(const QLineF* lines, int count) override {
        for (int k = 0; k < count; ++k)
            add(QRectF(lines[k].p1(), lines[k].p2()).normalized(), true);
    }
    void drawRects(const QRectF* rects, int count) override {
        for (int k = 0; k < count; ++k)
            add(rects[k].normalized(), true);
    }
    void drawEllipse(const QRectF& r) override { add(r.normalized(), true); }
    void drawPoints(const QPointF* points, int count) override {
        for (int k = 0; k < count; ++k)
            add(QRectF(points[k], QSizeF(0, 0)), true);
    }
    void drawPixmap(const QRectF& r, const QPixmap&, const QRectF&) override { add(r, false); }
    void drawImage(const QRectF& r, const QImage&, const QRectF&,
                   Qt::ImageConversionFlags) override {
        add(r, false);
    }
    void drawTiledPixmap(const QRectF& r, const QPixmap&, const QPointF&) override {
        add(r, false);
    }
    void drawTextItem(const QPointF& p, const QTextItem& item) override {
        // The line's box at the baseline, a character's width either side for glyphs that
        // overhang their advance.
        const QFontMetricsF m(item.font());
        const qreal extra = m.averageCharWidth();
        add(QRectF(p.x() - extra, p.y() - m.ascent(), item.width() + 2 * extra,
                   m.ascent() + m.descent()),
            false);
    }

    QRectF bounds;

private:
    void add(const QRectF& r, bool stroked) {
        QRectF mapped = m_transform.mapRect(r);
        // Half the pen's width in device pixels (a cosmetic pen is one pixel wide), and a
        // pixel for antialiased edges.
        qreal half = 1.0;
        if (stroked && m_pen.style() != Qt::NoPen) {
            const qreal width = std::max<qreal>(m_pen.widthF(), 1.0);
            const qreal scale =
                m_pen.isCosmetic() ? 1.0 : std::sqrt(std::abs(m_transform.determinant()));
            half += 0.5 * width * scale * (m_pen.joinStyle() == Qt::MiterJoin ? 2.0 : 1.0);
        }
        mapped.adjust(-half, -half, half, half);
        bounds = bounds.isNull() ? mapped : bounds.united(mapped);
    }

    QTransform m_transform;
    QPen m_pen;
};

OverlayBounds::OverlayBounds(const QPaintDevice& like)
    : m_engine(std::make_unique<OverlayBoundsEngine>()), m_width(like.width()),
      m_height(like.height()), m_dpiX(like.logicalDpiX()), m_dpiY(like.logicalDpiY()),
      m_physicalDpiX(like.physicalDpiX()), m_physicalDpiY(like.physicalDpiY()),
      m_depth(like.depth()), m_dpr(like.devicePixelRatioF()) {}

OverlayBounds::~OverlayBounds() = default;

QPaintEngine* OverlayBounds::paintEngine() const {
    return m_engine.get();
}

QRect OverlayBounds::bounds() const {
    // The engine sees device pixels already (the painter scales by the pixel ratio).
    return m_engine->bounds.isNull() ? QRect() : m_engine->bounds.toAlignedRect();
}

int OverlayBounds::metric(PaintDeviceMetric metric) const {
    switch (metric) {
    case PdmWidth:
        return m_width;
    case PdmHeight:
        return m_height;
    case PdmWidthMM:
        return qRound(m_width * 25.4 / m_dpiX);
    case PdmHeightMM:
        return qRound(m_height * 25.4 / m_dpiY);
    case PdmNumColors:
        return 0;
    case PdmDepth:
        return m_depth;
    case PdmDpiX:
        return m_dpiX;
    case PdmDpiY:
        return m_dpiY;
    case PdmPhysicalDpiX:
        return m_physicalDpiX;
    case PdmPhysicalDpiY:
        return m_physicalDpiY;
    case PdmDevicePixelRatio:
        return qRound(m_dpr);
    case PdmDevicePixelRatioScaled:
        return qRound(m_dpr * devicePixelRatioFScale());
    }
    return 0;
}

} // namespace kw
