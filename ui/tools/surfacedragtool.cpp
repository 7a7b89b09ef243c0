// SurfaceDragTool: Ctrl + drag moves, rotates or scales the selected surfaces. The live drag
// writes M * p for every press-time point p; the release commits one TransformSurfaces step
// with the same M applied to the press-time points, so the result is exactly the affine map
// applied once (NURBS are affinely invariant, The NURBS Book Sec. 4.4), and a placement that
// analytic forms follow (the live steps are point edits, which drop them until the release).
#include "ui/edit/modelcommands.h"
#include "ui/tools/viewtools.h"
#include "ui/viewport.h"

#include <QKeyEvent>
#include <QMouseEvent>
#include <QPainter>
#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace kw {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kSnapAngle = 15.0 * kPi / 180.0;

glm::dvec3 unitAxis(int axis) {
    glm::dvec3 a(0.0);
    a[axis] = 1.0;
    return a;
}

} // namespace

SurfaceDragTool::SurfaceDragTool(Viewport* view)
    : m_view(view), m_live(view->document(), view->undoStack()) {
    showRefusals(m_live, view);
}

bool SurfaceDragTool::press(QMouseEvent* event) {
    if (event->button() != Qt::LeftButton || !(event->modifiers() & Qt::ControlModifier) ||
        (event->modifiers() & Qt::AltModifier))
        return false;
    m_refs.clear();
    m_from.clear();
    m_surfaces = m_view->shownSurfaces(true);
    glm::dvec3 lo(1e300), hi(-1e300);
    for (SurfaceId id : m_surfaces) { // hidden ones stay where they are
        const NurbsSurface& g = m_view->document()->surface(id)->geometry;
        for (int j = 0; j < g.countV; ++j)
            for (int i = 0; i < g.countU; ++i) {
                const glm::dvec3 x = g.points[size_t(g.index(i, j))];
                m_refs.push_back(ControlPointRef{id, i, j});
                m_from.push_back(x);
                lo = glm::min(lo, x);
                hi = glm::max(hi, x);
            }
    }
    // Ctrl is this tool's even with nothing to drag: no band starts under it.
    if (m_refs.empty())
        return true;
    m_pivot = 0.5 * (lo + hi);
    m_press = m_last = event->position();
    m_snap = false;
    m_live.begin();
    return true;
}

void SurfaceDragTool::move(QMouseEvent* event) {
    m_last = event->position();
    m_snap = event->modifiers() & Qt::ShiftModifier;
    step();
}

void SurfaceDragTool::release(QMouseEvent* event) {
    if (event->button() != Qt::LeftButton)
        return;
    m_last = event->position();
    m_snap = event->modifiers() & Qt::ShiftModifier;
    // One map for the last live step, the command and its name.
    double amount = 0.0;
    const glm::dmat4 m = dragMap(&amount);
    if (dragging())
        apply(m);
    std::vector<SurfaceId> ids;
    for (SurfaceId id : m_surfaces)
        if (m_view->document()->surface(id)) // not removed under the drag
            ids.push_back(id);
    const QString name = m_view->surfaceDrag() != Viewport::SurfaceDrag::Move ? text(amount)
                         : ids.size() == 1 ? QObject::tr("Move surface")
                                           : QObject::tr("Move %1 surfaces").arg(ids.size());
    // Back to the press-time points, then one step with the exact map.
    m_live.commitWith([&]() -> std::unique_ptr<QUndoCommand> {
        if (ids.empty() || m == glm::dmat4(1.0))
            return nullptr;
        auto command = TransformSurfaces::create(m_view->document(), ids, m, name);
        if (!command) {
            m_view->showMessage(QObject::tr("Transform not recorded: %1").arg(command.message()));
            return nullptr;
        }
        return std::move(*command);
    });
    m_view->update();
}

bool SurfaceDragTool::key(QKeyEvent* event) {
    const int key = event->key();
    if (key != Qt::Key_X && key != Qt::Key_Y && key != Qt::Key_Z)
        return false;
    step(); // the view changed the constraint already
    return true;
}

bool SurfaceDragTool::keyRelease(QKeyEvent* event) {
    return key(event);
}

void SurfaceDragTool::cancel() {
    m_live.cancel();
    m_view->update();
}

