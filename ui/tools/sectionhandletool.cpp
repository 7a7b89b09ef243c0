// SectionHandleTool: each section plane's handle in the 3D view, an arrow along its normal; a
// drag on it moves the plane along the normal, live. Sections are view state saved with the
// project (not document edits): the drag pushes no undo step, and Esc puts the plane back.
#include "ui/tools/viewtools.h"
#include "ui/viewport.h"

#include <QMouseEvent>
#include <QPainter>
#include <cmath>

namespace kw {

namespace {

/// The arrow's length on screen, and how near to it a press takes it, in widget pixels.
constexpr double kArrowPixels = 60.0;
constexpr double kReachPixels = 7.0;

double distanceToSegment(QPointF p, QPointF a, QPointF b) {
    const QPointF ab = b - a, ap = p - a;
    const double len2 = QPointF::dotProduct(ab, ab);
    const double t = len2 > 0.0 ? std::clamp(QPointF::dotProduct(ap, ab) / len2, 0.0, 1.0) : 0.0;
    const QPointF d = ap - t * ab;
    return std::hypot(d.x(), d.y());
}

class SectionHandleTool : public Tool {
public:
    explicit SectionHandleTool(Viewport* view) : m_view(view) {}

    bool press(QMouseEvent* event) override {
        if (event->button() != Qt::LeftButton || event->modifiers() != Qt::NoModifier)
            return false;
        const ViewProjection view = m_view->viewProjection();
        const std::vector<SectionPlane>& planes = m_view->sections();
        for (int k = 0; k < int(planes.size()); ++k) {
            const auto arrow = handle(view, planes[size_t(k)]);
            if (!arrow ||
                distanceToSegment(event->position(), arrow->first, arrow->second) > kReachPixels)
                continue;
            m_index = k;
            m_from = planes;
            m_axis = glm::normalize(planes[size_t(k)].normal);
            m_pressAlong = along(view, event->position());
            return true;
        }
        return false;
    }

    void move(QMouseEvent* event) override {
        if (m_index < 0)
            return;
        const double shift = along(m_view->viewProjection(), event->position()) - m_pressAlong;
        std::vector<SectionPlane> planes = m_from;
        planes[size_t(m_index)].position += shift * m_axis;
        m_view->moveSections(planes);
    }

    void release(QMouseEvent* event) override {
        if (event->button() == Qt::LeftButton)
            m_index = -1; // the plane stays where the drag left it
    }

    void cancel() override {
        if (m_index < 0)
            return;
        m_index = -1;
        m_view->moveSections(m_from);
    }

    bool dragging() const override { return m_index >= 0; }

    void paint(QPainter& p) override {
        const ViewProjection view = m_view->viewProjection();
        const std::vector<SectionPlane>& planes = m_view->sections();
        for (int k = 0; k < int(planes.size()); ++k) {
            const auto arrow = handle(view, planes[size_t(k)]);
            if (!arrow)
                continue;
            const auto [base, tip] = *arrow;
            const QColor colour = k == m_index ? QColor(255, 170, 40) : QColor(60, 200, 255);
            p.setPen(QPen(colour, 2.0));
            p.setBrush(Qt::NoBrush);
            p.drawLine(base, tip);
            p.drawEllipse(base, 4.0, 4.0);
            // The head: two strokes back from the tip, 30 degrees either side.
            const QPointF d = tip - base;
            const double len = std::hypot(d.x(), d.y());
            if (len > 1.0) {
                const QPointF u = d / len, n(-u.y(), u.x());
                p.drawLine(tip, tip - 10.0 * u + 5.0 * n);
                p.drawLine(tip, tip - 10.0 * u - 5.0 * n);
            }
            p.drawText(tip + QPointF(6.0, -4.0), QObject::tr("Section %1").arg(k + 1));
        }
    }

private:
    /// The plane's handle on screen: from its point to kArrowPixels along its normal (shorter
    /// where the normal points at the eye); nullopt when the point is behind the eye.
    static std::optional<std::pair<QPointF, QPointF>> handle(const ViewProjection& view,
                                                             const SectionPlane& plane) {
        const std::optional<QPointF> base = view.project(plane.position);
        if (!base)
            return std::nullopt;
        const glm::dvec3 n = glm::normalize(plane.normal);
        // A world step along the normal small enough to stay in front of the eye, scaled on
        // screen to the arrow's length.
        const double step = 0.05 * std::max(view.depth(plane.position), 1e-12);
        const std::optional<QPointF> ahead = view.project(plane.position + step * n);
        if (!ahead)
            return std::pair{*base, *base};
        const QPointF d = *ahead - *base;
        const double len = std::hypot(d.x(), d.y());
        return std::pair{*base, len > 1e-9 ? *base + d * (kArrowPixels / len) : *base};
    }

    /// Where the ray through `pixel` passes the dragged plane's normal line through its point
    /// at the press: the distance along the normal.
    double along(const ViewProjection& view, QPointF pixel) const {
        const glm::dvec3 anchor = m_from[size_t(m_index)].position;
        return glm::dot(view.onAxis(pixel, anchor, m_axis) - anchor, m_axis);
    }

    Viewport* m_view;
    int m_index = -1;                 ///< the dragged plane, -1 when no drag runs
    std::vector<SectionPlane> m_from; ///< every plane at the press
    glm::dvec3 m_axis{0.0};           ///< the dragged plane's unit normal
    double m_pressAlong = 0.0;
};

} // namespace

std::unique_ptr<Tool> makeSectionHandleTool(Viewport* view) {
    return std::make_unique<SectionHandleTool>(view);
}

} // namespace kw
