// CurveTool: the Create menu's curve tool. Left clicks put points on a plane through the
// view's target facing the viewer (fixed at the first click); Enter ends the curve, Backspace
// takes back the last point, Esc cancels. The curve interpolates the points (The NURBS Book
// A9.1, kw::interpolateCurve3) or takes them as its control polygon. Revolve and extrude use
// one curve; loft collects curves until Enter is pressed with no new point.
#pragma once

#include "model/nurbs/nurbs_construct.h"
#include "ui/viewport.h"

#include <QObject>
#include <QPointer>
#include <vector>

namespace kw {

class CurveTool : public QObject, public Tool {
    Q_OBJECT
public:
    /// `viewport` must outlive the tool.
    CurveTool(Viewport* viewport, QObject* parent);
    ~CurveTool() override;

    /// Starts a new drawing (dropping any unfinished one) and installs the tool in the view.
    /// `curvesWanted`: 1 for revolve and extrude, 0 for "two or more" (loft).
    void start(int curvesWanted, const QString& purpose);
    /// Ends the drawing without a result.
    void cancel();
    bool isActive() const { return m_active; }

    /// Interpolating (default) or control-point curves.
    void setInterpolating(bool on) { m_interpolating = on; }
    bool interpolating() const { return m_interpolating; }

    /// The points of the curve being drawn, and the curves finished so far.
    const std::vector<glm::dvec3>& points() const { return m_points; }
    const std::vector<NurbsCurve3>& curves() const { return m_curves; }
    /// The curve through `points` as the tool builds it; an Error (the reason) when it cannot.
    Expected<NurbsCurve3> curveThrough(const std::vector<glm::dvec3>& points) const;
    /// curveThrough(points()) as paint() draws it: solved once per change of the points or of
    /// interpolating(), not on every repaint (a camera drag repaints many times a second).
    const NurbsCurve3& preview();

    /// A left click adds a point on the drawing's plane.
    bool press(QMouseEvent* event) override;
    bool key(QKeyEvent* event) override;
    /// Another tool took the view (a Measure mode): the drawing ends as with Esc.
    void uninstalled() override { cancel(); }
    void paint(QPainter& painter) override;

Q_SIGNALS:
    /// The drawing is complete: the curves to build from (the tool is already uninstalled).
    void finished(const std::vector<kw::NurbsCurve3>& curves);
    void message(const QString& text);

private:
    bool endCurve();
    void stop();
    QString hint() const;

    QPointer<Viewport> m_viewport; ///< the window may destroy the view first
    bool m_active = false;
    bool m_interpolating = true;
    int m_wanted = 1;
    QString m_purpose;
    std::vector<glm::dvec3> m_points;
    std::vector<NurbsCurve3> m_curves;
    /// preview()'s curve and what it was built from; a different m_points or m_interpolating
    /// rebuilds it.
    NurbsCurve3 m_preview;
    std::vector<glm::dvec3> m_previewPoints;
    bool m_previewInterpolating = true;
    glm::dvec3 m_planePoint{0.0}, m_planeNormal{0.0, 0.0, 1.0}; ///< set by the first click
};

} // namespace kw
