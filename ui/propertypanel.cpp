// PropertyPanel: widgets for the current surface and picked control point, each edit one command.
#include "ui/propertypanel.h"

#include "ui/edit/commands.h"
#include "ui/measure_properties.h"

#include <QColorDialog>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QPlainTextEdit>
#include <QPushButton>
#include <QSignalBlocker>
#include <QSlider>
#include <QSpinBox>
#include <QUndoStack>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>

namespace kw {

namespace {

QDoubleSpinBox* spin(double lo, double hi, double step, int decimals) {
    auto* s = new QDoubleSpinBox;
    s->setRange(lo, hi);
    s->setSingleStep(step);
    s->setDecimals(decimals);
    s->setKeyboardTracking(false); // one edit per committed value, not per keystroke
    return s;
}

QString knotText(const std::vector<double>& knots) {
    QStringList parts;
    for (double k : knots)
        parts << QString::number(k, 'g', 6);
    return parts.join(QStringLiteral(", "));
}

/// Fits the knot value field to a domain: decimals that resolve a ten-thousandth of its width
/// (imported faces have domains such as [4.61663, 4.6188] in model units, where four fixed
/// decimals left 22 positions and rounded a typed value by up to 2% of the domain) and a step
/// of a twentieth of it.
void fitKnotField(QDoubleSpinBox* box, const Interval& dom) {
    const double width = dom.last - dom.first;
    const int decimals =
        width > 0.0 ? std::clamp(4 + int(std::ceil(-std::log10(width))), 4, 12) : 4;
    box->setDecimals(decimals); // before the range and value, which it rounds
    box->setSingleStep(width > 0.0 ? width / 20.0 : 0.05);
}

/// Shows `value`, undoing blank().
template <class Box, class T> void showValue(Box* box, T value) {
    const QSignalBlocker b(box);
    box->setSpecialValueText(QString());
    box->setValue(value);
}

/// Clears a disabled field: no stale number from the last selection. The special value text
/// shows at the minimum, so a blank text there reads as empty.
template <class Box> void blank(Box* box) {
    const QSignalBlocker b(box);
    box->setSpecialValueText(QStringLiteral(" "));
    box->setValue(box->minimum());
}

QColor toColor(const glm::dvec3& c) {
    return QColor::fromRgbF(float(std::clamp(c.r, 0.0, 1.0)), float(std::clamp(c.g, 0.0, 1.0)),
                            float(std::clamp(c.b, 0.0, 1.0)));
}

} // namespace

PropertyPanel::PropertyPanel(Document* document, Selection* selection, QUndoStack* stack,
                             QWidget* parent)
    : QWidget(parent), m_doc(document), m_selection(selection), m_stack(stack) {
    auto* layout = new QVBoxLayout(this);
    m_title = new QLabel;
    m_title->setWordWrap(true);
    layout->addWidget(m_title);
    layout->addWidget(m_surfaceBox = buildSurfaceBox());
    layout->addWidget(m_pointBox = buildPointBox());
    layout->addWidget(m_displayBox = buildDisplayBox());
    layout->addWidget(new MeasuredProperties(m_doc, m_selection));
    layout->addStretch(1);

    connect(m_selection, &Selection::changed, this, &PropertyPanel::refresh);
    connect(m_doc, &Document::surfaceChanged, this, [this](SurfaceId id, Aspects aspects) {
        if (id != m_selection->currentSurface())
            return;
        // A drag changes points many times a second: refresh only the point fields then.
        if (aspects == Aspects(Aspect::Points))
            refreshPoint();
        else
            refresh();
    });
    connect(m_doc, &Document::sceneReset, this, &PropertyPanel::refresh);
    refresh();
}

QWidget* PropertyPanel::buildSurfaceBox() {
    auto* box = new QGroupBox(tr("Surface"));
    auto* form = new QFormLayout(box);
    m_degrees = new QLabel;
    form->addRow(tr("Degrees"), m_degrees);
    m_knots = new QPlainTextEdit;
    m_knots->setReadOnly(true);
    m_knots->setMaximumHeight(64);
    form->addRow(tr("Knots"), m_knots);
    m_direction = new QComboBox;
    m_direction->addItems({tr("u"), tr("v")});
    form->addRow(tr("Direction"), m_direction);
    auto* insertRow = new QHBoxLayout;
    m_knotValue = spin(-1e9, 1e9, 0.05, 4);
    m_insertKnot = new QPushButton(tr("Insert knot"));
    insertRow->addWidget(m_knotValue);
    insertRow->addWidget(m_insertKnot);
    form->addRow(tr("Knot"), insertRow);
    m_elevate = new QPushButton(tr("Elevate degree"));
    // Object names let tests and style sheets find the controls.
    m_direction->setObjectName(QStringLiteral("knotDirection"));
    m_knotValue->setObjectName(QStringLiteral("knotValue"));
    m_insertKnot->setObjectName(QStringLiteral("insertKnot"));
    m_elevate->setObjectName(QStringLiteral("elevateDegree"));
    form->addRow(QString(), m_elevate);

    auto direction = [this] {
        return m_direction->currentIndex() == 0 ? Direction::U : Direction::V;
    };
    connect(m_direction, &QComboBox::currentIndexChanged, this, &PropertyPanel::refresh);
    connect(m_insertKnot, &QPushButton::clicked, this, [this, direction] {
        rejected(pushCommand(m_stack, InsertKnot::create(m_doc, m_selection->currentSurface(),
                                                         direction(), m_knotValue->value(), 1)));
    });
    connect(m_elevate, &QPushButton::clicked, this, [this, direction] {
        rejected(pushCommand(
            m_stack, ElevateDegree::create(m_doc, m_selection->currentSurface(), direction(), 1)));
    });
    return box;
}

QWidget* PropertyPanel::buildPointBox() {
    auto* box = new QGroupBox(tr("Control point"));
    auto* form = new QFormLayout(box);
    m_pointLabel = new QLabel;
    form->addRow(m_pointLabel);
    static const char* const names[3] = {"x", "y", "z"};
    for (int k = 0; k < 3; ++k) {
        m_xyz[k] = spin(-1e6, 1e6, 0.05, 4);
        m_xyz[k]->setObjectName(QStringLiteral("point") + QString::fromLatin1(names[k]).toUpper());
        form->addRow(QLatin1String(names[k]), m_xyz[k]);
        connect(m_xyz[k], &QDoubleSpinBox::valueChanged, this, &PropertyPanel::editPoint);
    }
    m_weight = spin(1e-4, 1e4, 0.05, 4);
    m_weight->setObjectName(QStringLiteral("pointWeight"));
    form->addRow(tr("Weight"), m_weight);
    connect(m_weight, &QDoubleSpinBox::valueChanged, this, [this](double w) {
        const ControlPointRef r = shownPoint();
        const Surface* s = m_doc->surface(r.surface);
        if (!s)
            return;
        rejected(pushCommand(m_stack,
                             SetWeight::create(m_doc, r.surface, s->geometry.index(r.i, r.j), w)));
    });
    return box;
}

void PropertyPanel::setLengthUnit(LengthUnit unit) {
    for (QDoubleSpinBox* box : m_xyz)
        box->setSuffix(QLatin1Char(' ') + lengthUnitKey(unit));
}

QWidget* PropertyPanel::buildDisplayBox() {
    auto* box = new QGroupBox(tr("Display"));
    auto* form = new QFormLayout(box);
    auto partitionRow = [&](QSlider*& slider, QSpinBox*& spinBox, const QString& label) {
        auto* row = new QHBoxLayout;
        slider = new QSlider(Qt::Horizontal);
        slider->setRange(kMinPartitions, 64);
        spinBox = new QSpinBox;
        spinBox->setRange(kMinPartitions, kMaxPartitions);
        spinBox->setKeyboardTracking(false);
        row->addWidget(slider, 1);
        row->addWidget(spinBox);
        form->addRow(label, row);
    };
    partitionRow(m_sliderU, m_spinU, tr("Partitions u"));
    partitionRow(m_sliderV, m_spinV, tr("Partitions v"));
    connect(m_sliderU, &QSlider::valueChanged, this,
            [this](int v) { setPartitions(v, m_spinV->value()); });
    connect(m_sliderV, &QSlider::valueChanged, this,
            [this](int v) { setPartitions(m_spinU->value(), v); });
    connect(m_spinU, &QSpinBox::valueChanged, this,
            [this](int v) { setPartitions(v, m_spinV->value()); });
    connect(m_spinV, &QSpinBox::valueChanged, this,
            [this](int v) { setPartitions(m_spinU->value(), v); });

    m_color = new QPushButton;
    form->addRow(tr("Colour"), m_color);
    connect(m_color, &QPushButton::clicked, this, &PropertyPanel::pickColor);
    m_ka = spin(0.0, 1.0, 0.05, 3);
    m_kd = spin(0.0, 1.0, 0.05, 3);
    m_ks = spin(0.0, 1.0, 0.05, 3);
    m_shininess = spin(1.0, 1000.0, 1.0, 1);
    form->addRow(tr("Ambient ka"), m_ka);
    form->addRow(tr("Diffuse kd"), m_kd);
    form->addRow(tr("Specular ks"), m_ks);
    form->addRow(tr("Shininess"), m_shininess);
    for (QDoubleSpinBox* s : {m_ka, m_kd, m_ks, m_shininess})
        connect(s, &QDoubleSpinBox::valueChanged, this, &PropertyPanel::editMaterial);
    return box;
}

void PropertyPanel::rejected(const Status& pushed) {
    if (!pushed) {
        Q_EMIT editRejected(pushed.message());
        refresh(); // show the document's values again
    }
}

void PropertyPanel::setPartitions(int nu, int nv) {
    const Surface* s = m_doc->surface(m_selection->currentSurface());
    if (!s || (s->partitionsU == nu && s->partitionsV == nv))
        return;
    rejected(pushCommand(m_stack, SetPartitions::create(m_doc, s->id, nu, nv)));
}

void PropertyPanel::editPoint() {
    const ControlPointRef r = shownPoint();
    const Surface* s = m_doc->surface(r.surface);
    if (!s)
        return;
    const int index = s->geometry.index(r.i, r.j);
    const glm::dvec3 from = s->geometry.points[size_t(index)];
    const glm::dvec3 to(m_xyz[0]->value(), m_xyz[1]->value(), m_xyz[2]->value());
    if (from == to)
        return;
    rejected(pushCommand(m_stack, MoveControlPoints::create(m_doc, r.surface, {index}, {from}, {to},
                                                            MoveKind::Nudge)));
}

void PropertyPanel::editMaterial() {
    const Surface* s = m_doc->surface(m_selection->currentSurface());
    if (!s)
        return;
    Material m = s->material;
    m.ka = m_ka->value();
    m.kd = m_kd->value();
    m.ks = m_ks->value();
    m.shininess = m_shininess->value();
    if (m == s->material)
        return;
    rejected(pushCommand(m_stack, SetMaterial::create(m_doc, s->id, m)));
}

void PropertyPanel::pickColor() {
    const Surface* s = m_doc->surface(m_selection->currentSurface());
    if (!s)
        return;
    const SurfaceId id = s->id;
    const QColor c = QColorDialog::getColor(toColor(s->material.color), this, tr("Surface colour"));
    s = m_doc->surface(id);
    if (!c.isValid() || !s)
        return;
    Material m = s->material;
    m.color = glm::dvec3(c.redF(), c.greenF(), c.blueF());
    rejected(pushCommand(m_stack, SetMaterial::create(m_doc, id, m)));
}

ControlPointRef PropertyPanel::shownPoint() const {
    const SurfaceId current = m_selection->currentSurface();
    for (const ControlPointRef& r : m_selection->controlPoints())
        if (r.surface == current)
            return r;
    return {};
}

void PropertyPanel::refresh() {
    const Surface* s = m_doc->surface(m_selection->currentSurface());
    m_surfaceBox->setEnabled(s);
    m_displayBox->setEnabled(s);
    if (!s) {
        m_title->setText(tr("No surface selected. Pick one in the scene tree or the view."));
        m_pointBox->setEnabled(false);
        // Disabled fields are cleared, not left showing the last surface's values.
        m_degrees->clear();
        m_knots->clear();
        blank(m_knotValue);
        refreshPoint();
        for (QSpinBox* box : {m_spinU, m_spinV})
            blank(box);
        for (QSlider* slider : {m_sliderU, m_sliderV}) {
            const QSignalBlocker b(slider);
            slider->setValue(slider->minimum());
        }
        m_color->setStyleSheet(QString());
        m_color->setText(QString());
        for (QDoubleSpinBox* box : {m_ka, m_kd, m_ks, m_shininess})
            blank(box);
        return;
    }
    const NurbsSurface& g = s->geometry;
    m_title->setText(tr("<b>%1</b> (id %2)").arg(s->name.toHtmlEscaped()).arg(s->id.value));
    m_degrees->setText(tr("u %1, v %2; %3 × %4 control points")
                           .arg(g.degreeU)
                           .arg(g.degreeV)
                           .arg(g.countU)
                           .arg(g.countV));
    m_knots->setPlainText(tr("u: %1\nv: %2").arg(knotText(g.knotsU), knotText(g.knotsV)));
    const Interval dom = m_direction->currentIndex() == 0 ? surfaceDomainU(g) : surfaceDomainV(g);
    {
        const QSignalBlocker b(m_knotValue);
        m_knotValue->setSpecialValueText(QString());
        fitKnotField(m_knotValue, dom);
        m_knotValue->setRange(dom.first, dom.last);
        if (m_knotValue->value() <= dom.first || m_knotValue->value() >= dom.last)
            m_knotValue->setValue(0.5 * (dom.first + dom.last));
    }

    refreshPoint();

    for (auto [slider, spinBox, value] : {std::tuple{m_sliderU, m_spinU, s->partitionsU},
                                          std::tuple{m_sliderV, m_spinV, s->partitionsV}}) {
        const QSignalBlocker b1(slider);
        slider->setValue(value);
        showValue(spinBox, value);
    }
    const Material& m = s->material;
    m_color->setStyleSheet(QStringLiteral("background-color: %1").arg(toColor(m.color).name()));
    m_color->setText(toColor(m.color).name());
    for (auto [box, value] : {std::pair{m_ka, m.ka}, std::pair{m_kd, m.kd}, std::pair{m_ks, m.ks},
                              std::pair{m_shininess, m.shininess}})
        showValue(box, value);
}

void PropertyPanel::refreshPoint() {
    const Surface* s = m_doc->surface(m_selection->currentSurface());
    const ControlPointRef r = shownPoint();
    m_pointBox->setEnabled(r.surface.isValid());
    if (s && r.surface.isValid()) {
        const NurbsSurface& g = s->geometry;
        const int index = g.index(r.i, r.j);
        const size_t picked = m_selection->controlPoints().size();
        m_pointLabel->setText(picked > 1
                                  ? tr("(%1, %2), first of %3 picked").arg(r.i).arg(r.j).arg(picked)
                                  : tr("(%1, %2)").arg(r.i).arg(r.j));
        for (int k = 0; k < 3; ++k)
            showValue(m_xyz[k], g.points[size_t(index)][k]);
        showValue(m_weight, g.weights[size_t(index)]);
    } else {
        m_pointLabel->setText(tr("Click a control point in the view."));
        for (QDoubleSpinBox* box : {m_xyz[0], m_xyz[1], m_xyz[2], m_weight})
            blank(box);
    }
}

} // namespace kw
