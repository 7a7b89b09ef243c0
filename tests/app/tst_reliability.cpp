// Reliability of knotwork convert and info, run as processes: the reported hostile
// inputs are refused with one line and no crash or hang; every file convert writes reopens;
// kill -9 while convert writes leaves the old or the new complete file.
#include "expected_test_util.h"
#include "knotwork_process.h"
#include "model/document/validation.h"
#include "model/io/knotfile.h"
#include "model/io/objfile.h"
#include "model_fixtures.h"

#include <QDir>
#include <QDirIterator>
#include <QElapsedTimer>
#include <QFileInfo>
#include <QProcess>
#include <QRandomGenerator>
#include <QTest>
#include <csignal>

using namespace kw;

namespace {

QString out(const QString& name) {
    return QStringLiteral(KW_TEST_OUTPUT_DIR "/reliability_") + name;
}
QString data(const QString& name) {
    return QStringLiteral(KW_TEST_DATA_DIR "/") + name;
}
QByteArray bytesOf(const QString& path) {
    QFile f(path);
    return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
}
bool writeBytes(const QString& path, const QByteArray& bytes) {
    QFile f(path);
    return f.open(QIODevice::WriteOnly) && f.write(bytes) == bytes.size();
}
bool oneLine(const QString& text) {
    return !text.trimmed().isEmpty() && !text.trimmed().contains(QLatin1Char('\n'));
}

// Every file the property test converts: the samples, tests/data (recursively) and the fuzz
// corpora in tests/fuzz when present.
QStringList everyInput() {
    QStringList files;
    const QStringList roots = {QStringLiteral(KW_SAMPLES_DIR), QStringLiteral(KW_TEST_DATA_DIR),
                               QStringLiteral(KW_SOURCE_DIR "/tests/fuzz")};
    const QStringList patterns = {"*.knot", "*.obj",  "*.igs",  "*.iges",
                                  "*.stp",  "*.step", "*.brep", "*.brp"};
    for (const QString& root : roots) {
        QDirIterator it(root, patterns, QDir::Files, QDirIterator::Subdirectories);
        while (it.hasNext())
            files << it.next();
    }
    files.sort();
    return files;
}

} // namespace

class TestReliability : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void reportedCases_data();
    void reportedCases();
    void longStepListIsRefusedAtOnce();
    void timeLimitStopsTheReader();
    void memoryLimitGivesAClearError();
    void everyWrittenFileReopens();
    void meshOutputIsCapped();
    void killDuringConvertKeepsACompleteFile();
};

void TestReliability::reportedCases_data() {
    QTest::addColumn<QString>("file");
    QTest::addColumn<int>("code");
    QTest::addColumn<QString>("expected"); // in stderr (exit 1) or the report (exit 0)
    // STEP: an ORIENTED_EDGE that refers to itself overflows OCCT's stack: the child crashes.
    QTest::newRow("self-referring STEP edge")
        << QStringLiteral("reliability/screw_selfref_edge.step") << 1
        << QStringLiteral("the STEP reader crashed on ");
    // BREP: OCCT's reader looped for ever on these.
    QTest::newRow("BREP cut in Locations")
        << QStringLiteral("reliability/pump_nut_cut_locations.brep") << 1
        << QStringLiteral("truncated or corrupt BREP");
    QTest::newRow("BREP cut in TShapes") << QStringLiteral("reliability/pump_nut_cut_tshapes.brep")
                                         << 1 << QStringLiteral("truncated or corrupt BREP");
    // OBJ: "cstype rat" without a type read past the tokens (SIGSEGV or double free).
    QTest::newRow("OBJ cstype rat") << QStringLiteral("reliability/cstype_rat_no_type.obj") << 1
                                    << QStringLiteral(":2: 'cstype' needs at least 2 value(s)");
    QTest::newRow("OBJ material out of range")
        << QStringLiteral("reliability/material_out_of_range.obj") << 1
        << QStringLiteral(":8: knotwork surface: material colour components must be in [0, 1]");
    // An open loop from OBJ is imported with a warning and saved closed.
    QTest::newRow("OBJ open trim loop") << QStringLiteral("reliability/open_trim_loop.obj") << 0
                                        << QStringLiteral("bridged by a straight segment");
    // "lights": [] is allowed by docs/FILE_FORMAT.md: info and convert agree.
    QTest::newRow("unlit .knot") << QStringLiteral("reliability/unlit.knot") << 0 << QString();
}

