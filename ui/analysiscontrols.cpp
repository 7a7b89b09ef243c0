// View ▸ Analysis menu, Analysis toolbar, colour range dialog and the colour legend painter.
#include "ui/analysiscontrols.h"

#include "ui/viewport.h"

#include <QActionGroup>
#include <QCheckBox>
#include <QComboBox>
#include <QDialog>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QMainWindow>
#include <QMenu>
#include <QPainter>
#include <QToolBar>

namespace kw {

namespace {
QString camelName(AnalysisMode mode) {
    QString out;
    bool upper = true;
    for (QChar c : analysisModeName(mode)) {
        if (c == QLatin1Char('-')) {
            upper = true;
            continue;
        }
        out += upper ? c.toUpper() : c;
        upper = false;
    }
    return out;
}
} // namespace

AnalysisControls::AnalysisControls(QMainWindow* window, QMenu* viewMenu, Viewport* viewport)
    : QObject(window), m_window(window), m_viewport(viewport) {
    QMenu* menu = viewMenu->addMenu(tr("&Analysis"));
    m_menu = menu;
    QToolBar* bar = window->addToolBar(tr("Analysis"));
    bar->setObjectName(QStringLiteral("analysisToolBar"));
    // One combo box for the modes, not a button each: a row of ten text buttons overflowed the
    // toolbar area of the first window. The menu keeps an action per mode, with the same state.
    auto* modes = new QComboBox;
    modes->setObjectName(QStringLiteral("analysisModeBox"));
    modes->setToolTip(tr("Shading and analysis mode (View ▸ Analysis)"));
    modes->setSizeAdjustPolicy(QComboBox::AdjustToContents);
    bar->addWidget(modes);
    auto* group = new QActionGroup(this);
    for (AnalysisMode mode : analysisModes()) {
        QAction* a = menu->addAction(analysisModeTitle(mode));
        a->setObjectName(QStringLiteral("actionAnalysis") + camelName(mode));
        a->setCheckable(true);
        a->setChecked(mode == viewport->renderOptions().analysis.mode);
        group->addAction(a);
        const int index = modes->count();
        modes->addItem(analysisModeTitle(mode));
        if (a->isChecked())
            modes->setCurrentIndex(index);
        connect(a, &QAction::toggled, modes, [modes, index](bool on) {
            if (on)
                modes->setCurrentIndex(index);
        });
        connect(a, &QAction::triggered, this, [this, mode] {
            AnalysisOptions o = m_viewport->renderOptions().analysis;
            o.mode = mode;
            m_viewport->setAnalysis(o);
        });
    }
    const QList<QAction*> modeActions = group->actions();
    connect(modes, &QComboBox::activated, this, [modeActions](int index) {
        if (index >= 0 && index < modeActions.size() && !modeActions[index]->isChecked())
            modeActions[index]->trigger();
    });
    menu->addSeparator();
    bar->addSeparator();
    QAction* iso = menu->addAction(tr("&Isocurves"));
    iso->setObjectName(QStringLiteral("actionIsocurves"));
    iso->setCheckable(true);
    iso->setShortcut(QKeySequence(Qt::Key_I));
    bar->addAction(iso);
    connect(iso, &QAction::toggled, this, [this](bool on) {
        AnalysisOptions o = m_viewport->renderOptions().analysis;
        o.isocurves = on;
        m_viewport->setAnalysis(o);
    });
    QAction* dirs = menu->addAction(tr("Principal &Directions"));
    dirs->setObjectName(QStringLiteral("actionPrincipalDirections"));
    dirs->setCheckable(true);
    dirs->setToolTip(tr("Marks of the principal curvature directions (k1 red, k2 blue)"));
    bar->addAction(dirs);
    connect(dirs, &QAction::toggled, this, [this](bool on) {
        AnalysisOptions o = m_viewport->renderOptions().analysis;
        o.principalDirections = on;
        m_viewport->setAnalysis(o);
    });
    QAction* range = menu->addAction(tr("Colour &Range…"));
    range->setObjectName(QStringLiteral("actionAnalysisRange"));
    bar->addAction(range);
    connect(range, &QAction::triggered, this, &AnalysisControls::editRange);
    QAction* draft = menu->addAction(tr("Draft &Settings…"));
    draft->setObjectName(QStringLiteral("actionDraftSettings"));
    draft->setToolTip(tr("Pull direction and minimum draft angle of the Draft analysis"));
    bar->addAction(draft);
    connect(draft, &QAction::triggered, this, &AnalysisControls::editDraft);
}

void AnalysisControls::editDraft() {
    AnalysisOptions o = m_viewport->renderOptions().analysis;
    QDialog dialog(m_window);
    dialog.setWindowTitle(tr("Draft Settings"));
    dialog.setObjectName(QStringLiteral("draftSettingsDialog"));
    auto* form = new QFormLayout(&dialog);
    auto spin = [](double value, double lo, double hi, const char* name) {
        auto* s = new QDoubleSpinBox;
        s->setObjectName(QString::fromLatin1(name));
        s->setDecimals(4);
        s->setRange(lo, hi);
        s->setValue(value);
        return s;
    };
    QDoubleSpinBox* x = spin(o.pullDirection.x, -1e6, 1e6, "draftPullX");
    QDoubleSpinBox* y = spin(o.pullDirection.y, -1e6, 1e6, "draftPullY");
    QDoubleSpinBox* z = spin(o.pullDirection.z, -1e6, 1e6, "draftPullZ");
    QDoubleSpinBox* angle = spin(o.draftAngleDegrees, 0.0, 90.0, "draftAngle");
    angle->setSuffix(QStringLiteral("°"));
    // The usual pulls in one click: along an axis of the model, either way.
    auto* axes = new QComboBox;
    axes->setObjectName(QStringLiteral("draftPullAxis"));
    axes->addItem(tr("Custom"));
    const glm::dvec3 axisVectors[] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                      {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
    for (const char* name : {"+X", "−X", "+Y", "−Y", "+Z", "−Z"})
        axes->addItem(QString::fromUtf8(name));
    connect(axes, &QComboBox::activated, &dialog, [=](int index) {
        if (index < 1)
            return;
        const glm::dvec3 v = axisVectors[index - 1];
        x->setValue(v.x);
        y->setValue(v.y);
        z->setValue(v.z);
    });
    auto* row = new QHBoxLayout;
    row->addWidget(x);
    row->addWidget(y);
    row->addWidget(z);
    form->addRow(tr("Pull direction"), row);
    form->addRow(tr("Axis"), axes);
    form->addRow(tr("Minimum draft"), angle);
    auto* why = new QLabel;
    why->setObjectName(QStringLiteral("draftError"));
    form->addRow(why);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
    form->addRow(buttons);
    // A zero direction has no draft: refused in the dialog, with the reason.
    connect(buttons, &QDialogButtonBox::accepted, &dialog, [&] {
        if (glm::length(glm::dvec3(x->value(), y->value(), z->value())) > 0.0)
            dialog.accept();
        else
            why->setText(tr("The pull direction must not be zero."));
    });
    connect(buttons, &QDialogButtonBox::rejected, &dialog, &QDialog::reject);
    if (dialog.exec() != QDialog::Accepted)
        return;
    o.pullDirection = glm::dvec3(x->value(), y->value(), z->value());
    o.draftAngleDegrees = angle->value();
    m_viewport->setAnalysis(o);
}

void AnalysisControls::editRange() {
    AnalysisOptions o = m_viewport->renderOptions().analysis;
    const ValueRange current = o.range.value_or(m_viewport->lastFrameReport().analysisRange);
    QDialog dialog(m_window);
    dialog.setWindowTitle(tr("Colour Range"));
    auto* form = new QFormLayout(&dialog);
    auto* automatic = new QCheckBox(tr("Automatic (10th to 90th percentile of the area)"));
    automatic->setChecked(!o.range);
    auto spin = [](double value) {
        auto* s = new QDoubleSpinBox;
        s->setDecimals(6);
        s->setRange(-1e12, 1e12);
        s->setValue(value);
        return s;
    };
    QDoubleSpinBox* low = spin(current.low);
    QDoubleSpinBox* high = spin(current.high);
    auto* scale = new QComboBox;
    // Names for GUI tests (tst_editor_analysis drives this dialog through the real window).
    dialog.setObjectName(QStringLiteral("colourRangeDialog"));
    automatic->setObjectName(QStringLiteral("rangeAutomatic"));
    low->setObjectName(QStringLiteral("rangeLow"));
    high->setObjectName(QStringLiteral("rangeHigh"));
    scale->setObjectName(QStringLiteral("rangeScale"));
    scale->addItem(tr("Mode default"));
    for (ColourScale s : {ColourScale::Linear, ColourScale::Symmetric, ColourScale::Log})
        scale->addItem(colourScaleName(s), int(s));
    if (o.scale)
        scale->setCurrentIndex(int(*o.scale) + 1);
    form->addRow(automatic);
    form->addRow(tr("Low"), low);
    form->addRow(tr("High"), high);
    form->addRow(tr("Scale"), scale);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
    form->addRow(buttons);
    connect(buttons, &QDialogButtonBox::accepted, &dialog, &QDialog::accept);
    connect(buttons, &QDialogButtonBox::rejected, &dialog, &QDialog::reject);
    const auto sync = [=] {
        low->setEnabled(!automatic->isChecked());
        high->setEnabled(!automatic->isChecked());
    };
    connect(automatic, &QCheckBox::toggled, &dialog, sync);
    sync();
    if (dialog.exec() != QDialog::Accepted)
        return;
    if (automatic->isChecked() || !(high->value() > low->value()))
        o.range.reset();
    else
        o.range = ValueRange{low->value(), high->value()};
    if (scale->currentIndex() == 0)
        o.scale.reset();
    else
        o.scale = ColourScale(scale->currentData().toInt());
    m_viewport->setAnalysis(o);
}

void drawColourLegend(QPainter& p, const QRect& area, AnalysisMode mode, const ValueRange& range,
                      ColourScale scale, bool automatic) {
    const int barWidth = 18;
    const int titleHeight = 34;
    const QRect bar(area.left(), area.top() + titleHeight, barWidth, area.height() - titleHeight);
    p.save();
    p.setRenderHint(QPainter::Antialiasing, false);
    p.fillRect(area.adjusted(-6, -4, 6, 4), QColor(30, 32, 36, 190));
    // The bar, top = high end (t = 1), one row per pixel through the shader's ramp.
    for (int y = 0; y < bar.height(); ++y) {
        const double t = 1.0 - (y + 0.5) / bar.height();
        const glm::vec3 c = rampColour(t);
        p.setPen(QColor::fromRgbF(c.x, c.y, c.z));
        p.drawLine(bar.left(), bar.top() + y, bar.right(), bar.top() + y);
    }
    p.setPen(Qt::white);
    p.drawText(QRect(area.left(), area.top(), area.width() + 6, 16), Qt::AlignLeft,
               analysisModeTitle(mode));
    p.drawText(QRect(area.left(), area.top() + 16, area.width() + 6, 16), Qt::AlignLeft,
               QStringLiteral("%1, %2").arg(colourScaleName(scale),
                                            automatic ? QStringLiteral("auto")
                                                      : QStringLiteral("user range")));
    for (int k = 0; k <= 4; ++k) {
        const double t = k / 4.0;
        const int y = bar.bottom() - int(t * (bar.height() - 1));
        p.drawLine(bar.right() + 1, y, bar.right() + 5, y);
        const double value = colourScaleValue(t, range, scale);
        p.drawText(QRect(bar.right() + 8, y - 8, area.width() - barWidth - 8, 16),
                   Qt::AlignLeft | Qt::AlignVCenter, QString::number(value, 'g', 4));
    }
    p.restore();
}

void drawDraftLegend(QPainter& p, const QRect& area, const glm::dvec3& pull, double angleDegrees) {
    p.save();
    p.setRenderHint(QPainter::Antialiasing, false);
    p.fillRect(area.adjusted(-6, -4, 6, 4), QColor(30, 32, 36, 190));
    p.setPen(Qt::white);
    p.drawText(QRect(area.left(), area.top(), area.width() + 6, 16), Qt::AlignLeft,
               analysisModeTitle(AnalysisMode::Draft));
    const glm::dvec3 d = glm::length(pull) > 0.0 ? glm::normalize(pull) : glm::dvec3(0, 0, 1);
    p.drawText(QRect(area.left(), area.top() + 16, area.width() + 6, 16), Qt::AlignLeft,
               QStringLiteral("pull (%1, %2, %3)")
                   .arg(d.x, 0, 'g', 3)
                   .arg(d.y, 0, 'g', 3)
                   .arg(d.z, 0, 'g', 3));
    const QString a = QString::number(angleDegrees, 'g', 4) + QStringLiteral("°");
    const DraftColours& c = draftColours();
    const std::pair<glm::vec3, QString> rows[] = {
        {c.draft, QStringLiteral("≥ +") + a},
        {c.insufficient, QStringLiteral("< ") + a + QStringLiteral(" either way")},
        {c.undercut, QStringLiteral("≤ −") + a + QStringLiteral(" (undercut)")}};
    int y = area.top() + 38;
    for (const auto& [colour, text] : rows) {
        p.fillRect(QRect(area.left(), y, 18, 16), QColor::fromRgbF(colour.x, colour.y, colour.z));
        p.drawText(QRect(area.left() + 26, y, area.width() - 26, 16),
                   Qt::AlignLeft | Qt::AlignVCenter, text);
        y += 22;
    }
    p.restore();
}

} // namespace kw
