// UvPanel: domain, trim loops, mask, and its events routed to the tools.
#include "ui/uvpanel.h"

#include "model/nurbs/trim.h"
#include "ui/tools/uvpaneltools.h"

#include <QFontMetricsF>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QPainter>
#include <QUndoStack>
#include <algorithm>
#include <cmath>

namespace kw {

namespace {

const Surface* shown(const Document* doc, const Selection* sel) {
    return doc->surface(sel->currentSurface());
}

/// Segments (a, b) and (c, d) cross (proper intersection or touching).
bool segmentsCross(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, glm::dvec2 d) {
    auto cross = [](glm::dvec2 o, glm::dvec2 p, glm::dvec2 q) {
        return (p.x - o.x) * (q.y - o.y) - (p.y - o.y) * (q.x - o.x);
    };
    const double d1 = cross(c, d, a), d2 = cross(c, d, b), d3 = cross(a, b, c), d4 = cross(a, b, d);
    return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0)) && d1 != 0 && d2 != 0 && d3 != 0 &&
           d4 != 0;
}

/// "Loops 1 and 2 cross" for the first crossing pair of flattened loops (bounding boxes first),
/// else empty. Parity still gives a mask, but rarely the one intended.
QString crossingLoops(const std::vector<std::vector<glm::dvec2>>& loops) {
    for (size_t a = 0; a < loops.size(); ++a)
        for (size_t b = a + 1; b < loops.size(); ++b) {
            const auto& la = loops[a];
            const auto& lb = loops[b];
            for (size_t i = 0; i < la.size(); ++i)
                for (size_t j = 0; j < lb.size(); ++j)
                    if (segmentsCross(la[i], la[(i + 1) % la.size()], lb[j],
                                      lb[(j + 1) % lb.size()]))
                        return QObject::tr("Warning: trim loops %1 and %2 cross; the parity "
                                           "mask may not be what you meant.")
                            .arg(a + 1)
                            .arg(b + 1);
        }
    return {};
}

} // namespace

UvPanel::UvPanel(Document* document, Selection* selection, QUndoStack* stack, QWidget* parent)
    : QWidget(parent), m_doc(document), m_selection(selection), m_stack(stack) {
    setMinimumSize(160, 160);
    setFocusPolicy(Qt::ClickFocus);
    auto repaint = [this] {
        update();
    };
    connect(m_doc, &Document::surfaceChanged, this, repaint);
    connect(m_doc, &Document::trimLoopInserted, this, repaint);
    connect(m_doc, &Document::trimLoopRemoved, this, repaint);
    connect(m_doc, &Document::surfaceRemoved, this, repaint);
    m_tools.add(makeTrimDragTool(this));
    for (UvTool shape : {UvTool::Rectangle, UvTool::Circle})
        m_drawing[shape] = makeUvShapeTool(this, shape);
    for (UvTool shape : {UvTool::Polygon, UvTool::Spline})
        m_drawing[shape] = makeUvClickTool(this, shape);
    connect(m_doc, &Document::sceneReset, this, [this] {
        m_tools.cancel(); // the live edit has already let go of the old scene's points
        update();
    });
    connect(m_selection, &Selection::changed, this, repaint);
    setMouseTracking(true); // the rubber segment of the polygon and spline tools
    buildActions();
}

SurfaceId UvPanel::surface() const {
    const Surface* s = shown(m_doc, m_selection);
    return s ? s->id : SurfaceId{};
}

QString domainLabel(double value, double span) {
    const double magnitude = std::isfinite(span) && span > 0.0 ? std::floor(std::log10(span)) : 0.0;
    const int decimals = int(std::clamp(2.0 - magnitude, 0.0, 9.0));
    QString text = QString::number(value, 'f', decimals);
    if (text.startsWith(QLatin1Char('-')) && text.toDouble() == 0.0)
        text.remove(0, 1);
    return text;
}

