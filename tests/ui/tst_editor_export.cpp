// Editor GUI tests of File ▸ Export… and Export Selected… (STEP and IGES through the CAD child,
// the open-seam report) and of Save As with a CAD name, which exports and keeps the project.
#include "expected_test_util.h"
#include "knotwork_process.h"
#include "model/cad/cadimport.h"
#include "model/io/knotfile.h"
#include "model/nurbs/nurbs_shapes.h"
#include "render/offscreen_renderer.h"
#include "ui/mainwindow.h"

#include <QAction>
#include <QDir>
#include <QFile>
#include <QProgressDialog>
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
QString outputPath(const QString& name) {
    QDir().mkpath(QStringLiteral(KW_TEST_OUTPUT_DIR "/export"));
    return QStringLiteral(KW_TEST_OUTPUT_DIR "/export/") + name;
}
QByteArray readAll(const QString& path) {
    QFile f(path);
    return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
}

// A unit cube of six named bilinear faces, one corner of "top" lifted by `lift`.
Scene cube(double lift) {
    using glm::dvec3;
    const dvec3 c[8] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0},
                        {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
    NurbsSurface top = makeBilinear(c[4], c[5], c[6], c[7]);
    top.points[3].z += lift;
    const std::pair<const char*, NurbsSurface> faces[] = {
        {"bottom", makeBilinear(c[0], c[2], c[1], c[3])},
        {"top", top},
        {"front", makeBilinear(c[0], c[1], c[4], c[5])},
        {"back", makeBilinear(c[3], c[2], c[7], c[6])},
        {"left", makeBilinear(c[2], c[0], c[6], c[4])},
        {"right", makeBilinear(c[1], c[3], c[5], c[7])}};
    Scene s;
    std::uint32_t id = 1;
    for (const auto& [name, g] : faces) {
        Surface x;
        x.id = SurfaceId{id++};
        x.name = QString::fromLatin1(name);
        x.geometry = g;
        s.surfaces.push_back(x);
    }
    s.nextId = id;
    return s;
}

struct Script {
    QString savePath;
    QStringList errors;
    QStringList reports;
    int progressUpdates = 0;
};

} // namespace

class TestEditorExport : public QObject {
    Q_OBJECT
public:
    static void initMain() {
        QSurfaceFormat::setDefaultFormat(OffscreenRenderer::requiredFormat());
        qputenv("XDG_CONFIG_HOME", QByteArrayLiteral(KW_TEST_OUTPUT_DIR "/editor-export-config"));
    }

private:
    std::unique_ptr<MainWindow> m_window;
    Script m_script;

    void openWindow(const QString& project) {
        m_window = std::make_unique<MainWindow>();
        Script& s = m_script;
        MainWindow::Dialogs d;
        d.openFile = [](QWidget*, const QString&, const QString&) {
            return QString();
        };
        d.saveFile = [&s](QWidget*, const QString&, const QString&, const QString&) {
            return s.savePath;
        };
        d.error = [&s](QWidget*, const QString&, const QString& text) {
            s.errors << text;
        };
        d.askSave = [](QWidget*, const QString&) {
            return QMessageBox::Discard;
        };
        d.information = [&s](QWidget*, const QString&, const QString& text) {
            s.reports << text;
        };
        d.importProgress = [&s](QProgressDialog*) {
            ++s.progressUpdates;
        };
        m_window->setDialogs(std::move(d));
        m_window->resize(800, 600);
        m_window->show();
        QVERIFY(QTest::qWaitForWindowExposed(m_window.get()));
        QVERIFY(m_window->openFile(project));
    }

