// MeasureTool: measurements from probed points, painted as dimensions over the 3D view.
#include "ui/measure_tool.h"

#include "model/document/document.h"
#include "model/document/units.h"
#include "ui/viewport.h"

#include <QPainter>
#include <QPainterPath>

namespace kw {

namespace {

/// The probe marker's half-size on screen.
constexpr int kMarkerArm = 6;

/// A label in a rounded box at `at`, readable on any background.
void drawLabel(QPainter& p, QPointF at, const QString& text) {
    const QFontMetricsF fm(p.font());
    QRectF box = fm.boundingRect(text).adjusted(-4, -2, 4, 2);
    box.moveCenter(at + QPointF(0, -fm.height()));
    p.setPen(QColor(255, 220, 90));
    p.setBrush(QColor(20, 20, 24, 210));
    p.drawRoundedRect(box, 3, 3);
    p.setPen(QColor(255, 240, 180));
    p.drawText(box, Qt::AlignCenter, text);
}

void drawPoint(QPainter& p, QPointF at) {
    p.setPen(QPen(QColor(20, 20, 24), 1));
    p.setBrush(QColor(255, 200, 40));
    p.drawEllipse(at, 3.5, 3.5);
}

} // namespace

MeasureTool::MeasureTool(Viewport* viewport) : QObject(viewport), m_view(viewport) {
    setObjectName(QStringLiteral("measureOverlay"));
    // The dimensions follow the camera: drawn over every frame of the view.
    viewport->addOverlay(this, [this](QPainter& p) { paint(p); });
}

void MeasureTool::update() {
    m_view->updateOverlays();
}

void MeasureTool::setKind(Measurement::Kind kind) {
    if (kind != m_kind)
        m_pending.reset();
    m_kind = kind;
    update();
}

std::optional<Measurement>
MeasureTool::addPoint(const ProbePoint& p,
                      const std::function<bool(const ProbePoint&, const ProbePoint&)>& planes) {
    Measurement m;
    m.kind = m_kind;
    if (m_kind == Measurement::Kind::Radius) {
        m.a = p;
    } else if (!m_pending) {
        m_pending = p;
        update();
        return std::nullopt;
    } else {
        m.a = *m_pending;
        m.b = p;
        m_pending.reset();
        m.betweenPlanes = m_kind == Measurement::Kind::Angle && planes && planes(m.a, m.b);
    }
    m_done.push_back(m);
    update();
    return m;
}

bool MeasureTool::cancelPending() {
    const bool had = m_pending.has_value();
    m_pending.reset();
    update();
    return had;
}

void MeasureTool::clear() {
    m_done.clear();
    m_pending.reset();
    update();
}

void MeasureTool::setProbeMarker(std::optional<glm::dvec3> point) {
    if (point == m_marker)
        return;
    // The overlays alone are painted again over the last frame: no new frame at every hover.
    m_marker = point;
    update();
}

QString MeasureTool::unitKey() const {
    const Document* doc = m_view->document();
    return doc ? lengthUnitKey(doc->scene().unit) : QString();
}

QStringList MeasureTool::labels() const {
    QStringList out;
    for (const Measurement& m : m_done)
        out << measurementText(m, 8, unitKey());
    return out;
}

void MeasureTool::paint(QPainter& p) const {
    if (m_done.empty() && !m_pending && !m_marker)
        return;
    p.save();
    p.setRenderHint(QPainter::Antialiasing);
    const ViewProjection view = m_view->viewProjection();
    // Length on screen of a normal's arrow.
    constexpr double kArrow = 36.0;
    const auto arrow = [&](const ProbePoint& at) -> std::optional<QPointF> {
        const std::optional<QPointF> a = view.project(at.point);
        const double scale = std::max(view.depth(at.point), 1e-12);
        // A short world step along the normal, scaled on screen to kArrow pixels.
        const std::optional<QPointF> a2 = view.project(at.point + at.normal * (scale * 0.05));
        if (!a || !a2)
            return std::nullopt;
        const QPointF d = *a2 - *a;
        const double len = std::hypot(d.x(), d.y());
        return len > 1e-9 ? *a + d * (kArrow / len) : *a;
    };
    for (const Measurement& m : m_done) {
        const std::optional<QPointF> a = view.project(m.a.point);
        if (!a)
            continue;
        const QString text = measurementText(m, 6, unitKey());
        if (m.kind == Measurement::Kind::Distance) {
            const std::optional<QPointF> b = view.project(m.b.point);
            if (!b)
                continue;
            p.setPen(QPen(QColor(255, 200, 40), 1.5));
            p.drawLine(*a, *b);
            drawPoint(p, *a);
            drawPoint(p, *b);
            drawLabel(p, (*a + *b) / 2.0, text);
        } else if (m.kind == Measurement::Kind::Angle) {
            const std::optional<QPointF> b = view.project(m.b.point);
            if (!b)
                continue;
            p.setPen(QPen(QColor(255, 200, 40), 1.0, Qt::DashLine));
            p.drawLine(*a, *b);
            p.setPen(QPen(QColor(120, 200, 255), 1.5));
            for (const ProbePoint* at : {&m.a, &m.b})
                if (const auto tip = arrow(*at); tip && view.project(at->point))
                    p.drawLine(*view.project(at->point), *tip);
            drawPoint(p, *a);
            drawPoint(p, *b);
            drawLabel(p, (*a + *b) / 2.0, text);
        } else {
            drawPoint(p, *a);
            drawLabel(p, *a, text);
        }
    }
    if (m_pending)
        if (const auto a = view.project(m_pending->point))
            drawPoint(p, *a);
    if (m_marker)
        if (const auto a = view.project(*m_marker)) {
            p.setPen(QPen(QColor(255, 255, 255), 1.5));
            p.drawLine(*a + QPointF(-kMarkerArm, 0), *a + QPointF(kMarkerArm, 0));
            p.drawLine(*a + QPointF(0, -kMarkerArm), *a + QPointF(0, kMarkerArm));
        }
    p.restore();
}

} // namespace kw