QRectF UvPanel::domainRect() const {
    // The largest rectangle with the domain's proportions (u range : v range), centred.
    const double margin = 16.0;
    const QRectF area = QRectF(rect()).adjusted(margin, margin, -margin, -margin);
    const Surface* s = shown(m_doc, m_selection);
    if (!area.isValid() || !s)
        return area.isValid() ? area : QRectF(0, 0, 1, 1);
    const Interval du = surfaceDomainU(s->geometry), dv = surfaceDomainV(s->geometry);
    const double ratio = std::clamp((du.last - du.first) / (dv.last - dv.first), 0.05, 20.0);
    QSizeF size(area.width(), area.width() / ratio);
    if (size.height() > area.height())
        size = QSizeF(area.height() * ratio, area.height());
    // Zoomed about the domain fraction m_centre, which sits at the area's centre.
    size *= m_zoom;
    QRectF r(QPointF(), size);
    r.moveTopLeft(area.center() -
                  QPointF(m_centre.x * size.width(), (1.0 - m_centre.y) * size.height()));
    return QRectF(std::round(r.left()), std::round(r.top()), std::round(r.width()),
                  std::round(r.height()));
}

QPointF UvPanel::toWidget(glm::dvec2 uv) const {
    const Surface* s = shown(m_doc, m_selection);
    if (!s)
        return {};
    const Interval du = surfaceDomainU(s->geometry), dv = surfaceDomainV(s->geometry);
    const QRectF r = domainRect();
    return {r.left() + (uv.x - du.first) / (du.last - du.first) * r.width(),
            r.bottom() - (uv.y - dv.first) / (dv.last - dv.first) * r.height()};
}

glm::dvec2 UvPanel::toUv(QPointF pixel) const {
    const Surface* s = shown(m_doc, m_selection);
    if (!s)
        return glm::dvec2(0.0);
    const Interval du = surfaceDomainU(s->geometry), dv = surfaceDomainV(s->geometry);
    const QRectF r = domainRect();
    return {du.first + (pixel.x() - r.left()) / r.width() * (du.last - du.first),
            dv.first + (r.bottom() - pixel.y()) / r.height() * (dv.last - dv.first)};
}

void UvPanel::refreshMask() {
    const Surface* s = shown(m_doc, m_selection);
    if (!s) {
        m_mask = m_maskColors = QImage();
        m_trimLines.clear();
        m_crossing.clear();
        m_maskSurface = {};
        return;
    }
    const Revisions rev = m_doc->revisions(s->id);
    // Zoomed in, the mask is drawn scaled rather than computed at more than 1024 pixels a side.
    const QSize size = domainRect().size().toSize().boundedTo(QSize(1024, 1024));
    if (m_maskSurface == s->id && m_maskRevision == rev.trims && m_maskGeometry == rev.knots &&
        m_mask.size() == size)
        return;
    // Mask, its colouring and the flattened loops change only with the trims or the domain, so
    // they are made here once, not on every paint (a 3D drag repaints this panel each step).
    m_mask = trimMaskImage(*s, size);
    m_maskColors = m_mask.convertToFormat(QImage::Format_Indexed8);
    QList<QRgb> table(256);
    for (int i = 0; i < 256; ++i) // kept in light blue, removed in dark grey
        table[i] = i > 127 ? qRgb(176, 200, 230) : qRgb(58, 60, 66);
    m_maskColors.setColorTable(table);
    m_trimLines = trimPolylines(*s);
    m_crossing = crossingLoops(m_trimLines);
    m_maskSurface = s->id;
    m_maskRevision = rev.trims;
    m_maskGeometry = rev.knots;
}

QImage UvPanel::mask() {
    refreshMask();
    return m_mask;
}

std::optional<TrimPointRef> UvPanel::trimPointAt(QPointF pixel, double radius) const {
    const Surface* s = shown(m_doc, m_selection);
    if (!s)
        return std::nullopt;
    std::optional<TrimPointRef> best;
    double bestDistance = radius;
    for (const TrimLoop& loop : s->trims)
        for (size_t c = 0; c < loop.curves.size(); ++c)
            for (size_t k = 0; k < loop.curves[c].points.size(); ++k) {
                const QPointF p = toWidget(loop.curves[c].points[k]);
                const double d = std::hypot(p.x() - pixel.x(), p.y() - pixel.y());
                // Strictly nearer replaces: of coinciding points (a loop's shared start and
                // end) the first in loop order is picked.
                if (d <= radius && (!best || d < bestDistance)) {
                    bestDistance = d;
                    best = TrimPointRef{s->id, loop.id, int(c), int(k)};
                }
            }
    return best;
}

