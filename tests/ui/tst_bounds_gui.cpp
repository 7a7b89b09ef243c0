// Bounded on every input, where a display is needed: the editor's File ▸ Open and File ▸ Import
// and `knotwork render` answer a device, a FIFO and a directory at once, and `render` names a
// full disk's cause for every image type.
#include "knotwork_process.h"
#include "render/offscreen_renderer.h"
#include "ui/mainwindow.h"

#include <QAction>
#include <QDir>
#include <QElapsedTimer>
#include <QFile>
#include <QTemporaryDir>
#include <QTest>
#include <sys/stat.h>

using namespace kw;

class TestBoundsGui : public QObject {
    Q_OBJECT
public:
    static void initMain() {
        QSurfaceFormat::setDefaultFormat(OffscreenRenderer::requiredFormat());
        qputenv("XDG_CONFIG_HOME", QByteArrayLiteral(KW_TEST_OUTPUT_DIR "/bounds-gui-config"));
    }

private:
    QTemporaryDir m_work{QStringLiteral(KW_TEST_OUTPUT_DIR "/bounds-gui-XXXXXX")};
    QString work(const QString& name) const { return m_work.filePath(name); }

    // Every non-regular input, with the kind its error must name.
    QList<QPair<QString, QString>> inputs() const {
        return {{work(QStringLiteral("zero.knot")),
                 QStringLiteral("a symbolic link to a character device")},
                {work(QStringLiteral("zero.igs")),
                 QStringLiteral("a symbolic link to a character device")},
                {work(QStringLiteral("fifo.knot")), QStringLiteral("a FIFO (named pipe)")},
                {work(QStringLiteral("fifo.obj")), QStringLiteral("a FIFO (named pipe)")},
                {work(QStringLiteral("folder.knot")), QStringLiteral("a directory")},
                {work(QStringLiteral("folder.step")), QStringLiteral("a directory")}};
    }

private Q_SLOTS:
    void initTestCase() {
        QVERIFY(m_work.isValid());
        QVERIFY(QFile::link(QStringLiteral("/dev/zero"), work(QStringLiteral("zero.knot"))));
        QVERIFY(QFile::link(QStringLiteral("/dev/zero"), work(QStringLiteral("zero.igs"))));
        for (const char* name : {"fifo.knot", "fifo.obj"})
            QCOMPARE(::mkfifo(QFile::encodeName(work(QLatin1String(name))).constData(), 0600), 0);
        QVERIFY(QDir(m_work.path()).mkpath(QStringLiteral("folder.knot")));
        QVERIFY(QDir(m_work.path()).mkpath(QStringLiteral("folder.step")));
    }

    void editorOpenAndImportAnswerAtOnce() {
        MainWindow window;
        QStringList errors;
        MainWindow::Dialogs d;
        QString importPath;
        d.error = [&](QWidget*, const QString&, const QString& text) {
            errors << text;
        };
        d.importFile = [&](QWidget*, const QString&, const QString&) {
            return importPath;
        };
        d.openFile = [](QWidget*, const QString&, const QString&) {
            return QString();
        };
        window.setDialogs(std::move(d));
        window.show();
        QVERIFY(QTest::qWaitForWindowExposed(&window));
        for (const auto& [path, kind] : inputs()) {
            for (const bool import : {false, true}) {
                errors.clear();
                QElapsedTimer clock;
                clock.start();
                const bool ok =
                    import ? bool(window.importFile(path)) : bool(window.openFile(path));
                const qint64 ms = clock.elapsed();
                QVERIFY2(!ok, qPrintable(path));
                QVERIFY2(ms < 2000, qPrintable(QStringLiteral("%1: %2 ms").arg(path).arg(ms)));
                QCOMPARE(errors.size(), 1);
                QVERIFY2(errors[0].contains(QStringLiteral("not a regular file: it is ") + kind),
                         qPrintable(errors[0]));
                QVERIFY2(!errors[0].contains(QLatin1Char('\n')), qPrintable(errors[0]));
            }
        }
    }

    void renderAnswersAtOnce() {
        for (const auto& [path, kind] : inputs()) {
            QElapsedTimer clock;
            clock.start();
            const Run r = knotwork({QStringLiteral("render"), path, QStringLiteral("-o"),
                                    work(QStringLiteral("out.png"))},
                                   QProcessEnvironment::systemEnvironment(), 30000);
            const qint64 ms = clock.elapsed();
            QCOMPARE(r.code, 1);
            QVERIFY2(ms < 5000, qPrintable(QStringLiteral("%1: %2 ms").arg(path).arg(ms)));
            QVERIFY2(r.err.contains(QStringLiteral("not a regular file: it is ") + kind),
                     qPrintable(r.err));
            QVERIFY2(!r.err.trimmed().contains(QLatin1Char('\n')), qPrintable(r.err));
        }
    }

    void renderNamesAFullDisk_data() {
        QTest::addColumn<QString>("suffix");
        for (const char* s : {"png", "exr", "tif", "jpg"})
            QTest::newRow(s) << QString::fromLatin1(s);
    }

    void renderNamesAFullDisk() {
        QFETCH(QString, suffix);
        const QString full = work(QStringLiteral("full"));
        QVERIFY(QDir().mkpath(full));
        QProcessEnvironment e = QProcessEnvironment::systemEnvironment();
        e.insert(QStringLiteral("LD_PRELOAD"), QStringLiteral(KW_FAILWRITE_LIB));
        e.insert(QStringLiteral("KW_FAIL_WRITES_UNDER"), full);
        const Run r =
            knotwork({QStringLiteral("render"), QStringLiteral(KW_SAMPLES_DIR "/bicubic.knot"),
                      QStringLiteral("-o"), full + QStringLiteral("/out.") + suffix},
                     e, 120000);
        QCOMPARE(r.code, 1);
        // libjpeg (inside OpenImageIO) ends the process on a write error with its own words;
        // the temporary file must go all the same.
        QVERIFY2(r.err.contains(QLatin1String(suffix == QLatin1String("jpg")
                                                  ? "out of disk space"
                                                  : "No space left on device")),
                 qPrintable(r.err));
        QVERIFY2(
            QDir(full).entryList(QDir::AllEntries | QDir::NoDotAndDotDot | QDir::Hidden).isEmpty(),
            "a temporary file was left");
    }
};

QTEST_MAIN(TestBoundsGui)
#include "tst_bounds_gui.moc"
