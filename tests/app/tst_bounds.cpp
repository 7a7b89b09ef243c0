// Bounded on every input: knotwork run as a process on what a hostile user would feed it
// (devices, FIFOs, directories, reproducers of slow CAD reads, huge tokens, random bytes, a full
// disk, kill -9 and SIGTERM during a CAD read). Each answer must come at once, as one short
// printable line, within the time and memory stated, and leave $TMPDIR as it was.
#include "knotwork_process.h"
#include "model/cad/cadprecheck.h"
#include "model/io/safetext.h"
#include "tests/support/expected_test_util.h"

#include <QDir>
#include <QElapsedTimer>
#include <QFile>
#include <QProcess>
#include <QRandomGenerator>
#include <QTemporaryDir>
#include <QTest>
#include <QThread>
#include <csignal>
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

using namespace kw;

namespace {

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

// IGES: `before` (the first 64 columns of a parameter record, trailing blanks cut) replaced
// by `after`, padded to keep the columns.
QByteArray igesWith(const QByteArray& file, const QByteArray& before, const QByteArray& after) {
    QList<QByteArray> lines = file.split('\n');
    for (QByteArray& l : lines)
        if (l.size() >= 73 && l.left(64).trimmed() == before) {
            l = after.leftJustified(64, ' ') + l.mid(64);
            return lines.join('\n');
        }
    return {};
}

// STEP: `entity` added as the last entity of the DATA section.
QByteArray stepWith(const QByteArray& file, const QByteArray& entity) {
    const qsizetype end = file.indexOf("ENDSEC;", file.indexOf("DATA;"));
    return end < 0 ? QByteArray() : file.left(end) + entity + '\n' + file.mid(end);
}

QByteArray stepList(int items, const char* separator) {
    QByteArray list = "#999999=CARTESIAN_POINT('',(";
    for (int k = 0; k < items; ++k) {
        if (k)
            list += separator;
        list += "0.";
    }
    return list + "));";
}

// BREP: the first edge's curve representations all end at parameter 0.
QByteArray brepEdgeRangeEndingAtZero(const QByteArray& file) {
    const qsizetype start = file.indexOf("\nEd\n");
    const qsizetype end = file.indexOf("\n0\n", start + 1);
    if (start < 0 || end < 0)
        return {};
    QList<QByteArray> lines = file.mid(start, end - start).split('\n');
    for (QByteArray& l : lines) {
        QList<QByteArray> words = l.simplified().split(' ');
        if (words.size() >= 5 && (words[0] == "1" || words[0] == "2")) {
            words.back() = "0";
            l = words.join(' ');
        }
    }
    return file.left(start) + lines.join('\n') + file.mid(end);
}

// BREP: the `index`-th trimmed curve ("8 FIRST LAST", 2D and 3D curves in file order) made to
// end at parameter 0.
QByteArray brepTrimEndingAtZero(const QByteArray& file, int index) {
    QList<QByteArray> lines = file.split('\n');
    int seen = 0;
    for (QByteArray& l : lines) {
        const QList<QByteArray> words = l.simplified().split(' ');
        if (words.size() == 3 && words[0] == "8" && seen++ == index) {
            l = "8 " + words[1] + " 0";
            return lines.join('\n');
        }
    }
    return {};
}

// BREP: the first pole of the first 2D B-spline curve replaced by `value`.
QByteArray brepPole(const QByteArray& file, const QByteArray& value) {
    QList<QByteArray> lines = file.split('\n');
    for (QByteArray& l : lines)
        if (l.startsWith("7 0 0  ")) {
            QList<QByteArray> words = l.simplified().split(' ');
            words[6] = value; // "7 rational periodic degree poles knots x y ..."
            l = words.join(' ');
            return lines.join('\n');
        }
    return {};
}

bool printableLine(const QString& text) {
    for (const QChar c : text) {
        const char16_t u = c.unicode();
        if (u < 0x20 || u == 0x7f || (u >= 0x80 && u < 0xa0))
            return false;
    }
    return true;
}

long long childrenMaxRssKiB() {
    rusage usage{};
    ::getrusage(RUSAGE_CHILDREN, &usage);
    return usage.ru_maxrss;
}

// The pid of a child of `parent` whose command line contains `needle`, or 0.
pid_t childOf(qint64 parent, const QByteArray& needle) {
    const QStringList pids = QDir(QStringLiteral("/proc")).entryList(QDir::Dirs);
    for (const QString& p : pids) {
        bool ok = false;
        const pid_t pid = pid_t(p.toInt(&ok));
        if (!ok)
            continue;
        const QByteArray stat = bytesOf(QStringLiteral("/proc/%1/stat").arg(pid));
        const QList<QByteArray> f = stat.mid(stat.lastIndexOf(')') + 2).split(' ');
        if (f.size() > 1 && f[1].toLongLong() == parent &&
            bytesOf(QStringLiteral("/proc/%1/cmdline").arg(pid)).contains(needle))
            return pid;
    }
    return 0;
}

// True once `pid` no longer runs (gone, or a zombie waiting for whoever adopted it).
bool gone(pid_t pid) {
    const QByteArray stat = bytesOf(QStringLiteral("/proc/%1/stat").arg(pid));
    return stat.isEmpty() || stat.mid(stat.lastIndexOf(')') + 2, 1) == "Z";
}

} // namespace