glm::dmat4 SurfaceDragTool::dragMap(double* amount) const {
    if (!dragging() || m_view->surfaceDrag() != Viewport::SurfaceDrag::Move)
        return matrix(amount);
    if (amount)
        *amount = 1.0;
    const ViewProjection view = m_view->viewProjection();
    const int axis = m_view->axisConstraint();
    const glm::dvec3 delta =
        axis >= 0 ? view.onAxis(m_last, m_pivot, unitAxis(axis)) -
                        view.onAxis(m_press, m_pivot, unitAxis(axis))
                  : view.onViewPlane(m_last, m_pivot) - view.onViewPlane(m_press, m_pivot);
    return glm::translate(glm::dmat4(1.0), delta);
}

void SurfaceDragTool::step() {
    if (dragging())
        apply(dragMap());
}

void SurfaceDragTool::apply(const glm::dmat4& map) {
    std::vector<glm::dvec3> to;
    to.reserve(m_from.size());
    for (const glm::dvec3& p : m_from)
        to.push_back(glm::dvec3(map * glm::dvec4(p, 1.0)));
    (void)m_live.moveControlPoints(m_refs, to); // a refusal goes to the status bar
    m_view->update();
}

glm::dmat4 SurfaceDragTool::matrix(double* amount) const {
    const bool rotate = m_view->surfaceDrag() == Viewport::SurfaceDrag::Rotate;
    if (amount)
        *amount = rotate ? 0.0 : 1.0;
    if (!dragging() || m_view->surfaceDrag() == Viewport::SurfaceDrag::Move)
        return glm::dmat4(1.0);
    const ViewProjection view = m_view->viewProjection();
    const int held = m_view->axisConstraint();
    const glm::dvec3 c = m_pivot;
    const glm::dmat4 toOrigin = glm::translate(glm::dmat4(1.0), -c);
    const glm::dmat4 back = glm::translate(glm::dmat4(1.0), c);
    if (rotate) {
        // The axis: the held one, else the view direction pointing at the viewer, so that
        // turning the cursor counter-clockwise on screen turns the surfaces likewise.
        const glm::dvec3 axis = held >= 0 ? unitAxis(held) : -view.forward();
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
        if (onPlane(m_press, a) && onPlane(m_last, b)) {
            angle = std::atan2(glm::dot(axis, glm::cross(a, b)), glm::dot(a, b));
        } else if (const auto pc = view.project(c)) {
            const QPointF va = m_press - *pc, vb = m_last - *pc;
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
    const double ra = glm::length(view.onViewPlane(m_press, c) - c);
    const double rb = glm::length(view.onViewPlane(m_last, c) - c);
    double factor = ra > 0.0 && std::isfinite(rb / ra) ? std::clamp(rb / ra, 1e-3, 1e3) : 1.0;
    if (m_snap)
        factor = std::max(0.1, std::round(factor * 10.0) / 10.0);
    if (amount)
        *amount = factor;
    glm::dvec3 f(factor);
    if (held >= 0)
        f = glm::dvec3(1.0) + (factor - 1.0) * unitAxis(held);
    return back * glm::scale(glm::dmat4(1.0), f) * toOrigin;
}

QString SurfaceDragTool::text(double amount) const {
    const int surfaces = int(m_surfaces.size());
    const QString noun =
        surfaces == 1 ? QObject::tr("surface") : QObject::tr("%1 surfaces").arg(surfaces);
    static const char* const names[3] = {"x", "y", "z"};
    const int axis = m_view->axisConstraint();
    if (m_view->surfaceDrag() == Viewport::SurfaceDrag::Rotate)
        return QObject::tr("Rotate %1 %2° about %3")
            .arg(noun)
            .arg(amount * 180.0 / kPi, 0, 'g', 4)
            .arg(axis >= 0 ? QLatin1String(names[axis]) : QLatin1String("the view axis"));
    QString text = QObject::tr("Scale %1 ×%2").arg(noun).arg(amount, 0, 'g', 4);
    if (axis >= 0)
        text += QObject::tr(" along %1").arg(QLatin1String(names[axis]));
    return text;
}

void SurfaceDragTool::paint(QPainter& p) {
    if (!dragging() || m_view->surfaceDrag() == Viewport::SurfaceDrag::Move)
        return;
    double amount = 0.0;
    matrix(&amount);
    p.setPen(Qt::white);
    p.drawText(QPointF(10, m_view->height() - 28), text(amount));
}

} // namespace kw
