// The 3D view's tools: the registry (viewtools.cpp), and the surface drag whose map the view
// reports.
#pragma once

#include "model/document/selection.h"
#include "ui/edit/liveedit.h"
#include "ui/tools/tool.h"

#include <QPointF>
#include <QString>
#include <glm/glm.hpp>
#include <memory>
#include <vector>

namespace kw {

class Viewport;

/// The view's registered tools, in the order a left press is offered to them.
std::vector<std::unique_ptr<Tool>> makeViewTools(Viewport* view);

/// Shows each step `live` refuses in the view's status bar ("Drag step refused: why").
void showRefusals(LiveEdit& live, Viewport* view);

/// Ctrl + drag on the selected surfaces (Viewport::SurfaceDrag): every control point follows
/// the move, rotation or scale (viewport.h tells how each is measured). Each is one
/// TransformSurfaces step with the exact affine map applied to the press-time points: a
/// placement, which the surfaces' analytic forms follow (Document::placeControlPoints).
class SurfaceDragTool : public Tool {
public:
    explicit SurfaceDragTool(Viewport* view);
    bool press(QMouseEvent* event) override;
    void move(QMouseEvent* event) override;
    void release(QMouseEvent* event) override;
    bool key(QKeyEvent* event) override;
    bool keyRelease(QKeyEvent* event) override;
    void cancel() override;
    bool dragging() const override { return m_live.isActive(); }
    bool editing() const override { return m_live.isActive(); }
    void paint(QPainter& painter) override;
    /// The map the running drag applies (identity when none runs or in the Move mode), and
    /// its angle in radians or its factor through `amount`.
    glm::dmat4 matrix(double* amount = nullptr) const;

private:
    /// Applies dragMap() to the press-time points as a live step (nothing when none runs).
    void step();
    /// Moves the press-time points by `map` as a live step. Precondition: dragging().
    void apply(const glm::dmat4& map);
    /// The map the running drag applies: matrix(), or the translation in the Move mode;
    /// `amount` as matrix() gives it (1 for a move).
    glm::dmat4 dragMap(double* amount = nullptr) const;
    QString text(double amount) const;

    Viewport* m_view;
    LiveEdit m_live;
    std::vector<ControlPointRef> m_refs; ///< every point of the dragged surfaces
    std::vector<glm::dvec3> m_from;      ///< and their positions at the press
    std::vector<SurfaceId> m_surfaces;
    glm::dvec3 m_pivot{0.0};
    QPointF m_press, m_last;
    bool m_snap = false;
};

} // namespace kw
