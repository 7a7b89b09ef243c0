// UvPanel: the selected surface's (u, v) domain with its trim loops, their control points and
// the CPU trim mask; trim control points are dragged here as undoable edits.
#pragma once

#include "model/document/selection.h"
#include "ui/tools/tool.h"
#include "ui/trimmask.h"

#include <QImage>
#include <QWidget>
#include <map>
#include <memory>
#include <optional>
#include <vector>

class QAction;
class QUndoStack;

namespace kw {

/// Position of an existing trim point (precondition: the ref names one).
inline glm::dvec2 trimPointPosition(const Document& doc, const TrimPointRef& ref) {
    for (const TrimLoop& l : doc.surface(ref.surface)->trims)
        if (l.id == ref.loop)
            return l.curves[size_t(ref.curve)].points[size_t(ref.index)];
    return glm::dvec2(0.0);
}

/// A closed polyline as one degree-1 curve (the first point repeated at the end), and a
/// closed clamped B-spline (cubic when there are enough points) whose control polygon is
/// `pts`: the loops the panel's drawing tools make.
NurbsCurve2 closedPolylineCurve(const std::vector<glm::dvec2>& pts);
NurbsCurve2 closedSplineCurve(const std::vector<glm::dvec2>& pts);

class UvPanel;
/// The UV dock's content: a toolbar with the panel's tools, fields for the picked trim
/// point's exact (u, v) (named "uvPointU" / "uvPointV"; disabled and empty when none is
/// picked), and the panel.
QWidget* makeUvEditor(UvPanel* panel, Selection* selection, Document* document);

/// A domain bound for the UV panel's axis labels: rounded to three significant digits of the
/// domain's `span` (0.72 -> 0.001, 20.9 -> 0.1), with no "-0" ("-0.00293838" over a span of
/// 0.72 reads "-0.003").
QString domainLabel(double value, double span);

/// What a left press in the UV panel does: pick and drag trim points, or draw a new loop.
enum class UvTool { Select, Rectangle, Circle, Polygon, Spline };

/// Shows the current surface's domain (u to the right, v up) filled with the trim mask (light:
/// kept, dark: removed), the trim loops and the trim curves' control polygons. Presses go to
/// tools (ui/tools/uvpaneltools.h) through a ToolRouter, as in the 3D view. Left click picks
/// the nearest trim control point within a few pixels; dragging moves it (and any curve end
/// that coincides with it, so loops stay closed), live in the document through a LiveEdit; the
/// release pushes one MoveTrimPoints command. Esc cancels a drag; a refused step says why.
///
/// Drawing tools add a trim loop (one undo step): Rectangle and Circle (exact rational) by a
/// press-drag-release (corner to corner, centre to radius); Polygon and Spline by clicks, ended
/// by a double click or Enter (Backspace drops the last point, Esc cancels). With "draw holes"
/// on, the first loop drawn on an untrimmed surface comes with the domain's boundary as outer
/// loop, so the new loop cuts a hole; off, the loop is an outer boundary. The wheel zooms
/// about the cursor and a middle or right drag pans. Loops that cross each other are reported
/// (crossingWarning) but kept.
class UvPanel : public QWidget {
    Q_OBJECT
public:
    static constexpr double kPickRadius = 6.0;
    static constexpr double kMaxZoom = 64.0;

    UvPanel(Document* document, Selection* selection, QUndoStack* stack, QWidget* parent = nullptr);

    // For the tools.
    Document* document() const { return m_doc; }
    Selection* selection() const { return m_selection; }
    QUndoStack* undoStack() const { return m_stack; }
    /// Emits message(text).
    void showMessage(const QString& text) { Q_EMIT message(text); }

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

    UvTool tool() const { return m_tool; }
    void setTool(UvTool tool);
    bool drawHoles() const { return m_drawHoles; }
    void setDrawHoles(bool on) { m_drawHoles = on; }
    /// Adds a loop drawn with a tool (see the class comment): one undo step. False (and
    /// message()) when refused.
    bool addLoop(const std::vector<NurbsCurve2>& curves, const QString& what);
    /// Removes the loops of the picked trim points (one undo step); false when none is picked.
    bool deleteSelectedLoops();
    /// Inserts a control point after the picked one (knot insertion, the curve keeps its
    /// shape), or deletes the picked interior control point. One undo step each.
    bool insertTrimPoint();
    bool deleteTrimPoint();
    /// Moves the first picked trim point (and the curve ends that coincide with it) to `uv`.
    bool setTrimPointPosition(glm::dvec2 uv);
    /// Zoom factor (1: the whole domain fits) and the domain fraction at the panel's centre.
    double zoom() const { return m_zoom; }
    void setView(double zoom, glm::dvec2 centre);
    /// Empty, or which loops cross (computed with the mask, after every trim change).
    QString crossingWarning();
    /// The tool actions (checkable, exclusive), the holes toggle and the point edits, for the
    /// panel's toolbar.
    QList<QAction*> toolActions() const { return m_actions; }

Q_SIGNALS:
    /// A refusal or a warning for the status bar.
    void message(const QString& text);

protected:
    void paintEvent(QPaintEvent* event) override;
    void mousePressEvent(QMouseEvent* event) override;
    void mouseMoveEvent(QMouseEvent* event) override;
    void mouseReleaseEvent(QMouseEvent* event) override;
    void keyPressEvent(QKeyEvent* event) override;
    void wheelEvent(QWheelEvent* event) override;
    void mouseDoubleClickEvent(QMouseEvent* event) override;

private:
    QRectF domainRect() const;
    void refreshMask();
    void buildActions();

    Document* m_doc;
    Selection* m_selection;
    QUndoStack* m_stack;
    QImage m_mask;       ///< the parity mask (grey 0 / 255), what mask() returns
    QImage m_maskColors; ///< m_mask in the panel's colours, drawn by paintEvent
    std::vector<std::vector<glm::dvec2>> m_trimLines; ///< flattened trim loops, drawn by paintEvent
    SurfaceId m_maskSurface;
    std::uint64_t m_maskRevision = 0;
    std::uint64_t m_maskGeometry = 0;
    ToolRouter m_tools;
    /// The drawing tool of each UvTool but Select, installed by setTool.
    std::map<UvTool, std::unique_ptr<Tool>> m_drawing;

    UvTool m_tool = UvTool::Select;
    bool m_drawHoles = true;
    double m_zoom = 1.0;
    glm::dvec2 m_centre{0.5, 0.5};
    bool m_panning = false;
    QPointF m_panLast;
    QString m_crossing;
    QList<QAction*> m_actions;
};

} // namespace kw
