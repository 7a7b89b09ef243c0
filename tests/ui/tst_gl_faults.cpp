// GL faults in the editor, under Xvfb: a shader that does not build (forced
// through ShaderLibrary::setSourceDirectory, the renderer's shader-source hook), a control net
// larger than the GPU's texture limit, and the GL context destroyed and recreated (the viewport
// moved to another window). Each must give a clear message, keep the document editable and savable,
// and not crash. One binary, three CTest entries: KW_GL_FAULT=variant|init breaks shaders, unset
// runs the others.
#include "editor_test_util.h"
#include "model/io/knotfile.h"
#include "render/frame_report.h"
#include "render/gl_context.h"
#include "render/gpu_scene.h"
#include "render/offscreen_renderer.h"
#include "render/shader_library.h"
#include "ui/edit/commands.h"

#include <QApplication>
#include <QDir>
#include <QDirIterator>
#include <QFile>
#include <QOpenGLContext>
#include <QOpenGLFunctions>
#include <QScopeGuard>
#include <QSignalSpy>
#include <QStatusBar>
#include <QUndoStack>
#include <QVBoxLayout>

using namespace kw;
using namespace kwtest;

namespace {

/// The folder this process works in. CTest runs the three fault modes of this binary as
/// separate tests, possibly at once: each needs its own copy of the sample, its own shaders and
/// its own settings, or one process deletes the file another is opening.
QString workDir() {
    const QByteArray fault = qgetenv("KW_GL_FAULT");
    return QStringLiteral(KW_TEST_OUTPUT_DIR "/gl-faults-") +
           (fault.isEmpty() ? QStringLiteral("none") : QString::fromLatin1(fault));
}
constexpr char kForced[] = "forced by tst_gl_faults";

/// Copies the bundled shaders to `dir`, with `#error` at the top of `file`, guarded by `guard`
/// (a define only some variants have) when not empty.
bool writeBrokenShaders(const QString& dir, const QString& file, const QString& guard) {
    if (!QDir(dir).removeRecursively() || !QDir().mkpath(dir))
        return false;
    QDirIterator it(QStringLiteral(":/shaders"), QDir::Files);
    int copied = 0;
    while (it.hasNext()) {
        const QString from = it.next();
        QFile in(from);
        if (!in.open(QIODevice::ReadOnly))
            return false;
        QByteArray text = in.readAll();
        const QString name = QFileInfo(from).fileName();
        if (name == file) {
            const QByteArray error = QByteArray("#error ") + kForced + '\n';
            const QByteArray inject =
                guard.isEmpty() ? error : "#ifdef " + guard.toLatin1() + '\n' + error + "#endif\n";
            // After the #version line the library prepends: the source has none, so at the top.
            text.prepend(inject);
        }
        QFile out(dir + QLatin1Char('/') + name);
        if (!out.open(QIODevice::WriteOnly) || out.write(text) != text.size())
            return false;
        ++copied;
    }
    return copied > 5;
}

/// A window on a copy of the trimmed_plate sample, shown, with scripted dialogs.
struct Editor {
    DialogScript script;
    std::unique_ptr<MainWindow> w = std::make_unique<MainWindow>();
    QString path = workDir() + QStringLiteral("/plate.knot");

