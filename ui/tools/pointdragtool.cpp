// PointDragTool: a left press on a control point picks it (Shift adds or removes) and a drag
// moves the picked points in the view plane, or along the held world axis (X, Y, Z).
#include "ui/tools/viewtools.h"
#include "ui/viewport.h"

#include <QItemSelectionModel>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QPainter>
#include <algorithm>

namespace kw {

namespace {

class PointDragTool : public Tool {
public:
    explicit PointDragTool(Viewport* view)
        : m_view(view), m_live(view->document(), view->undoStack()) {
        showRefusals(m_live, view);
    }

    bool press(QMouseEvent* event) override {
        if (event->button() != Qt::LeftButton ||
            (event->modifiers() & (Qt::ControlModifier | Qt::AltModifier)))
            return false;
        const std::optional<ControlPointRef> hit = m_view->controlPointAt(event->position());
        if (!hit)
            return false;
        if (pick(*hit, event->modifiers() & Qt::ShiftModifier))
            begin(*hit, event->position());
        return true;
    }

    void move(QMouseEvent* event) override {
        m_last = event->position();
        step();
    }

    void release(QMouseEvent* event) override {
        if (event->button() != Qt::LeftButton)
            return;
        m_last = event->position();
        step();
        m_live.commit();
        m_view->update();
    }

    bool key(QKeyEvent* event) override { return axisKey(event); }
    bool keyRelease(QKeyEvent* event) override { return axisKey(event); }

    void cancel() override {
        m_live.cancel();
        m_view->update();
    }

    bool dragging() const override { return m_live.isActive(); }
    bool editing() const override { return m_live.isActive(); }

    void paint(QPainter& p) override {
        const int axis = m_view->axisConstraint();
        if (!dragging() || axis < 0)
            return;
        static const char* const names[3] = {"X", "Y", "Z"};
        static const QColor colors[3] = {QColor(230, 70, 70), QColor(90, 200, 90),
                                         QColor(90, 130, 240)};
        const ViewProjection view = m_view->viewProjection();
        glm::dvec3 dir(0.0);
        dir[axis] = 1.0;
        const auto a = view.project(m_anchor - dir * 1e3), b = view.project(m_anchor + dir * 1e3);
        p.setPen(QPen(colors[axis], 1.0, Qt::DashLine));
        if (a && b)
            p.drawLine(*a, *b);
        p.drawText(QPointF(10, m_view->height() - 10),
                   QStringLiteral("Constrained to %1").arg(QLatin1String(names[axis])));
    }

private:
    /// Updates the picked points for a press on `ref`; true when a drag of them follows
    /// (Shift on a picked point unpicks it instead).
    bool pick(const ControlPointRef& ref, bool additive) {
        Selection* selection = m_view->selection();
        std::vector<ControlPointRef> sel = selection->controlPoints();
        const bool selected = std::binary_search(sel.begin(), sel.end(), ref);
        if (additive && selected) {
            sel.erase(std::lower_bound(sel.begin(), sel.end(), ref));
            selection->setControlPoints(sel);
            return false;
        }
        if (additive)
            sel.push_back(ref);
        else if (!selected)
            sel = {ref};
        std::sort(sel.begin(), sel.end());
        selection->setControlPoints(sel);
        // Show the picked point's surface in the tree and panels.
        if (selection->currentSurface() != ref.surface) {
            const QModelIndex row = m_view->sceneModel()->surfaceIndex(ref.surface);
            selection->itemSelection()->setCurrentIndex(row, QItemSelectionModel::ClearAndSelect |
                                                                 QItemSelectionModel::Rows);
            // Changing the current row must not drop the picked points.
            selection->setControlPoints(sel);
        }
        return true;
    }

    void begin(const ControlPointRef& pressed, QPointF pixel) {
        m_refs = m_view->selection()->controlPoints();
        m_from.clear();
        const Document* doc = m_view->document();
        for (const ControlPointRef& r : m_refs) {
            const NurbsSurface& g = doc->surface(r.surface)->geometry;
            m_from.push_back(g.points[size_t(g.index(r.i, r.j))]);
            if (r == pressed)
                m_anchor = m_from.back();
        }
        m_press = m_last = pixel;
        if (!m_refs.empty())
            m_live.begin();
    }

    /// Moves every point by the cursor's travel on the view plane through the pressed point,
    /// or along the held axis through it: exactly press-time position + delta, one checked
    /// step for all surfaces.
    void step() {
        if (!dragging())
            return;
        const ViewProjection view = m_view->viewProjection();
        const int axis = m_view->axisConstraint();
        glm::dvec3 delta(0.0);
        if (axis >= 0) {
            glm::dvec3 a(0.0);
            a[axis] = 1.0;
            delta = view.onAxis(m_last, m_anchor, a) - view.onAxis(m_press, m_anchor, a);
        } else {
            delta = view.onViewPlane(m_last, m_anchor) - view.onViewPlane(m_press, m_anchor);
        }
        std::vector<glm::dvec3> to;
        for (const glm::dvec3& from : m_from)
            to.push_back(from + delta);
        (void)m_live.moveControlPoints(m_refs, to); // a refusal goes to the status bar
    }

    bool axisKey(QKeyEvent* event) {
        const int key = event->key();
        if (key != Qt::Key_X && key != Qt::Key_Y && key != Qt::Key_Z)
            return false;
        step(); // the view changed the constraint already
        return true;
    }

    Viewport* m_view;
    LiveEdit m_live;
    std::vector<ControlPointRef> m_refs; ///< the picked points at the press
    std::vector<glm::dvec3> m_from;      ///< and their positions then
    glm::dvec3 m_anchor{0.0};
    QPointF m_press, m_last;
};

} // namespace

std::unique_ptr<Tool> makePointDragTool(Viewport* view) {
    return std::make_unique<PointDragTool>(view);
}

} // namespace kw
