// CurveTool: clicked points on a view plane -> interpolating or control-point B-spline curves.
#include "ui/curvetool.h"

#include <QKeyEvent>
#include <QMouseEvent>
#include <QPainter>
#include <cmath>

namespace kw {

CurveTool::CurveTool(Viewport* viewport, QObject* parent) : QObject(parent), m_viewport(viewport) {}

CurveTool::~CurveTool() {
    m_active = false; // nothing to cancel or report when uninstalled below
    if (m_viewport && m_viewport->tool() == this)
        m_viewport->setTool(nullptr);
}

void CurveTool::start(int curvesWanted, const QString& purpose) {
    m_points.clear();
    m_curves.clear();
    m_wanted = curvesWanted;
    m_purpose = purpose;
    m_active = true;
    m_viewport->setTool(this);
    m_viewport->setFocus(Qt::OtherFocusReason);
    Q_EMIT message(hint());
}

void CurveTool::stop() {
    m_active = false;
    m_points.clear();
    m_curves.clear();
    if (m_viewport->tool() == this)
        m_viewport->setTool(nullptr);
}

void CurveTool::cancel() {
    if (!m_active)
        return;
    stop();
    Q_EMIT message(tr("Curve tool cancelled."));
}

QString CurveTool::hint() const {
    const QString action = m_wanted == 1 ? tr("Enter finishes the curve")
                                         : tr("Enter ends each curve, Enter again lofts");
    return tr("%1: click points in the view plane; %2, Backspace removes the last point, Esc "
              "cancels.")
        .arg(m_purpose, action);
}

Expected<NurbsCurve3> CurveTool::curveThrough(const std::vector<glm::dvec3>& points) const {
    if (points.size() < 2)
        return Error(tr("a curve needs at least two points"));
    if (!m_interpolating)
        return controlPointCurve3(points, 3);
    return interpolateCurve3(points, 3);
}

const NurbsCurve3& CurveTool::preview() {
    // Keyed on the points themselves rather than invalidated at each edit of m_points, so that
    // no path that changes them can leave a stale curve.
    if (m_previewPoints != m_points || m_previewInterpolating != m_interpolating) {
        m_preview = curveThrough(m_points).value_or(NurbsCurve3{});
        m_previewPoints = m_points;
        m_previewInterpolating = m_interpolating;
    }
    return m_preview;
}

bool CurveTool::press(QMouseEvent* event) {
    if (!m_active || event->button() != Qt::LeftButton)
        return false;
    const ViewProjection view = m_viewport->viewProjection();
    if (m_points.empty() && m_curves.empty()) {
        // The plane of this drawing: through the view's target, facing the viewer.
        m_planePoint = m_viewport->cameraController().camera().target;
        m_planeNormal = view.forward();
    }
    glm::dvec3 origin, direction;
    view.ray(event->position(), origin, direction);
    const double den = glm::dot(direction, m_planeNormal);
    if (std::abs(den) < 1e-6) {
        Q_EMIT message(tr("The curve's plane is seen edge-on; turn the view back to draw."));
        return true;
    }
    const glm::dvec3 p =
        origin + direction * (glm::dot(m_planePoint - origin, m_planeNormal) / den);
    if (!m_points.empty() && glm::length(p - m_points.back()) == 0.0)
        return true; // a double click: the same point twice would make no curve
    m_points.push_back(p);
    Q_EMIT message(tr("%1 point%2. %3")
                       .arg(m_points.size())
                       .arg(m_points.size() == 1 ? QString() : QStringLiteral("s"))
                       .arg(hint()));
    return true;
}

bool CurveTool::endCurve() {
    Expected<NurbsCurve3> c = curveThrough(m_points);
    if (!c) {
        Q_EMIT message(tr("Cannot end the curve: %1").arg(c.message()));
        return false;
    }
    m_curves.push_back(std::move(c).value());
    m_points.clear();
    return true;
}

bool CurveTool::key(QKeyEvent* event) {
    if (!m_active)
        return false;
    switch (event->key()) {
    case Qt::Key_Escape:
        cancel();
        return true;
    case Qt::Key_Backspace:
        if (!m_points.empty())
            m_points.pop_back();
        return true;
    case Qt::Key_Return:
    case Qt::Key_Enter: {
        const bool lofting = m_wanted == 0;
        const bool hadPoints = !m_points.empty();
        if (hadPoints && !endCurve())
            return true;
        const size_t needed = lofting ? 2 : size_t(m_wanted);
        // Loft: Enter ends a curve; Enter with no new point lofts.
        if ((lofting && hadPoints) || m_curves.size() < needed) {
            Q_EMIT message(
                m_curves.size() < needed
                    ? tr("%1 of %2 curves drawn. %3").arg(m_curves.size()).arg(needed).arg(hint())
                    : tr("%1 curves drawn. %2").arg(m_curves.size()).arg(hint()));
            return true;
        }
        const std::vector<NurbsCurve3> curves = m_curves;
        stop();
        Q_EMIT finished(curves);
        return true;
    }
    default:
        return false;
    }
}

void CurveTool::paint(QPainter& p) {
    if (!m_active)
        return;
    const ViewProjection view = m_viewport->viewProjection();
    auto drawCurve = [&](const NurbsCurve3& c, const QColor& colour) {
        if (c.points.empty())
            return;
        p.setPen(QPen(colour, 2.0));
        QPolygonF line;
        for (int k = 0; k <= 200; ++k)
            if (const auto px = view.project(curve3Point(c, k / 200.0)))
                line << *px;
        p.drawPolyline(line);
    };
    for (const NurbsCurve3& c : m_curves)
        drawCurve(c, QColor(120, 200, 255));
    drawCurve(preview(), QColor(80, 240, 200)); // empty (nothing drawn) below two points
    p.setPen(QPen(QColor(80, 240, 200), 1.5));
    p.setBrush(Qt::NoBrush);
    for (const glm::dvec3& x : m_points)
        if (const auto px = view.project(x))
            p.drawRect(QRectF(*px - QPointF(4, 4), QSizeF(8, 8)));
    p.setPen(Qt::white);
    p.drawText(QPointF(10, 20), hint());
}

} // namespace kw
