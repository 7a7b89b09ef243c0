// Autosave and crash recovery in the editor, under Xvfb: an editor process
// with unsaved edits is killed with SIGKILL, and the next start offers the autosaved edits and
// restores them exactly; recovery files follow the clean state; Save keeps one .bak; an editor
// killed during Save leaves the old or the new complete file.
// The killed editor is this test binary run as `tst_recovery --editor-child FILE EXPECTED`:
// the real MainWindow and autosave timer, with edits pushed as undo commands.
#include "editor_test_util.h"
#include "expected_test_util.h"
#include "model/io/knotfile.h"
#include "model_fixtures.h"
#include "render/offscreen_renderer.h"
#include "ui/autosave.h"
#include "ui/edit/commands.h"

#include <QApplication>
#include <QDir>
#include <QElapsedTimer>
#include <QFile>
#include <QProcess>
#include <QRandomGenerator>
#include <QSettings>
#include <QUndoStack>
#include <csignal>
#include <cstdio>

using namespace kw;
using namespace kwtest;

namespace {

const QString kWorkDir = QStringLiteral(KW_TEST_OUTPUT_DIR "/recovery");

QByteArray fileBytes(const QString& path) {
    QFile f(path);
    return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
}

/// Four edits of four kinds on the first surface, as the panels and the viewport make them.
bool editFirstSurface(MainWindow& w) {
    Document* d = w.document();
    QUndoStack* stack = w.undoStack();
    const Surface& s = d->scene().surfaces.front();
    const glm::dvec3 p = s.geometry.points[5];
    return pushCommand(stack, MoveControlPoints::create(d, s.id, {5}, {p},
                                                        {p + glm::dvec3(0.25, -0.5, 1.0 / 3.0)})) &&
           pushCommand(stack, SetWeight::create(d, s.id, 2, 1.75)) &&
           pushCommand(stack, RenameSurface::create(d, s.id, QStringLiteral("Recovered"))) &&
           pushCommand(stack, SetPartitions::create(d, s.id, 17, 9));
}

/// The editor that gets killed: opens FILE, edits, writes the expected scene to EXPECTED, waits
/// until its recovery file holds exactly that scene, prints READY and runs until killed.
int runChild(int argc, char** argv) {
    QApplication app(argc, argv);
    QCoreApplication::setOrganizationName(QStringLiteral("KnotworkTest"));
    if (argc < 4)
        return 2;
    MainWindow w;
    w.show();
    if (!w.openFile(QString::fromLocal8Bit(argv[2])) || !editFirstSurface(w))
        return 3;
    if (!writeKnotFile(QString::fromLocal8Bit(argv[3]), w.document()->scene()))
        return 4;
    QElapsedTimer clock;
    clock.start();
    while (clock.elapsed() < 60000) {
        QCoreApplication::processEvents(QEventLoop::AllEvents, 50);
        const auto saved = readKnotFile(w.autosave()->scenePath());
        if (saved && *saved == w.document()->scene()) {
            std::printf("READY\n");
            std::fflush(stdout);
            return app.exec();
        }
    }
    return 5;
}

/// A scene large enough that a save takes a while (about 8 MB as .knot).
Scene bigScene() {
    return kw::test::bigFlatScene(250);
}

/// The editor killed during Save: opens FILE, then renames the surface to "Save K" and saves
/// FILE (with its .bak) for K = 1, 2, ... until killed, printing "SAVING K" before and
/// "SAVED K" after each save.
int runSaveChild(int argc, char** argv) {
    QApplication app(argc, argv);
    QCoreApplication::setOrganizationName(QStringLiteral("KnotworkTest"));
    if (argc < 3)
        return 2;
    const QString path = QString::fromLocal8Bit(argv[2]);
    MainWindow w;
    w.show();
    if (!w.openFile(path))
        return 3;
    QCoreApplication::processEvents();
    for (int k = 1;; ++k) { // no event processing: back-to-back saves, nothing else
        const SurfaceId id = w.document()->scene().surfaces.front().id;
        if (!pushCommand(w.undoStack(),
                         RenameSurface::create(w.document(), id, QStringLiteral("Save %1").arg(k))))
            return 4;
        std::printf("SAVING %d\n", k);
        std::fflush(stdout);
        if (!w.saveFile(path))
            return 5;
        std::printf("SAVED %d\n", k);
        std::fflush(stdout);
    }
}

} // namespace

class TestRecovery : public QObject {
    Q_OBJECT

    QString m_plate; ///< a copy of the trimmed_plate sample in kWorkDir
    QByteArray m_plateBytes;