class TestBounds : public QObject {
    Q_OBJECT

    QTemporaryDir m_work{QStringLiteral(KW_TEST_OUTPUT_DIR "/bounds-XXXXXX")};
    QString m_tmp; // $TMPDIR of every knotwork run: must stay as it was

    QString work(const QString& name) const { return m_work.filePath(name); }
    QStringList tmpEntries() const {
        return QDir(m_tmp).entryList(QDir::AllEntries | QDir::Hidden | QDir::NoDotAndDotDot |
                                     QDir::System);
    }
    QProcessEnvironment env() const {
        QProcessEnvironment e = QProcessEnvironment::systemEnvironment();
        e.insert(QStringLiteral("TMPDIR"), m_tmp);
        return e;
    }

    struct Outcome {
        int code = -1;
        QString err;
        double seconds = 0;
    };
    Outcome run(const QStringList& args, QProcessEnvironment environment = {}) {
        if (environment.isEmpty())
            environment = env();
        QElapsedTimer clock;
        clock.start();
        const Run r = knotwork(args, environment, 30000);
        return {r.code, r.err, clock.elapsed() / 1000.0};
    }

    // The targets every reproducer must meet.
    void verifyBounded(const Outcome& o, const QString& what, double maxSeconds = 10.0) {
        const QString err = o.err.trimmed();
        QVERIFY2(o.code == 0 || o.code == 1,
                 qPrintable(QStringLiteral("%1: exit %2: %3").arg(what).arg(o.code).arg(err)));
        QVERIFY2(o.seconds <= maxSeconds,
                 qPrintable(QStringLiteral("%1: %2 s").arg(what).arg(o.seconds)));
        if (o.code == 1)
            QVERIFY2(!err.isEmpty(), qPrintable(what));
        QVERIFY2(!err.contains(QLatin1Char('\n')), qPrintable(what + QStringLiteral(": ") + err));
        QVERIFY2(err.size() <= 300, qPrintable(QStringLiteral("%1: %2 characters: %3")
                                                   .arg(what)
                                                   .arg(err.size())
                                                   .arg(err.left(400))));
        QVERIFY2(printableLine(err), qPrintable(what + QStringLiteral(": ") + err));
        QVERIFY2(tmpEntries().isEmpty(),
                 qPrintable(what + QStringLiteral(": left in $TMPDIR: ") + tmpEntries().join(' ')));
        QVERIFY2(childrenMaxRssKiB() <= (1LL << 20),
                 qPrintable(QStringLiteral("%1: %2 KiB").arg(what).arg(childrenMaxRssKiB())));
    }

private Q_SLOTS:
    void initTestCase();
    void notRegularFilesAnswerAtOnce_data();
    void notRegularFilesAnswerAtOnce();
    void reproducers_data();
    void reproducers();
    void garbageIsRefusedFromItsFirstBytes();
    void killOfConvertLeavesNoProcessAndNoFolder();
    void sigtermRemovesTheFolder();
    void fullDiskNamesTheCause_data();
    void fullDiskNamesTheCause();
    void stepListsCountItemsHoweverSeparated();
    void igesStringsAreNotNumbers();
    void messagesAreSafe();
};

