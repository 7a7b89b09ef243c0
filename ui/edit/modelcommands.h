// Modeling commands: place surfaces by an affine map, hide and show surfaces, remove
// knots within a tolerance, and replace a trim loop's curves (trim point insertion and deletion).
#pragma once

#include "model/document/matchsurface.h"
#include "model/error.h"
#include "ui/edit/commands.h"

#include <glm/glm.hpp>

namespace kw {

class TransformSurfaces : public DocumentCommand {
public:
    /// Applies the affine map `transform` (last row 0 0 0 1, finite) to every control point of
    /// the listed surfaces (unique, existing). NURBS are affinely invariant, so the surfaces are
    /// transformed exactly; weights, knots and trims are unchanged. `text` names the step
    /// ("Move 2 surfaces"). Rejected when nothing would move.
    static Expected<std::unique_ptr<TransformSurfaces>> create(Document* document,
                                                               std::vector<SurfaceId> surfaces,
                                                               const glm::dmat4& transform,
                                                               const QString& text);
    void redo() override;
    void undo() override;

private:
    TransformSurfaces(Document* d, const QString& text) : DocumentCommand(d, text) {}
    void apply(bool forward, const char* what);
    std::vector<SurfaceId> m_surfaces;
    std::vector<std::vector<glm::dvec3>> m_from, m_to;
};

class SetUnits : public DocumentCommand {
public:
    /// Gives the document the length unit `unit`. With `convert` every length is scaled so the
    /// part keeps its size (25.4 mm per inch: control points, edge tolerances, camera, point
    /// lights); without, the numbers stay and only their unit changes (a file read with the
    /// wrong unit). Rejected when nothing would change or a scaled value is not finite. Undo
    /// puts back the values as they were, bit for bit.
    static Expected<std::unique_ptr<SetUnits>> create(Document* document, LengthUnit unit,
                                                      bool convert);
    void redo() override;
    void undo() override;

private:
    SetUnits(Document* d, const QString& text) : DocumentCommand(d, text) {}
    Document::Lengths m_from, m_to;
};

/// The project's continuity tolerances (Scene::continuity, saved with it): authored data that
/// re-classifies every edge, so a change is an undo step like any other edit.
class SetContinuityTolerances : public DocumentCommand {
public:
    /// Refused when `to` is invalid (checkContinuityTolerances) or equal to the document's.
    static Expected<std::unique_ptr<SetContinuityTolerances>>
    create(Document* document, const ContinuityTolerances& to);
    void redo() override;
    void undo() override;

private:
    SetContinuityTolerances(Document* d, const QString& text) : DocumentCommand(d, text) {}
    ContinuityTolerances m_from, m_to;
};

class SetSurfacesHidden : public DocumentCommand {
public:
    /// Gives each listed surface (unique, existing) its `hidden` value: hide, show, isolate and
    /// show all are one step each. Surfaces already in that state are left out; rejected when
    /// none is left. `text` names the step ("Hide 2 surfaces").
    static Expected<std::unique_ptr<SetSurfacesHidden>>
    create(Document* document, const std::vector<std::pair<SurfaceId, bool>>& states,
           const QString& text);
    void redo() override;
    void undo() override;
    int changed() const { return int(m_ids.size()); }

private:
    SetSurfacesHidden(Document* d, const QString& text) : DocumentCommand(d, text) {}
    void apply(bool forward, const char* what);
    std::vector<SurfaceId> m_ids;
    std::vector<bool> m_to; ///< the new state per id (undo restores the other)
};

class RemoveKnots : public GeometryCommand {
public:
    /// Removes every interior knot of the direction that can go while the surface moves by at
    /// most `tolerance` (kw::surfaceRemoveKnots, The NURBS Book A5.8). Rejected when none can.
    static Expected<std::unique_ptr<RemoveKnots>> create(Document* document, SurfaceId surface,
                                                         Direction direction, double tolerance);
    int removed() const { return m_removed; }

private:
    using GeometryCommand::GeometryCommand;
    int m_removed = 0;
};

class MatchSurfaceCommand : public GeometryCommand {
public:
    /// Modify > Match Surface: the surface's new geometry from kw::matchSurface (its boundary
    /// rows moved, knots inserted as needed), one undo step. Rejected when matchSurface refuses
    /// the request; a match that does not reach the tolerance is still a step, and result()
    /// says so with the deviation.
    static Expected<std::unique_ptr<MatchSurfaceCommand>>
    create(Document* document, const MatchRequest& request, const ContinuityTolerances& tolerances);
    const MatchResult& result() const { return m_result; }

private:
    using GeometryCommand::GeometryCommand;
    MatchResult m_result;
};

class ReplaceTrimLoop : public DocumentCommand {
public:
    /// Replaces the curves of an existing loop (same id, same place among the surface's loops);
    /// the new loop must pass checkTrimLoop. `text` names the step ("Insert trim point").
    static Expected<std::unique_ptr<ReplaceTrimLoop>> create(Document* document, SurfaceId surface,
                                                             TrimLoop loop, const QString& text);
    void redo() override;
    void undo() override;

private:
    ReplaceTrimLoop(Document* d, const QString& text) : DocumentCommand(d, text) {}
    SurfaceId m_surface;
    TrimLoop m_from, m_to;
    int m_index = 0;
};

} // namespace kw