    bool open() {
        QDir().mkpath(workDir());
        QFile::remove(path);
        if (!QFile::copy(samplePath("trimmed_plate"), path))
            return false;
        scriptDialogs(*w, script);
        w->resize(900, 600);
        w->show();
        return QTest::qWaitForWindowExposed(w.get()) && w->openFile(path);
    }
    /// Waits for `n` more frames of the viewport (wherever it is).
    bool frames(int n) {
        Viewport* vp = w->viewport();
        const std::int64_t start = vp->framesDrawn();
        return QTest::qWaitFor(
            [&] {
                vp->update(); // one frame per update
                return vp->framesDrawn() >= start + n;
            },
            20000);
    }
    /// The document still takes an edit, undoes it and saves.
    bool stillEditable() {
        const Scene before = w->document()->scene();
        const Surface& s = before.surfaces.front();
        if (!pushCommand(w->undoStack(), SetPartitions::create(w->document(), s.id, 7, 5)))
            return false;
        const bool changed = w->document()->scene() != before;
        w->undoStack()->undo();
        if (!changed || w->document()->scene() != before || !w->saveFile(path))
            return false;
        // Save also writes the view's camera and partition mode;
        // everything else is the document.
        auto written = readKnotFile(path);
        if (!written)
            return false;
        written->camera = before.camera;
        written->display = before.display;
        return *written == before;
    }
};

/// Pixels of the frame that are not the background (the corner pixel's colour).
int covered(const QImage& frame) {
    const QRgb background = frame.pixel(2, 2);
    int n = 0;
    for (int y = 0; y < frame.height(); y += 4)
        for (int x = 0; x < frame.width(); x += 4)
            n += frame.pixel(x, y) != background;
    return n;
}

} // namespace

/// KW_GL_FAULT=variant: only the trimmed tessellated variant fails to build.
class TestShaderVariantFault : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void failedVariantIsReportedAndTheRestKeepsWorking() {
        Editor e;
        QVERIFY(e.open());
        QSignalSpy errors(e.w->viewport(), &Viewport::renderError);
        QVERIFY(e.frames(2));
        QVERIFY2(e.w->viewport()->lastFrameReport().ok,
                 qPrintable(e.w->viewport()->lastFrameReport().error));
        const Scene before = e.w->document()->scene();

        e.w->viewport()->setRenderMode(RenderMode::Tessellated); // trims need KW_TRIM
        QVERIFY(e.frames(2));
        const FrameReport& bad = e.w->viewport()->lastFrameReport();
        QVERIFY(!bad.ok);
        QVERIFY2(bad.error.contains(QLatin1String("tessellated.frag")) &&
                     bad.error.contains(QLatin1String(kForced)),
                 qPrintable(bad.error));
        QCOMPARE(errors.count(), 1); // said once, not every frame
        const QString message = errors.at(0).at(0).toString();
        QVERIFY2(message.startsWith(QLatin1String("Frame failed:")), qPrintable(message));
        QCOMPARE(e.w->statusBar()->currentMessage(), message);
        QVERIFY(e.w->isVisible());
        QVERIFY(e.w->document()->scene() == before);
        QVERIFY(e.stillEditable());

        e.w->viewport()->setRenderMode(RenderMode::Exact); // the other variants still draw
        QVERIFY(e.frames(2));
        QVERIFY2(e.w->viewport()->lastFrameReport().ok,
                 qPrintable(e.w->viewport()->lastFrameReport().error));
        QVERIFY(covered(e.w->viewport()->grabFramebuffer()) > 200);
        QVERIFY(e.script.errors.isEmpty());
        e.w->undoStack()->setClean();
    }
};

/// KW_GL_FAULT=init: the exact surface shader, which every default frame needs, fails. (The
/// renderer builds programs on first use, so this is a failed frame, not a failed start-up.)
class TestShaderInitFault : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void exactShaderFailureKeepsTheDocument() {
        Editor e;
        QSignalSpy errors(e.w->viewport(), &Viewport::renderError);
        QVERIFY(e.open());
        QVERIFY(e.frames(3));
        const FrameReport& bad = e.w->viewport()->lastFrameReport();
        QVERIFY(!bad.ok);
        QVERIFY2(bad.error.contains(QLatin1String("exact_surface.frag")) &&
                     bad.error.contains(QLatin1String(kForced)),
                 qPrintable(bad.error));
        QCOMPARE(errors.count(), 1); // said once, not every frame
        QVERIFY2(errors.at(0).at(0).toString().startsWith(QLatin1String("Frame failed:")),
                 qPrintable(errors.at(0).at(0).toString()));
        QCOMPARE(e.w->statusBar()->currentMessage(), errors.at(0).at(0).toString());
        QCOMPARE(e.w->document()->scene().surfaces.size(), size_t(1));
        QVERIFY(!e.w->viewport()->pickSurface(QPointF(450, 300)));
        QVERIFY(e.stillEditable());
        e.w->viewport()->setRenderMode(RenderMode::Tessellated); // the baseline still draws
        QVERIFY(e.frames(2));
        QVERIFY2(e.w->viewport()->lastFrameReport().ok,
                 qPrintable(e.w->viewport()->lastFrameReport().error));
        e.w->undoStack()->setClean();
    }
};

