// View › Section…: up to kMaxSectionPlanes section planes typed as a point and a normal, with
// Flip and caps, applied to the view as they are typed (a modeless dialog: the view can be
// orbited and edited while it is open).
#pragma once

#include "model/document/scene.h"

#include <QDialog>
#include <array>
#include <functional>

class QCheckBox;
class QDoubleSpinBox;
class QLabel;

namespace kw {

class SectionDialog : public QDialog {
    Q_OBJECT
public:
    /// `centre` gives the point a newly enabled plane starts at (the model's middle).
    SectionDialog(std::function<glm::dvec3()> centre, QWidget* parent = nullptr);

    /// Shows `planes` (the first kMaxSectionPlanes) and `caps`; emits nothing.
    void setSections(const std::vector<SectionPlane>& planes, bool caps);
    /// The enabled rows whose normal is not zero, in row order.
    std::vector<SectionPlane> sections() const;
    bool caps() const;

Q_SIGNALS:
    /// Any value changed: the planes to draw now (rows with a zero normal left out).
    void sectionsChanged(const std::vector<SectionPlane>& planes, bool caps);

private:
    struct Row {
        QCheckBox* enabled = nullptr;
        std::array<QDoubleSpinBox*, 3> position{};
        std::array<QDoubleSpinBox*, 3> normal{};
        QCheckBox* flip = nullptr;
        QLabel* status = nullptr;
        SectionPlane plane() const;
    };
    void changed();
    void enableRow(int k, bool on);

    std::function<glm::dvec3()> m_centre;
    std::array<Row, kMaxSectionPlanes> m_rows;
    QCheckBox* m_caps = nullptr;
    bool m_quiet = false; ///< setSections is filling the fields
    bool m_built = false; ///< every row exists
};

} // namespace kw
