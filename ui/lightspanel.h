// LightsPanel: the document's lights — count, kind, direction or position, intensities — edited
// through SetLights commands.
#pragma once

#include "model/document/document.h"

#include <QWidget>

class QComboBox;
class QDoubleSpinBox;
class QSpinBox;
class QUndoStack;

namespace kw {

class LightsPanel : public QWidget {
    Q_OBJECT
public:
    LightsPanel(Document* document, QUndoStack* stack, QWidget* parent = nullptr);

    QSpinBox* countBox() const { return m_count; }

Q_SIGNALS:
    void editRejected(const QString& message);

private:
    void refresh();
    void setCount(int count);
    void editLight();

    Document* m_doc;
    QUndoStack* m_stack;
    QSpinBox* m_count = nullptr;
    QComboBox* m_which = nullptr;
    QComboBox* m_kind = nullptr;
    QDoubleSpinBox* m_vector[3] = {nullptr, nullptr, nullptr};
    QDoubleSpinBox* m_ambient = nullptr;
    QDoubleSpinBox* m_diffuse = nullptr;
    QDoubleSpinBox* m_specular = nullptr;
};

} // namespace kw