class TestGlFaults : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void controlNetTooLargeForTheGpu() {
        Editor e;
        QVERIFY(e.open());
        QVERIFY(e.frames(2));
        QVERIFY(e.w->viewport()->lastFrameReport().ok);
        const int before = covered(e.w->viewport()->grabFramebuffer());
        // 40000 x 2 points: within the file format's limits, beyond the shared control buffer
        // under a buffer limit lowered to 1 MiB (80000 texels of 16 bytes need 1.28 MB).
        GpuScene::setBufferLimitForTests(1048576);
        const auto restore = qScopeGuard([] { GpuScene::setBufferLimitForTests(0); });
        Surface big;
        big.id = e.w->document()->allocateSurfaceId();
        big.name = QStringLiteral("Long strip");
        NurbsSurface& g = big.geometry;
        g.countU = 40000;
        g.countV = 2;
        g.knotsU = {0.0};
        for (int i = 0; i < g.countU; ++i)
            g.knotsU.push_back(double(i) / (g.countU - 1));
        g.knotsU.push_back(1.0);
        g.knotsV = {0, 0, 1, 1};
        for (int j = 0; j < 2; ++j)
            for (int i = 0; i < g.countU; ++i)
                g.points.emplace_back(5.0 + i * 1e-4, j, 0.0);
        g.weights.assign(g.points.size(), 1.0);
        QSignalSpy errors(e.w->viewport(), &Viewport::renderError);
        QVERIFY(e.w->document()->insertSurface(1, big));
        QVERIFY(e.frames(2));
        const FrameReport& r = e.w->viewport()->lastFrameReport();
        QVERIFY(!r.ok);
        QVERIFY2(r.error.contains(QLatin1String("Long strip")) &&
                     r.error.contains(QLatin1String("buffer limit of 1048576 bytes")),
                 qPrintable(r.error));
        QCOMPARE(errors.count(), 1);
        QCOMPARE(e.w->statusBar()->currentMessage(), errors.at(0).at(0).toString());
        // The plate is still drawn.
        QVERIFY(covered(e.w->viewport()->grabFramebuffer()) > before / 2);
        QVERIFY(e.w->document()->removeSurface(big.id));
        QVERIFY(e.frames(2));
        QVERIFY(e.w->viewport()->lastFrameReport().ok);
        QVERIFY(e.stillEditable());
    }

    void glDebugInTheEditor() {
        // KW_GL_DEBUG=1 (kw::setGlDebug): the viewport asks for a debug context and prints the
        // driver's messages (how a user's GPU fault gets reported, docs/PERFORMANCE.md "On a GPU").
        setGlDebug(true);
        auto unset = qScopeGuard([] { setGlDebug(false); });
        Editor e;
        QVERIFY(e.open());
        QVERIFY(e.frames(1));
        Viewport* vp = e.w->viewport();
        QVERIFY(vp->format().testOption(QSurfaceFormat::DebugContext));
        vp->makeCurrent();
        QTest::ignoreMessage(QtWarningMsg, QRegularExpression(QStringLiteral("^GL debug: .+")));
        QOpenGLContext::currentContext()->functions()->glBindBuffer(GL_ARRAY_BUFFER, 987654321u);
        QVERIFY(QOpenGLContext::currentContext()->functions()->glGetError() != GL_NO_ERROR);
        vp->doneCurrent();
        QVERIFY(e.frames(1)); // and it still draws
        QVERIFY(vp->lastFrameReport().ok);
    }

    void contextDestroyedAndRecreated_data() {
        QTest::addColumn<bool>("native");
        QTest::newRow("native window") << true;
        QTest::newRow("QOpenGLWidget") << false;
    }
    void contextDestroyedAndRecreated() {
        // Moving the viewport to another top-level window: its native window moves with it and
        // keeps its context; the QOpenGLWidget fallback (KNOTWORK_VIEW=widget) destroys its
        // context and makes a new one: the renderer is released and rebuilt, every upload
        // redone.
        QFETCH(bool, native);
        if (!native)
            qputenv("KNOTWORK_VIEW", "widget");
        auto unset = qScopeGuard([] { qunsetenv("KNOTWORK_VIEW"); });
        Editor e;
        QCOMPARE(e.w->viewport()->isNativeWindow(), native);
        QVERIFY(e.open());
        QVERIFY(e.frames(2));
        QVERIFY(e.w->viewport()->lastFrameReport().ok);
        const Scene scene = e.w->document()->scene();
        Viewport* vp = e.w->viewport();
        QSignalSpy destroyed(vp->context(), &QOpenGLContext::aboutToBeDestroyed);
        QVERIFY(e.w->takeCentralWidget() == vp);
        QWidget other;
        auto* layout = new QVBoxLayout(&other);
        layout->addWidget(vp);
        other.resize(700, 500);
        other.show();
        QVERIFY(QTest::qWaitForWindowExposed(&other));
        QVERIFY(e.frames(2));
        // Without a native window the first context is gone: these frames used another.
        QCOMPARE(destroyed.count(), native ? 0 : 1);
        QVERIFY2(vp->glError(), qPrintable(vp->glError().message()));
        QVERIFY(vp->lastFrameReport().ok);
        QVERIFY(covered(vp->grabFramebuffer()) > 200);
        e.w->setCentralWidget(vp); // and back: a third context
        QVERIFY(e.frames(2));
        QVERIFY(vp->lastFrameReport().ok);
        QVERIFY(covered(vp->grabFramebuffer()) > 200);
        QVERIFY(e.w->document()->scene() == scene);
        QVERIFY(e.stillEditable());
    }
};