void TestBounds::initTestCase() {
    QVERIFY(m_work.isValid());
    QVERIFY(QDir(m_work.path()).mkpath(QStringLiteral("tmp")));
    m_tmp = work(QStringLiteral("tmp"));
    QVERIFY(QFile::link(QStringLiteral("/dev/zero"), work(QStringLiteral("zero.knot"))));
    QVERIFY(QFile::link(QStringLiteral("/dev/zero"), work(QStringLiteral("zero.obj"))));
    QVERIFY(QFile::link(QStringLiteral("/dev/zero"), work(QStringLiteral("zero.igs"))));
    for (const char* name : {"fifo.knot", "fifo.step", "fifo.obj"})
        QCOMPARE(::mkfifo(QFile::encodeName(work(QLatin1String(name))).constData(), 0600), 0);
    QVERIFY(QDir(m_work.path()).mkpath(QStringLiteral("folder.knot")));
    QVERIFY(QDir(m_work.path()).mkpath(QStringLiteral("folder.brep")));
}

void TestBounds::notRegularFilesAnswerAtOnce_data() {
    QTest::addColumn<QStringList>("args");
    QTest::addColumn<QString>("kind");
    const struct {
        const char* file;
        const char* kind;
    } inputs[] = {{"zero.knot", "a symbolic link to a character device"},
                  {"zero.obj", "a symbolic link to a character device"},
                  {"zero.igs", "a symbolic link to a character device"},
                  {"fifo.knot", "a FIFO (named pipe)"},
                  {"fifo.step", "a FIFO (named pipe)"},
                  {"fifo.obj", "a FIFO (named pipe)"},
                  {"folder.knot", "a directory"},
                  {"folder.brep", "a directory"}};
    // /dev/zero itself: no extension, so info and eval read it as a .knot file.
    QTest::addRow("info /dev/zero") << QStringList{"info", "/dev/zero"} << "a character device";
    QTest::addRow("eval /dev/zero")
        << QStringList{"eval", "--surface", "1", "--uv", "0,0", "/dev/zero"}
        << "a character device";
    for (const auto& in : inputs) {
        const QString file = work(QLatin1String(in.file));
        const QString out = work(QStringLiteral("out.knot"));
        QTest::addRow("info %s", in.file) << QStringList{"info", file} << in.kind;
        QTest::addRow("convert %s", in.file) << QStringList{"convert", file, out} << in.kind;
        if (QString::fromLatin1(in.file).endsWith(QLatin1String(".knot")))
            QTest::addRow("eval %s", in.file)
                << QStringList{"eval", "--surface", "1", "--uv", "0,0", file} << in.kind;
        if (QString::fromLatin1(in.file).contains(QRegularExpression("\\.(igs|step|brep)$")))
            QTest::addRow("mesh %s", in.file)
                << QStringList{"mesh", file, "-o", work(QStringLiteral("out.obj"))} << in.kind;
    }
}

void TestBounds::notRegularFilesAnswerAtOnce() {
    QFETCH(QStringList, args);
    QFETCH(QString, kind);
    const Outcome o = run(args);
    verifyBounded(o, args.join(' '), 2.0);
    QCOMPARE(o.code, 1);
    QVERIFY2(o.err.contains(QStringLiteral("not a regular file: it is ") + kind),
             qPrintable(o.err));
    QVERIFY2(
        o.err.startsWith(args.value(args[0] == QLatin1String("mesh")
                                        ? 1
                                        : args.size() - 1 - (args[0] == QLatin1String("convert")))),
        qPrintable(o.err));
}