void UvPanel::paintEvent(QPaintEvent*) {
    QPainter p(this);
    p.fillRect(rect(), palette().window());
    const Surface* s = shown(m_doc, m_selection);
    if (!s) {
        p.drawText(rect(), Qt::AlignCenter | Qt::TextWordWrap,
                   tr("Select a surface to see its parameter domain and trims."));
        return;
    }
    refreshMask();
    const QRectF r = domainRect();
    p.drawImage(r, m_maskColors);
    p.setPen(QPen(palette().text().color(), 1.0));
    p.drawRect(r);
    const Interval du = surfaceDomainU(s->geometry), dv = surfaceDomainV(s->geometry);
    const double spanU = du.last - du.first;
    const QString first = QStringLiteral("u %1").arg(domainLabel(du.first, spanU));
    const QString last = domainLabel(du.last, spanU);
    const QFontMetricsF fm(font());
    const QRectF below(r.left(), r.bottom(), r.width(), 14);
    if (fm.horizontalAdvance(first) + fm.horizontalAdvance(last) + 8 <= r.width()) {
        p.drawText(below, Qt::AlignLeft, first);
        p.drawText(below, Qt::AlignRight, last);
    } else { // too narrow for both ends apart: one label, never one over the other
        p.drawText(QRectF(r.left(), r.bottom(), width() - r.left(), 14), Qt::AlignLeft,
                   fm.elidedText(first + QStringLiteral(" … ") + last, Qt::ElideRight,
                                 width() - r.left()));
    }
    p.drawText(QRectF(r.left() + 2, r.top() - 14, r.width(), 14), Qt::AlignLeft,
               QStringLiteral("v %1").arg(domainLabel(dv.last, dv.last - dv.first)));

    p.setRenderHint(QPainter::Antialiasing);
    // Trim loops, then control polygons and points.
    p.setPen(QPen(QColor(230, 130, 30), 2.0));
    for (const auto& line : m_trimLines) {
        QPolygonF poly;
        for (const glm::dvec2& uv : line)
            poly << toWidget(uv);
        p.drawPolygon(poly);
    }
    const auto& picked = m_selection->trimPoints();
    for (const TrimLoop& loop : s->trims)
        for (size_t c = 0; c < loop.curves.size(); ++c) {
            const NurbsCurve2& curve = loop.curves[c];
            QPolygonF poly;
            for (const glm::dvec2& uv : curve.points)
                poly << toWidget(uv);
            p.setPen(QPen(QColor(90, 90, 90), 1.0, Qt::DashLine));
            p.drawPolyline(poly);
            for (size_t k = 0; k < curve.points.size(); ++k) {
                const TrimPointRef ref{s->id, loop.id, int(c), int(k)};
                const bool sel = std::find(picked.begin(), picked.end(), ref) != picked.end();
                p.setPen(QPen(sel ? QColor(255, 60, 30) : QColor(20, 20, 20), 1.0));
                p.setBrush(sel ? QColor(255, 120, 60) : QColor(250, 250, 250));
                p.drawRect(QRectF(poly[int(k)] - QPointF(3, 3), QSizeF(6, 6)));
            }
            p.setBrush(Qt::NoBrush);
        }
    m_tools.paint(p);
    if (!m_crossing.isEmpty()) {
        p.setPen(QColor(220, 40, 40));
        p.drawText(rect().adjusted(4, 2, -4, -2), Qt::AlignTop | Qt::AlignLeft | Qt::TextWordWrap,
                   m_crossing);
    }
}

void UvPanel::mousePressEvent(QMouseEvent* event) {
    if (event->button() == Qt::MiddleButton || event->button() == Qt::RightButton) {
        m_panning = true;
        m_panLast = event->position();
        return;
    }
    m_tools.press(event);
}

void UvPanel::mouseMoveEvent(QMouseEvent* event) {
    if (m_panning) {
        const QRectF r = domainRect();
        const QPointF d = event->position() - m_panLast;
        m_panLast = event->position();
        setView(m_zoom, m_centre - glm::dvec2(d.x() / r.width(), -d.y() / r.height()));
        return;
    }
    if (Tool* gesture = m_tools.active())
        gesture->move(event);
    else
        m_tools.hover(event);
}

void UvPanel::mouseReleaseEvent(QMouseEvent* event) {
    if (m_panning && event->button() != Qt::LeftButton) {
        m_panning = false;
        return;
    }
    m_tools.release(event);
}

void UvPanel::mouseDoubleClickEvent(QMouseEvent* event) {
    if (m_tools.doubleClick(event)) {
        event->accept();
        return;
    }
    QWidget::mouseDoubleClickEvent(event);
}

void UvPanel::keyPressEvent(QKeyEvent* event) {
    if (m_tools.key(event))
        return;
    QWidget::keyPressEvent(event);
}

} // namespace kw
