// UvShapeTool: a rectangle or circle trim loop dragged out in the UV panel.
#include "model/nurbs/nurbs_shapes.h"
#include "ui/tools/uvpaneltools.h"

#include <QMouseEvent>
#include <QPainter>
#include <cmath>

namespace kw {

namespace {

class UvShapeTool : public Tool {
public:
    UvShapeTool(UvPanel* panel, UvTool shape) : m_panel(panel), m_shape(shape) {}

    bool press(QMouseEvent* event) override {
        if (event->button() != Qt::LeftButton || !m_panel->surface().isValid())
            return false;
        m_press = m_end = event->position();
        m_shaping = true;
        m_panel->update();
        return true;
    }

    void move(QMouseEvent* event) override {
        m_end = event->position();
        m_panel->update();
    }

    void release(QMouseEvent* event) override {
        if (event->button() != Qt::LeftButton)
            return;
        cancel();
        const QPointF pixel = event->position();
        if (std::hypot(pixel.x() - m_press.x(), pixel.y() - m_press.y()) < 3.0)
            return; // a click, not a shape
        const glm::dvec2 a = m_panel->toUv(m_press), b = m_panel->toUv(pixel);
        if (m_shape == UvTool::Rectangle) {
            const glm::dvec2 lo = glm::min(a, b), hi = glm::max(a, b);
            m_panel->addLoop({closedPolylineCurve({lo, {hi.x, lo.y}, hi, {lo.x, hi.y}})},
                             QObject::tr("rectangular"));
        } else {
            m_panel->addLoop({makeCircle2(a, glm::length(b - a))}, QObject::tr("circular"));
        }
    }

    void cancel() override {
        m_shaping = false;
        m_panel->update();
    }

    bool dragging() const override { return m_shaping; }

    void paint(QPainter& p) override {
        if (!m_shaping)
            return;
        p.setPen(QPen(QColor(40, 160, 60), 1.5, Qt::DashLine));
        p.setBrush(Qt::NoBrush);
        if (m_shape == UvTool::Rectangle) {
            p.drawRect(QRectF(m_press, m_end).normalized());
        } else {
            const double r = std::hypot(m_end.x() - m_press.x(), m_end.y() - m_press.y());
            p.drawEllipse(m_press, r, r);
        }
    }

private:
    UvPanel* m_panel;
    UvTool m_shape;
    QPointF m_press, m_end;
    bool m_shaping = false;
};

} // namespace

std::unique_ptr<Tool> makeUvShapeTool(UvPanel* panel, UvTool shape) {
    return std::make_unique<UvShapeTool>(panel, shape);
}

} // namespace kw