void TestBounds::reproducers_data() {
    QTest::addColumn<QString>("name");
    QTest::addColumn<QByteArray>("bytes");
    QTest::addColumn<int>("code");
    QTest::addColumn<QString>("expected"); // in stderr
    const QByteArray teapot = bytesOf(data(QStringLiteral("teapot.igs")));
    const QByteArray screw = bytesOf(data(QStringLiteral("screw.step")));
    const QByteArray nut = bytesOf(data(QStringLiteral("Pump_Nut.brep")));
    QVERIFY(!teapot.isEmpty() && !screw.isEmpty() && !nut.isEmpty());
    // Ran into the 62 s time limit.
    QTest::newRow("IGES coordinate 1.0D308")
        << "teapot_1e308.igs" << igesWith(teapot, "1.4,0.0,2.4,", "1.0D308,0.0,2.4,") << 1
        << "the value 1.0D308 is out of range";
    // The reader aborts (SIGABRT); its repaired copy was left in $TMPDIR.
    QTest::newRow("IGES type-128 count -2147483648")
        << "teapot_count.igs"
        << igesWith(teapot, "128,3,3,3,3,0,0,1,0,0,", "128,3,3,-2147483648,3,0,0,1,0,0,") << 1
        << "teapot_count.igs";
    QTest::newRow("IGES -inf coordinate")
        << "teapot_inf.igs" << igesWith(teapot, "1.4,0.0,2.4,", "1.4,-1.0D999,2.4,") << 1
        << "is infinite";
    // 25 to 68 s and 4.4 GB.
    QTest::newRow("STEP 100000 items separated by spaces")
        << "screw_spaces.step" << stepWith(screw, stepList(100000, " ")) << 1
        << "a list has more than 50000 items";
    QTest::newRow("STEP 60000 items on separate lines")
        << "screw_lines.step" << stepWith(screw, stepList(60000, "\n")) << 1
        << "a list has more than 50000 items";
    QTest::newRow("STEP coordinate 1.E400")
        << "screw_1e400.step" << stepWith(screw, "#999999=CARTESIAN_POINT('',(1.E400,0.,0.));") << 1
        << "is infinite";
    // 65 s.
    QTest::newRow("BREP edge range ending at 0")
        << "nut_range0.brep" << brepEdgeRangeEndingAtZero(nut) << 0 << "";
    // A trimmed curve whose range ends at 0 no longer holds its edges' ranges: OCCT's NURBS
    // conversion projected for a minute (the time limit); the face is now skipped at once.
    QTest::newRow("BREP trimmed p-curve ending at 0")
        << "nut_trim2d.brep" << brepTrimEndingAtZero(nut, 7) << 0 << "1 face(s) skipped";
    QTest::newRow("BREP trimmed 3D curve ending at 0")
        << "nut_trim3d.brep" << brepTrimEndingAtZero(nut, 10) << 0 << "2 face(s) skipped";
    // 45 s, then a face skipped.
    QTest::newRow("BREP 2D pole -inf")
        << "nut_inf.brep" << brepPole(nut, "-inf") << 1 << "the value -inf is infinite";
    QTest::newRow("BREP 2D pole nan")
        << "nut_nan.brep" << brepPole(nut, "nan") << 1 << "is not a number";
    QTest::newRow("BREP 2D pole 1e308")
        << "nut_1e308.brep" << brepPole(nut, "1e308") << 1 << "is out of range";
    // One error line was 1 to 3 MB, with a colour code and invalid UTF-8.
    QByteArray token = "\x1b[31m\xff\xfe";
    while (token.size() < 3'000'000)
        token += "1.5e3xyz";
    // Past the first 4 KiB, which are sniffed for control bytes.
    const QByteArray comment = "# " + QByteArray(5000, 'c') + '\n';
    QTest::newRow("OBJ 3 MB token")
        << "long_token.obj" << (comment + "v 1 2 " + token + "\n") << 1 << "\\x1b[31m";
    QTest::newRow("OBJ keyword with escape")
        << "escape.obj" << QByteArray("\x1b[31mv 1 2 3\n") << 1 << "\\x1b";
}

