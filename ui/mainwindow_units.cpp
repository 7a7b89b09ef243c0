// Edit ▸ Units…: the document's length unit, relabelled or converted in one undoable step, and
// where the editor shows it (status bar, Properties).
#include "ui/edit/modelcommands.h"
#include "ui/mainwindow.h"
#include "ui/propertypanel.h"

#include <QComboBox>
#include <QDialog>
#include <QDialogButtonBox>
#include <QFormLayout>
#include <QLabel>
#include <QRadioButton>
#include <QStatusBar>
#include <QUndoStack>

namespace kw {

std::optional<MainWindow::Dialogs::UnitsChoice> unitsDialogStandard(QWidget* parent,
                                                                    LengthUnit current) {
    QDialog dialog(parent);
    dialog.setWindowTitle(QObject::tr("Units"));
    auto* form = new QFormLayout(&dialog);
    form->addRow(new QLabel(QObject::tr("The document is in %1.").arg(lengthUnitName(current))));
    auto* units = new QComboBox;
    for (LengthUnit u : kLengthUnits)
        units->addItem(lengthUnitName(u), int(u));
    units->setCurrentIndex(units->findData(int(current)));
    form->addRow(QObject::tr("Unit"), units);
    auto* convert = new QRadioButton(QObject::tr("Convert: scale every length so the part keeps "
                                                 "its size"));
    auto* relabel = new QRadioButton(QObject::tr("Relabel: keep the numbers, change only their "
                                                 "unit (the file's unit was wrong)"));
    convert->setChecked(true);
    form->addRow(convert);
    form->addRow(relabel);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
    QObject::connect(buttons, &QDialogButtonBox::accepted, &dialog, &QDialog::accept);
    QObject::connect(buttons, &QDialogButtonBox::rejected, &dialog, &QDialog::reject);
    form->addRow(buttons);
    if (dialog.exec() != QDialog::Accepted)
        return std::nullopt;
    return MainWindow::Dialogs::UnitsChoice{LengthUnit(units->currentData().toInt()),
                                            convert->isChecked()};
}

void MainWindow::unitsDialog() {
    if (!m_dialogs.units)
        return;
    const auto choice = m_dialogs.units(this, m_doc->scene().unit);
    if (!choice)
        return;
    if (const Status pushed =
            pushCommand(m_stack, SetUnits::create(m_doc, choice->unit, choice->convert));
        !pushed)
        statusBar()->showMessage(pushed.message(), 5000);
}

void MainWindow::showUnit() {
    const LengthUnit unit = m_doc->scene().unit;
    m_unitLabel->setText(tr("Units: %1").arg(lengthUnitKey(unit)));
    if (m_properties)
        m_properties->setLengthUnit(unit);
}

} // namespace kw
