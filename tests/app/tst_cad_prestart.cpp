// `knotwork render FILE.iges`: the launcher starts the CAD reader's child before it becomes
// knotwork-gl, which takes it over (model/cad/cadprestart.h). The image is the one the usual
// read gives, and the child is watched as before: a crash, a time-out and an error name the
// file; a child nobody takes over is killed; no folder is left behind.
#include "knotwork_process.h"

#include <QDir>
#include <QElapsedTimer>
#include <QFile>
#include <QTemporaryDir>
#include <QTest>
#include <QThread>

namespace {

const QString kHammer = QStringLiteral(KW_TEST_DATA_DIR "/hammer.iges");

QByteArray readAll(const QString& path) {
    QFile f(path);
    return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
}

// A stand-in for the reader (KNOTWORK_CAD_READER): a shell script that writes its arguments to
// NAME.args, then runs `body`.
QString script(const QTemporaryDir& dir, const QString& name, const QByteArray& body) {
    const QString path = dir.filePath(name);
    QFile f(path);
    const QByteArray args = QFile::encodeName(path + QStringLiteral(".args"));
    if (!f.open(QIODevice::WriteOnly) ||
        f.write("#!/bin/sh\necho \"$@\" > '" + args + "'\n" + body + '\n') < 0)
        qFatal("cannot write %s", qPrintable(path));
    f.close();
    f.setPermissions(f.permissions() | QFileDevice::ExeOwner);
    return path;
}

// True when the stand-in ran as the launcher starts it (its --die-with-parent argument).
bool prestarted(const QString& scriptPath) {
    return readAll(scriptPath + QStringLiteral(".args")).contains("--die-with-parent");
}

} // namespace

class TestCadPrestart : public QObject {
    Q_OBJECT
    QTemporaryDir m_work;
    QString m_tmp; // TMPDIR of the runs: whatever they leave is here

    QProcessEnvironment env(const QString& reader = {}) const {
        QProcessEnvironment e = QProcessEnvironment::systemEnvironment();
        e.insert(QStringLiteral("TMPDIR"), m_tmp);
        if (!reader.isEmpty())
            e.insert(QStringLiteral("KNOTWORK_CAD_READER"), reader);
        return e;
    }
    QStringList leftOver() const {
        return QDir(m_tmp).entryList({QStringLiteral("knotwork-*")}, QDir::AllEntries);
    }

private Q_SLOTS:
    void init() {
        QVERIFY(m_work.isValid());
        m_tmp = m_work.filePath(QStringLiteral("tmp-") + QTest::currentTestFunction());
        QVERIFY(QDir().mkpath(m_tmp));
    }

    void sameImageAsTheUsualRead() {
        const QString a = m_work.filePath(QStringLiteral("prestarted.png"));
        const QString b = m_work.filePath(QStringLiteral("usual.png"));
        // FILE right after the verb: prestarted. After an option: read by knotwork-gl itself.
        const Run first = knotwork({QStringLiteral("render"), kHammer, QStringLiteral("-o"), a,
                                    QStringLiteral("--size"), QStringLiteral("64x64")},
                                   env());
        QVERIFY2(first.code == 0, qPrintable(first.err));
        const Run second = knotwork({QStringLiteral("render"), QStringLiteral("-o"), b, kHammer,
                                     QStringLiteral("--size"), QStringLiteral("64x64")},
                                    env());
        QVERIFY2(second.code == 0, qPrintable(second.err));
        QVERIFY(!readAll(a).isEmpty());
        QCOMPARE(readAll(a), readAll(b));
        QVERIFY2(leftOver().isEmpty(), qPrintable(leftOver().join(QLatin1Char(' '))));
    }

    void crashNamesTheFile() {
        const QString reader = script(m_work, QStringLiteral("crash.sh"), "kill -SEGV $$");
        const Run r = knotwork({QStringLiteral("render"), kHammer, QStringLiteral("-o"),
                                m_work.filePath(QStringLiteral("crash.png"))},
                               env(reader));
        QCOMPARE(r.code, 1);
        QVERIFY(prestarted(reader));
        QVERIFY2(
            r.err.contains(QStringLiteral("the IGES reader crashed on %1 (signal 11").arg(kHammer)),
            qPrintable(r.err));
        QVERIFY(leftOver().isEmpty());
    }

    void errorLineIsPassedOn() {
        const QString reader =
            script(m_work, QStringLiteral("error.sh"), "echo \"$2: a reader error\" >&2; exit 1");
        const Run r = knotwork({QStringLiteral("render"), kHammer, QStringLiteral("-o"),
                                m_work.filePath(QStringLiteral("error.png"))},
                               env(reader));
        QCOMPARE(r.code, 1);
        QVERIFY(prestarted(reader));
        QVERIFY2(r.err.contains(kHammer + QStringLiteral(": a reader error")), qPrintable(r.err));
        QVERIFY(leftOver().isEmpty());
    }

    void timeLimitStopsIt() {
        const QString reader = script(m_work, QStringLiteral("slow.sh"), "exec sleep 60");
        QProcessEnvironment e = env(reader);
        e.insert(QStringLiteral("KNOTWORK_CAD_TIME_LIMIT"), QStringLiteral("1"));
        QElapsedTimer clock;
        clock.start();
        const Run r = knotwork({QStringLiteral("render"), kHammer, QStringLiteral("-o"),
                                m_work.filePath(QStringLiteral("slow.png"))},
                               e);
        QCOMPARE(r.code, 1);
        QVERIFY2(r.err.contains(QStringLiteral("did not finish within 1 s")), qPrintable(r.err));
        QVERIFY(clock.elapsed() < 30000);
        QVERIFY(prestarted(reader));
        QVERIFY(leftOver().isEmpty());
    }

    void readNobodyTakesOverIsKilled() {
        // A usage error after FILE: knotwork-gl exits before it reads; the child must not live on.
        const QString mark = m_work.filePath(QStringLiteral("still-running"));
        const QString reader =
            script(m_work, QStringLiteral("late.sh"), "sleep 2; touch " + mark.toLocal8Bit());
        const Run r = knotwork(
            {QStringLiteral("render"), kHammer, QStringLiteral("--size"), QStringLiteral("0x0")},
            env(reader));
        QCOMPARE(r.code, 2);
        QThread::msleep(3000);
        QVERIFY(prestarted(reader)); // it did start, and was killed before it could go on
        QVERIFY(!QFile::exists(mark));
        QVERIFY2(leftOver().isEmpty(), qPrintable(leftOver().join(QLatin1Char(' '))));
    }
};

QTEST_GUILESS_MAIN(TestCadPrestart)
#include "tst_cad_prestart.moc"