void TestBounds::reproducers() {
    QFETCH(QString, name);
    QFETCH(QByteArray, bytes);
    QFETCH(int, code);
    QFETCH(QString, expected);
    QVERIFY(!bytes.isEmpty());
    const QString file = work(name);
    QVERIFY(writeBytes(file, bytes));
    const Outcome o = run({QStringLiteral("convert"), file, work(QStringLiteral("out.knot"))});
    qInfo("%s: exit %d in %.2f s: %s", qPrintable(name), o.code, o.seconds,
          qPrintable(o.err.trimmed()));
    verifyBounded(o, name);
    QCOMPARE(o.code, code);
    QVERIFY2(o.err.contains(expected), qPrintable(o.err));
    QVERIFY2(o.err.startsWith(file) || o.err.contains(file), qPrintable(o.err));
    if (name.endsWith(QLatin1String(".obj")))
        QVERIFY2(o.err.contains(QChar(0x2026)) || name != QLatin1String("long_token.obj"),
                 qPrintable(o.err));
}

void TestBounds::garbageIsRefusedFromItsFirstBytes() {
    // 200 MB of random bytes under each reader's name (hard links: written once).
    constexpr qsizetype kBytes = 200LL << 20;
    const QString base = work(QStringLiteral("random.bin"));
    {
        QFile f(base);
        QVERIFY(f.open(QIODevice::WriteOnly));
        QByteArray block(1 << 20, Qt::Uninitialized);
        QRandomGenerator random(45);
        for (qsizetype written = 0; written < kBytes; written += block.size()) {
            random.fillRange(reinterpret_cast<quint32*>(block.data()), block.size() / 4);
            QCOMPARE(f.write(block), block.size());
        }
    }
    for (const char* name :
         {"random.obj", "random.knot", "random.igs", "random.step", "random.brep"}) {
        const QString file = work(QLatin1String(name));
        QVERIFY(QFile::link(base, file) || ::link(QFile::encodeName(base).constData(),
                                                  QFile::encodeName(file).constData()) == 0);
        const Outcome o = run({QStringLiteral("convert"), file, work(QStringLiteral("out.knot"))});
        qInfo("%s (200 MB): exit %d in %.3f s: %s", name, o.code, o.seconds,
              qPrintable(o.err.trimmed()));
        // The process's own start is most of it; 7.9 s and 443 MB before.
        verifyBounded(o, QLatin1String(name), 1.5);
        QCOMPARE(o.code, 1);
        QVERIFY2(o.err.contains(QLatin1String("not a")) ||
                     o.err.contains(QLatin1String("not valid JSON")),
                 qPrintable(o.err));
        QFile::remove(file);
    }
    QFile::remove(base);
}

void TestBounds::killOfConvertLeavesNoProcessAndNoFolder() {
#ifndef KW_HAVE_OCCT
    QSKIP("built without OpenCASCADE");
#endif
    // A read that takes seconds: OCCT's parser is quadratic in one list's length (30 000
    // items: several seconds, below the guard's 50 000).
    const QString slow = work(QStringLiteral("slow.step"));
    QVERIFY(writeBytes(
        slow, stepWith(bytesOf(data(QStringLiteral("screw.step"))), stepList(30000, ","))));
    QProcess convert;
    QProcessEnvironment e = env();
    e.insert(QStringLiteral("KNOTWORK_CAD_TIME_LIMIT"), QStringLiteral("120"));
    convert.setProcessEnvironment(e);
    convert.start(QStringLiteral(KW_KNOTWORK_BIN),
                  {QStringLiteral("convert"), slow, work(QStringLiteral("slow.knot"))});
    QVERIFY(convert.waitForStarted());
    pid_t reader = 0;
    QTRY_VERIFY_WITH_TIMEOUT((reader = childOf(convert.processId(), "__read-cad")) != 0, 10000);
    QTest::qWait(300); // inside OCCT's parser
    QVERIFY(!gone(reader));
    const qint64 owner = convert.processId();
    ::kill(pid_t(owner), SIGKILL);
    QVERIFY(convert.waitForFinished(5000));
    QElapsedTimer clock;
    clock.start();
    QTRY_VERIFY_WITH_TIMEOUT(gone(reader), 2000);
    qInfo("the reader ended %lld ms after kill -9 of convert", clock.elapsed());
    // Its folder stays until a later run sweeps it: a minute old and its owner gone.
    const QStringList left = tmpEntries();
    QCOMPARE(left.size(), 1);
    QVERIFY2(left[0].startsWith(QStringLiteral("knotwork-%1-").arg(owner)), qPrintable(left[0]));
    const QByteArray folder = QFile::encodeName(QDir(m_tmp).filePath(left[0]));
    const timespec old[2] = {{::time(nullptr) - 120, 0}, {::time(nullptr) - 120, 0}};
    QCOMPARE(::utimensat(AT_FDCWD, folder.constData(), old, 0), 0);
    const Outcome next = run({QStringLiteral("convert"), data(QStringLiteral("teapot.igs")),
                              work(QStringLiteral("teapot.knot"))});
    QCOMPARE(next.code, 0);
    QVERIFY2(tmpEntries().isEmpty(), qPrintable(tmpEntries().join(' ')));
}