int main(int argc, char** argv) {
    QSurfaceFormat::setDefaultFormat(OffscreenRenderer::requiredFormat());
    qputenv("XDG_CONFIG_HOME", (workDir() + QStringLiteral("/config")).toLocal8Bit());
    QApplication app(argc, argv);
    QCoreApplication::setOrganizationName(QStringLiteral("KnotworkTest"));
    const QByteArray fault = qgetenv("KW_GL_FAULT");
    if (!fault.isEmpty()) {
        // The shader source directory (KW_SHADER_DIR in the executables): before any window.
        const QString dir = workDir() + QStringLiteral("/shaders");
        const bool variant = fault == "variant";
        if (!writeBrokenShaders(dir,
                                variant ? QStringLiteral("tessellated.frag")
                                        : QStringLiteral("exact_surface.frag"),
                                variant ? QStringLiteral("KW_TRIM") : QString())) {
            qCritical("cannot write the broken shaders to %s", qPrintable(dir));
            return 1;
        }
        ShaderLibrary::setSourceDirectory(dir);
        qputenv("QT_DISABLE_SHADER_DISK_CACHE", "1");
        if (variant) {
            TestShaderVariantFault t;
            return QTest::qExec(&t, argc, argv);
        }
        TestShaderInitFault t;
        return QTest::qExec(&t, argc, argv);
    }
    TestGlFaults t;
    return QTest::qExec(&t, argc, argv);
}

#include "tst_gl_faults.moc"
