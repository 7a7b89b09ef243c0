// Editor GUI tests of File ▸ Import… under Xvfb: IGES and OBJ replace the document, a truncated
// file, Cancel and closing the window keep it, the progress dialog fills up, the imported scene
// is saved as .knot.
#include "expected_test_util.h"
#include "model/cad/cadimport.h"
#include "model/io/knotfile.h"
#include "model/io/objfile.h"
#include "render/offscreen_renderer.h"
#include "ui/edit/commands.h"
#include "ui/mainwindow.h"
#include "ui/viewport.h"

#include <QAction>
#include <QDir>
#include <QFile>
#include <QMenu>
#include <QMenuBar>
#include <QProgressDialog>
#include <QPushButton>
#include <QSettings>
#include <QStatusBar>
#include <QTest>
#include <QUndoStack>
#include <memory>

using namespace kw;

namespace {

QString samplePath(const char* name) {
    return QStringLiteral(KW_SAMPLES_DIR "/") + QLatin1String(name) + QStringLiteral(".knot");
}
QString dataPath(const char* name) {
    return QStringLiteral(KW_TEST_DATA_DIR "/") + QLatin1String(name);
}
QString outputPath(const QString& name) {
    QDir().mkpath(QStringLiteral(KW_TEST_OUTPUT_DIR "/import"));
    return QStringLiteral(KW_TEST_OUTPUT_DIR "/import/") + name;
}

/// What the scripted dialogs were asked and answered.
struct Script {
    QString importPath;
    QString importFilter;
    QString savePath;
    QString suggestedSave;
    QMessageBox::StandardButton askAnswer = QMessageBox::Discard;
    bool cancelImport = false;
    QWidget* closeDuringImport = nullptr; ///< closed from the first progress update
    int imports = 0;
    int asks = 0;
    int saves = 0;
    QStringList errors;
    QStringList reports;
    QList<QPair<int, int>> progress; ///< (value, maximum) at each progress update
};

/// Pixels of the frame (sampled every 4th) that are not the background colour.
int coveredPixels(const QImage& frame) {
    const QRgb background = frame.pixel(2, 2);
    int covered = 0;
    for (int y = 0; y < frame.height(); y += 4)
        for (int x = 0; x < frame.width(); x += 4)
            covered += frame.pixel(x, y) != background;
    return covered;
}

} // namespace

class TestEditorImport : public QObject {
    Q_OBJECT
public:
    static void initMain() {
        QSurfaceFormat::setDefaultFormat(OffscreenRenderer::requiredFormat());
        qputenv("XDG_CONFIG_HOME", QByteArrayLiteral(KW_TEST_OUTPUT_DIR "/editor-import-config"));
    }

private:
    std::unique_ptr<MainWindow> m_window;
    Script m_script;

    void scriptDialogs() {
        Script& s = m_script;
        MainWindow::Dialogs d;
        d.openFile = [](QWidget*, const QString&, const QString&) {
            return QString();
        };
        d.saveFile = [&s](QWidget*, const QString&, const QString&, const QString& suggested) {
            ++s.saves;
            s.suggestedSave = suggested;
            return s.savePath;
        };
        d.error = [&s](QWidget*, const QString&, const QString& text) {
            s.errors << text;
        };
        d.askSave = [&s](QWidget*, const QString&) {
            ++s.asks;
            return s.askAnswer;
        };
        d.importFile = [&s](QWidget*, const QString&, const QString& filter) {
            ++s.imports;
            s.importFilter = filter;
            return s.importPath;
        };
        d.information = [&s](QWidget*, const QString&, const QString& text) {
            s.reports << text;
        };
        d.importProgress = [&s](QProgressDialog* p) {
            s.progress.append({p->value(), p->maximum()});
            if (s.closeDuringImport && s.progress.size() == 1)
                s.closeDuringImport->close();
            if (s.cancelImport && !p->wasCanceled()) {
                // Press the dialog's own Cancel button, as a user would.
                p->show();
                auto* cancel = p->findChild<QPushButton*>();
                QVERIFY(cancel);
                QTest::mouseClick(cancel, Qt::LeftButton);
            }
        };
        m_window->setDialogs(std::move(d));
    }

