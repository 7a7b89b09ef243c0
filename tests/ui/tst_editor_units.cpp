// Edit › Units… in the editor: the status bar and Properties show the document's unit; Convert
// scales the part to the new unit and Relabel keeps its numbers, each one undoable step; Save
// writes the unit and Open brings it back.
#include "editor_test_util.h"
#include "model/io/knotfile.h"
#include "render/offscreen_renderer.h"
#include "ui/propertypanel.h"

#include <QDoubleSpinBox>
#include <QLabel>
#include <QSurfaceFormat>
#include <QTemporaryDir>
#include <QUndoStack>

using namespace kw;

class TestEditorUnits : public kwtest::EditorTestBase {
    Q_OBJECT
public:
    static void initMain() {
        QSurfaceFormat::setDefaultFormat(OffscreenRenderer::requiredFormat());
    }
private Q_SLOTS:
    void cleanup() { closeWindow(); }

    void units() {
        openWindow("sphere");
        std::optional<MainWindow::Dialogs::UnitsChoice> answer;
        int asked = 0;
        LengthUnit offered = LengthUnit::Micrometre;
        MainWindow::Dialogs d;
        d.error = [this](QWidget*, const QString&, const QString& text) {
            m_script.errors << text;
        };
        d.saveFile = [](QWidget*, const QString&, const QString&, const QString&) {
            return QString();
        };
        d.units = [&](QWidget*, LengthUnit current) {
            ++asked;
            offered = current;
            return answer;
        };
        m_window->setDialogs(d);
        const auto label = [&] {
            return m_window->findChild<QLabel*>(QStringLiteral("unitLabel"))->text();
        };
        auto* x = m_window->propertyPanel()->findChild<QDoubleSpinBox*>(QStringLiteral("pointX"));
        QVERIFY(x);
        QCOMPARE(label(), QStringLiteral("Units: mm"));
        QCOMPARE(x->suffix(), QStringLiteral(" mm"));

        const Scene before = m_window->document()->scene();
        QAction* units = act("actionUnits");
        QVERIFY(units);
        // Cancelled: nothing happens.
        units->trigger();
        QCOMPARE(asked, 1);
        QCOMPARE(offered, LengthUnit::Millimetre); // the dialog starts at the document's unit
        QCOMPARE(m_window->undoStack()->count(), 0);

        // Convert to inches: the part keeps its size, one undo step.
        answer = MainWindow::Dialogs::UnitsChoice{LengthUnit::Inch, true};
        units->trigger();
        const Scene& now = m_window->document()->scene();
        QCOMPARE(now.unit, LengthUnit::Inch);
        QCOMPARE(now.surfaces[0].geometry.points[5],
                 before.surfaces[0].geometry.points[5] * (1.0 / 25.4));
        QCOMPARE(m_window->undoStack()->count(), 1);
        QCOMPARE(label(), QStringLiteral("Units: in"));
        QCOMPARE(x->suffix(), QStringLiteral(" in"));
        act("actionUndo")->trigger();
        QVERIFY(m_window->document()->scene() == before);
        QCOMPARE(label(), QStringLiteral("Units: mm"));
        act("actionRedo")->trigger();
        QCOMPARE(m_window->document()->scene().unit, LengthUnit::Inch);

        // Relabel as metres: the numbers stay.
        answer = MainWindow::Dialogs::UnitsChoice{LengthUnit::Metre, false};
        units->trigger();
        QCOMPARE(m_window->document()->scene().unit, LengthUnit::Metre);
        QCOMPARE(m_window->document()->scene().surfaces[0].geometry.points[5],
                 before.surfaces[0].geometry.points[5] * (1.0 / 25.4));
        QCOMPARE(label(), QStringLiteral("Units: m"));

        // The same unit again: refused, nothing pushed.
        const int steps = m_window->undoStack()->count();
        units->trigger();
        QCOMPARE(m_window->undoStack()->count(), steps);

        QTemporaryDir dir;
        const QString path = dir.filePath(QStringLiteral("metres.knot"));
        QVERIFY(m_window->saveFile(path));
        QString error;
        const auto saved = readKnotFile(path);
        QVERIFY2(saved, qPrintable(saved.message()));
        QCOMPARE(saved->unit, LengthUnit::Metre);
        QVERIFY(m_window->openFile(kwtest::samplePath("torus")));
        QCOMPARE(label(), QStringLiteral("Units: mm"));
        QVERIFY(m_window->openFile(path));
        QCOMPARE(label(), QStringLiteral("Units: m"));
        QCOMPARE(x->suffix(), QStringLiteral(" m"));
    }
};

QTEST_MAIN(TestEditorUnits)
#include "tst_editor_units.moc"