    /// A window with scripted dialogs; askRecover answers `answer` and records the question.
    std::unique_ptr<MainWindow> window(DialogScript& script, QMessageBox::StandardButton answer,
                                       QStringList* asked) {
        auto w = std::make_unique<MainWindow>();
        MainWindow::Dialogs d; // as scriptDialogs, plus the recovery question
        d.openFile = [&script](QWidget*, const QString&, const QString&) {
            return script.openPath;
        };
        d.saveFile = [&script](QWidget*, const QString&, const QString&, const QString&) {
            return script.savePath;
        };
        d.error = [&script](QWidget*, const QString&, const QString& text) {
            script.errors << text;
        };
        d.askSave = [&script](QWidget*, const QString&) {
            ++script.asks;
            return script.askAnswer;
        };
        d.askRecover = [answer, asked](QWidget*, const QString& text) {
            asked->append(text);
            return answer;
        };
        w->setDialogs(std::move(d));
        return w;
    }

private Q_SLOTS:
    void init() {
        QSettings().clear();
        QSettings().setValue(kAutosaveIntervalKey, 1);
        QDir(Autosave::directory()).removeRecursively();
        QDir(kWorkDir).removeRecursively();
        QVERIFY(QDir().mkpath(kWorkDir));
        m_plate = kWorkDir + QStringLiteral("/plate.knot");
        QVERIFY(QFile::copy(samplePath("trimmed_plate"), m_plate));
        m_plateBytes = fileBytes(m_plate);
    }

    void killedEditorIsRecoveredExactly() {
        const QString expectedPath = kWorkDir + QStringLiteral("/expected.knot");
        QProcess child;
        child.start(QCoreApplication::applicationFilePath(),
                    {QStringLiteral("--editor-child"), m_plate, expectedPath});
        QVERIFY(child.waitForStarted());
        QByteArray out;
        QElapsedTimer clock;
        clock.start();
        while (!out.contains("READY") && child.state() == QProcess::Running &&
               clock.elapsed() < 120000) {
            child.waitForReadyRead(500);
            out += child.readAllStandardOutput();
        }
        QVERIFY2(out.contains("READY"),
                 qPrintable(QStringLiteral("child: exit %1, stderr %2")
                                .arg(child.exitCode())
                                .arg(QString::fromLocal8Bit(child.readAllStandardError()))));
        child.kill(); // SIGKILL: no destructor, no clean-up
        QVERIFY(child.waitForFinished(10000));
        QCOMPARE(child.exitStatus(), QProcess::CrashExit);

        const std::vector<Recovery> orphans = Autosave::orphans();
        QCOMPARE(orphans.size(), size_t(1));
        QCOMPARE(orphans[0].originalPath, m_plate);

        DialogScript script;
        QStringList asked;
        auto w = window(script, QMessageBox::Yes, &asked);
        w->show();
        QVERIFY(QTest::qWaitForWindowExposed(w.get()));
        QVERIFY(w->offerRecovery());
        QCOMPARE(asked.size(), 1);
        QVERIFY2(asked[0].contains(QLatin1String("plate.knot")), qPrintable(asked[0]));
        const auto expected = readKnotFile(expectedPath);
        QVERIFY(expected);
        QVERIFY(*expected != *readKnotFile(m_plate));          // the edits did change something
        QVERIFY(w->document()->scene() == *expected);          // every edit, exactly
        QCOMPARE(w->filePath(), m_plate);
        QVERIFY(!w->undoStack()->isClean());
        QVERIFY(w->isWindowModified());
        QCOMPARE(fileBytes(m_plate), m_plateBytes); // the user's file was never touched
        QVERIFY(script.errors.isEmpty());
        // The restored edits are autosaved under this session at once; the old file is gone.
        QVERIFY(Autosave::orphans().empty());
        QVERIFY([&] {
            const auto autosaved = readKnotFile(w->autosave()->scenePath());
            return autosaved && *autosaved == *expected;
        }());

        // Save: the file gets the edits, the previous version is kept, recovery files go.
        QVERIFY(w->saveFile(m_plate));
        // Save also writes the view's camera and partition mode;
        // everything else is the edits.
        auto written = readKnotFile(m_plate);
        QVERIFY(written && written->camera.authored);
        QVERIFY(!written->display.partitionMode.isEmpty());
        written->camera = expected->camera;
        written->display = expected->display;
        QVERIFY(*written == *expected);
        QCOMPARE(fileBytes(m_plate + QStringLiteral(".bak")), m_plateBytes);
        QVERIFY(!QFile::exists(w->autosave()->scenePath()));
        QVERIFY(!w->offerRecovery()); // nothing left to offer
        QCOMPARE(asked.size(), 1);
    }