    /// A fresh window showing the bicubic sample, saved (clean).
    void openWindow() {
        m_window = std::make_unique<MainWindow>();
        scriptDialogs();
        m_window->resize(960, 640);
        m_window->show();
        QVERIFY(QTest::qWaitForWindowExposed(m_window.get()));
        QVERIFY(m_window->openFile(samplePath("bicubic")));
        QTest::qWait(50);
        QVERIFY2(m_window->viewport()->glError(),
                 qPrintable(m_window->viewport()->glError().message()));
    }

    /// File ▸ Import… with the scripted answers.
    void triggerImport(const QString& path) {
        m_script.importPath = path;
        m_window->action(QStringLiteral("actionImport"))->trigger();
        QVERIFY(!m_window->isImporting());
    }

    /// Asserts the bicubic sample is still the unmodified document.
    void verifyBicubicKept(const Scene& before) {
        QVERIFY(m_window->document()->scene() == before);
        QCOMPARE(m_window->filePath(), samplePath("bicubic"));
        QVERIFY(m_window->importedFrom().isEmpty());
        QVERIFY(m_window->windowTitle().startsWith(QStringLiteral("bicubic.knot")));
        QVERIFY(!m_window->isWindowModified());
        QVERIFY(m_script.reports.isEmpty());
    }

private Q_SLOTS:
    void initTestCase() {
        QCoreApplication::setOrganizationName(QStringLiteral("KnotworkImportTest"));
        QSettings().clear();
    }
    void cleanup() {
        if (m_window) {
            m_window->undoStack()->setClean();
            m_window->close();
        }
        m_window.reset();
        m_script = {};
    }

    void importActionFollowsOpenRecent() {
        openWindow();
        QAction* import = m_window->action(QStringLiteral("actionImport"));
        QVERIFY(import);
        QVERIFY(import->shortcut().isEmpty());
        auto* recent = m_window->findChild<QMenu*>(QStringLiteral("menuRecent"));
        QVERIFY(recent);
        const QList<QAction*> file = m_window->menuBar()->actions().first()->menu()->actions();
        const qsizetype at = file.indexOf(recent->menuAction());
        QVERIFY(at >= 0);
        QCOMPARE(file.value(at + 1), import);
    }

    void filterNamesFormatsAndUnavailability() {
        const QString with = importFileFilter(true);
        for (const char* entry :
             {"IGES (*.igs *.iges)", "STEP (*.stp *.step)", "BREP (*.brep *.brp)", "OBJ (*.obj)"})
            QVERIFY2(with.split(QStringLiteral(";;")).contains(QLatin1String(entry)), entry);
        QVERIFY(!with.contains(QStringLiteral("unavailable")));
        const QStringList without = importFileFilter(false).split(QStringLiteral(";;"));
        for (const char* format : {"IGES", "STEP", "BREP"}) {
            const auto it = std::find_if(without.begin(), without.end(), [&](const QString& f) {
                return f.startsWith(QLatin1String(format));
            });
            QVERIFY(it != without.end());
            QVERIFY2(it->contains(QStringLiteral("unavailable")) &&
                         it->contains(QStringLiteral("OpenCASCADE")),
                     qPrintable(*it));
        }
        QVERIFY(without.contains(QStringLiteral("OBJ (*.obj)")));
        // The dialog is given the filter of this build; cancelling it changes nothing.
        openWindow();
        const Scene before = m_window->document()->scene();
        triggerImport(QString());
        QCOMPARE(m_script.imports, 1);
        QCOMPARE(m_script.importFilter, importFileFilter(occtAvailable()));
        verifyBicubicKept(before);
    }

