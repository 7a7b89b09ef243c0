// Preferences: QSettings keys with defaults, and a form dialog for them.
#include "ui/preferences.h"

#include "model/analysis/continuity.h"
#include "render/render_types.h"

#include <QCheckBox>
#include <QColorDialog>
#include <QComboBox>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QGridLayout>
#include <QGroupBox>
#include <QLabel>
#include <QPushButton>
#include <QSettings>
#include <QSpinBox>
#include <algorithm>

namespace kw {

QStringList Preferences::availablePartitionModes() {
    return {QStringLiteral("adaptive"), QStringLiteral("uniform")};
}

Preferences Preferences::load() {
    QSettings s;
    Preferences d, p;
    p.autosaveSeconds =
        std::max(0, s.value(QStringLiteral("autosave/intervalSeconds"), d.autosaveSeconds).toInt());
    p.keepBackup = s.value(QStringLiteral("save/keepBackup"), d.keepBackup).toBool();
    p.partitionMode = s.value(QStringLiteral("view/partitionMode"), d.partitionMode).toString();
    p.pixelTolerance = s.value(QStringLiteral("view/pixelTolerance"), d.pixelTolerance).toDouble();
    if (!(p.pixelTolerance > 0.0))
        p.pixelTolerance = d.pixelTolerance;
    p.trimMaskCap =
        std::clamp(s.value(QStringLiteral("view/trimMaskCap"), d.trimMaskCap).toInt(), 64, 16384);
    p.trimMode = s.value(QStringLiteral("view/trimMode"), d.trimMode).toString();
    if (!trimModeNamed(p.trimMode))
        p.trimMode = d.trimMode;
    p.trimBudgetMiB =
        std::clamp(s.value(QStringLiteral("view/trimBudgetMiB"), d.trimBudgetMiB).toInt(), 1,
                   int(kMaxTrimBudgetBytes >> 20));
    p.samples =
        std::clamp(s.value(QStringLiteral("view/samples"), d.samples).toInt(), 0, kMaxSamples);
    p.aaMethod = s.value(QStringLiteral("view/aaMethod"), d.aaMethod).toString();
    if (!antialiasingNamed(p.aaMethod))
        p.aaMethod = d.aaMethod;
    p.headlight = s.value(QStringLiteral("view/headlight"), d.headlight).toBool();
    const QColor c(s.value(QStringLiteral("view/background"), d.background.name()).toString());
    p.background = c.isValid() ? c : d.background;
    ContinuityTolerances t;
    t.g0 = s.value(QStringLiteral("continuity/g0"), d.continuity.g0).toDouble();
    t.g1Degrees =
        s.value(QStringLiteral("continuity/g1Degrees"), d.continuity.g1Degrees).toDouble();
    t.g2Percent =
        s.value(QStringLiteral("continuity/g2Percent"), d.continuity.g2Percent).toDouble();
    t.match = s.value(QStringLiteral("continuity/match"), d.continuity.match).toDouble();
    if (checkContinuityTolerances(t))
        p.continuity = t;
    return p;
}

void Preferences::save() const {
    QSettings s;
    s.setValue(QStringLiteral("autosave/intervalSeconds"), autosaveSeconds);
    s.setValue(QStringLiteral("save/keepBackup"), keepBackup);
    s.setValue(QStringLiteral("view/partitionMode"), partitionMode);
    s.setValue(QStringLiteral("view/pixelTolerance"), pixelTolerance);
    s.setValue(QStringLiteral("view/trimMaskCap"), trimMaskCap);
    s.setValue(QStringLiteral("view/trimMode"), trimMode);
    s.setValue(QStringLiteral("view/trimBudgetMiB"), trimBudgetMiB);
    s.setValue(QStringLiteral("view/samples"), samples);
    s.setValue(QStringLiteral("view/aaMethod"), aaMethod);
    s.setValue(QStringLiteral("view/headlight"), headlight);
    s.setValue(QStringLiteral("view/background"), background.name());
    s.setValue(QStringLiteral("continuity/g0"), continuity.g0);
    s.setValue(QStringLiteral("continuity/g1Degrees"), continuity.g1Degrees);
    s.setValue(QStringLiteral("continuity/g2Percent"), continuity.g2Percent);
    s.setValue(QStringLiteral("continuity/match"), continuity.match);
}

namespace {

std::array<double, 4> toArray(const ContinuityTolerances& t) {
    return {t.g0, t.g1Degrees, t.g2Percent, t.match};
}

ContinuityTolerances fromSpins(const std::array<QDoubleSpinBox*, 4>& s) {
    return {s[0]->value(), s[1]->value(), s[2]->value(), s[3]->value()};
}

} // namespace

/// The Continuity group: the open project's tolerances beside the defaults for new ones, so
/// that which one a value sets is never in doubt.
QGroupBox* PreferencesDialog::continuityGroup(const PreferencesEdit& e) {
    auto* box = new QGroupBox(tr("Continuity tolerances (Edge Continuity, Match Surface)"));
    box->setObjectName(QStringLiteral("prefContinuity"));
    auto* grid = new QGridLayout(box);
    grid->addWidget(new QLabel(tr("This project")), 0, 1);
    grid->addWidget(new QLabel(tr("New projects")), 0, 2);
    const QString rows[4] = {tr("G0 gap (model units)"), tr("G1 angle"), tr("G2 curvature jump"),
                             tr("Edges without a record match within")};
    const QString suffixes[4] = {QString(), tr(" deg"), tr(" %"), QString()};
    const char* keys[4] = {"G0", "G1", "G2", "Match"};
    for (int r = 0; r < 4; ++r)
        grid->addWidget(new QLabel(rows[r]), r + 1, 0);
    for (int column = 0; column < 2; ++column) {
        const std::optional<ContinuityTolerances> t =
            column == 0 ? e.project : std::optional(e.preferences.continuity);
        if (!t) {
            grid->addWidget(new QLabel(tr("(no project)")), 1, 1);
            continue;
        }
        const std::array<double, 4> values = toArray(*t);
        for (int r = 0; r < 4; ++r) {
            auto* spin = new QDoubleSpinBox;
            spin->setObjectName(
                QStringLiteral("pref%1%2")
                    .arg(column == 0 ? QStringLiteral("Project") : QStringLiteral("Default"),
                         QLatin1String(keys[r])));
            spin->setDecimals(6);
            spin->setRange(1e-6, 1e6);
            spin->setValue(values[size_t(r)]);
            spin->setSuffix(suffixes[r]);
            grid->addWidget(spin, r + 1, column + 1);
            m_continuity[size_t(column)][size_t(r)] = spin;
        }
    }
    m_continuityError = new QLabel;
    m_continuityError->setObjectName(QStringLiteral("prefContinuityError"));
    m_continuityError->setWordWrap(true);
    grid->addWidget(m_continuityError, 5, 0, 1, 3);
    return box;
}

void PreferencesDialog::focusContinuity() {
    QDoubleSpinBox* g0 = m_continuity[0][0] ? m_continuity[0][0] : m_continuity[1][0];
    g0->setFocus();
    g0->selectAll();
}

void PreferencesDialog::acceptIfValid() {
    for (size_t column = 0; column < 2; ++column) {
        if (!m_continuity[column][0])
            continue;
        const QString why = checkContinuityTolerances(fromSpins(m_continuity[column])).message();
        if (!why.isEmpty()) {
            m_continuityError->setText(
                (column == 0 ? tr("This project: %1") : tr("New projects: %1")).arg(why));
            return;
        }
    }
    accept();
}

PreferencesEdit PreferencesDialog::edit() const {
    PreferencesEdit e{value(), std::nullopt};
    if (m_continuity[0][0])
        e.project = fromSpins(m_continuity[0]);
    return e;
}

PreferencesDialog::PreferencesDialog(const PreferencesEdit& e, QWidget* parent)
    : QDialog(parent), m_color(e.preferences.background) {
    const Preferences& p = e.preferences;
    setWindowTitle(tr("Preferences"));
    auto* form = new QFormLayout(this);
    m_autosave = new QSpinBox;
    m_autosave->setObjectName(QStringLiteral("prefAutosave"));
    m_autosave->setRange(0, 3600);
    m_autosave->setSuffix(tr(" s"));
    m_autosave->setSpecialValueText(tr("off"));
    m_autosave->setValue(p.autosaveSeconds);
    m_backup = new QCheckBox(tr("Keep a .bak of the previous version on save"));
    m_backup->setObjectName(QStringLiteral("prefKeepBackup"));
    m_backup->setChecked(p.keepBackup);
    m_partitionMode = new QComboBox;
    m_partitionMode->setObjectName(QStringLiteral("prefPartitionMode"));
    // Only the modes this build draws are offered: a choice that changes nothing would mislead.
    // A stored mode it lacks (from a newer build) is kept in the settings untouched.
    const QStringList modes = Preferences::availablePartitionModes();
    m_partitionMode->addItems(modes);
    if (!modes.contains(p.partitionMode))
        m_partitionMode->addItem(p.partitionMode);
    m_partitionMode->setCurrentText(p.partitionMode);
    const bool adaptive = modes.contains(QStringLiteral("adaptive"));
    m_partitionMode->setEnabled(modes.size() > 1);
    m_partitionMode->setToolTip(adaptive ? tr("Partitions of the base polygon")
                                         : tr("This build draws uniform partitions only (the "
                                              "sliders' nu x nv)."));
    m_tolerance = new QDoubleSpinBox;
    m_tolerance->setObjectName(QStringLiteral("prefPixelTolerance"));
    m_tolerance->setRange(kMinPixelTolerance, kMaxPixelTolerance);
    m_tolerance->setDecimals(2);
    m_tolerance->setSuffix(tr(" px"));
    m_tolerance->setValue(p.pixelTolerance);
    m_tolerance->setEnabled(adaptive); // the tolerance of adaptive partitions only
    m_trimCap = new QSpinBox;
    m_trimCap->setObjectName(QStringLiteral("prefTrimMaskCap"));
    m_trimCap->setRange(64, 16384);
    m_trimCap->setSuffix(tr(" texels"));
    m_trimCap->setValue(p.trimMaskCap);
    m_trimMode = new QComboBox;
    m_trimMode->setObjectName(QStringLiteral("prefTrimMode"));
    m_trimMode->addItems({QStringLiteral("exact"), QStringLiteral("mask")});
    m_trimMode->setCurrentText(p.trimMode);
    m_trimMode->setToolTip(tr("exact: trim edges exact at any zoom; mask: the paper's trim mask "
                              "alone, accurate to its texels"));
    m_trimBudget = new QSpinBox;
    m_trimBudget->setObjectName(QStringLiteral("prefTrimBudget"));
    m_trimBudget->setRange(1, int(kMaxTrimBudgetBytes >> 20));
    m_trimBudget->setSuffix(tr(" MiB"));
    m_trimBudget->setValue(p.trimBudgetMiB);
    m_trimBudget->setToolTip(tr("GPU memory for exact trims; past it trims get coarser grids "
                                "(slower, never wrong) and a warning"));
    const auto enableTrimFields = [this] {
        const bool exact = m_trimMode->currentText() == QLatin1String("exact");
        m_trimBudget->setEnabled(exact);
        m_trimCap->setEnabled(!exact);
    };
    enableTrimFields();
    connect(m_trimMode, &QComboBox::currentTextChanged, this, enableTrimFields);
    m_samples = new QSpinBox;
    m_samples->setObjectName(QStringLiteral("prefSamples"));
    m_samples->setRange(0, kMaxSamples);
    m_samples->setSpecialValueText(tr("automatic"));
    m_samples->setSuffix(tr(" per pixel"));
    m_samples->setValue(p.samples);
    m_samples->setToolTip(tr("Anti-aliasing: samples per pixel; 1 is off; automatic: 4, and on "
                             "software OpenGL, where it costs several times the frame, only "
                             "once the view is still (accumulated one sample per frame)"));
    m_aaMethod = new QComboBox;
    m_aaMethod->setObjectName(QStringLiteral("prefAaMethod"));
    m_aaMethod->addItems({QStringLiteral("accumulate"), QStringLiteral("coverage")});
    m_aaMethod->setCurrentText(p.aaMethod);
    m_aaMethod->setToolTip(tr("accumulate: the whole frame once per sample, each shifted by a "
                              "sub-pixel offset, averaged (seams between faces stay closed, "
                              "highlights and analysis stripes are smoothed too); coverage: "
                              "MSAA samples (at most what the GPU allows), trim edges covered "
                              "by their exact distance"));
    m_headlight = new QCheckBox(tr("Lights follow the camera (headlight)"));
    m_headlight->setObjectName(QStringLiteral("prefHeadlight"));
    m_headlight->setChecked(p.headlight);
    m_background = new QPushButton;
    m_background->setObjectName(QStringLiteral("prefBackground"));
    auto showColor = [this] {
        m_background->setText(m_color.name());
        m_background->setStyleSheet(QStringLiteral("background:%1").arg(m_color.name()));
    };
    showColor();
    connect(m_background, &QPushButton::clicked, this, [this, showColor] {
        const QColor c = QColorDialog::getColor(m_color, this, tr("Background"));
        if (c.isValid()) {
            m_color = c;
            showColor();
        }
    });
    form->addRow(tr("Autosave every"), m_autosave);
    form->addRow(QString(), m_backup);
    form->addRow(tr("Partition mode"), m_partitionMode);
    form->addRow(tr("Pixel tolerance"), m_tolerance);
    form->addRow(tr("Trims"), m_trimMode);
    form->addRow(tr("Trim memory budget"), m_trimBudget);
    form->addRow(tr("Trim mask size cap"), m_trimCap);
    form->addRow(tr("Anti-aliasing"), m_samples);
    form->addRow(tr("Anti-aliasing method"), m_aaMethod);
    form->addRow(tr("Light rig"), m_headlight);
    form->addRow(tr("Background"), m_background);
    form->addRow(continuityGroup(e));
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
    connect(buttons, &QDialogButtonBox::accepted, this, &PreferencesDialog::acceptIfValid);
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    form->addRow(buttons);
}

Preferences PreferencesDialog::value() const {
    Preferences p;
    p.autosaveSeconds = m_autosave->value();
    p.keepBackup = m_backup->isChecked();
    p.partitionMode = m_partitionMode->currentText();
    p.pixelTolerance = m_tolerance->value();
    p.trimMaskCap = m_trimCap->value();
    p.trimMode = m_trimMode->currentText();
    p.trimBudgetMiB = m_trimBudget->value();
    p.samples = m_samples->value();
    p.aaMethod = m_aaMethod->currentText();
    p.headlight = m_headlight->isChecked();
    p.background = m_color;
    p.continuity = fromSpins(m_continuity[1]);
    return p;
}

} // namespace kw
