// ModelingTools: the editor's Create and Modify menus and toolbar — primitives, patches,
// revolve / extrude / loft from surface curves or drawn curves (CurveTool), move / rotate /
// scale (dialog and Ctrl + drag modes), duplicate, delete and knot removal — each one undo
// step on the window's stack.
#pragma once

#include "model/document/matchsurface.h"
#include "model/document/selection.h"
#include "model/nurbs/nurbs_construct.h"
#include "ui/edit/commands.h"

#include <QObject>
#include <functional>
#include <optional>

class QMenu;
class QMenuBar;
class QToolBar;
class QUndoStack;
class QWidget;

namespace kw {

class CurveTool;
class Viewport;

class ModelingTools : public QObject {
    Q_OBJECT
public:
    enum class Primitive { Plane, Sphere, Cylinder, Cone, Torus };

    /// File ▸ New patch: clamped uniform knots, control points evenly over size (0: a size
    /// that fills about a third of the view).
    struct PatchParams {
        int degreeU = 3, degreeV = 3;
        int countU = 4, countV = 4;
        double sizeU = 0.0, sizeV = 0.0;
    };

    /// Which curve of a surface revolve, extrude and loft use: a boundary or an iso-curve at
    /// `fraction` (0..1) of the domain in the other direction.
    enum class CurveEdge { VStart, VEnd, UStart, UEnd, IsoU, IsoV };
    struct CurveSpec {
        CurveEdge edge = CurveEdge::VStart;
        double fraction = 0.5;
    };
    /// The parameters of a revolve / extrude / loft; `vector` is the axis direction (revolve)
    /// or the extrusion vector; `point` a point on the axis.
    struct CurveOperation {
        CurveSpec curve;
        glm::dvec3 point{0.0};
        glm::dvec3 vector{0.0, 0.0, 1.0};
        /// The curves come from the curve tool, not from selected surfaces (`curve` unused).
        bool drawnCurves = false;
    };
    enum class CurveOperationKind { Revolve, Extrude, Loft };

    /// Move, rotate (degrees about an axis through the selection's centre) and scale (about
    /// the centre), applied in the order scale, rotate, move.
    struct TransformParams {
        glm::dvec3 offset{0.0};
        int rotationAxis = 2; ///< 0 x, 1 y, 2 z
        double degrees = 0.0;
        double scale = 1.0;
    };

    /// The dialogs the tools ask through; tests replace them. Empty optional: cancelled.
    struct Prompts {
        std::function<std::optional<PatchParams>(QWidget*, const PatchParams&)> patch;
        std::function<std::optional<CurveOperation>(QWidget*, CurveOperationKind,
                                                    const CurveOperation&)>
            curveOperation;
        std::function<std::optional<TransformParams>(QWidget*)> transform;
        /// Direction (0 u, 1 v) and tolerance for knot removal.
        std::function<std::optional<std::pair<int, double>>(QWidget*, double suggested)>
            knotRemoval;
        /// Modify > Match Surface: the edge of `surface` to match, the target side and the
        /// continuity.
        std::function<std::optional<MatchRequest>(QWidget*, const Scene&, SurfaceId surface)>
            matchSurface;
        static Prompts standard();
    };

    /// All pointers must outlive the tools; `window` parents the dialogs.
    ModelingTools(QWidget* window, Document* document, SceneModel* model, Selection* selection,
                  QUndoStack* stack, Viewport* viewport);

    void setPrompts(Prompts prompts) { m_prompts = std::move(prompts); }
    /// Adds the Create and Modify menus to `bar` and their main entries to `toolbar`.
    void buildMenus(QMenuBar* bar, QToolBar* toolbar);

    // Each creates one undo step, selects the new surface, shows what was done (message())
    // and returns its id; when refused, the Error says why, in the words the status bar shows
    // (the menu actions show it there).
    Expected<SurfaceId> createPrimitive(Primitive kind);
    Expected<SurfaceId> createPatch(const PatchParams& params);
    Expected<SurfaceId> createFromCurves(CurveOperationKind kind, const CurveOperation& op);
    /// The same from given curves (the curve tool's).
    Expected<SurfaceId> createFromCurveList(CurveOperationKind kind, const CurveOperation& op,
                                            const std::vector<NurbsCurve3>& curves);
    /// Create ▸ Draw Curve to Revolve / Extrude / Loft: starts the curve tool; when it
    /// finishes, the operation's dialog is asked and the surface made (one undo step).
    void drawCurvesFor(CurveOperationKind kind);
    CurveTool* curveTool() const { return m_curveTool; }
    /// Applies to the selected surfaces (one undo step); the Error says why when refused (as
    /// for the create functions). Several surfaces are deleted or duplicated one by one in
    /// one step: one refused leaves the others done, and the Error names the last refused.
    Status transformSelected(const TransformParams& params);
    Status duplicateSelected();
    Status deleteSelected();
    /// Of the current surface; message() names what was removed.
    Status removeKnots(Direction direction, double tolerance);
    /// Modify > Match Surface (one undo step); message() gives the kernel's measure of the
    /// result.
    Status matchSurface(const MatchRequest& request);

    /// The curve `spec` of a surface (kernel iso-curve, exact).
    static NurbsCurve3 surfaceCurve(const NurbsSurface& s, const CurveSpec& spec);
    /// A length that fills about a third of the view at the camera's target.
    double viewScale() const;
    /// Where a new shape of bounding radius `radius` goes: the camera's target when nothing
    /// shown is within its reach, else beside the shown surfaces, to the view's right of them
    /// with a gap of a fifth of the radius, so new shapes never appear inside others.
    glm::dvec3 placeBesideShown(double radius) const;
    /// Makes `ids` the selected surfaces (the first one current).
    void selectSurfaces(const std::vector<SurfaceId>& ids);

Q_SIGNALS:
    /// A status-bar message: what was done, or why a menu action was refused.
    void message(const QString& text);

private:
    Expected<SurfaceId> add(Surface surface, const QString& text);
    /// Shows why an action was refused (message()); nothing when it was done.
    template <class T> void report(const Expected<T>& result) {
        if (!result)
            Q_EMIT message(result.message());
    }
    QString uniqueName(const QString& base) const;

    QWidget* m_window;
    Document* m_doc;
    SceneModel* m_model;
    Selection* m_selection;
    QUndoStack* m_stack;
    Viewport* m_viewport;
    Prompts m_prompts;
    CurveTool* m_curveTool = nullptr;
};

} // namespace kw