    void importsTeapotIges() {
        openWindow();
        const QString teapot = dataPath("teapot.igs");
        if (!occtAvailable()) { // the clear error of a build without OpenCASCADE
            const Scene before = m_window->document()->scene();
            triggerImport(teapot);
            QCOMPARE(m_script.errors.size(), 1);
            QVERIFY(m_script.errors.front().contains(occtUnavailableMessage()));
            verifyBicubicKept(before);
            QSKIP("built without OpenCASCADE: IGES import is unavailable (error checked)");
        }
        const QImage bicubicFrame = m_window->viewport()->grabFramebuffer();
        triggerImport(teapot);
        QVERIFY2(m_script.errors.isEmpty(), qPrintable(m_script.errors.join('\n')));
        QCOMPARE(m_script.asks, 0); // the document was saved
        QCOMPARE(m_window->document()->scene().surfaces.size(), size_t(32));
        QCOMPARE(m_window->selection()->currentSurface(),
                 m_window->document()->scene().surfaces.front().id);
        // Unsaved, named after the imported file, no .knot path yet.
        QVERIFY(m_window->windowTitle().startsWith(QStringLiteral("teapot.igs")));
        QVERIFY(m_window->isWindowModified());
        QVERIFY(m_window->filePath().isEmpty());
        QCOMPARE(m_window->importedFrom(), teapot);
        QCOMPARE(m_window->undoStack()->count(), 0);
        // teapot.igs needs its IGES numbering repaired: the report says so in a message box.
        QCOMPARE(m_script.reports.size(), 1);
        QVERIFY2(m_script.reports.front().contains(QStringLiteral("warning: ")),
                 qPrintable(m_script.reports.front()));
        QVERIFY(m_window->statusBar()->currentMessage().contains(QStringLiteral("32 surface")));
        // The progress dialog was updated and ended full.
        QVERIFY(!m_script.progress.isEmpty());
        QCOMPARE(m_script.progress.last().first, m_script.progress.last().second);
        QVERIFY(m_script.progress.last().second > 0);
        for (qsizetype k = 1; k < m_script.progress.size(); ++k)
            if (m_script.progress[k].second == m_script.progress[k - 1].second)
                QVERIFY(m_script.progress[k].first >= m_script.progress[k - 1].first);
        // The frame shows the teapot: covered, and not the bicubic's picture.
        QTest::qWait(50);
        const QImage frame = m_window->viewport()->grabFramebuffer();
        QVERIFY2(m_window->viewport()->glError(),
                 qPrintable(m_window->viewport()->glError().message()));
        QVERIFY2(coveredPixels(frame) > 200, qPrintable(QString::number(coveredPixels(frame))));
        QVERIFY(frame != bicubicFrame);

        // Importing again asks about the unsaved import; Cancel keeps it.
        m_script.askAnswer = QMessageBox::Cancel;
        triggerImport(dataPath("teapot.igs"));
        QCOMPARE(m_script.asks, 1);
        QCOMPARE(m_script.imports, 1);
        QCOMPARE(m_window->importedFrom(), teapot);

        // Save goes to Save As, suggesting teapot.knot next to the source; the result reloads.
        const QString saved = outputPath(QStringLiteral("teapot_imported.knot"));
        QFile::remove(saved);
        m_script.savePath = saved;
        m_window->action(QStringLiteral("actionSave"))->trigger();
        QCOMPARE(m_script.saves, 1);
        QCOMPARE(m_script.suggestedSave, QStringLiteral(KW_TEST_DATA_DIR "/teapot.knot"));
        QCOMPARE(m_window->filePath(), saved);
        QVERIFY(m_window->importedFrom().isEmpty());
        QVERIFY(!m_window->isWindowModified());
        QVERIFY(m_window->windowTitle().startsWith(QStringLiteral("teapot_imported.knot")));
        const auto reread = readKnotFile(saved);
        QVERIFY(reread);
        QCOMPARE(reread->surfaces, m_window->document()->scene().surfaces);
    }

