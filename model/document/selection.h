// Selection: what the user has picked — tree rows, control points and trim points — shared by
// views.
#pragma once

#include "model/document/scenemodel.h"

#include <QItemSelectionModel>
#include <QObject>
#include <vector>

namespace kw {

/// One selection shared by the scene tree, the viewport and the trim editor. Rows are held by a
/// QItemSelectionModel over the SceneModel; picked control and trim points as typed refs, kept
/// sorted and unique. The selection follows the document: points of a removed surface or
/// loop, of a surface whose net was re-sized (knot insertion renumbers points) or hidden, and
/// of surfaces outside a new row selection, are dropped; a scene reset clears everything.
/// changed() fires after any of these.
class Selection : public QObject {
    Q_OBJECT
public:
    /// `model` (and its document) must outlive the selection.
    explicit Selection(SceneModel& model, QObject* parent = nullptr);

    /// The row selection; owned by this Selection (its QObject child) and deleted with it.
    /// If the SceneModel goes first, the item selection is left with no model (Qt clears it).
    QItemSelectionModel* itemSelection() { return m_items; }
    /// The surface of the current tree row, or invalid.
    SurfaceId currentSurface() const;
    /// Surfaces with a selected row (the surface's own row or any row below it), in document
    /// order, each once.
    std::vector<SurfaceId> selectedSurfaces() const;

    const std::vector<ControlPointRef>& controlPoints() const { return m_points; }
    const std::vector<TrimPointRef>& trimPoints() const { return m_trimPoints; }
    /// Replaces the picked control points. Returns false (and changes nothing) if any ref
    /// names no control point of the document.
    bool setControlPoints(std::vector<ControlPointRef> refs);
    /// Replaces the picked trim points. Returns false (and changes nothing) if any ref names
    /// no trim point of the document.
    bool setTrimPoints(std::vector<TrimPointRef> refs);
    /// Clears rows and points.
    void clear();

Q_SIGNALS:
    void changed();

private:
    bool validRef(const ControlPointRef& r) const;
    bool validRef(const TrimPointRef& r) const;
    void dropSurface(SurfaceId id, bool points, bool trims);
    /// Unpicks the points of surfaces whose rows are not selected, when any row is (another
    /// surface picked in the tree or the view); emits nothing (the caller does).
    void keepPointsOfSelectedRows();
    void dropLoop(SurfaceId id, TrimLoopId loop);

    const Document* m_doc;
    // Held by pointer as this object's child: a QObject member must not have a parent that could
    // delete it, and QItemSelectionModel(model) alone would make the model its parent.
    QItemSelectionModel* m_items;
    std::vector<ControlPointRef> m_points;
    std::vector<TrimPointRef> m_trimPoints;
};

} // namespace kw
