// RubberBandTool: a left drag on empty space picks the control points inside the band (Shift
// adds them); a click there picks the surface drawn at that pixel (Shift toggles it).
#include "ui/tools/viewtools.h"
#include "ui/viewport.h"

#include <QMouseEvent>
#include <QPainter>
#include <QRubberBand>
#include <QStyle>
#include <QStyleOptionRubberBand>
#include <algorithm>

namespace kw {

namespace {

class RubberBandTool : public Tool {
public:
    explicit RubberBandTool(Viewport* view) : m_view(view) {}

    bool press(QMouseEvent* event) override {
        if (event->button() != Qt::LeftButton ||
            (event->modifiers() & (Qt::ControlModifier | Qt::AltModifier)))
            return false;
        m_press = event->position();
        m_band = QRect(m_press.toPoint(), QSize());
        m_dragging = true;
        m_view->updateOverlays();
        return true;
    }

    void move(QMouseEvent* event) override {
        if (!m_dragging)
            return;
        m_band = QRectF(m_press, event->position()).normalized().toRect();
        m_view->updateOverlays();
    }

    void paint(QPainter& painter) override {
        // As a QRubberBand child of the view draws itself (a widget would be hidden under the
        // view's native window): the style's rubber band over the frame.
        if (!m_dragging || m_band.isEmpty())
            return;
        QStyleOptionRubberBand option;
        option.initFrom(m_view);
        option.rect = m_band;
        option.shape = QRubberBand::Rectangle;
        option.opaque = false;
        painter.save();
        m_view->style()->drawControl(QStyle::CE_RubberBand, &option, &painter, m_view);
        painter.restore();
    }

    void release(QMouseEvent* event) override {
        if (event->button() != Qt::LeftButton)
            return;
        cancel();
        finish(event->position(), event->modifiers() & Qt::ShiftModifier);
    }

    void cancel() override {
        if (m_dragging)
            m_view->updateOverlays();
        m_dragging = false;
    }

    bool dragging() const override { return m_dragging; }

private:
    void finish(QPointF pixel, bool additive) {
        const QRectF rect = QRectF(m_press, pixel).normalized();
        if (rect.width() < 3 && rect.height() < 3) {
            // A click, not a band: select the surface drawn at that pixel (the renderer's own
            // id buffer, so what is picked is what is seen, trims included).
            if (const std::optional<PickHit> hit = m_view->pickSurface(pixel)) {
                m_view->selectClickedSurface(hit->surface, additive);
                return;
            }
        }
        std::vector<ControlPointRef> picked;
        if (rect.width() >= 3 || rect.height() >= 3)
            picked = m_view->controlPointsIn(rect);
        Selection* selection = m_view->selection();
        if (additive) {
            std::vector<ControlPointRef> sel = selection->controlPoints();
            sel.insert(sel.end(), picked.begin(), picked.end());
            std::sort(sel.begin(), sel.end());
            sel.erase(std::unique(sel.begin(), sel.end()), sel.end());
            picked = std::move(sel);
        }
        selection->setControlPoints(picked);
    }

    Viewport* m_view;
    QRect m_band; ///< the band while dragging, view pixels
    QPointF m_press;
    bool m_dragging = false;
};

} // namespace

std::unique_ptr<Tool> makeRubberBandTool(Viewport* view) {
    return std::make_unique<RubberBandTool>(view);
}

} // namespace kw