    void discardDeletesAndLaterKeeps() {
        // A recovery file with no lock: its editor is gone.
        const QString base = Autosave::directory() + QStringLiteral("/session-999999");
        QVERIFY(QDir().mkpath(Autosave::directory()));
        QVERIFY(writeKnotFile(base + QStringLiteral(".knot"), *readKnotFile(m_plate)));
        DialogScript script;
        QStringList asked;
        {
            auto later = window(script, QMessageBox::Cancel, &asked);
            QVERIFY(!later->offerRecovery());
            QCOMPARE(asked.size(), 1);
            QVERIFY(asked[0].contains(QLatin1String("an untitled document")));
            QVERIFY(later->document()->scene().surfaces.empty());
        }
        QVERIFY(QFile::exists(base + QStringLiteral(".knot")));
        auto discard = window(script, QMessageBox::Discard, &asked);
        QVERIFY(!discard->offerRecovery());
        QCOMPARE(asked.size(), 2);
        QVERIFY(!QFile::exists(base + QStringLiteral(".knot")));
        QVERIFY(discard->document()->scene().surfaces.empty());
    }

    void recoveryFileFollowsTheCleanState() {
        DialogScript script;
        script.askAnswer = QMessageBox::Discard;
        QStringList asked;
        auto w = window(script, QMessageBox::Cancel, &asked);
        QVERIFY(w->openFile(m_plate));
        const QString recovery = w->autosave()->scenePath();
        QVERIFY(!QFile::exists(recovery));
        QVERIFY(editFirstSurface(*w));
        QTRY_VERIFY_WITH_TIMEOUT(QFile::exists(recovery), 10000);
        QTRY_VERIFY_WITH_TIMEOUT(
            [&] {
                const auto saved = readKnotFile(recovery);
                return saved && *saved == w->document()->scene();
            }(),
            10000);
        w->undoStack()->setIndex(0); // undone to the saved state: nothing to recover
        QVERIFY(!QFile::exists(recovery));
        w->undoStack()->redo();
        QTRY_VERIFY_WITH_TIMEOUT(QFile::exists(recovery), 10000);
        // A normal close (unsaved changes discarded) leaves nothing behind.
        QVERIFY(w->close());
        QCOMPARE(script.asks, 1);
        w.reset();
        QVERIFY(!QFile::exists(recovery));
        QVERIFY(Autosave::orphans().empty());
    }

    void intervalZeroTurnsAutosaveOff() {
        QSettings().setValue(kAutosaveIntervalKey, 0);
        DialogScript script;
        QStringList asked;
        auto w = window(script, QMessageBox::Cancel, &asked);
        QVERIFY(w->openFile(m_plate));
        QVERIFY(editFirstSurface(*w));
        QTest::qWait(2500);
        QVERIFY(!QFile::exists(w->autosave()->scenePath()));
        w->undoStack()->setClean();
    }

    void saveKeepsOneBackupWhenAsked() {
        DialogScript script;
        QStringList asked;
        auto w = window(script, QMessageBox::Cancel, &asked);
        const QString bak = m_plate + QStringLiteral(".bak");
        QVERIFY(w->openFile(m_plate));
        QVERIFY(editFirstSurface(*w));
        QVERIFY(w->saveFile(m_plate));
        QCOMPARE(fileBytes(bak), m_plateBytes);
        const QByteArray firstSave = fileBytes(m_plate);
        QVERIFY(firstSave != m_plateBytes);
        w->undoStack()->undo();
        QVERIFY(w->saveFile(m_plate));
        QCOMPARE(fileBytes(bak), firstSave); // one generation: the previous save
        QSettings().setValue(kKeepBackupKey, false);
        w->undoStack()->undo();
        QVERIFY(w->saveFile(m_plate));
        QCOMPARE(fileBytes(bak), firstSave); // not replaced when turned off
        // A new file has no previous version.
        const QString fresh = kWorkDir + QStringLiteral("/fresh.knot");
        QSettings().setValue(kKeepBackupKey, true);
        QVERIFY(w->saveFile(fresh));
        QVERIFY(!QFile::exists(fresh + QStringLiteral(".bak")));
    }

