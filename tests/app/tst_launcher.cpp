// The launcher split: `knotwork` maps no GUI, OpenGL, OpenImageIO or GLU library (ldd lists
// what the dynamic loader maps at start), the drawing commands run in knotwork-gl and
// knotwork-bench (OpenImageIO only in libknotwork_oiio.so, loaded to write an image), and a
// missing sibling executable is a clear error, not a crash.
#include "knotwork_process.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QTemporaryDir>
#include <QTest>

namespace {

/// The shared libraries the dynamic loader maps for `binary` (ldd's first column).
QStringList mappedLibraries(const QString& binary) {
    QProcess p;
    p.start(QStringLiteral("ldd"), {binary});
    if (!p.waitForFinished(60000) || p.exitCode() != 0)
        return {};
    QStringList libs;
    for (const QString& line : QString::fromLocal8Bit(p.readAllStandardOutput()).split('\n')) {
        const QString name = line.trimmed().section(QLatin1Char(' '), 0, 0);
        if (!name.isEmpty())
            libs << QFileInfo(name).fileName();
    }
    return libs;
}

QStringList matching(const QStringList& libs, const QStringList& prefixes) {
    QStringList found;
    for (const QString& lib : libs)
        for (const QString& prefix : prefixes)
            if (lib.startsWith(prefix))
                found << lib;
    return found;
}

const QStringList kDrawingLibraries = {
    QStringLiteral("libQt6Gui"),    QStringLiteral("libQt6Widgets"),
    QStringLiteral("libQt6OpenGL"), QStringLiteral("libOpenImageIO"),
    QStringLiteral("libGLU"),       QStringLiteral("libGL."),
    QStringLiteral("libGLX"),       QStringLiteral("libOpenGL"),
    QStringLiteral("libxcb"),       QStringLiteral("libX11"),
};

} // namespace

class TestLauncher : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void launcherMapsNoDrawingLibraries();
    void siblingsMapWhatTheyDraw();
    void drawingCommandsRunThroughTheLauncher();
    void missingSiblingIsAClearError();
};

void TestLauncher::launcherMapsNoDrawingLibraries() {
    const QStringList libs = mappedLibraries(QStringLiteral(KW_KNOTWORK_BIN));
    QVERIFY2(libs.contains(QStringLiteral("libQt6Core.so.6")), qPrintable(libs.join(' ')));
    const QStringList found = matching(libs, kDrawingLibraries);
    QVERIFY2(found.isEmpty(), qPrintable(QStringLiteral("knotwork maps ") + found.join(' ')));
}

void TestLauncher::siblingsMapWhatTheyDraw() {
    const QStringList gl = mappedLibraries(QStringLiteral(KW_GL_BIN));
    QVERIFY2(!matching(gl, {QStringLiteral("libQt6Widgets")}).isEmpty(), qPrintable(gl.join(' ')));
    // OpenImageIO is loaded only to write an image (render/image_writer.cpp).
    QVERIFY2(matching(gl, {QStringLiteral("libOpenImageIO")}).isEmpty(), qPrintable(gl.join(' ')));
    const QStringList oiio = mappedLibraries(QFileInfo(QStringLiteral(KW_GL_BIN)).path() +
                                             QStringLiteral("/libknotwork_oiio.so"));
    QVERIFY2(!matching(oiio, {QStringLiteral("libOpenImageIO")}).isEmpty(),
             qPrintable(oiio.join(' ')));
    // libGLU belongs to the bench alone (its NURBS tessellator is a comparison row).
    QVERIFY2(matching(gl, {QStringLiteral("libGLU")}).isEmpty(), qPrintable(gl.join(' ')));
    const QStringList bench = mappedLibraries(QStringLiteral(KW_BENCH_BIN));
    QVERIFY2(!matching(bench, {QStringLiteral("libGLU")}).isEmpty(), qPrintable(bench.join(' ')));
}

