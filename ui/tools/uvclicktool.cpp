// UvClickTool: a polygon or spline trim loop clicked point by point in the UV panel.
#include "ui/tools/uvpaneltools.h"

#include <QKeyEvent>
#include <QMouseEvent>
#include <QPainter>
#include <algorithm>

namespace kw {

namespace {

class UvClickTool : public Tool {
public:
    UvClickTool(UvPanel* panel, UvTool shape) : m_panel(panel), m_shape(shape) {}

    bool press(QMouseEvent* event) override {
        if (event->button() != Qt::LeftButton || !m_panel->surface().isValid())
            return false;
        m_clicked.push_back(m_panel->toUv(event->position()));
        m_hover = event->position();
        m_panel->update();
        return true;
    }

    void hover(QMouseEvent* event) override {
        m_hover = event->position();
        if (!m_clicked.empty())
            m_panel->update(); // the rubber segment
    }

    bool doubleClick(QMouseEvent*) override {
        if (m_clicked.empty())
            return false;
        // The double click's first press already added this point; its second adds nothing.
        finish();
        return true;
    }

    bool key(QKeyEvent* event) override {
        if (m_clicked.empty())
            return false;
        switch (event->key()) {
        case Qt::Key_Escape:
            cancel();
            return true;
        case Qt::Key_Return:
        case Qt::Key_Enter:
            finish();
            return true;
        case Qt::Key_Backspace:
            m_clicked.pop_back();
            m_panel->update();
            return true;
        default:
            return false;
        }
    }

    void cancel() override {
        m_clicked.clear();
        m_panel->update();
    }

    void paint(QPainter& p) override {
        if (m_clicked.empty())
            return;
        p.setPen(QPen(QColor(40, 160, 60), 1.5, Qt::DashLine));
        p.setBrush(Qt::NoBrush);
        QPolygonF poly;
        for (const glm::dvec2& uv : m_clicked)
            poly << m_panel->toWidget(uv);
        poly << m_hover;
        p.drawPolyline(poly);
        for (const QPointF& q : poly)
            p.drawEllipse(q, 2.5, 2.5);
    }

private:
    void finish() {
        std::vector<glm::dvec2> pts = m_clicked;
        cancel();
        // A double click can leave its point twice; drop consecutive duplicates.
        pts.erase(
            std::unique(pts.begin(), pts.end(),
                        [](glm::dvec2 x, glm::dvec2 y) { return glm::length(x - y) < 1e-12; }),
            pts.end());
        if (pts.size() < 3) {
            m_panel->showMessage(QObject::tr("A loop needs at least three points."));
            return;
        }
        if (m_shape == UvTool::Polygon)
            m_panel->addLoop({closedPolylineCurve(pts)}, QObject::tr("polygonal"));
        else
            m_panel->addLoop({closedSplineCurve(pts)}, QObject::tr("spline"));
    }

    UvPanel* m_panel;
    UvTool m_shape;
    std::vector<glm::dvec2> m_clicked;
    QPointF m_hover;
};

} // namespace

std::unique_ptr<Tool> makeUvClickTool(UvPanel* panel, UvTool shape) {
    return std::make_unique<UvClickTool>(panel, shape);
}

} // namespace kw