void TestBounds::sigtermRemovesTheFolder() {
#ifndef KW_HAVE_OCCT
    QSKIP("built without OpenCASCADE");
#endif
    const QString slow = work(QStringLiteral("slow_term.step"));
    QVERIFY(writeBytes(
        slow, stepWith(bytesOf(data(QStringLiteral("screw.step"))), stepList(30000, ","))));
    for (const int sig : {SIGTERM, SIGINT}) {
        QProcess convert;
        convert.setProcessEnvironment(env());
        convert.start(QStringLiteral(KW_KNOTWORK_BIN),
                      {QStringLiteral("convert"), slow, work(QStringLiteral("slow.knot"))});
        QVERIFY(convert.waitForStarted());
        pid_t reader = 0;
        QTRY_VERIFY_WITH_TIMEOUT((reader = childOf(convert.processId(), "__read-cad")) != 0, 10000);
        QTRY_VERIFY_WITH_TIMEOUT(!tmpEntries().isEmpty(), 5000);
        QTest::qWait(200);
        ::kill(pid_t(convert.processId()), sig);
        QVERIFY(convert.waitForFinished(5000));
        QCOMPARE(convert.exitStatus(), QProcess::CrashExit); // ended by the signal, as before
        QTRY_VERIFY_WITH_TIMEOUT(gone(reader), 2000);
        QVERIFY2(tmpEntries().isEmpty(), qPrintable(tmpEntries().join(' ')));
    }
}

void TestBounds::fullDiskNamesTheCause_data() {
    QTest::addColumn<QStringList>("args");
    QTest::addColumn<bool>("tmpdirFull"); // the CAD child's folder is on the full disk
    const QString sample = QStringLiteral(KW_SAMPLES_DIR "/bicubic.knot");
    const QString full = work(QStringLiteral("full"));
    QTest::newRow("convert to .knot")
        << QStringList{"convert", sample, full + QStringLiteral("/out.knot")} << false;
    QTest::newRow("convert to OBJ")
        << QStringList{"convert", sample, full + QStringLiteral("/out.obj")} << false;
#ifdef KW_HAVE_OCCT
    QTest::newRow("mesh to OBJ") << QStringList{"mesh", data(QStringLiteral("teapot.igs")), "-o",
                                                full + QStringLiteral("/out.obj")}
                                 << false;
    QTest::newRow("the CAD child's hand-over")
        << QStringList{"convert", data(QStringLiteral("screw.step")),
                       work(QStringLiteral("screw.knot"))}
        << true;
    QTest::newRow("the IGES repair's copy")
        << QStringList{"convert", data(QStringLiteral("teapot.igs")),
                       work(QStringLiteral("teapot.knot"))}
        << true;
#endif
}

void TestBounds::fullDiskNamesTheCause() {
    QFETCH(QStringList, args);
    QFETCH(bool, tmpdirFull);
    const QString full = work(QStringLiteral("full"));
    QVERIFY(QDir().mkpath(full));
    // Every write under `full` fails with ENOSPC (tests/support/failwrite.c).
    QProcessEnvironment e = env();
    e.insert(QStringLiteral("LD_PRELOAD"), QStringLiteral(KW_FAILWRITE_LIB));
    e.insert(QStringLiteral("KW_FAIL_WRITES_UNDER"), full);
    if (tmpdirFull)
        e.insert(QStringLiteral("TMPDIR"), full);
    const Outcome o = run(args, e);
    QCOMPARE(o.code, 1);
    QVERIFY2(o.err.contains(QLatin1String("No space left on device")), qPrintable(o.err));
    QVERIFY2(!o.err.trimmed().contains(QLatin1Char('\n')), qPrintable(o.err));
    QVERIFY2(QDir(full).entryList(QDir::AllEntries | QDir::NoDotAndDotDot | QDir::Hidden).isEmpty(),
             qPrintable(QDir(full).entryList(QDir::AllEntries | QDir::NoDotAndDotDot).join(' ')));
}