    // kill -9 of the editor at random moments while it saves a large file again and again:
    // the file and its .bak always hold a complete scene, the old version or the new one
    // (at least 20 trials). tst_reliability does the same for convert.
    void killDuringSaveKeepsACompleteFile() {
        QSettings().setValue(kAutosaveIntervalKey, 0); // only Save writes
        const Scene original = bigScene();
        const QString path = kWorkDir + QStringLiteral("/big.knot");
        const QString backup = path + QStringLiteral(".bak");
        QString error;
        QRandomGenerator rng(14);
        int midSave = 0;
        for (int trial = 0; trial < 20; ++trial) {
            QFile::remove(backup);
            KW_VERIFY_OK(writeKnotFile(path, original));
            QProcess child;
            child.start(QCoreApplication::applicationFilePath(),
                        {QStringLiteral("--save-child"), path});
            QVERIFY(child.waitForStarted());
            // Save 2 times one save (SAVING 2 to SAVED 2); kill at a random moment of save 3.
            QByteArray out;
            QElapsedTimer clock;
            clock.start();
            qint64 seen = 0; // when `line` arrived
            const auto waitFor = [&](const QByteArray& line) {
                while (!out.contains(line) && child.state() == QProcess::Running &&
                       clock.elapsed() < 120000) {
                    child.waitForReadyRead(100);
                    out += child.readAllStandardOutput();
                }
                seen = clock.elapsed();
                return out.contains(line);
            };
            const bool started = waitFor("SAVING 2");
            const qint64 start = seen;
            QVERIFY2(started && waitFor("SAVED 2") && waitFor("SAVING 3"),
                     qPrintable(QStringLiteral("child: exit %1, stderr %2")
                                    .arg(child.exitCode())
                                    .arg(QString::fromLocal8Bit(child.readAllStandardError()))));
            const qint64 oneSave = std::max<qint64>(seen - start, 2);
            QTest::qWait(int(rng.bounded(int(oneSave))));
            // The child saves until killed: if it ended by itself, say how (its exit code and
            // stderr), not only that waiting failed.
            QVERIFY2(child.state() == QProcess::Running,
                     qPrintable(QStringLiteral("trial %1: the child ended by itself: exit %2, "
                                               "stderr %3")
                                    .arg(trial)
                                    .arg(child.exitCode())
                                    .arg(QString::fromLocal8Bit(child.readAllStandardError()))));
            ::kill(pid_t(child.processId()), SIGKILL);
            // Generous: tearing down a process with a GL context takes long on a loaded machine.
            QVERIFY2(child.waitForFinished(60000) || child.state() == QProcess::NotRunning,
                     qPrintable(QStringLiteral("trial %1: no exit 60 s after SIGKILL").arg(trial)));
            QCOMPARE(child.exitStatus(), QProcess::CrashExit);
            out += child.readAllStandardOutput();
            const QList<QByteArray> lines = out.trimmed().split('\n');
            const bool duringSave = lines.last().startsWith("SAVING");
            midSave += duringSave ? 1 : 0;
            const int lastStarted = lines.last().split(' ').value(1).toInt();

            // Both files reopen, with the original geometry and a name some save wrote.
            for (const QString& file : {path, backup}) {
                if (file == backup && !QFile::exists(backup))
                    continue; // killed before the first .bak was complete
                const auto now = readKnotFile(file);
                QVERIFY2(now,
                         qPrintable(QStringLiteral("trial %1: %2").arg(trial).arg(now.message())));
                QCOMPARE(now->surfaces.size(), size_t(1));
                QVERIFY(now->surfaces.front().geometry == original.surfaces.front().geometry);
                const QString name = now->surfaces.front().name;
                const int k = name.startsWith(QLatin1String("Save "))
                                  ? name.mid(5).toInt()
                                  : (name == QLatin1String("big") ? 0 : -1);
                QVERIFY2(k >= 0 && k <= lastStarted,
                         qPrintable(QStringLiteral("trial %1: %2 holds '%3' after save %4 began")
                                        .arg(trial)
                                        .arg(file, name)
                                        .arg(lastStarted)));
            }
        }
        qInfo("kill -9 during Save: 20 trials, %d of them killed while a save was running",
              midSave);
        QVERIFY(midSave >= 10); // the kills did hit saves, not only the time between them
    }
};

int main(int argc, char** argv) {
    // Before QApplication: GL 4.5 core for every context, settings (and so the recovery folder)
    // in the build tree. The child inherits the environment.
    QSurfaceFormat::setDefaultFormat(OffscreenRenderer::requiredFormat());
    qputenv("XDG_CONFIG_HOME", QByteArrayLiteral(KW_TEST_OUTPUT_DIR "/recovery-config"));
    if (argc >= 2 && qstrcmp(argv[1], "--editor-child") == 0)
        return runChild(argc, argv);
    if (argc >= 2 && qstrcmp(argv[1], "--save-child") == 0)
        return runSaveChild(argc, argv);
    QApplication app(argc, argv);
    QCoreApplication::setOrganizationName(QStringLiteral("KnotworkTest"));
    TestRecovery test;
    return QTest::qExec(&test, argc, argv);
}

#include "tst_recovery.moc"
