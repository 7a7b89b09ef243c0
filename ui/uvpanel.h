// UvPanel: the selected surface's (u, v) domain with its trim loops, their control points and
// the CPU trim mask; trim control points are dragged here as undoable edits.
#pragma once

#include "model/selection.h"
#include "ui/trimmask.h"

#include <QImage>
#include <QWidget>
#include <optional>
#include <vector>

class QUndoStack;

namespace kw {

/// Shows the current surface's domain (u to the right, v up) filled with the trim mask (light:
/// kept, dark: removed), the trim loops and the trim curves' control polygons. Left click picks
/// the nearest trim control point within a few pixels; dragging moves it (and any curve end
/// that coincides with it, so loops stay closed), live in the document; the release pushes one
/// MoveTrimPoints command. Esc cancels a drag.
class UvPanel : public QWidget {
    Q_OBJECT
public:
    static constexpr double kPickRadius = 6.0;

    UvPanel(Document* document, Selection* selection, QUndoStack* stack, QWidget* parent = nullptr);

    /// The surface shown (the selection's current surface), or invalid.
    SurfaceId surface() const;
    /// Widget position of a (u, v) point, and back, for the current size and surface.
    QPointF toWidget(glm::dvec2 uv) const;
    glm::dvec2 toUv(QPointF pixel) const;
    /// The mask drawn last (Grayscale8, the domain rectangle's size); null with no surface.
    QImage mask();
    /// The nearest trim control point within `radius` pixels, if any.
    std::optional<TrimPointRef> trimPointAt(QPointF pixel, double radius = kPickRadius) const;

    QSize sizeHint() const override { return {280, 280}; }

protected:
    void paintEvent(QPaintEvent* event) override;
    void mousePressEvent(QMouseEvent* event) override;
    void mouseMoveEvent(QMouseEvent* event) override;
    void mouseReleaseEvent(QMouseEvent* event) override;
    void keyPressEvent(QKeyEvent* event) override;

private:
    struct Dragged {
        TrimPointRef ref;
        glm::dvec2 from;
    };
    QRectF domainRect() const;
    void refreshMask();
    void finishDrag(bool cancel);

    Document* m_doc;
    Selection* m_selection;
    QUndoStack* m_stack;
    QImage m_mask;       ///< the parity mask (grey 0 / 255), what mask() returns
    QImage m_maskColors; ///< m_mask in the panel's colours, drawn by paintEvent
    std::vector<std::vector<glm::dvec2>> m_trimLines; ///< flattened trim loops, drawn by paintEvent
    SurfaceId m_maskSurface;
    std::uint64_t m_maskRevision = 0;
    std::uint64_t m_maskGeometry = 0;
    std::vector<Dragged> m_drag;
    QPointF m_pressPixel;
    bool m_dragging = false;
};

} // namespace kw
