// PropertyPanel: the selected surface's degrees, knot vectors (insert knot, elevate degree),
// the picked control point's position and weight, partitions and material; edits are commands.
#pragma once

#include "model/document/selection.h"
#include "model/error.h"

#include <QWidget>
#include <memory>

class QDoubleSpinBox;
class QLabel;
class QPlainTextEdit;
class QPushButton;
class QSlider;
class QSpinBox;
class QComboBox;
class QUndoCommand;
class QUndoStack;

namespace kw {

class PropertyPanel : public QWidget {
    Q_OBJECT
public:
    PropertyPanel(Document* document, Selection* selection, QUndoStack* stack,
                  QWidget* parent = nullptr);

    QSlider* partitionSliderU() const { return m_sliderU; }
    QSlider* partitionSliderV() const { return m_sliderV; }
    QSpinBox* partitionSpinU() const { return m_spinU; }
    /// Shows the control point's x, y, z with this unit ("12.5 mm").
    void setLengthUnit(LengthUnit unit);

Q_SIGNALS:
    /// A command was rejected; the text says why (for the status bar).
    void editRejected(const QString& message);

private:
    QWidget* buildSurfaceBox();
    QWidget* buildPointBox();
    QWidget* buildDisplayBox();
    void refresh();
    /// Only the picked point's position and weight (cheap; called on every drag step).
    void refreshPoint();
    /// The picked control point shown in the point box (the first picked point of the current
    /// surface), or a ref with an invalid surface.
    ControlPointRef shownPoint() const;
    /// Shows a refused edit (pushCommand's Error) and the document's values again.
    void rejected(const Status& pushed);
    void setPartitions(int nu, int nv);
    void editPoint();
    void editMaterial();
    void pickColor();

    Document* m_doc;
    Selection* m_selection;
    QUndoStack* m_stack;

    QLabel* m_title = nullptr;
    QLabel* m_degrees = nullptr;
    QPlainTextEdit* m_knots = nullptr;
    QComboBox* m_direction = nullptr;
    QDoubleSpinBox* m_knotValue = nullptr;
    QPushButton* m_insertKnot = nullptr;
    QPushButton* m_elevate = nullptr;
    QWidget* m_surfaceBox = nullptr;

    QWidget* m_pointBox = nullptr;
    QLabel* m_pointLabel = nullptr;
    QDoubleSpinBox* m_xyz[3] = {nullptr, nullptr, nullptr};
    QDoubleSpinBox* m_weight = nullptr;

    QWidget* m_displayBox = nullptr;
    QSlider* m_sliderU = nullptr;
    QSlider* m_sliderV = nullptr;
    QSpinBox* m_spinU = nullptr;
    QSpinBox* m_spinV = nullptr;
    QPushButton* m_color = nullptr;
    QDoubleSpinBox* m_ka = nullptr;
    QDoubleSpinBox* m_kd = nullptr;
    QDoubleSpinBox* m_ks = nullptr;
    QDoubleSpinBox* m_shininess = nullptr;
};

} // namespace kw
