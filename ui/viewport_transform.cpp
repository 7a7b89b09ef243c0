// Viewport: rotate and scale drags of whole surfaces (Ctrl + drag in the Rotate or Scale mode).
// The live drag writes M * p for every press-time point p; the release puts the press-time
// points back and pushes one TransformSurfaces step with the same M, so the result is exactly
// the affine map applied once (NURBS are affinely invariant, The NURBS Book Sec. 4.4).
#include "ui/edit/modelcommands.h"
#include "ui/viewport.h"

#include <QUndoStack>
#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <map>

namespace kw {

namespace {

constexpr double kSnapAngle = 15.0 * 3.14159265358979323846 / 180.0;

glm::dvec3 unitAxis(int axis) {
    glm::dvec3 a(0.0);
    a[axis] = 1.0;
    return a;
}

} // namespace

glm::dmat4 Viewport::surfaceDragMatrix(double* amount) const {
    const bool rotate = m_surfaceDrag == SurfaceDrag::Rotate;
    if (amount)
        *amount = rotate ? 0.0 : 1.0;
    if (!(m_gesture == Gesture::DragPoints && m_movingSurfaces) ||
        m_surfaceDrag == SurfaceDrag::Move)
        return glm::dmat4(1.0);
    const ViewProjection view = viewProjection();
    const glm::dvec3 c = m_anchor;
    const glm::dmat4 toOrigin = glm::translate(glm::dmat4(1.0), -c);
    const glm::dmat4 back = glm::translate(glm::dmat4(1.0), c);
    if (rotate) {
        // The axis: the held one, else the view direction pointing at the viewer, so that
        // turning the cursor counter-clockwise on screen turns the surfaces likewise.
        const glm::dvec3 axis = m_axis >= 0 ? unitAxis(m_axis) : -view.forward();
        // The cursor's turn about the pivot, measured on the plane through it across the
        // axis; on screen when that plane is seen nearly edge-on.
        auto onPlane = [&](QPointF pixel, glm::dvec3& out) {
            glm::dvec3 o, d;
            view.ray(pixel, o, d);
            const double den = glm::dot(d, axis);
            if (std::abs(den) < 0.1)
                return false;
            out = o + d * (glm::dot(c - o, axis) / den) - c;
            return true;
        };
        glm::dvec3 a, b;
        double angle = 0.0;
        if (onPlane(m_pressPixel, a) && onPlane(m_lastPixel, b)) {
            angle = std::atan2(glm::dot(axis, glm::cross(a, b)), glm::dot(a, b));
        } else if (const auto pc = view.project(c)) {
            const QPointF va = m_pressPixel - *pc, vb = m_lastPixel - *pc;
            // Screen y points down: a counter-clockwise turn has a negative cross product.
            angle =
                -std::atan2(va.x() * vb.y() - va.y() * vb.x(), va.x() * vb.x() + va.y() * vb.y());
            if (glm::dot(axis, view.forward()) > 0.0)
                angle = -angle;
        }
        if (m_snap)
            angle = std::round(angle / kSnapAngle) * kSnapAngle;
        if (amount)
            *amount = angle;
        return back * glm::rotate(glm::dmat4(1.0), angle, axis) * toOrigin;
    }
    const double ra = glm::length(view.onViewPlane(m_pressPixel, c) - c);
    const double rb = glm::length(view.onViewPlane(m_lastPixel, c) - c);
    double factor = ra > 0.0 && std::isfinite(rb / ra) ? std::clamp(rb / ra, 1e-3, 1e3) : 1.0;
    if (m_snap)
        factor = std::max(0.1, std::round(factor * 10.0) / 10.0);
    if (amount)
        *amount = factor;
    glm::dvec3 f(factor);
    if (m_axis >= 0)
        f = glm::dvec3(1.0) + (factor - 1.0) * unitAxis(m_axis);
    return back * glm::scale(glm::dmat4(1.0), f) * toOrigin;
}

QString Viewport::surfaceDragText(double amount) const {
    int surfaces = 0;
    SurfaceId last;
    for (const DragPoint& d : m_drag)
        if (d.ref.surface != last) {
            last = d.ref.surface;
            ++surfaces;
        }
    const QString noun = surfaces == 1 ? tr("surface") : tr("%1 surfaces").arg(surfaces);
    static const char* const names[3] = {"x", "y", "z"};
    if (m_surfaceDrag == SurfaceDrag::Rotate)
        return tr("Rotate %1 %2° about %3")
            .arg(noun)
            .arg(amount * 180.0 / 3.14159265358979323846, 0, 'g', 4)
            .arg(m_axis >= 0 ? QLatin1String(names[m_axis]) : QLatin1String("the view axis"));
    QString text = tr("Scale %1 ×%2").arg(noun).arg(amount, 0, 'g', 4);
    if (m_axis >= 0)
        text += tr(" along %1").arg(QLatin1String(names[m_axis]));
    return text;
}

void Viewport::applyTransformDrag() {
    const PointsBySurface bySurface = dragPointsBySurface(surfaceDragMatrix());
    for (const auto& [id, change] : bySurface)
        m_doc->setControlPoints(id, change.first, change.second);
    update();
}

void Viewport::finishTransformDrag(bool cancel) {
    double amount = 0.0;
    const glm::dmat4 m = surfaceDragMatrix(&amount);
    const QString text = surfaceDragText(amount);
    m_gesture = Gesture::None;
    m_movingSurfaces = false;
    // Back to the press-time points, then one step with the exact map.
    const PointsBySurface bySurface = dragPointsBySurface(glm::dmat4(1.0));
    m_drag.clear();
    std::vector<SurfaceId> ids;
    for (const auto& [id, change] : bySurface) {
        m_doc->setControlPoints(id, change.first, change.second);
        ids.push_back(id);
    }
    if (!cancel && !ids.empty() && m != glm::dmat4(1.0)) {
        QString error;
        if (!pushCommand(m_stack, TransformSurfaces::create(m_doc, ids, m, text, &error)))
            qWarning("knotwork: drag not recorded: %s", qPrintable(error));
    }
    update();
}

} // namespace kw
