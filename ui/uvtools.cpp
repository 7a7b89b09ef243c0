// UvPanel's tool actions and the loops its drawing tools make, loop deletion, trim point
// insertion / deletion / exact placement, zoom and pan.
#include "model/nurbs/nurbs_construct.h"
#include "model/nurbs/nurbs_shapes.h"
#include "model/nurbs/trim.h"
#include "ui/edit/commands.h"
#include "ui/edit/modelcommands.h"
#include "ui/uvpanel.h"

#include <QAction>
#include <QActionGroup>
#include <QDoubleSpinBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QMouseEvent>
#include <QPainter>
#include <QToolBar>
#include <QUndoStack>
#include <QVBoxLayout>
#include <QWheelEvent>
#include <algorithm>
#include <cmath>
#include <set>

namespace kw {

NurbsCurve2 closedPolylineCurve(const std::vector<glm::dvec2>& pts) {
    NurbsCurve2 c;
    c.degree = 1;
    c.points = pts;
    c.points.push_back(pts.front());
    c.weights.assign(c.points.size(), 1.0);
    c.knots = clampedUniformKnots(1, int(c.points.size()));
    return c;
}

// Clamped, so it starts and ends on the first point.
NurbsCurve2 closedSplineCurve(const std::vector<glm::dvec2>& pts) {
    NurbsCurve2 c;
    c.points = pts;
    c.points.push_back(pts.front());
    c.degree = std::min(3, int(c.points.size()) - 1);
    c.weights.assign(c.points.size(), 1.0);
    c.knots = clampedUniformKnots(c.degree, int(c.points.size()));
    return c;
}

namespace {

/// Greville abscissa of control point k: where it pulls hardest on the curve.
double greville(const NurbsCurve2& c, int k) {
    double sum = 0.0;
    for (int i = 1; i <= c.degree; ++i)
        sum += c.knots[size_t(k + i)];
    return sum / double(c.degree);
}

const TrimLoop* loopOf(const Document* doc, SurfaceId s, TrimLoopId id) {
    if (const Surface* surface = doc->surface(s))
        for (const TrimLoop& l : surface->trims)
            if (l.id == id)
                return &l;
    return nullptr;
}

} // namespace

void UvPanel::buildActions() {
    auto* group = new QActionGroup(this);
    const struct {
        const char* name;
        QString text;
        UvTool tool;
    } tools[] = {{"uvToolSelect", tr("Select"), UvTool::Select},
                 {"uvToolRectangle", tr("Rectangle"), UvTool::Rectangle},
                 {"uvToolCircle", tr("Circle"), UvTool::Circle},
                 {"uvToolPolygon", tr("Polygon"), UvTool::Polygon},
                 {"uvToolSpline", tr("Spline"), UvTool::Spline}};
    for (const auto& t : tools) {
        auto* a = new QAction(t.text, this);
        a->setObjectName(QLatin1String(t.name));
        a->setCheckable(true);
        a->setChecked(t.tool == m_tool);
        const UvTool tool = t.tool;
        connect(a, &QAction::triggered, this, [this, tool] { setTool(tool); });
        group->addAction(a);
        m_actions << a;
    }
    auto* holes = new QAction(tr("Holes"), this);
    holes->setObjectName(QStringLiteral("uvDrawHoles"));
    holes->setCheckable(true);
    holes->setChecked(m_drawHoles);
    holes->setToolTip(tr("On: a loop drawn on an untrimmed surface cuts a hole (the domain "
                         "boundary is added as outer loop). Off: it is an outer boundary."));
    connect(holes, &QAction::toggled, this, [this](bool on) { m_drawHoles = on; });
    m_actions << holes;
    auto* insert = new QAction(tr("+Pt"), this);
    insert->setObjectName(QStringLiteral("uvInsertPoint"));
    insert->setToolTip(tr("Insert a trim control point after the picked one"));
    connect(insert, &QAction::triggered, this, [this] { insertTrimPoint(); });
    auto* remove = new QAction(tr("−Pt"), this);
    remove->setObjectName(QStringLiteral("uvDeletePoint"));
    remove->setToolTip(tr("Delete the picked trim control point"));
    connect(remove, &QAction::triggered, this, [this] { deleteTrimPoint(); });
    m_actions << insert << remove;
}

void UvPanel::setTool(UvTool tool) {
    m_tool = tool;
    if (Tool* drawing = m_tools.installed())
        drawing->cancel(); // drops a half-drawn loop
    m_tools.install(tool == UvTool::Select ? nullptr : m_drawing[tool].get());
    setCursor(tool == UvTool::Select ? Qt::ArrowCursor : Qt::CrossCursor);
    for (QAction* a : m_actions)
        if (a->isCheckable() && a->actionGroup())
            a->setChecked(a->objectName().endsWith(tool == UvTool::Select      ? "Select"
                                                   : tool == UvTool::Rectangle ? "Rectangle"
                                                   : tool == UvTool::Circle    ? "Circle"
                                                   : tool == UvTool::Polygon   ? "Polygon"
                                                                               : "Spline"));
    update();
}

void UvPanel::setView(double zoom, glm::dvec2 centre) {
    m_zoom = std::clamp(zoom, 1.0, kMaxZoom);
    m_centre = glm::clamp(centre, glm::dvec2(0.0), glm::dvec2(1.0));
    update();
}

void UvPanel::wheelEvent(QWheelEvent* event) {
    if (!surface().isValid())
        return;
    // Zoom about the cursor: the domain point under it stays under it.
    const QPointF at = event->position();
    const QRectF before = domainRect();
    const glm::dvec2 f((at.x() - before.left()) / before.width(),
                       (before.bottom() - at.y()) / before.height());
    const double factor = std::pow(1.25, event->angleDelta().y() / 120.0);
    const double zoom = std::clamp(m_zoom * factor, 1.0, kMaxZoom);
    const double k = m_zoom / zoom; // how the fraction offset from the centre scales
    setView(zoom, f + (m_centre - f) * k);
    event->accept();
}

QString UvPanel::crossingWarning() {
    refreshMask();
    return m_crossing;
}

bool UvPanel::addLoop(const std::vector<NurbsCurve2>& curves, const QString& what) {
    const Surface* s = m_doc->surface(surface());
    if (!s) {
        Q_EMIT message(tr("Select a surface to trim."));
        return false;
    }
    TrimLoop loop;
    loop.curves = curves;
    const bool hole = m_drawHoles && s->trims.empty();
    auto add = AddTrimLoop::create(m_doc, s->id, loop, -1);
    if (!add) {
        Q_EMIT message(tr("Cannot add the trim loop: %1").arg(add.message()));
        return false;
    }
    if (!hole) {
        (*add)->setText(tr("Add %1 trim loop").arg(what));
        pushCommand(m_stack, std::move(*add));
    } else {
        // The domain boundary as outer loop first, so parity makes the new loop a hole.
        const Interval du = surfaceDomainU(s->geometry), dv = surfaceDomainV(s->geometry);
        TrimLoop outer;
        outer.curves = {closedPolylineCurve(
            {{du.first, dv.first}, {du.last, dv.first}, {du.last, dv.last}, {du.first, dv.last}})};
        auto boundary = AddTrimLoop::create(m_doc, s->id, outer, 0);
        m_stack->beginMacro(tr("Add %1 hole").arg(what));
        if (boundary)
            pushCommand(m_stack, std::move(*boundary));
        // Made again now that the boundary is in: appended after it (the first one checked
        // the loop).
        if (const Status pushed = pushCommand(m_stack, AddTrimLoop::create(m_doc, s->id, loop, -1));
            !pushed)
            Q_EMIT message(pushed.message());
        m_stack->endMacro();
    }
    if (const QString w = crossingWarning(); !w.isEmpty())
        Q_EMIT message(w);
    return true;
}

bool UvPanel::deleteSelectedLoops() {
    std::set<std::pair<SurfaceId, TrimLoopId>> loops;
    for (const TrimPointRef& r : m_selection->trimPoints())
        loops.insert({r.surface, r.loop});
    if (loops.empty())
        return false;
    if (loops.size() > 1)
        m_stack->beginMacro(tr("Remove %1 trim loops").arg(loops.size()));
    for (const auto& [s, l] : loops) {
        if (const Status pushed = pushCommand(m_stack, RemoveTrimLoop::create(m_doc, s, l));
            !pushed)
            Q_EMIT message(pushed.message());
    }
    if (loops.size() > 1)
        m_stack->endMacro();
    return true;
}

bool UvPanel::insertTrimPoint() {
    const auto& picked = m_selection->trimPoints();
    const TrimLoop* loop =
        picked.empty() ? nullptr : loopOf(m_doc, picked.front().surface, picked.front().loop);
    if (!loop) {
        Q_EMIT message(tr("Pick a trim control point first."));
        return false;
    }
    const TrimPointRef ref = picked.front();
    TrimLoop changed = *loop;
    NurbsCurve2& c = changed.curves[size_t(ref.curve)];
    // Between the picked point's Greville abscissa and the next one: the new point appears
    // between the two on the control polygon, and the curve keeps its shape (A5.1).
    const int k = std::min(ref.index, int(c.points.size()) - 2);
    const NurbsCurve2 more = curve2InsertKnot(c, 0.5 * (greville(c, k) + greville(c, k + 1)));
    if (more.points.size() == c.points.size()) {
        Q_EMIT message(tr("No control point can be inserted there."));
        return false;
    }
    c = more;
    if (const Status pushed =
            pushCommand(m_stack, ReplaceTrimLoop::create(m_doc, ref.surface, changed,
                                                         tr("Insert trim control point")));
        !pushed) {
        Q_EMIT message(pushed.message());
        return false;
    }
    return true;
}

bool UvPanel::deleteTrimPoint() {
    const auto& picked = m_selection->trimPoints();
    const TrimLoop* loop =
        picked.empty() ? nullptr : loopOf(m_doc, picked.front().surface, picked.front().loop);
    if (!loop) {
        Q_EMIT message(tr("Pick a trim control point first."));
        return false;
    }
    const TrimPointRef ref = picked.front();
    TrimLoop changed = *loop;
    NurbsCurve2& c = changed.curves[size_t(ref.curve)];
    const NurbsCurve2 fewer = curve2RemovePoint(c, ref.index);
    if (fewer == c) {
        Q_EMIT message(tr("A curve's end points close the loop and stay; pick an interior "
                          "point of a curve with three or more points."));
        return false;
    }
    c = fewer;
    if (const Status pushed =
            pushCommand(m_stack, ReplaceTrimLoop::create(m_doc, ref.surface, changed,
                                                         tr("Delete trim control point")));
        !pushed) {
        Q_EMIT message(pushed.message());
        return false;
    }
    return true;
}

bool UvPanel::setTrimPointPosition(glm::dvec2 uv) {
    const auto& picked = m_selection->trimPoints();
    if (picked.empty()) {
        Q_EMIT message(tr("Pick a trim control point first."));
        return false;
    }
    std::vector<TrimPointRef> refs =
        trimPointWithCoincidentEnds(*m_doc->surface(picked.front().surface), picked.front());
    std::vector<glm::dvec2> from, to;
    for (const TrimPointRef& r : refs) {
        from.push_back(trimPointPosition(*m_doc, r));
        to.push_back(uv);
    }
    auto c = MoveTrimPoints::create(m_doc, refs, from, to, MoveKind::Drag);
    if (!c) {
        Q_EMIT message(c.message());
        return false;
    }
    (*c)->setText(tr("Set trim point to (%1, %2)").arg(uv.x).arg(uv.y));
    pushCommand(m_stack, std::move(*c));
    return true;
}

QWidget* makeUvEditor(UvPanel* panel, Selection* selection, Document* document) {
    auto* box = new QWidget;
    auto* layout = new QVBoxLayout(box);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->setSpacing(2);
    auto* bar = new QToolBar;
    bar->setToolButtonStyle(Qt::ToolButtonTextOnly);
    bar->setIconSize(QSize(12, 12));
    for (QAction* a : panel->toolActions()) {
        bar->addAction(a);
        if (a->objectName() == QLatin1String("uvToolSpline") ||
            a->objectName() == QLatin1String("uvDrawHoles"))
            bar->addSeparator();
    }
    // A plain row, not a toolbar: the fields share a narrow dock's width instead of hiding
    // behind an overflow button (their size hint is that of +-1e9 with six decimals).
    auto* point = new QWidget;
    auto* row = new QHBoxLayout(point);
    row->setContentsMargins(4, 0, 4, 0);
    QDoubleSpinBox* fields[2];
    for (int k = 0; k < 2; ++k) {
        fields[k] = new QDoubleSpinBox;
        fields[k]->setObjectName(k == 0 ? QStringLiteral("uvPointU") : QStringLiteral("uvPointV"));
        fields[k]->setRange(-1e9, 1e9);
        fields[k]->setDecimals(6);
        fields[k]->setKeyboardTracking(false); // one edit per committed value
        fields[k]->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Fixed);
        fields[k]->setMinimumWidth(48);
        row->addWidget(new QLabel(k == 0 ? QObject::tr("u") : QObject::tr("v")));
        row->addWidget(fields[k], 1);
    }
    layout->addWidget(bar);
    layout->addWidget(point);
    layout->addWidget(panel, 1);
    auto refresh = [=] {
        const auto& picked = selection->trimPoints();
        const bool any = !picked.empty() && document->surface(picked.front().surface);
        for (int k = 0; k < 2; ++k) {
            QSignalBlocker block(fields[k]);
            fields[k]->setEnabled(any);
            if (any) {
                fields[k]->setSpecialValueText(QString());
                fields[k]->setValue(trimPointPosition(*document, picked.front())[k]);
            } else {
                // Cleared, not left showing the last point's value.
                fields[k]->setSpecialValueText(QStringLiteral(" "));
                fields[k]->setValue(fields[k]->minimum());
            }
        }
    };
    QObject::connect(selection, &Selection::changed, box, refresh);
    QObject::connect(document, &Document::surfaceChanged, box, refresh);
    for (int k = 0; k < 2; ++k)
        QObject::connect(fields[k], &QDoubleSpinBox::valueChanged, box, [=] {
            if (selection->trimPoints().empty())
                return;
            panel->setTrimPointPosition({fields[0]->value(), fields[1]->value()});
        });
    refresh();
    return box;
}

} // namespace kw
