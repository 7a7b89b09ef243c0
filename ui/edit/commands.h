// Edit commands: one QUndoCommand per user intent, changing the Document only through its API.
#pragma once

#include "model/document/document.h"
#include "model/error.h"

#include <QUndoCommand>
#include <memory>
#include <vector>

class QUndoStack;

namespace kw {

/// Parameter direction of a surface.
enum class Direction { U, V };

/// How a point edit came about: a drag is one undo step of its own; consecutive nudges of the
/// same points (arrow keys, spin boxes) merge into one.
enum class MoveKind { Drag, Nudge };

/// Command ids for QUndoCommand::id(); equal ids may merge.
enum CommandId {
    MoveControlPointsId = 1,
    SetWeightId,
    SetPartitionsId,
    MoveTrimPointsId,
    SetMaterialId,
    SetLightsId,
    SetCameraId,
};

/// Every command is built by a static `create` that checks the edit against the document as it
/// is now and returns an Error (the reason, as the status bar shows it) when the edit is invalid,
/// so nothing
/// invalid reaches the stack. Commands hold ids and authored values, never pointers into the
/// scene. Should the document still refuse a step (the stack was bypassed and the document
/// changed under it), the command warns and marks itself obsolete so the stack drops it.
/// Commands that merge become obsolete when the merged edit changes nothing.
class DocumentCommand : public QUndoCommand {
protected:
    DocumentCommand(Document* document, const QString& text);
    Document* document() const { return m_doc; }
    /// Call with the result of a document mutator; when it was refused, warns with the
    /// document's reason and marks the command obsolete.
    void check(const Status& done, const char* what);

private:
    Document* m_doc;
};

/// Pushes a command; returns false (pushing nothing) for nullptr or no stack.
bool pushCommand(QUndoStack* stack, std::unique_ptr<QUndoCommand> command);
/// Pushes what a `create` factory made; its Error (pushing nothing) when it refused the edit,
/// "no undo stack" without a stack.
template <class C> Status pushCommand(QUndoStack* stack, Expected<std::unique_ptr<C>> command) {
    if (!command)
        return std::move(command).error();
    if (!pushCommand(stack, std::unique_ptr<QUndoCommand>(std::move(*command))))
        return Error(QStringLiteral("no undo stack"));
    return ok();
}

class MoveControlPoints : public DocumentCommand {
public:
    /// `indices` are NurbsSurface::index values, unique and in range; `from` are the positions
    /// at press time, `to` the positions at release (both finite, one per index). The points
    /// of neighbouring faces that the document's seam link carries along (Keep Seams Closed)
    /// move with them in redo and back in undo: one step.
    static Expected<std::unique_ptr<MoveControlPoints>>
    create(Document* document, SurfaceId surface, std::vector<int> indices,
           std::vector<glm::dvec3> from, std::vector<glm::dvec3> to,
           MoveKind kind = MoveKind::Drag);
    void redo() override;
    void undo() override;
    int id() const override { return m_kind == MoveKind::Nudge ? MoveControlPointsId : -1; }
    bool mergeWith(const QUndoCommand* other) override;

private:
    MoveControlPoints(Document* d, const QString& text) : DocumentCommand(d, text) {}
    SurfaceId m_surface;
    std::vector<int> m_indices;
    std::vector<glm::dvec3> m_from, m_to;
    MoveKind m_kind = MoveKind::Drag;
    /// The document's seam link when the move was made: undo and redo carry the same
    /// neighbours' points (Keep Seams Closed), whatever the setting is then.
    Document::SeamLink m_link = Document::SeamLink::Off;
};

class SetWeight : public DocumentCommand {
public:
    /// `index` as in NurbsSurface::index; weight finite and > 0. Merges with the next SetWeight
    /// of the same point.
    static Expected<std::unique_ptr<SetWeight>> create(Document* document, SurfaceId surface,
                                                       int index, double weight);
    void redo() override;
    void undo() override;
    int id() const override { return SetWeightId; }
    bool mergeWith(const QUndoCommand* other) override;

private:
    SetWeight(Document* d, const QString& text) : DocumentCommand(d, text) {}
    SurfaceId m_surface;
    int m_index = 0;
    double m_from = 1.0, m_to = 1.0;
};

class SetPartitions : public DocumentCommand {
public:
    /// Both in [kMinPartitions, kMaxPartitions]. Consecutive steps on one surface (a slider
    /// sweep) merge into one undo step.
    static Expected<std::unique_ptr<SetPartitions>> create(Document* document, SurfaceId surface,
                                                           int nu, int nv);
    void redo() override;
    void undo() override;
    int id() const override { return SetPartitionsId; }
    bool mergeWith(const QUndoCommand* other) override;

private:
    SetPartitions(Document* d, const QString& text) : DocumentCommand(d, text) {}
    SurfaceId m_surface;
    int m_fromU = 0, m_fromV = 0, m_toU = 0, m_toV = 0;
};

/// Replaces a surface's geometry (degrees, knots, net) with a new value; the common part of
/// the knot and degree edits below.
class GeometryCommand : public DocumentCommand {
public:
    void redo() override;
    void undo() override;

protected:
    GeometryCommand(Document* d, const QString& text, SurfaceId surface, NurbsSurface from,
                    NurbsSurface to);

private:
    SurfaceId m_surface;
    NurbsSurface m_from, m_to;
};

class SetKnotVector : public GeometryCommand {
public:
    /// Replaces the u (or v) knot vector; it must pass kw::checkKnotVector for the current
    /// degree and control point count in that direction.
    static Expected<std::unique_ptr<SetKnotVector>>
    create(Document* document, SurfaceId surface, Direction direction, std::vector<double> knots);

private:
    using GeometryCommand::GeometryCommand;
};

class InsertKnot : public GeometryCommand {
public:
    /// Inserts `value` `times` times (A5.3); the surface does not move. Rejected when value is
    /// outside the open domain or the multiplicity would exceed the degree.
    static Expected<std::unique_ptr<InsertKnot>>
    create(Document* document, SurfaceId surface, Direction direction, double value, int times = 1);

private:
    using GeometryCommand::GeometryCommand;
};

class ElevateDegree : public GeometryCommand {
public:
    /// Raises the degree by `by` >= 1 (A5.9); rejected above kMaxDegree.
    static Expected<std::unique_ptr<ElevateDegree>> create(Document* document, SurfaceId surface,
                                                           Direction direction, int by = 1);

private:
    using GeometryCommand::GeometryCommand;
};

class AddSurface : public DocumentCommand {
public:
    /// Adds `surface` at `index` (-1 appends). An invalid surface id or trim loop id is replaced
    /// by a freshly allocated one; valid ids must be unused. The surface must pass
    /// kw::checkSurface.
    static Expected<std::unique_ptr<AddSurface>> create(Document* document, Surface surface,
                                                        int index = -1);
    SurfaceId surfaceId() const { return m_surface.id; }
    void redo() override;
    void undo() override;

private:
    AddSurface(Document* d, const QString& text) : DocumentCommand(d, text) {}
    Surface m_surface;
    int m_index = 0;
};

class RemoveSurface : public DocumentCommand {
public:
    /// Undo restores the surface at the same index with the same id.
    static Expected<std::unique_ptr<RemoveSurface>> create(Document* document, SurfaceId surface);
    void redo() override;
    void undo() override;

private:
    RemoveSurface(Document* d, const QString& text) : DocumentCommand(d, text) {}
    Surface m_surface;
    int m_index = 0;
};

class RenameSurface : public DocumentCommand {
public:
    /// `name` must contain a non-space character and differ from the current name.
    static Expected<std::unique_ptr<RenameSurface>> create(Document* document, SurfaceId surface,
                                                           const QString& name);
    void redo() override;
    void undo() override;

private:
    RenameSurface(Document* d, const QString& text) : DocumentCommand(d, text) {}
    SurfaceId m_surface;
    QString m_from, m_to;
};

class AddTrimLoop : public DocumentCommand {
public:
    /// Adds `loop` at `index` (-1 appends) to the surface's trims. An invalid loop id is
    /// replaced by a fresh one; a valid one must be unused. The loop must pass checkTrimLoop.
    static Expected<std::unique_ptr<AddTrimLoop>> create(Document* document, SurfaceId surface,
                                                         TrimLoop loop, int index = -1);
    TrimLoopId loopId() const { return m_loop.id; }
    void redo() override;
    void undo() override;

private:
    AddTrimLoop(Document* d, const QString& text) : DocumentCommand(d, text) {}
    SurfaceId m_surface;
    TrimLoop m_loop;
    int m_index = 0;
};

class RemoveTrimLoop : public DocumentCommand {
public:
    /// Undo restores the loop at the same index with the same id.
    static Expected<std::unique_ptr<RemoveTrimLoop>> create(Document* document, SurfaceId surface,
                                                            TrimLoopId loop);
    void redo() override;
    void undo() override;

private:
    RemoveTrimLoop(Document* d, const QString& text) : DocumentCommand(d, text) {}
    SurfaceId m_surface;
    TrimLoop m_loop;
    int m_index = 0;
};

class MoveTrimPoints : public DocumentCommand {
public:
    /// Trim points (unique, existing) with press-time and release positions, all finite.
    /// Several refs let a caller keep a loop closed by moving a curve's end and the next
    /// curve's start together. Nudges of the same refs merge.
    static Expected<std::unique_ptr<MoveTrimPoints>>
    create(Document* document, std::vector<TrimPointRef> refs, std::vector<glm::dvec2> from,
           std::vector<glm::dvec2> to, MoveKind kind = MoveKind::Drag);
    void redo() override;
    void undo() override;
    int id() const override { return m_kind == MoveKind::Nudge ? MoveTrimPointsId : -1; }
    bool mergeWith(const QUndoCommand* other) override;

private:
    MoveTrimPoints(Document* d, const QString& text) : DocumentCommand(d, text) {}
    void apply(const std::vector<glm::dvec2>& positions, const char* what);
    std::vector<TrimPointRef> m_refs;
    std::vector<glm::dvec2> m_from, m_to;
    MoveKind m_kind = MoveKind::Drag;
};

class SetMaterial : public DocumentCommand {
public:
    /// Material must pass kw::checkMaterial. Consecutive changes of one surface merge.
    static Expected<std::unique_ptr<SetMaterial>> create(Document* document, SurfaceId surface,
                                                         const Material& material);
    void redo() override;
    void undo() override;
    int id() const override { return SetMaterialId; }
    bool mergeWith(const QUndoCommand* other) override;

private:
    SetMaterial(Document* d, const QString& text) : DocumentCommand(d, text) {}
    SurfaceId m_surface;
    Material m_from, m_to;
};

class SetLights : public DocumentCommand {
public:
    /// Replaces all lights (1..kMaxLights, each valid).
    static Expected<std::unique_ptr<SetLights>> create(Document* document,
                                                       std::vector<Light> lights);
    /// Appends a light; rejected at kMaxLights.
    static Expected<std::unique_ptr<SetLights>> addLight(Document* document, const Light& light);
    /// Removes light `index`; rejected for the last remaining light.
    static Expected<std::unique_ptr<SetLights>> removeLight(Document* document, int index);
    /// Changes light `index`; consecutive changes of the same light merge.
    static Expected<std::unique_ptr<SetLights>> changeLight(Document* document, int index,
                                                            const Light& light);
    void redo() override;
    void undo() override;
    int id() const override { return SetLightsId; }
    bool mergeWith(const QUndoCommand* other) override;

private:
    SetLights(Document* d, const QString& text) : DocumentCommand(d, text) {}
    static Expected<std::unique_ptr<SetLights>> make(Document* document, std::vector<Light> lights,
                                                     const QString& text, int changed);
    std::vector<Light> m_from, m_to;
    int m_changed = -1; ///< index for changeLight (merge key), else -1 (never merges)
};

class SetCamera : public DocumentCommand {
public:
    /// Camera must pass kw::checkCamera; consecutive camera changes merge (one orbit, one step).
    static Expected<std::unique_ptr<SetCamera>> create(Document* document, const Camera& camera);
    void redo() override;
    void undo() override;
    int id() const override { return SetCameraId; }
    bool mergeWith(const QUndoCommand* other) override;

private:
    SetCamera(Document* d, const QString& text) : DocumentCommand(d, text) {}
    Camera m_from, m_to;
};

} // namespace kw