void TestReliability::reportedCases() {
    QFETCH(QString, file);
    QFETCH(int, code);
    QFETCH(QString, expected);
    const QString target = out(QFileInfo(file).completeBaseName() + QStringLiteral(".knot"));
    QFile::remove(target);
    QElapsedTimer clock;
    clock.start();
    const Run r =
        knotwork({QStringLiteral("convert"), data(file), target, QStringLiteral("--report")});
    QVERIFY2(clock.elapsed() < 60000, "convert took more than a minute");
    QVERIFY2(r.code == code, qPrintable(QStringLiteral("exit %1: %2").arg(r.code).arg(r.err)));
    if (code == 1) {
        QVERIFY2(oneLine(r.err), qPrintable(r.err));
        QVERIFY2(r.err.contains(expected), qPrintable(r.err));
        QVERIFY2(r.err.contains(QFileInfo(file).fileName()), qPrintable(r.err));
        QVERIFY(!QFileInfo::exists(target));
        return;
    }
    QVERIFY2(r.out.contains(expected), qPrintable(r.out));
    const Run info = knotwork({QStringLiteral("info"), target});
    QVERIFY2(info.code == 0, qPrintable(info.err));
}

// 400k numbers in one STEP entity: OCCT's parser is quadratic in a list's length.
void TestReliability::longStepListIsRefusedAtOnce() {
    QByteArray step = bytesOf(data(QStringLiteral("screw.step")));
    QByteArray list = "#99999 = B_SPLINE_CURVE_WITH_KNOTS('',1,(#1,#2),.UNSPECIFIED.,.F.,.F.,(";
    for (int i = 0; i < 400000; ++i)
        list += i ? ",0." : "0.";
    list += "),(0.,1.),.UNSPECIFIED.);\n";
    step.insert(step.indexOf("ENDSEC;", step.indexOf("DATA;")), list);
    const QString path = out(QStringLiteral("long_list.step"));
    QVERIFY(writeBytes(path, step));
    QElapsedTimer clock;
    clock.start();
    const Run r = knotwork({QStringLiteral("convert"), path, out(QStringLiteral("ll.knot"))});
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains(QStringLiteral("more than 50000 items")), qPrintable(r.err));
    QVERIFY2(clock.elapsed() < 30000, "the long list was not refused before parsing");
}

void TestReliability::timeLimitStopsTheReader() {
    const Run r = knotwork(
        {QStringLiteral("convert"), data(QStringLiteral("hammer.iges")),
         out(QStringLiteral("late.knot"))},
        environmentWith(QStringLiteral("KNOTWORK_CAD_TIME_LIMIT"), QStringLiteral("0.05")));
    QCOMPARE(r.code, 1);
    QVERIFY2(oneLine(r.err) && r.err.contains(QStringLiteral("did not finish within")) &&
                 r.err.contains(QStringLiteral("hammer.iges")),
             qPrintable(r.err));
}

void TestReliability::memoryLimitGivesAClearError() {
    const Run r =
        knotwork({QStringLiteral("convert"), data(QStringLiteral("hammer.iges")),
                  out(QStringLiteral("small.knot"))},
                 environmentWith(QStringLiteral("KNOTWORK_CAD_MEMORY_MB"), QStringLiteral("40")));
    QCOMPARE(r.code, 1);
    QVERIFY2(oneLine(r.err) && r.err.contains(QStringLiteral("hammer.iges")), qPrintable(r.err));
}

// The round-trip property: whatever convert accepts, it writes as .knot and OBJ files that
// reopen (info exit 0, and the OBJ converts back); whatever it refuses, it refuses with exit 1
// and one line.
void TestReliability::everyWrittenFileReopens() {
    const QStringList files = everyInput();
    QVERIFY(files.size() > 40);
    int accepted = 0;
    for (const QString& file : files) {
        const QString knot = out(QStringLiteral("prop.knot")),
                      obj = out(QStringLiteral("prop.obj"));
        QFile::remove(knot);
        QFile::remove(obj);
        const Run r = knotwork({QStringLiteral("convert"), file, knot});
        if (r.code == 1) {
            QVERIFY2(oneLine(r.err), qPrintable(file + QStringLiteral(": ") + r.err));
            continue;
        }
        QVERIFY2(r.code == 0, qPrintable(file + QStringLiteral(": ") + r.err));
        ++accepted;
        const Run info = knotwork({QStringLiteral("info"), knot});
        QVERIFY2(info.code == 0, qPrintable(file + QStringLiteral(" -> .knot: ") + info.err));
        // The OBJ writer in-process (the same writeObjFile convert uses; processes cost about
        // a second each on the shared CI machine): what it writes must read back valid.
        const auto scene = readKnotFile(knot);
        QVERIFY2(scene, qPrintable(scene.message()));
        KW_VERIFY_OK(writeObjFile(obj, *scene));
        Scene back;
        ImportReport report;
        const Status read = readObjFile(obj, back, report);
        QVERIFY2(read, qPrintable(file + QStringLiteral(": ") + read.message()));
        QVERIFY2(bool(checkScene(back)),
                 qPrintable(file + QStringLiteral(" OBJ: ") + checkScene(back).message()));
    }
    QVERIFY(accepted >= 10);
}

