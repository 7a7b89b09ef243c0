// WeightDragTool: Ctrl + Shift + drag on a control point changes its weight, doubling per 100
// pixels up; the release records one SetWeight step.
#include "ui/tools/viewtools.h"
#include "ui/viewport.h"

#include <QMouseEvent>
#include <QPainter>
#include <algorithm>
#include <cmath>

namespace kw {

namespace {

class WeightDragTool : public Tool {
public:
    explicit WeightDragTool(Viewport* view)
        : m_view(view), m_live(view->document(), view->undoStack()) {
        showRefusals(m_live, view);
    }

    bool press(QMouseEvent* event) override {
        const Qt::KeyboardModifiers mods = event->modifiers();
        if (event->button() != Qt::LeftButton || !(mods & Qt::ControlModifier) ||
            !(mods & Qt::ShiftModifier) || (mods & Qt::AltModifier))
            return false;
        const std::optional<ControlPointRef> hit = m_view->controlPointAt(event->position());
        if (!hit)
            return false;
        const NurbsSurface& g = m_view->document()->surface(hit->surface)->geometry;
        m_ref = *hit;
        m_index = g.index(hit->i, hit->j);
        m_from = g.weights[size_t(m_index)];
        m_pressY = event->position().y();
        m_view->selection()->setControlPoints({*hit});
        m_live.begin();
        return true;
    }

    void move(QMouseEvent* event) override {
        const double w = m_from * std::pow(2.0, (m_pressY - event->position().y()) / 100.0);
        // A refusal goes to the status bar.
        (void)m_live.setWeight(m_ref.surface, m_index, std::clamp(w, 1e-6, 1e6));
        m_view->update();
    }

    void release(QMouseEvent* event) override {
        if (event->button() != Qt::LeftButton)
            return;
        m_live.commit();
        m_view->update();
    }

    void cancel() override {
        m_live.cancel();
        m_view->update();
    }

    bool dragging() const override { return m_live.isActive(); }
    bool editing() const override { return m_live.isActive(); }

    void paint(QPainter& p) override {
        if (!dragging())
            return;
        const Surface* s = m_view->document()->surface(m_ref.surface);
        if (!s || size_t(m_index) >= s->geometry.weights.size())
            return;
        p.setPen(QPen(QColor(255, 80, 40), 2.0));
        p.drawText(
            QPointF(10, m_view->height() - 10),
            QStringLiteral("Weight %1").arg(s->geometry.weights[size_t(m_index)], 0, 'g', 5));
    }

private:
    Viewport* m_view;
    LiveEdit m_live;
    ControlPointRef m_ref;
    int m_index = 0;
    double m_from = 1.0;
    double m_pressY = 0.0;
};

} // namespace

std::unique_ptr<Tool> makeWeightDragTool(Viewport* view) {
    return std::make_unique<WeightDragTool>(view);
}

} // namespace kw