void TestLauncher::drawingCommandsRunThroughTheLauncher() {
    // The subcommand's own help comes back through exec, under the name the user typed.
    for (const QString& cmd : {QStringLiteral("render"), QStringLiteral("bench")}) {
        const Run r = knotwork({cmd, QStringLiteral("--help")});
        QCOMPARE(r.code, 0);
        QVERIFY2(r.out.startsWith(QStringLiteral("Usage: knotwork ") + cmd), qPrintable(r.out));
    }
    // A usage error's exit code passes through unchanged.
    const Run bad = knotwork({QStringLiteral("render"), QStringLiteral("--no-such-option")});
    QCOMPARE(bad.code, 2);
    QVERIFY2(bad.err.contains(QStringLiteral("knotwork render")), qPrintable(bad.err));
    // Without a display the drawing commands refuse before Qt's xcb plugin can abort.
    QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
    for (const char* name : {"QT_QPA_PLATFORM", "DISPLAY", "WAYLAND_DISPLAY"})
        env.remove(QLatin1String(name));
    for (const QString& cmd : {QStringLiteral("render"), QStringLiteral("bench")}) {
        QStringList args{cmd, QStringLiteral(KW_SAMPLES_DIR "/torus.knot")};
        if (cmd == QLatin1String("render")) // valid arguments: the display is what is missing
            args << QStringLiteral("-o") << QDir::temp().filePath(QStringLiteral("never.png"));
        const Run r = knotwork(args, env);
        QCOMPARE(r.code, 1);
        QVERIFY2(r.err.contains(QStringLiteral("knotwork ") + cmd) &&
                     r.err.contains(QStringLiteral("no X display")),
                 qPrintable(r.err));
    }
    // The input comes before the display: a missing file or a folder is the error reported.
    const QString missing = QDir::temp().filePath(QStringLiteral("no-such-model.knot"));
    for (const QString& input : {missing, QDir::tempPath()}) {
        const Run r = knotwork(
            {QStringLiteral("render"), input, QStringLiteral("-o"), QStringLiteral("x.png")}, env);
        QCOMPARE(r.code, 1);
        QVERIFY2(r.err.startsWith(input + QStringLiteral(": ")) &&
                     !r.err.contains(QStringLiteral("display")),
                 qPrintable(r.err));
    }
    // Arguments are checked before the display is reached: a usage error and --help answer
    // the same with or without one (no X connection that load could break).
    const Run usage =
        knotwork({QStringLiteral("render"), QStringLiteral(KW_SAMPLES_DIR "/torus.knot"),
                  QStringLiteral("-o"), QStringLiteral("x.png"), QStringLiteral("--size"),
                  QStringLiteral("0x10")},
                 env);
    QCOMPARE(usage.code, 2);
    QVERIFY2(usage.err.contains(QStringLiteral("--size")), qPrintable(usage.err));
    for (const QString& cmd : {QStringLiteral("render"), QStringLiteral("bench")}) {
        const Run r = knotwork({cmd, QStringLiteral("--help")}, env);
        QCOMPARE(r.code, 0);
        QVERIFY2(r.out.startsWith(QStringLiteral("Usage: knotwork ") + cmd), qPrintable(r.out));
    }
}

void TestLauncher::missingSiblingIsAClearError() {
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    const QString alone = dir.filePath(QStringLiteral("knotwork"));
    QVERIFY(QFile::copy(QStringLiteral(KW_KNOTWORK_BIN), alone));
    QVERIFY(QFile::setPermissions(alone, QFile::ReadOwner | QFile::ExeOwner));
    const struct {
        QStringList args;
        const char* program;
    } cases[] = {
        {{QStringLiteral("render"), QStringLiteral(KW_SAMPLES_DIR "/torus.knot"),
          QStringLiteral("-o"), QStringLiteral("x.png")},
         "knotwork-gl"},
        {{QStringLiteral("bench")}, "knotwork-bench"},
        {{}, "knotwork-gl"}, // the editor
    };
    for (const auto& c : cases) {
        QProcess p;
        p.start(alone, c.args);
        QVERIFY(p.waitForFinished(60000));
        QCOMPARE(p.exitStatus(), QProcess::NormalExit);
        QCOMPARE(p.exitCode(), 1);
        const QString err = QString::fromLocal8Bit(p.readAllStandardError());
        QVERIFY2(err.contains(QStringLiteral("cannot run")) &&
                     err.contains(QDir(dir.path()).filePath(QLatin1String(c.program))),
                 qPrintable(err));
    }
    // What knotwork runs itself still works there.
    QProcess p;
    p.start(alone, {QStringLiteral("--version")});
    QVERIFY(p.waitForFinished(60000));
    QCOMPARE(p.exitCode(), 0);
    QVERIFY(p.readAllStandardOutput().startsWith("knotwork "));
}

QTEST_GUILESS_MAIN(TestLauncher)
#include "tst_launcher.moc"