void TestReliability::meshOutputIsCapped() {
    const QString mesh = out(QStringLiteral("capped.obj"));
    QVERIFY(writeBytes(mesh, "old\n"));
    const QString teapot = QStringLiteral(KW_SAMPLES_DIR "/teapot.knot");
    // Refused at once from the vertex count (64 x 64 per cell would be gigabytes)...
    QElapsedTimer clock;
    clock.start();
    Run r = knotwork({QStringLiteral("convert"), teapot, mesh, QStringLiteral("--mesh"),
                      QStringLiteral("--subdivisions"), QStringLiteral("64")});
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains(QStringLiteral("larger than the limit of 1024 MB")), qPrintable(r.err));
    QVERIFY(clock.elapsed() < 20000);
    // ...or while writing, at a limit the user lowered; the old file stays.
    r = knotwork({QStringLiteral("convert"), teapot, mesh, QStringLiteral("--mesh"),
                  QStringLiteral("--max-mesh-mb"), QStringLiteral("1")});
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains(QStringLiteral("--max-mesh-mb")), qPrintable(r.err));
    QCOMPARE(bytesOf(mesh), QByteArray("old\n"));
    r = knotwork({QStringLiteral("convert"), teapot, mesh, QStringLiteral("--mesh"),
                  QStringLiteral("--max-mesh-mb"), QStringLiteral("100")});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY(bytesOf(mesh).startsWith("# Knotwork triangle mesh"));
}

// kill -9 at random moments while convert reads and writes a large file: the target is always
// the old file or the new complete one (QSaveFile writes a temporary file and renames it).
void TestReliability::killDuringConvertKeepsACompleteFile() {
    const Scene scene = kw::test::bigFlatScene(400); // a file of about 22 MB
    const QString source = out(QStringLiteral("kill_source.knot"));
    QString error;
    KW_VERIFY_OK(writeKnotFile(source, scene));
    const QString target = out(QStringLiteral("kill_target.knot"));
    const QByteArray old = bytesOf(QStringLiteral(KW_SAMPLES_DIR "/bicubic.knot"));
    QVERIFY(writeBytes(target, old));

    // One undisturbed run: how long convert takes, and the new file's bytes.
    const QString reference = out(QStringLiteral("kill_reference.knot"));
    QElapsedTimer clock;
    clock.start();
    const Run full = knotwork({QStringLiteral("convert"), source, reference});
    QVERIFY2(full.code == 0, qPrintable(full.err));
    const qint64 duration = clock.elapsed();
    const QByteArray complete = bytesOf(reference);
    QVERIFY(complete.size() > 10'000'000);

    int sawOld = 0, sawNew = 0;
    QRandomGenerator rng(14);
    for (int trial = 0; trial < 20; ++trial) {
        QProcess p;
        p.start(QStringLiteral(KW_KNOTWORK_BIN), {QStringLiteral("convert"), source, target});
        QVERIFY(p.waitForStarted());
        // Half the trials anywhere in the run, half in its second half, where it writes.
        const double from = trial % 2 ? 0.5 : 0.0;
        QTest::qWait(int(double(duration) * (from + rng.bounded(1.1 - from))));
        // processId() is 0 once the process has finished, and kill(0) would hit this test.
        if (const qint64 pid = p.processId(); pid > 0)
            ::kill(pid_t(pid), SIGKILL);
        p.waitForFinished();
        const QByteArray now = bytesOf(target);
        QVERIFY2(now == old || now == complete,
                 qPrintable(QStringLiteral("trial %1: %2 bytes, neither old nor new")
                                .arg(trial)
                                .arg(now.size())));
        (now == old ? sawOld : sawNew)++;
        if (now == complete)
            QVERIFY(writeBytes(target, old)); // start the next trial from the old file again
    }
    qInfo("kill -9 during convert: %d trials left the old file, %d the new one", sawOld, sawNew);
    // Temporary files of killed writers are left behind (QSaveFile cannot clean up after
    // SIGKILL); they never replace the target.
}

QTEST_GUILESS_MAIN(TestReliability)
#include "tst_reliability.moc"