    // The written file read back by the importer: its surface count.
    static int facesIn(const QString& path) {
        const auto r = importFile(path);
        if (!r)
            qWarning("%s", qPrintable(r.message()));
        return r ? int(r->scene.surfaces.size()) : -1;
    }

private Q_SLOTS:
    void initTestCase() {
        QCoreApplication::setOrganizationName(QStringLiteral("KnotworkExportTest"));
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

    // File ▸ Export… writes STEP and IGES in the child; the document keeps its path and state.
    void exportWritesCadFiles() {
        openWindow(samplePath("teapot"));
        const int surfaces = int(m_window->document()->scene().surfaces.size());
        for (const char* name : {"teapot.step", "teapot.igs"}) {
            const QString path = outputPath(QString::fromLatin1(name));
            QFile::remove(path);
            m_script.savePath = path;
            m_window->action(QStringLiteral("actionExport"))->trigger();
            QVERIFY2(m_script.errors.isEmpty(), qPrintable(m_script.errors.join('\n')));
            QCOMPARE(facesIn(path), surfaces);
            QCOMPARE(m_window->filePath(), samplePath("teapot"));
            QVERIFY(!m_window->isWindowModified());
            QVERIFY(m_window->statusBar()->currentMessage().startsWith(QStringLiteral("Exported")));
        }
        QVERIFY(m_script.progressUpdates > 0); // the progress dialog ran
    }

    // Export Selected… writes the selected surface only.
    void exportSelectedWritesTheSelection() {
        openWindow(samplePath("teapot"));
        m_window->selectSurface(m_window->document()->scene().surfaces[3].id);
        const QString path = outputPath(QStringLiteral("selected.step"));
        QFile::remove(path);
        m_script.savePath = path;
        m_window->action(QStringLiteral("actionExportSelected"))->trigger();
        QVERIFY2(m_script.errors.isEmpty(), qPrintable(m_script.errors.join('\n')));
        QCOMPARE(facesIn(path), 1);
    }

    // The open seams of an edited solid are reported in the export's report.
    void exportReportsOpenSeams() {
        const QString project = outputPath(QStringLiteral("lifted_cube.knot"));
        QString error;
        KW_VERIFY_OK(writeKnotFile(project, cube(0.05)));
        openWindow(project);
        m_script.savePath = outputPath(QStringLiteral("lifted_cube.iges"));
        m_window->action(QStringLiteral("actionExport"))->trigger();
        QVERIFY2(m_script.errors.isEmpty(), qPrintable(m_script.errors.join('\n')));
        QCOMPARE(m_script.reports.size(), 1);
        QVERIFY2(m_script.reports[0].contains(QStringLiteral("seam between face 'top'")) ||
                     m_script.reports[0].contains(QStringLiteral("and face 'top'")),
                 qPrintable(m_script.reports[0]));
    }

    // Save As with a .step name exports (the project stays the .knot); a .brep name is refused.
    void saveAsWithCadNameExports() {
        openWindow(samplePath("bicubic"));
        const QString step = outputPath(QStringLiteral("bicubic_saved.step"));
        QFile::remove(step);
        m_script.savePath = step;
        m_window->action(QStringLiteral("actionSaveAs"))->trigger();
        QVERIFY2(m_script.errors.isEmpty(), qPrintable(m_script.errors.join('\n')));
        QVERIFY(readAll(step).startsWith("ISO-10303-21;")); // STEP, not the project's JSON
        QCOMPARE(facesIn(step), 1);
        QCOMPARE(m_window->filePath(), samplePath("bicubic"));
        QVERIFY2(m_window->statusBar()->currentMessage().contains(QStringLiteral("project")),
                 qPrintable(m_window->statusBar()->currentMessage()));
        const QString brep = outputPath(QStringLiteral("bicubic_saved.brep"));
        QFile::remove(brep);
        m_script.savePath = brep;
        m_window->action(QStringLiteral("actionSaveAs"))->trigger();
        QCOMPARE(m_script.errors.size(), 1);
        QVERIFY2(m_script.errors[0].startsWith(brep + QLatin1Char(':')),
                 qPrintable(m_script.errors[0]));
        QVERIFY(!QFile::exists(brep));
        QCOMPARE(m_window->filePath(), samplePath("bicubic"));
    }

    // `knotwork FILE.step` opens the part in the editor as File ▸ Import… would.
    void editorOpensCadFiles() {
        const QString shot = outputPath(QStringLiteral("screw.png"));
        QFile::remove(shot);
        const Run r = knotwork(
            {QStringLiteral(KW_TEST_DATA_DIR "/screw.step"), QStringLiteral("--screenshot"), shot});
        QVERIFY2(r.code == 0, qPrintable(r.err));
        QVERIFY(QFile::exists(shot));
        const Run missing = knotwork({outputPath(QStringLiteral("missing.step"))});
        QCOMPARE(missing.code, 1);
        QVERIFY2(missing.err.contains(QStringLiteral("no such file")), qPrintable(missing.err));
    }
};

QTEST_MAIN(TestEditorExport)
#include "tst_editor_export.moc"
