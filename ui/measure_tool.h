// Measurements in the 3D view: distance, angle between normals and radius from probed exact
// points, kept as labelled dimensions over the view until cleared. Not document edits: nothing
// here touches the document or the undo stack.
#pragma once

#include "model/analysis/probe.h"

#include <QObject>
#include <QString>
#include <QStringList>
#include <functional>
#include <optional>
#include <vector>

class QPainter;

namespace kw {

class Viewport;

/// The dimensions drawn over a viewport (a QPainter overlay of its frames, Viewport::addOverlay)
/// and the clicks that make them: Distance and Angle take two points, Radius one.
class MeasureTool : public QObject {
    Q_OBJECT
public:
    explicit MeasureTool(Viewport* viewport);

    /// The kind the next clicks measure; changing it drops a half-made measurement.
    void setKind(Measurement::Kind kind);
    Measurement::Kind kind() const { return m_kind; }
    /// A probed point clicked: completes a measurement (returned) or starts one. `planes`
    /// (Angle): tells whether two points lie on plane faces (Measurement::betweenPlanes).
    std::optional<Measurement>
    addPoint(const ProbePoint& p,
             const std::function<bool(const ProbePoint&, const ProbePoint&)>& planes = {});
    /// Drops the half-made measurement; false when there was none.
    bool cancelPending();
    bool hasPending() const { return m_pending.has_value(); }
    const std::vector<Measurement>& measurements() const { return m_done; }
    void clear();
    /// The probe's marker (nullopt: none), drawn as a small cross.
    void setProbeMarker(std::optional<glm::dvec3> point);

    /// The label of each dimension as drawn, in order (for the status bar and tests).
    /// The document's length unit ("mm"), shown after every length.
    QString unitKey() const;
    QStringList labels() const;

    /// Draws the dimensions, the half-made one's point and the marker (view pixels).
    void paint(QPainter& p) const;

private:
    /// Paints the view's overlays again (a changed dimension or marker; no new frame).
    void update();

    Viewport* m_view;
    Measurement::Kind m_kind = Measurement::Kind::Distance;
    std::optional<ProbePoint> m_pending;
    std::vector<Measurement> m_done;
    std::optional<glm::dvec3> m_marker;
};

} // namespace kw
