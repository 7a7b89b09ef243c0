// The standard dialogs of ModelingTools: patch parameters, curve operations, transforms and
// knot removal, each a small form (tests replace them through ModelingTools::Prompts).
#include "ui/modelingtools.h"

#include <QComboBox>
#include <QDialog>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QSpinBox>

namespace kw {

namespace {

QDoubleSpinBox* number(double value, double lo = -1e9, double hi = 1e9, int decimals = 4) {
    auto* s = new QDoubleSpinBox;
    s->setRange(lo, hi);
    s->setDecimals(decimals);
    s->setValue(value);
    return s;
}

QSpinBox* integer(int value, int lo, int hi) {
    auto* s = new QSpinBox;
    s->setRange(lo, hi);
    s->setValue(value);
    return s;
}

/// Three spin boxes in a row for a vector.
struct VectorRow {
    QDoubleSpinBox* c[3];
    QWidget* widget;
    explicit VectorRow(const glm::dvec3& v) : widget(new QWidget) {
        auto* row = new QHBoxLayout(widget);
        row->setContentsMargins(0, 0, 0, 0);
        for (int k = 0; k < 3; ++k)
            row->addWidget(c[k] = number(v[k]));
    }
    glm::dvec3 value() const { return {c[0]->value(), c[1]->value(), c[2]->value()}; }
};

/// A dialog with OK / Cancel around `form`; true when accepted.
bool run(QDialog& d, QFormLayout* form) {
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
    QObject::connect(buttons, &QDialogButtonBox::accepted, &d, &QDialog::accept);
    QObject::connect(buttons, &QDialogButtonBox::rejected, &d, &QDialog::reject);
    form->addRow(buttons);
    return d.exec() == QDialog::Accepted;
}

} // namespace

ModelingTools::Prompts ModelingTools::Prompts::standard() {
    Prompts p;
    p.patch = [](QWidget* parent, const PatchParams& init) -> std::optional<PatchParams> {
        QDialog d(parent);
        d.setWindowTitle(QObject::tr("New NURBS patch"));
        auto* form = new QFormLayout(&d);
        QSpinBox* du = integer(init.degreeU, 1, kMaxDegree);
        QSpinBox* dv = integer(init.degreeV, 1, kMaxDegree);
        QSpinBox* nu = integer(init.countU, 2, 64);
        QSpinBox* nv = integer(init.countV, 2, 64);
        QDoubleSpinBox* su = number(init.sizeU, 0.0, 1e6);
        QDoubleSpinBox* sv = number(init.sizeV, 0.0, 1e6);
        su->setSpecialValueText(QObject::tr("fit the view"));
        sv->setSpecialValueText(QObject::tr("fit the view"));
        form->addRow(QObject::tr("Degree u"), du);
        form->addRow(QObject::tr("Degree v"), dv);
        form->addRow(QObject::tr("Control points u"), nu);
        form->addRow(QObject::tr("Control points v"), nv);
        form->addRow(QObject::tr("Size u"), su);
        form->addRow(QObject::tr("Size v"), sv);
        if (!run(d, form))
            return std::nullopt;
        return PatchParams{du->value(), dv->value(), nu->value(),
                           nv->value(), su->value(), sv->value()};
    };
    p.curveOperation = [](QWidget* parent, CurveOperationKind kind,
                          const CurveOperation& init) -> std::optional<CurveOperation> {
        QDialog d(parent);
        d.setWindowTitle(kind == CurveOperationKind::Revolve ? QObject::tr("Revolve curve")
                         : kind == CurveOperationKind::Extrude
                             ? QObject::tr("Extrude curve")
                             : QObject::tr("Loft through curves"));
        auto* form = new QFormLayout(&d);
        auto* edge = new QComboBox;
        edge->addItems({QObject::tr("Boundary v = start"), QObject::tr("Boundary v = end"),
                        QObject::tr("Boundary u = start"), QObject::tr("Boundary u = end"),
                        QObject::tr("Iso-curve u = const"), QObject::tr("Iso-curve v = const")});
        edge->setCurrentIndex(int(init.curve.edge));
        QDoubleSpinBox* fraction = number(init.curve.fraction, 0.0, 1.0, 3);
        if (init.drawnCurves) { // drawn curves need no choice of surface curve
            for (QWidget* w : {static_cast<QWidget*>(edge), static_cast<QWidget*>(fraction)}) {
                w->setParent(&d);
                w->hide();
            }
        } else {
            form->addRow(kind == CurveOperationKind::Loft
                             ? QObject::tr("Curve of each selected surface")
                             : QObject::tr("Curve of the selected surface"),
                         edge);
            form->addRow(QObject::tr("Iso-curve at (0..1 of the domain)"), fraction);
        }
        VectorRow point(init.point), vector(init.vector);
        if (kind == CurveOperationKind::Revolve) {
            form->addRow(QObject::tr("Axis point"), point.widget);
            form->addRow(QObject::tr("Axis direction"), vector.widget);
        } else if (kind == CurveOperationKind::Extrude) {
            form->addRow(QObject::tr("Extrusion vector"), vector.widget);
        }
        if (!run(d, form))
            return std::nullopt;
        CurveOperation op;
        op.curve.edge = CurveEdge(edge->currentIndex());
        op.curve.fraction = fraction->value();
        op.point = point.value();
        op.vector = vector.value();
        return op;
    };
    p.transform = [](QWidget* parent) -> std::optional<TransformParams> {
        QDialog d(parent);
        d.setWindowTitle(QObject::tr("Move, rotate, scale"));
        auto* form = new QFormLayout(&d);
        VectorRow offset(glm::dvec3(0.0));
        auto* axis = new QComboBox;
        axis->addItems({QStringLiteral("x"), QStringLiteral("y"), QStringLiteral("z")});
        axis->setCurrentIndex(2);
        QDoubleSpinBox* degrees = number(0.0, -360.0, 360.0, 3);
        QDoubleSpinBox* scale = number(1.0, 1e-6, 1e6, 6);
        form->addRow(QObject::tr("Move by"), offset.widget);
        form->addRow(QObject::tr("Rotation axis (through the centre)"), axis);
        form->addRow(QObject::tr("Rotation (degrees)"), degrees);
        form->addRow(QObject::tr("Scale (about the centre)"), scale);
        if (!run(d, form))
            return std::nullopt;
        return TransformParams{offset.value(), axis->currentIndex(), degrees->value(),
                               scale->value()};
    };
    p.knotRemoval = [](QWidget* parent, double suggested) -> std::optional<std::pair<int, double>> {
        QDialog d(parent);
        d.setWindowTitle(QObject::tr("Remove knots"));
        auto* form = new QFormLayout(&d);
        auto* direction = new QComboBox;
        direction->addItems({QStringLiteral("u"), QStringLiteral("v")});
        QDoubleSpinBox* tol = number(suggested, 0.0, 1e6, 8);
        form->addRow(QObject::tr("Direction"), direction);
        form->addRow(QObject::tr("Tolerance (model units)"), tol);
        if (!run(d, form))
            return std::nullopt;
        return std::make_pair(direction->currentIndex(), tol->value());
    };
    p.matchSurface = [](QWidget* parent, const Scene& scene,
                        SurfaceId surface) -> std::optional<MatchRequest> {
        QDialog d(parent);
        d.setWindowTitle(QObject::tr("Match surface"));
        auto* form = new QFormLayout(&d);
        auto* edge = new QComboBox;
        const DomainEdge edges[] = {DomainEdge::U0, DomainEdge::U1, DomainEdge::V0, DomainEdge::V1};
        edge->addItems({QObject::tr("u = start"), QObject::tr("u = end"), QObject::tr("v = start"),
                        QObject::tr("v = end")});
        auto* target = new QComboBox;
        std::vector<SurfaceId> targets;
        for (const Surface& s : scene.surfaces)
            if (s.id != surface) {
                targets.push_back(s.id);
                target->addItem(s.name);
            }
        auto* side = new QComboBox;
        std::vector<ContinuitySide> sides;
        auto* continuity = new QComboBox;
        continuity->addItems({QStringLiteral("G0 (position)"), QStringLiteral("G1 (tangency)"),
                              QStringLiteral("G2 (curvature)")});
        continuity->setCurrentIndex(1);
        // The target's boundaries, the one nearest the chosen edge first selected.
        const auto fillSides = [&] {
            side->clear();
            sides.clear();
            const size_t t = size_t(std::max(0, target->currentIndex()));
            if (t >= targets.size())
                return;
            const Surface* s = nullptr;
            for (const Surface& x : scene.surfaces)
                s = x.id == targets[t] ? &x : s;
            for (const ContinuitySide& b : continuityBoundaries(*s)) {
                sides.push_back(b);
                side->addItem(
                    b.domainEdge != DomainEdge::None
                        ? QObject::tr("edge %1").arg(domainEdgeName(b.domainEdge))
                        : QObject::tr("trim loop %1, curve %2").arg(b.loop.value).arg(b.curve + 1));
            }
            const std::optional<ContinuitySide> nearest =
                nearestSide(scene, surface, edges[std::max(0, edge->currentIndex())], targets[t]);
            for (size_t k = 0; k < sides.size(); ++k)
                if (nearest && sides[k] == *nearest)
                    side->setCurrentIndex(int(k));
        };
        // The surface's edge nearest to any other surface, as a start.
        double best = -1.0;
        for (int e = 0; e < 4; ++e)
            for (size_t t = 0; t < targets.size(); ++t)
                if (const auto n = nearestSide(scene, surface, edges[e], targets[t])) {
                    const Surface* a = nullptr;
                    const Surface* b = nullptr;
                    for (const Surface& x : scene.surfaces) {
                        a = x.id == surface ? &x : a;
                        b = x.id == targets[t] ? &x : b;
                    }
                    const auto mine = continuitySideCurve(
                        *a, ContinuitySide{surface, TrimLoopId{}, -1, edges[e]}, 8);
                    const auto theirs = continuitySideCurve(*b, *n, 8);
                    if (!mine || !theirs)
                        continue;
                    double dist = 0.0;
                    for (const glm::dvec3& q : mine->at)
                        dist += nearestOnSeamSide(*theirs, q).distance;
                    if (best < 0.0 || dist < best) {
                        best = dist;
                        edge->setCurrentIndex(e);
                        target->setCurrentIndex(int(t));
                    }
                }
        fillSides();
        QObject::connect(edge, &QComboBox::currentIndexChanged, &d, fillSides);
        QObject::connect(target, &QComboBox::currentIndexChanged, &d, fillSides);
        form->addRow(QObject::tr("Edge to move"), edge);
        form->addRow(QObject::tr("Match to surface"), target);
        form->addRow(QObject::tr("Its edge"), side);
        form->addRow(QObject::tr("Continuity"), continuity);
        if (!run(d, form) || side->currentIndex() < 0)
            return std::nullopt;
        MatchRequest r;
        r.surface = surface;
        r.edge = edges[edge->currentIndex()];
        r.target = sides[size_t(side->currentIndex())];
        r.continuity = MatchContinuity(continuity->currentIndex());
        return r;
    };
    return p;
}

} // namespace kw
