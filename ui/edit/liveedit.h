// LiveEdit: the protocol of every drag that edits the document live, written once.
#pragma once

#include "model/document/document.h"
#include "model/document/selection.h"

#include <QObject>
#include <QString>
#include <functional>
#include <map>
#include <memory>

class QUndoCommand;
class QUndoStack;

namespace kw {

/// begin() -> update steps as the mouse moves (the document follows live, so the surface and
/// the panels do) -> commit() as ONE undo step, or cancel() putting back the state at begin().
///
/// Each step is checked by the document's rule (Document::checkControlPoints, checkWeight,
/// checkTrimPoints) before anything changes: a refused step changes nothing, returns the
/// reason as an Error and emits refused(reason) for the status bar. The press-time value of
/// every point is recorded the first time a step touches it. A scene reset (Open, New) ends the
/// edit without restoring anything: the points it recorded are gone.
class LiveEdit : public QObject {
    Q_OBJECT
public:
    LiveEdit(Document* document, QUndoStack* stack, QObject* parent = nullptr);

    Document* document() const { return m_doc; }
    bool isActive() const { return m_active; }
    /// Starts an edit (ending a running one as cancel() does).
    void begin();

    /// One step; ok() when applied, else why it was refused. Out of an edit the step is
    /// refused ("no edit running").
    Status moveControlPoints(SurfaceId surface, const std::vector<int>& indices,
                             const std::vector<glm::dvec3>& positions);
    /// The same for points of any surfaces, by net position: every surface's step is checked
    /// before any is applied. A point no longer in its net (an undo re-sized it under the drag)
    /// refuses the step.
    Status moveControlPoints(const std::vector<ControlPointRef>& refs,
                             const std::vector<glm::dvec3>& positions);
    Status setWeight(SurfaceId surface, int index, double weight);
    /// Refs of one surface (a curve end with the coinciding end of its neighbour).
    Status moveTrimPoints(const std::vector<TrimPointRef>& refs,
                          const std::vector<glm::dvec2>& positions);

    /// Surfaces whose control points now differ from their press-time values.
    int movedSurfaces() const;

    /// Ends the edit as one undo step from the press-time to the current values: one command
    /// (named `text`, or its own name when empty) or a macro of several (named `severalText`
    /// with %1 the command count, or "Move N control points"). Nothing is pushed when nothing
    /// changed. Returns whether a step was pushed.
    bool commit(const QString& text = {}, const QString& severalText = {});
    /// Ends the edit with the caller's own command (an exact affine map, say): the press-time
    /// state is put back first, then `make` builds the command against it and it is pushed,
    /// its redo() making the change. A null command pushes nothing (as cancel()).
    bool commitWith(const std::function<std::unique_ptr<QUndoCommand>()>& make);
    /// Ends the edit, putting back every touched value as it was at begin().
    void cancel();

Q_SIGNALS:
    /// A step was refused; the reason is in the document's words.
    void refused(const QString& reason);

private:
    /// Emits refused() with the reason and returns it.
    Error refuse(Error reason);
    /// A checked points step: records the press-time values it touches first, then moves the
    /// points in the document. The one place a drag step of points reaches the document; the
    /// document's reason should it still refuse.
    Status applyPoints(SurfaceId surface, const std::vector<int>& indices,
                       const std::vector<glm::dvec3>& positions);
    /// Puts back the press-time values; the surfaces or loops gone since are skipped.
    void restore();
    void clear();

    Document* m_doc;
    QUndoStack* m_stack;
    bool m_active = false;
    /// Press-time points by surface, with the surface's knots revision when first touched: a
    /// net re-sized or re-knotted under the drag (an undo by key) gives its indices another
    /// meaning, so that surface's steps are refused and its record is neither committed nor
    /// restored.
    struct Recorded {
        std::uint64_t knots = 0;
        std::map<int, glm::dvec3> from;
    };
    /// ok() while `surface`'s net is the one its record began with (or it has none), else
    /// why not.
    Status checkNet(SurfaceId surface) const;
    std::map<SurfaceId, Recorded> m_points;
    std::map<std::pair<SurfaceId, int>, double> m_weights;
    std::map<TrimPointRef, glm::dvec2> m_trims;
};

} // namespace kw
