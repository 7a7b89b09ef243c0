// ModelingTools: Create / Modify actions and the commands they push.
#include "ui/modelingtools.h"

#include "model/nurbs/analytic_eval.h"
#include "model/nurbs/nurbs_construct.h"
#include "model/nurbs/nurbs_shapes.h"
#include "ui/curvetool.h"
#include "ui/edit/modelcommands.h"
#include "ui/viewport.h"

#include <QAction>
#include <QActionGroup>
#include <QMenu>
#include <QMenuBar>
#include <QToolBar>
#include <QUndoStack>
#include <glm/gtc/matrix_transform.hpp>

namespace kw {

ModelingTools::ModelingTools(QWidget* window, Document* document, SceneModel* model,
                             Selection* selection, QUndoStack* stack, Viewport* viewport)
    : QObject(window), m_window(window), m_doc(document), m_model(model), m_selection(selection),
      m_stack(stack), m_viewport(viewport), m_prompts(Prompts::standard()),
      m_curveTool(new CurveTool(viewport, this)) {
    connect(m_curveTool, &CurveTool::message, this, &ModelingTools::message);
}

double ModelingTools::viewScale() const {
    const Camera& c = m_viewport->cameraController().camera();
    const double d = glm::length(c.eye - c.target);
    return std::isfinite(d) && d > 0.0 ? 0.35 * d : 1.0;
}

QString ModelingTools::uniqueName(const QString& base) const {
    int n = 1;
    for (const Surface& s : m_doc->scene().surfaces)
        if (s.name.startsWith(base))
            ++n;
    return QStringLiteral("%1 %2").arg(base).arg(n);
}

void ModelingTools::selectSurfaces(const std::vector<SurfaceId>& ids) {
    QItemSelectionModel* items = m_selection->itemSelection();
    QItemSelection rows;
    for (SurfaceId id : ids) {
        const QModelIndex row = m_model->surfaceIndex(id);
        if (row.isValid())
            rows.select(row, row);
    }
    items->select(rows, QItemSelectionModel::ClearAndSelect | QItemSelectionModel::Rows);
    if (!ids.empty())
        items->setCurrentIndex(m_model->surfaceIndex(ids.front()), QItemSelectionModel::NoUpdate);
}

Expected<SurfaceId> ModelingTools::add(Surface surface, const QString& text) {
    auto c = AddSurface::create(m_doc, std::move(surface), -1);
    if (!c)
        return Error(tr("Cannot create: %1").arg(c.message()));
    (*c)->setText(text);
    const SurfaceId id = (*c)->surfaceId();
    pushCommand(m_stack, std::move(*c));
    selectSurfaces({id});
    Q_EMIT message(text);
    return id;
}

glm::dvec3 ModelingTools::placeBesideShown(double radius) const {
    const Camera& c = m_viewport->cameraController().camera();
    glm::dvec3 lo, hi;
    if (!sceneBounds(m_doc->scene(), lo, hi, true))
        return c.target;
    // The box's nearest point: is the new shape's sphere clear of it, with the gap?
    const double gap = 0.2 * radius;
    const glm::dvec3 nearest = glm::clamp(c.target, lo, hi);
    if (glm::length(c.target - nearest) >= radius + gap)
        return c.target;
    glm::dvec3 right = glm::cross(c.target - c.eye, c.up);
    right = glm::length(right) > 1e-12 ? glm::normalize(right) : glm::dvec3(1.0, 0.0, 0.0);
    double reach = -std::numeric_limits<double>::infinity();
    for (int k = 0; k < 8; ++k) {
        const glm::dvec3 corner((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y,
                                (k & 4) ? hi.z : lo.z);
        reach = std::max(reach, glm::dot(corner - c.target, right));
    }
    return c.target + right * (reach + radius + gap);
}

Expected<SurfaceId> ModelingTools::createPrimitive(Primitive kind) {
    const double r = 0.5 * viewScale();
    // 1.45 r bounds every shape below (the plane's half diagonal is 1.41 r).
    const glm::dvec3 at = placeBesideShown(1.45 * r);
    Surface s;
    switch (kind) {
    case Primitive::Plane:
        s.geometry = makePlane(at - glm::dvec3(r, r, 0.0), {2 * r, 0, 0}, {0, 2 * r, 0});
        s.name = uniqueName(tr("Plane"));
        break;
    case Primitive::Sphere:
        s.geometry = makeSphere(at, r);
        s.name = uniqueName(tr("Sphere"));
        break;
    case Primitive::Cylinder:
        s.geometry = makeCylinder(at - glm::dvec3(0, 0, r), 0.5 * r, 2 * r);
        s.name = uniqueName(tr("Cylinder"));
        break;
    case Primitive::Cone:
        s.geometry = makeCone(at - glm::dvec3(0, 0, r), 0.7 * r, 2 * r);
        s.name = uniqueName(tr("Cone"));
        break;
    case Primitive::Torus:
        s.geometry = makeTorus(at, 0.7 * r, 0.25 * r);
        s.name = uniqueName(tr("Torus"));
        break;
    }
    const QString text = tr("Create %1").arg(s.name.section(QLatin1Char(' '), 0, 0).toLower());
    return add(std::move(s), text);
}

Expected<SurfaceId> ModelingTools::createPatch(const PatchParams& p) {
    if (p.degreeU < 1 || p.degreeV < 1 || p.degreeU > kMaxDegree || p.degreeV > kMaxDegree ||
        p.countU <= p.degreeU || p.countV <= p.degreeV)
        return Error(tr("Cannot create: a patch needs 1 <= degree < control points (degree "
                        "at most %1)")
                         .arg(kMaxDegree));
    const double size = viewScale();
    Surface s;
    const double sizeU = p.sizeU > 0 ? p.sizeU : size, sizeV = p.sizeV > 0 ? p.sizeV : size;
    s.geometry = makePatch(placeBesideShown(0.5 * std::hypot(sizeU, sizeV)), p.degreeU, p.degreeV,
                           p.countU, p.countV, sizeU, sizeV);
    s.name = uniqueName(tr("Patch"));
    return add(std::move(s), tr("Create patch"));
}

NurbsCurve3 ModelingTools::surfaceCurve(const NurbsSurface& s, const CurveSpec& spec) {
    const Interval du = surfaceDomainU(s), dv = surfaceDomainV(s);
    const double f = std::clamp(spec.fraction, 0.0, 1.0);
    switch (spec.edge) {
    case CurveEdge::VStart:
        return surfaceIsoCurve(s, true, dv.first);
    case CurveEdge::VEnd:
        return surfaceIsoCurve(s, true, dv.last);
    case CurveEdge::UStart:
        return surfaceIsoCurve(s, false, du.first);
    case CurveEdge::UEnd:
        return surfaceIsoCurve(s, false, du.last);
    case CurveEdge::IsoU: // the curve u = const, running in v
        return surfaceIsoCurve(s, false, du.first + f * (du.last - du.first));
    case CurveEdge::IsoV:
        return surfaceIsoCurve(s, true, dv.first + f * (dv.last - dv.first));
    }
    return {};
}

Expected<SurfaceId> ModelingTools::createFromCurves(CurveOperationKind kind,
                                                    const CurveOperation& op) {
    const std::vector<SurfaceId> ids = m_selection->selectedSurfaces();
    std::vector<NurbsCurve3> curves;
    for (SurfaceId id : ids)
        if (const Surface* s = m_doc->surface(id))
            curves.push_back(surfaceCurve(s->geometry, op.curve));
    return createFromCurveList(kind, op, curves);
}

void ModelingTools::drawCurvesFor(CurveOperationKind kind) {
    static const char* const purposes[3] = {"Curve to revolve", "Curve to extrude",
                                            "Curves to loft"};
    disconnect(m_curveTool, &CurveTool::finished, this, nullptr);
    connect(m_curveTool, &CurveTool::finished, this,
            [this, kind](const std::vector<NurbsCurve3>& curves) {
                CurveOperation initial;
                initial.drawnCurves = true;
                initial.point = m_viewport->cameraController().camera().target;
                // Extrude along the view direction by default: the curve lies across it.
                const Camera& c = m_viewport->cameraController().camera();
                const glm::dvec3 forward = glm::normalize(c.target - c.eye);
                initial.vector =
                    kind == CurveOperationKind::Extrude ? -0.5 * viewScale() * forward : c.up;
                if (auto op = m_prompts.curveOperation(m_window, kind, initial)) {
                    op->drawnCurves = true;
                    report(createFromCurveList(kind, *op, curves));
                }
            });
    m_curveTool->start(kind == CurveOperationKind::Loft ? 0 : 1, tr(purposes[int(kind)]));
}

Expected<SurfaceId> ModelingTools::createFromCurveList(CurveOperationKind kind,
                                                       const CurveOperation& op,
                                                       const std::vector<NurbsCurve3>& curves) {
    const size_t needed = kind == CurveOperationKind::Loft ? 2 : 1;
    if (curves.size() < needed)
        return Error(op.drawnCurves ? tr("Draw the curves first.")
                     : kind == CurveOperationKind::Loft
                         ? tr("Select two or more surfaces whose curves to loft through.")
                         : tr("Select a surface whose curve to use."));
    Surface s;
    QString text;
    switch (kind) {
    case CurveOperationKind::Revolve:
        if (!(glm::length(op.vector) > 0.0))
            return Error(tr("Cannot revolve: the axis direction is zero."));
        s.geometry = makeRevolution3(curves.front(), op.point, op.vector);
        s.name = uniqueName(tr("Revolution"));
        text = tr("Create revolution");
        break;
    case CurveOperationKind::Extrude:
        if (!(glm::length(op.vector) > 0.0))
            return Error(tr("Cannot extrude: the direction is zero."));
        s.geometry = makeExtrusion(curves.front(), op.vector);
        s.name = uniqueName(tr("Extrusion"));
        text = tr("Create extrusion");
        break;
    case CurveOperationKind::Loft: {
        Expected<NurbsSurface> loft = makeLoft(curves, 3);
        if (!loft)
            return Error(tr("Cannot loft: %1").arg(loft.message()));
        s.geometry = std::move(loft).value();
        s.name = uniqueName(tr("Loft"));
        text = tr("Create loft through %1 curves").arg(curves.size());
        break;
    }
    }
    return add(std::move(s), text);
}

Status ModelingTools::transformSelected(const TransformParams& p) {
    const std::vector<SurfaceId> ids = m_selection->selectedSurfaces();
    if (ids.empty())
        return Error(tr("Select the surfaces to transform."));
    // Rotation and scale act about the centre of the selection's control-point bounds.
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (SurfaceId id : ids) {
        glm::dvec3 a, b;
        surfaceControlBounds(m_doc->surface(id)->geometry, a, b);
        lo = glm::min(lo, a);
        hi = glm::max(hi, b);
    }
    const glm::dvec3 centre = 0.5 * (lo + hi);
    glm::dvec3 axis(0.0);
    axis[std::clamp(p.rotationAxis, 0, 2)] = 1.0;
    glm::dmat4 m = glm::translate(glm::dmat4(1.0), p.offset + centre);
    m = glm::rotate(m, glm::radians(p.degrees), axis);
    m = glm::scale(m, glm::dvec3(p.scale));
    m = glm::translate(m, -centre);
    if (p.degrees == 0.0 && p.scale == 1.0) // exactly the offset, no rounding through the centre
        m = glm::translate(glm::dmat4(1.0), p.offset);
    QStringList what;
    if (p.offset != glm::dvec3(0.0))
        what << tr("Move");
    if (p.degrees != 0.0)
        what << tr("Rotate");
    if (p.scale != 1.0)
        what << tr("Scale");
    const QString noun = ids.size() == 1 ? tr("surface") : tr("%1 surfaces").arg(ids.size());
    const QString text = QStringLiteral("%1 %2").arg(what.join(QStringLiteral(", ")), noun);
    if (const Status pushed = pushCommand(m_stack, TransformSurfaces::create(m_doc, ids, m, text));
        !pushed)
        return Error(tr("Cannot transform: %1").arg(pushed.message()));
    return ok();
}

Status ModelingTools::duplicateSelected() {
    const std::vector<SurfaceId> ids = m_selection->selectedSurfaces();
    if (ids.empty())
        return Error(tr("Select the surfaces to duplicate."));
    // The copies are offset by a tenth of the view scale so they can be told apart.
    const glm::dvec3 offset(0.1 * viewScale(), 0.1 * viewScale(), 0.0);
    std::vector<SurfaceId> copies;
    Status result;
    m_stack->beginMacro(ids.size() == 1 ? tr("Duplicate surface")
                                        : tr("Duplicate %1 surfaces").arg(ids.size()));
    for (SurfaceId id : ids) {
        Surface copy = *m_doc->surface(id);
        copy.id = {};
        for (TrimLoop& l : copy.trims)
            l.id = {};
        for (glm::dvec3& p : copy.geometry.points)
            p += offset;
        // The copy is the face moved: its closed form moves with it (Surface::analytic).
        copy.analytic = analyticTransformed(copy.analytic, glm::dmat3(1.0), offset);
        copy.name = uniqueName(copy.name.section(QLatin1Char(' '), 0, 0));
        if (auto c = AddSurface::create(m_doc, std::move(copy))) {
            copies.push_back((*c)->surfaceId());
            pushCommand(m_stack, std::move(*c));
        } else {
            result = Error(tr("Cannot duplicate: %1").arg(c.message()));
        }
    }
    m_stack->endMacro();
    selectSurfaces(copies);
    return result;
}

Status ModelingTools::deleteSelected() {
    const std::vector<SurfaceId> ids = m_selection->selectedSurfaces();
    if (ids.empty())
        return Error(tr("Select a surface to delete."));
    if (ids.size() == 1)
        return pushCommand(m_stack, RemoveSurface::create(m_doc, ids.front()));
    Status result;
    m_stack->beginMacro(tr("Delete %1 surfaces").arg(ids.size()));
    for (SurfaceId id : ids)
        if (Status pushed = pushCommand(m_stack, RemoveSurface::create(m_doc, id)); !pushed)
            result = std::move(pushed);
    m_stack->endMacro();
    return result;
}

Status ModelingTools::removeKnots(Direction direction, double tolerance) {
    const SurfaceId id = m_selection->currentSurface();
    auto c = RemoveKnots::create(m_doc, id, direction, tolerance);
    if (!c)
        return Error(tr("Knot removal: %1").arg(c.message()));
    Q_EMIT message((*c)->text());
    pushCommand(m_stack, std::move(*c));
    return ok();
}

Status ModelingTools::matchSurface(const MatchRequest& request) {
    auto c = MatchSurfaceCommand::create(m_doc, request, continuityTolerances(m_doc->scene()));
    if (!c)
        return Error(tr("Match Surface: %1").arg(c.message()));
    Q_EMIT message((*c)->result().summary);
    pushCommand(m_stack, std::move(*c));
    return ok();
}

void ModelingTools::buildMenus(QMenuBar* bar, QToolBar* toolbar) {
    auto make = [this](QMenu* menu, const char* name, const QString& text, const QKeySequence& key,
                       std::function<void()> slot) {
        QAction* a = menu->addAction(text);
        a->setObjectName(QLatin1String(name));
        if (!key.isEmpty())
            a->setShortcut(key);
        connect(a, &QAction::triggered, this, std::move(slot));
        return a;
    };
    QMenu* create = bar->addMenu(tr("&Create"));
    QAction* patch = make(create, "actionCreatePatch", tr("NURBS &Patch…"), QKeySequence(), [this] {
        if (auto p = m_prompts.patch(m_window, PatchParams{}))
            report(createPatch(*p));
    });
    create->addSeparator();
    const struct {
        const char* name;
        QString text;
        Primitive kind;
    } shapes[] = {{"actionCreatePlane", tr("P&lane"), Primitive::Plane},
                  {"actionCreateSphere", tr("&Sphere"), Primitive::Sphere},
                  {"actionCreateCylinder", tr("C&ylinder"), Primitive::Cylinder},
                  {"actionCreateCone", tr("C&one"), Primitive::Cone},
                  {"actionCreateTorus", tr("&Torus"), Primitive::Torus}};
    std::vector<QAction*> shapeActions;
    for (const auto& s : shapes) {
        const Primitive kind = s.kind;
        shapeActions.push_back(make(create, s.name, s.text, QKeySequence(),
                                    [this, kind] { report(createPrimitive(kind)); }));
    }
    create->addSeparator();
    const struct {
        const char* name;
        QString text;
        CurveOperationKind kind;
    } ops[] = {{"actionRevolve", tr("&Revolve Curve…"), CurveOperationKind::Revolve},
               {"actionExtrude", tr("&Extrude Curve…"), CurveOperationKind::Extrude},
               {"actionLoft", tr("&Loft Through Curves…"), CurveOperationKind::Loft}};
    std::vector<QAction*> opActions;
    for (const auto& o : ops) {
        const CurveOperationKind kind = o.kind;
        opActions.push_back(make(create, o.name, o.text, QKeySequence(), [this, kind] {
            CurveOperation initial;
            const Camera& c = m_viewport->cameraController().camera();
            initial.point = c.target;
            initial.vector = kind == CurveOperationKind::Extrude
                                 ? glm::dvec3(0.0, 0.0, 0.5 * viewScale())
                                 : glm::dvec3(0.0, 0.0, 1.0);
            if (auto op = m_prompts.curveOperation(m_window, kind, initial))
                report(createFromCurves(kind, *op));
        }));
    }
    opActions.front()->setStatusTip(tr("Revolve a boundary or iso-curve of the selected surface "
                                       "about an axis"));
    create->addSeparator();
    const struct {
        const char* name;
        QString text;
        CurveOperationKind kind;
    } draws[] = {{"actionDrawRevolve", tr("Draw Curve to Re&volve…"), CurveOperationKind::Revolve},
                 {"actionDrawExtrude", tr("Draw Curve to Extr&ude…"), CurveOperationKind::Extrude},
                 {"actionDrawLoft", tr("Draw Curves to Lo&ft…"), CurveOperationKind::Loft}};
    std::vector<QAction*> drawActions;
    for (const auto& d : draws) {
        const CurveOperationKind kind = d.kind;
        drawActions.push_back(
            make(create, d.name, d.text, QKeySequence(), [this, kind] { drawCurvesFor(kind); }));
        drawActions.back()->setStatusTip(tr("Click points in the view plane, Enter to finish"));
    }
    QAction* interpolate = make(create, "actionCurveInterpolates",
                                tr("Drawn Curves &Interpolate the Points"), QKeySequence(), [] {});
    interpolate->setCheckable(true);
    interpolate->setChecked(m_curveTool->interpolating());
    interpolate->setStatusTip(tr("On: the curve passes through the clicked points (A9.1). Off: "
                                 "the points are its control polygon."));
    connect(interpolate, &QAction::toggled, m_curveTool, &CurveTool::setInterpolating);

    QMenu* modify = bar->addMenu(tr("&Modify"));
    make(modify, "actionTransform", tr("&Move, Rotate, Scale…"), QKeySequence(Qt::CTRL | Qt::Key_T),
         [this] {
             if (auto p = m_prompts.transform(m_window))
                 report(transformSelected(*p));
         });
    make(modify, "actionDuplicate", tr("D&uplicate"), QKeySequence(Qt::CTRL | Qt::Key_D),
         [this] { report(duplicateSelected()); });
    modify->addSeparator();
    // What Ctrl + drag in the view does to the selected surfaces (X / Y / Z held lock an axis).
    auto* dragModes = new QActionGroup(this);
    const struct {
        const char* name;
        QString text;
        Qt::Key key;
        Viewport::SurfaceDrag mode;
    } modes[] = {
        {"actionDragMove", tr("Ctrl+Drag &Moves"), Qt::Key_G, Viewport::SurfaceDrag::Move},
        {"actionDragRotate", tr("Ctrl+Drag &Rotates"), Qt::Key_R, Viewport::SurfaceDrag::Rotate},
        {"actionDragScale", tr("Ctrl+Drag &Scales"), Qt::Key_S, Viewport::SurfaceDrag::Scale}};
    for (const auto& m : modes) {
        const Viewport::SurfaceDrag mode = m.mode;
        QAction* a = make(modify, m.name, m.text, QKeySequence(m.key),
                          [this, mode] { m_viewport->setSurfaceDrag(mode); });
        a->setCheckable(true);
        a->setChecked(mode == m_viewport->surfaceDrag());
        dragModes->addAction(a);
    }
    modify->addSeparator();
    make(modify, "actionRemoveKnots", tr("Remove &Knots…"), QKeySequence(), [this] {
        const Surface* s = m_doc->surface(m_selection->currentSurface());
        if (!s) {
            Q_EMIT message(tr("Select a surface."));
            return;
        }
        glm::dvec3 lo, hi;
        surfaceControlBounds(s->geometry, lo, hi);
        if (auto r = m_prompts.knotRemoval(m_window, 1e-4 * glm::length(hi - lo)))
            report(removeKnots(r->first == 0 ? Direction::U : Direction::V, r->second));
    });
    QAction* match =
        make(modify, "actionMatchSurface", tr("Match &Surface…"), QKeySequence(), [this] {
            const SurfaceId id = m_selection->currentSurface();
            if (!m_doc->surface(id) || m_doc->scene().surfaces.size() < 2) {
                Q_EMIT message(tr("Select the surface to change, next to another one."));
                return;
            }
            if (auto r = m_prompts.matchSurface(m_window, m_doc->scene(), id))
                report(matchSurface(*r));
        });
    match->setStatusTip(tr("Move the selected surface's edge rows so that it meets a "
                           "neighbour's edge with G0, G1 or G2 continuity"));

    // Short labels on the toolbar (the menus keep the full ones, shown as tool tips), so that
    // the row fits a first window.
    const std::pair<QAction*, QString> shortLabels[] = {{patch, tr("Patch")},
                                                        {opActions[0], tr("Revolve")},
                                                        {opActions[1], tr("Extrude")},
                                                        {opActions[2], tr("Loft")},
                                                        {drawActions[0], tr("Draw Revolve")},
                                                        {drawActions[1], tr("Draw Extrude")},
                                                        {drawActions[2], tr("Draw Loft")}};
    for (const auto& [action, label] : shortLabels) {
        action->setToolTip(QString(action->text()).remove(QLatin1Char('&')));
        action->setIconText(label);
    }
    toolbar->addAction(patch);
    for (QAction* a : shapeActions)
        toolbar->addAction(a);
    toolbar->addSeparator();
    for (QAction* a : opActions)
        toolbar->addAction(a);
    toolbar->addSeparator();
    for (QAction* a : drawActions)
        toolbar->addAction(a);
}

} // namespace kw
