// Preferences: the editor's defaults kept with QSettings, and the dialog that edits them.
#pragma once

#include "model/document/scene.h"

#include <QColor>
#include <QDialog>
#include <QString>
#include <array>
#include <optional>

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QGroupBox;
class QLabel;
class QSpinBox;
class QPushButton;

namespace kw {

/// Every key, default and meaning in one place. Autosave and backup are read by the document
/// recovery code; the view keys by the viewport (applyTo).
struct Preferences {
    int autosaveSeconds = 60; ///< "autosave/intervalSeconds", 0 = off
    bool keepBackup = true;   ///< "save/keepBackup": keep NAME.knot.bak on save
    QString partitionMode =
        QStringLiteral("adaptive"); ///< "view/partitionMode": adaptive | uniform
    double pixelTolerance = 0.5;    ///< "view/pixelTolerance" (adaptive partitions)
    int trimMaskCap = 1024;         ///< "view/trimMaskCap": mask mode, texels per mask side
    QString trimMode = QStringLiteral("exact"); ///< "view/trimMode": exact | mask
    int trimBudgetMiB = 512; ///< "view/trimBudgetMiB": exact trims' GPU memory budget
    /// "view/samples": anti-aliasing samples per pixel, 1 (off)..kMaxSamples, or 0: automatic
    /// (4, and on software OpenGL only for still frames: Viewport::setSamples)
    int samples = 0;
    /// "view/aaMethod": accumulate (whole frames at sub-pixel offsets, averaged: seams stay
    /// closed) | coverage (MSAA, trim edges covered exactly); RenderOptions::Antialiasing
    QString aaMethod = QStringLiteral("accumulate");
    bool headlight = true;         ///< "view/headlight": lights follow the camera
    QColor background{46, 48, 54}; ///< "view/background"
    /// "continuity/g0", "continuity/g1Degrees", "continuity/g2Percent", "continuity/match": the
    /// tolerances new projects and imports start with (a project keeps its own, saved in it);
    /// stored values that are not valid together load as the built-in ones (CATIA's).
    ContinuityTolerances continuity;

    static Preferences load();
    void save() const;
    bool operator==(const Preferences&) const = default;
    /// The partition modes this build implements (adaptive came later); a stored
    /// mode that does not exist selects uniform.
    static QStringList availablePartitionModes();
};

/// What the Preferences dialog edits: the application's preferences and, when a project is
/// open, that project's continuity tolerances (saved in it; a change is an undoable edit).
struct PreferencesEdit {
    Preferences preferences;
    std::optional<ContinuityTolerances> project;
    bool operator==(const PreferencesEdit&) const = default;
};

class PreferencesDialog : public QDialog {
    Q_OBJECT
public:
    explicit PreferencesDialog(const Preferences& initial, QWidget* parent = nullptr)
        : PreferencesDialog(PreferencesEdit{initial, std::nullopt}, parent) {}
    explicit PreferencesDialog(const PreferencesEdit& initial, QWidget* parent = nullptr);
    Preferences value() const;
    /// value() and the project's tolerances as shown (nullopt when the dialog had none).
    PreferencesEdit edit() const;
    /// Gives the keyboard focus to the project's G0 tolerance (else the defaults'): the dialog
    /// as View > Analysis > Continuity Tolerances opens it.
    void focusContinuity();

private:
    QGroupBox* continuityGroup(const PreferencesEdit& e);
    /// OK: accepts when both columns of tolerances are valid, else says why in the dialog.
    void acceptIfValid();

    QSpinBox* m_autosave;
    QCheckBox* m_backup;
    QComboBox* m_partitionMode;
    QDoubleSpinBox* m_tolerance;
    QSpinBox* m_trimCap;
    QComboBox* m_trimMode;
    QSpinBox* m_trimBudget;
    QSpinBox* m_samples;
    QComboBox* m_aaMethod;
    QCheckBox* m_headlight;
    QPushButton* m_background;
    QColor m_color;
    /// G0, G1, G2 and match spin boxes: [0] the open project's (null without one), [1] the
    /// defaults for new projects.
    std::array<std::array<QDoubleSpinBox*, 4>, 2> m_continuity{};
    QLabel* m_continuityError = nullptr;
};

} // namespace kw