void TestBounds::stepListsCountItemsHoweverSeparated() {
    const QByteArray head = "ISO-10303-21;\nHEADER;\nFILE_NAME('(((',');;');\nENDSEC;\nDATA;\n";
    const QByteArray tail = "\nENDSEC;\nEND-ISO-10303-21;\n";
    const auto file = [&](int items, const char* separator) {
        return head + stepList(items, separator) + tail;
    };
    for (const char* separator : {",", " ", "\n", " ,\t", "/* (1 2 3) */"}) {
        QVERIFY2(bool(checkCadContent(CadFormat::Step, file(50000, separator))), separator);
        QVERIFY2(
            checkCadContent(CadFormat::Step, file(50001, separator)).message().contains("50000"),
            separator);
    }
    // Nested lists count once in their parent; strings and comments are not lists.
    QByteArray nested = "#1=X((";
    for (int k = 0; k < 40000; ++k)
        nested += "(1 2) ";
    QVERIFY(checkCadContent(CadFormat::Step, head + nested + "));" + tail).message().isEmpty());
    QVERIFY(
        checkCadContent(CadFormat::Step, head + "#1=X('1.E400 (((');" + tail).message().isEmpty());
    QVERIFY(checkCadContent(CadFormat::Step, head + "#1=X(.T.,#12,-1.5E99);" + tail)
                .message()
                .isEmpty());
    QVERIFY(checkCadContent(CadFormat::Step, head + "#1=X(-1.5E101);" + tail)
                .message()
                .startsWith(QLatin1String("line 6: the value -1.5E101 is out of range")));
}

void TestBounds::igesStringsAreNotNumbers() {
    const QByteArray teapot = bytesOf(data(QStringLiteral("teapot.igs")));
    KW_VERIFY_OK(checkCadContent(CadFormat::Iges, teapot));
    QVERIFY(bool(checkCadContent(CadFormat::Iges, bytesOf(data(QStringLiteral("hammer.iges"))))));
    // A Hollerith string holding a huge number and delimiters is text, not a value.
    const QByteArray string = igesWith(teapot, "1.4,0.0,2.4,", "12H1.0D308,,;;,1.4,0.0,2.4,");
    QVERIFY(!string.isEmpty());
    KW_VERIFY_OK(checkCadContent(CadFormat::Iges, string));
    QVERIFY(checkCadContent(CadFormat::Iges, igesWith(teapot, "1.4,0.0,2.4,", "1.4,1.0E101,2.4,"))
                .message()
                .contains(QLatin1String("1.0E101")));
    QVERIFY(checkCadContent(CadFormat::Iges, QByteArray("PK\x03\x04 not IGES"))
                .message()
                .startsWith(QLatin1String("line 1: not an IGES file")));
}

void TestBounds::messagesAreSafe() {
    QCOMPARE(quoteInput("ab\x1b[31mc\xff"), QStringLiteral("ab\\x1b[31mc") + QChar(0xfffd));
    const QString cut = quoteInput(QByteArray(3'000'000, 'x'));
    QCOMPARE(cut.size(), kMaxQuotedChars);
    QVERIFY(cut.endsWith(QChar(0x2026)));
    QCOMPARE(occtMessageText("Parameter Data  : parameter %d (Coordinate of Point) is "
                             "incorrect (Real was expected)."),
             QStringLiteral("Parameter Data : a parameter (Coordinate of Point) is incorrect "
                            "(Real was expected)."));
    QCOMPARE(occtMessageText("Total number of loaded entities %d.\n"),
             QStringLiteral("Total number of loaded entities."));
    QCOMPARE(safeMessageText(QStringLiteral("a\tb\nc\x7f")), QStringLiteral("a\\x09b\\x0ac\\x7f"));
}

QTEST_GUILESS_MAIN(TestBounds)
#include "tst_bounds.moc"
