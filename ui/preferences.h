// Preferences: the editor's defaults kept with QSettings, and the dialog that edits them.
#pragma once

#include <QColor>
#include <QDialog>
#include <QString>

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
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

    static Preferences load();
    void save() const;
    bool operator==(const Preferences&) const = default;
    /// The partition modes this build implements (adaptive came later); a stored
    /// mode that does not exist selects uniform.
    static QStringList availablePartitionModes();
};

class PreferencesDialog : public QDialog {
    Q_OBJECT
public:
    explicit PreferencesDialog(const Preferences& initial, QWidget* parent = nullptr);
    Preferences value() const;

private:
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
};

} // namespace kw