    void truncatedIgesKeepsDocument() {
        QFile source(dataPath("teapot.igs"));
        QVERIFY(source.open(QIODevice::ReadOnly));
        QByteArray bytes = source.readAll();
        bytes.truncate(bytes.size() / 2);
        const QString truncated = outputPath(QStringLiteral("truncated.igs"));
        QFile out(truncated);
        QVERIFY(out.open(QIODevice::WriteOnly | QIODevice::Truncate));
        QCOMPARE(out.write(bytes), bytes.size());
        out.close();
        const auto refused = kw::importFile(truncated);
        QVERIFY(!refused);
        const QString importerMessage = refused.message();
        QVERIFY(!importerMessage.isEmpty());

        openWindow();
        const Scene before = m_window->document()->scene();
        triggerImport(truncated);
        QCOMPARE(m_script.errors, QStringList{importerMessage});
        verifyBicubicKept(before);
    }

    void cancelKeepsDocument() {
        if (!occtAvailable())
            QSKIP("built without OpenCASCADE: no cancellable IGES import");
        openWindow();
        const Scene before = m_window->document()->scene();
        m_script.cancelImport = true;
        triggerImport(dataPath("hammer.iges"));
        QVERIFY(!m_script.progress.isEmpty());
        QVERIFY2(m_script.errors.isEmpty(), qPrintable(m_script.errors.join('\n')));
        verifyBicubicKept(before);
        // The importer itself stopped (its "cancelled" error), not just its result dropped.
        const QString status = m_window->statusBar()->currentMessage();
        QCOMPARE(status, dataPath("hammer.iges") + QStringLiteral(": import cancelled"));
        // The window works on: the same file imports when not cancelled.
        m_script.cancelImport = false;
        triggerImport(dataPath("hammer.iges"));
        QCOMPARE(m_window->document()->scene().surfaces.size(), size_t(45));
    }

    void closingDuringImportCancelsIt() {
        if (!occtAvailable())
            QSKIP("built without OpenCASCADE: no cancellable IGES import");
        openWindow();
        const Scene before = m_window->document()->scene();
        m_script.closeDuringImport = m_window.get();
        triggerImport(dataPath("hammer.iges"));
        QVERIFY(m_window->isVisible()); // the close was refused while importing
        verifyBicubicKept(before);
        QCOMPARE(m_window->statusBar()->currentMessage(),
                 dataPath("hammer.iges") + QStringLiteral(": import cancelled"));
        QVERIFY(m_window->close()); // and works once the import is over
    }

    void importsObj() {
        const auto sphere = readKnotFile(samplePath("sphere"));
        QVERIFY(sphere);
        const QString obj = outputPath(QStringLiteral("sphere.obj"));
        QString error;
        KW_VERIFY_OK(writeFileBytes(obj, writeObj(*sphere)));

        openWindow();
        triggerImport(obj);
        QVERIFY2(m_script.errors.isEmpty(), qPrintable(m_script.errors.join('\n')));
        QCOMPARE(m_window->document()->scene().surfaces, sphere->surfaces);
        QCOMPARE(m_window->importedFrom(), obj);
        QVERIFY(m_window->windowTitle().startsWith(QStringLiteral("sphere.obj")));
        QVERIFY(m_window->isWindowModified());
        QVERIFY(m_script.reports.isEmpty()); // nothing to report: status bar only
        QVERIFY(m_window->statusBar()->currentMessage().startsWith(QStringLiteral("Imported")));
        QCOMPARE(m_script.progress.last(), qMakePair(1, 1)); // OBJ has no steps: full at the end
        QTest::qWait(50);
        QVERIFY(coveredPixels(m_window->viewport()->grabFramebuffer()) > 200);
    }

    void unknownFileTypeIsAnError() {
        openWindow();
        const Scene before = m_window->document()->scene();
        const QString text = outputPath(QStringLiteral("notes.txt"));
        KW_VERIFY_OK(writeFileBytes(text, "not a model\n"));
        triggerImport(text);
        QCOMPARE(m_script.errors.size(), 1);
        QVERIFY2(m_script.errors.front().contains(QStringLiteral("unknown file type")),
                 qPrintable(m_script.errors.front()));
        verifyBicubicKept(before);
    }
};

QTEST_MAIN(TestEditorImport)
#include "tst_editor_import.moc"
