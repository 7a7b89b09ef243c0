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
    return p;
}

} // namespace kw
