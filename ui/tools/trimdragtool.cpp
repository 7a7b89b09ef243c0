// TrimDragTool: the UV panel's trim control point drag, through the same LiveEdit protocol as
// the 3D view's drags.
#include "model/nurbs/trim.h"
#include "ui/edit/liveedit.h"
#include "ui/tools/uvpaneltools.h"

#include <QMouseEvent>
#include <algorithm>

namespace kw {

namespace {

class TrimDragTool : public Tool {
public:
    explicit TrimDragTool(UvPanel* panel)
        : m_panel(panel), m_live(panel->document(), panel->undoStack()) {
        QObject::connect(&m_live, &LiveEdit::refused, panel, [panel](const QString& why) {
            panel->showMessage(QObject::tr("Drag step refused: %1").arg(why));
        });
    }

    bool press(QMouseEvent* event) override {
        if (event->button() != Qt::LeftButton)
            return false;
        Selection* selection = m_panel->selection();
        const std::optional<TrimPointRef> hit = m_panel->trimPointAt(event->position());
        if (!hit) {
            selection->setTrimPoints({});
            return true;
        }
        const Document* doc = m_panel->document();
        m_refs = trimPointWithCoincidentEnds(*doc->surface(hit->surface), *hit);
        m_from.clear();
        for (const TrimPointRef& ref : m_refs)
            m_from.push_back(trimPointPosition(*doc, ref));
        std::vector<TrimPointRef> picked = m_refs;
        std::sort(picked.begin(), picked.end());
        selection->setTrimPoints(picked);
        m_press = event->position();
        m_live.begin();
        return true;
    }

    void move(QMouseEvent* event) override {
        const glm::dvec2 delta = m_panel->toUv(event->position()) - m_panel->toUv(m_press);
        std::vector<glm::dvec2> to;
        for (const glm::dvec2& from : m_from)
            to.push_back(from + delta);
        // Coinciding ends together: the loop stays closed. A refusal goes to the panel's status.
        (void)m_live.moveTrimPoints(m_refs, to);
    }

    void release(QMouseEvent* event) override {
        if (event->button() != Qt::LeftButton)
            return;
        move(event);
        m_live.commit();
    }

    void cancel() override { m_live.cancel(); }
    bool dragging() const override { return m_live.isActive(); }
    bool editing() const override { return m_live.isActive(); }

private:
    UvPanel* m_panel;
    LiveEdit m_live;
    std::vector<TrimPointRef> m_refs;
    std::vector<glm::dvec2> m_from;
    QPointF m_press;
};

} // namespace

std::unique_ptr<Tool> makeTrimDragTool(UvPanel* panel) {
    return std::make_unique<TrimDragTool>(panel);
}

} // namespace kw
