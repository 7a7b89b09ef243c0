// The editor entry point: display and OpenGL checks, the main window, and --screenshot.
#include "app/editor.h"

#include "app/commands.h"
#include "app/version.h"
#include "model/cad/cadimport.h"
#include "model/io/inputcheck.h"
#include "model/io/knotfile.h"
#include "model/io/savefile.h"
#include "model/nurbs/nurbs_shapes.h"
#include "render/analysis.h"
#include "render/gl_context.h"
#include "render/image_save.h"
#include "ui/edit/commands.h"
#include "ui/mainwindow.h"
#include "ui/modelingtools.h"
#include "ui/uvpanel.h"
#include "ui/viewport.h"

#include <QAction>
#include <QApplication>
#include <QCommandLineParser>
#include <QElapsedTimer>
#include <QFileInfo>
#include <QIcon>
#include <QMessageBox>
#include <QOffscreenSurface>
#include <QOpenGLContext>
#include <QPainter>
#include <QSurfaceFormat>
#include <QTimer>

namespace kw::app {

namespace {

/// Empty when this machine can make an OpenGL 4.5 core context, else why not.
QString probeOpenGL() {
    QOffscreenSurface surface;
    surface.setFormat(requiredSurfaceFormat());
    surface.create();
    QOpenGLContext context;
    context.setFormat(requiredSurfaceFormat());
    if (!context.create())
        return QStringLiteral("no OpenGL context could be created on the '%1' platform")
            .arg(QGuiApplication::platformName());
    if (const QString got = openGlShortfall(context.format(), context.isOpenGLES()); !got.isEmpty())
        return QStringLiteral("the best OpenGL context available is %1").arg(got);
    if (!context.makeCurrent(&surface))
        return QStringLiteral("the OpenGL context cannot be made current");
    context.doneCurrent();
    return {};
}

bool headlessPlatform() {
    const QString p = QGuiApplication::platformName();
    return p == QLatin1String("offscreen") || p == QLatin1String("minimal");
}

/// --demo: a scene made with the editor's own tools, as a user would: a NURBS patch shaped by
/// one control-point edit, cut by a circular hole drawn in the UV panel, and a torus moved
/// beside it. Each step is an undo step of the window.
void buildDemo(MainWindow& window) {
    ModelingTools* tools = window.modelingTools();
    if (const auto torus = tools->createPrimitive(ModelingTools::Primitive::Torus); !torus)
        qWarning("%s", qPrintable(torus.message()));
    else if (const Status moved = tools->transformSelected({{2.2, 1.2, 0.0}, 0, 35.0, 1.6}); !moved)
        qWarning("%s", qPrintable(moved.message()));
    const Expected<SurfaceId> created = tools->createPatch({3, 3, 7, 6, 3.0, 2.4});
    if (!created) {
        qWarning("%s", qPrintable(created.message()));
        return;
    }
    const SurfaceId patch = *created;
    const NurbsSurface& g = window.document()->surface(patch)->geometry;
    std::vector<int> indices;
    std::vector<glm::dvec3> from, to;
    for (int k = 0; k < int(g.points.size()); ++k) {
        const glm::dvec3 p = g.points[size_t(k)];
        indices.push_back(k);
        from.push_back(p);
        to.push_back(p + glm::dvec3(0.0, 0.0, 0.45 * std::sin(2.0 * p.x) * std::cos(1.6 * p.y)));
    }
    if (const Status moved = pushCommand(
            window.undoStack(),
            MoveControlPoints::create(window.document(), patch, indices, from, to, MoveKind::Drag));
        !moved)
        qWarning("%s", qPrintable(moved.message()));
    window.uvPanel()->addLoop({makeCircle2({0.62, 0.5}, 0.2)}, QObject::tr("circular"));
    // From above the front right, so the hole is seen, framing both surfaces.
    Camera c = window.viewport()->cameraController().camera();
    c.eye = c.target + glm::dvec3(1.2, -3.0, 4.0);
    window.viewport()->setCamera(c);
    window.viewport()->fitToView();
    QTimer::singleShot(0, window.viewport(), [&window] { window.viewport()->fitToView(); });
}

/// Message boxes of a run no one watches (--screenshot, KNOTWORK_QUIT_AFTER_OPEN): errors and
/// reports on stderr, no questions (a file is never left unsaved there).
MainWindow::Dialogs scriptedDialogs() {
    MainWindow::Dialogs d = MainWindow::Dialogs::standard();
    d.error = [](QWidget*, const QString& title, const QString& text) {
        cli::printError(QStringLiteral("knotwork: %1: %2").arg(title, text));
    };
    d.information = [](QWidget*, const QString&, const QString& text) {
        cli::printError(QStringLiteral("knotwork: ") + text);
    };
    d.askRecover = [](QWidget*, const QString&) {
        return QMessageBox::Cancel;
    };
    return d;
}

/// Set on the window once the file it was started with is in the document.
constexpr const char* kLoadedProperty = "knotworkStartFileLoaded";

/// KNOTWORK_QUIT_AFTER_OPEN=REPORT: once the viewport has drawn the file the editor was started
/// with, writes "file PATH" and "surfaces N" lines to REPORT and quits with 0. For scripted
/// checks that a launcher (a desktop entry, a file manager) started the editor on a file.
void quitOnceShown(MainWindow& window, const QString& report, bool loaded) {
    window.setProperty(kLoadedProperty, loaded);
    QObject::connect(window.viewport(), &Viewport::frameDrawn, &window, [&window, report] {
        if (!window.property(kLoadedProperty).toBool())
            return;
        window.setProperty(kLoadedProperty, false); // once
        const QString source =
            window.filePath().isEmpty() ? window.importedFrom() : window.filePath();
        const QString text =
            QStringLiteral("file\t%1\nsurfaces\t%2\ntitle\t%3\n")
                .arg(source.isEmpty() ? QString() : QFileInfo(source).absoluteFilePath())
                .arg(window.document()->scene().surfaces.size())
                .arg(window.windowTitle());
        const Status saved = saveBytesAtomically(report, text.toUtf8());
        if (!saved)
            cli::printError(saved.message());
        const bool written = bool(saved);
        // Queued: the first frame can be drawn before QApplication::exec() runs, and exit()
        // does nothing while no event loop does.
        QTimer::singleShot(0, qApp, [written] {
            QCoreApplication::exit(written ? cli::kExitOk : cli::kExitBadInput);
        });
    });
}

/// Shows the window, waits until the viewport has drawn a few frames, saves a grab.
int screenshot(MainWindow& window, const QString& out, bool refit) {
    // Show a picked control point too, so the property panel's point box is filled.
    if (const SurfaceId id = window.selection()->currentSurface(); id.isValid())
        window.selection()->setControlPoints({ControlPointRef{id, 1, 2}});
    window.show();
    QElapsedTimer clock;
    clock.start();
    // Let the window be exposed and the viewport draw (llvmpipe: allow a few seconds).
    while (clock.elapsed() < 1500) {
        QCoreApplication::processEvents(QEventLoop::AllEvents, 50);
        if (refit && clock.elapsed() > 300) { // once the viewport has its final size
            window.viewport()->fitToView();
            refit = false;
        }
    }
    // QWidget::grab() may show the viewport's previous composition; paint its current frame
    // (which includes the picked-point marks drawn with QPainter) over it.
    QImage image = window.grab().toImage();
    {
        QPainter p(&image);
        const QPoint at = window.viewport()->mapTo(&window, QPoint(0, 0));
        p.drawImage(QRect(at, window.viewport()->size()), window.viewport()->grabFramebuffer());
    }
    if (const Status saved = saveImageAtomically(image, out); !saved) {
        cli::printError(saved.message());
        return 1;
    }
    return 0;
}

} // namespace

int runEditor(int argc, char** argv) {
    QStringList arguments;
    for (int k = 0; k < argc; ++k)
        arguments << QString::fromLocal8Bit(argv[k]);
    QCommandLineParser parser;
    const QCommandLineOption shot(QStringLiteral("screenshot"),
                                  QStringLiteral("Open FILE, select its first surface, save a "
                                                 "picture of the window to OUT and exit."),
                                  QStringLiteral("OUT"));
    const QCommandLineOption demo(QStringLiteral("demo"),
                                  QStringLiteral("Start with a scene made by the Create and trim "
                                                 "tools (a shaped patch with a hole, a torus)."));
    const QCommandLineOption size(QStringLiteral("size"),
                                  QStringLiteral("Window size, e.g. 1280x800."),
                                  QStringLiteral("WxH"));
    const QCommandLineOption shading(QStringLiteral("shading"),
                                     QStringLiteral("Start with this View > Analysis mode."),
                                     QStringLiteral("MODE"));
    parser.addOptions({shot, size, demo, shading});
    if (!parser.parse(arguments) || parser.positionalArguments().size() > 1) {
        cli::printError(QStringLiteral("knotwork: %1 (see knotwork --help)")
                            .arg(parser.errorText().isEmpty() ? QStringLiteral("more than one FILE")
                                                              : parser.errorText()));
        return cli::kExitUsage;
    }
    QSize windowSize;
    if (parser.isSet(size)) {
        const QStringList wh = parser.value(size).split(QLatin1Char('x'));
        bool okW = false, okH = false;
        windowSize = QSize(wh.value(0).toInt(&okW), wh.value(1).toInt(&okH));
        if (wh.size() != 2 || !okW || !okH || windowSize.width() < 200 ||
            windowSize.height() < 150 || windowSize.width() > 8192 || windowSize.height() > 8192) {
            cli::printError(QStringLiteral("knotwork: --size wants WxH, 200x150 to 8192x8192, "
                                           "got '%1'")
                                .arg(parser.value(size)));
            return cli::kExitUsage;
        }
    }
    std::optional<AnalysisMode> mode;
    if (parser.isSet(shading)) {
        mode = parseAnalysisMode(parser.value(shading));
        if (!mode) {
            cli::printError(QStringLiteral("knotwork: --shading: unknown mode '%1'")
                                .arg(parser.value(shading)));
            return cli::kExitUsage;
        }
    }
    // Without a display Qt's xcb plugin aborts; say so plainly instead (usage errors above
    // need no display).
    if (qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM") && qEnvironmentVariableIsEmpty("DISPLAY") &&
        qEnvironmentVariableIsEmpty("WAYLAND_DISPLAY")) {
        cli::printError(QStringLiteral(
            "knotwork: cannot start the editor: no display (DISPLAY and WAYLAND_DISPLAY are "
            "unset). The command-line tools work without one: see knotwork --help."));
        return cli::kExitBadInput;
    }
    const QString file = parser.positionalArguments().value(0);
    // An IGES, STEP, BREP or OBJ file (a file manager opens those with Knotwork) is imported
    // into a new project once the window is up, as File > Import does, behind its progress
    // dialog; here only that it can be opened is checked.
    const CadFormat format = file.isEmpty() ? CadFormat::Unknown : cadFormatFromPath(file);
    const bool import = format != CadFormat::Knot && format != CadFormat::Unknown;
    if (const QString why = import ? checkRegularFile(file).message() : QString(); !why.isEmpty()) {
        cli::printError(QStringLiteral("%1: %2").arg(file, why));
        return cli::kExitBadInput;
    }
    if (import && format != CadFormat::Obj && !occtAvailable()) {
        cli::printError(QStringLiteral("%1: cannot read %2: %3")
                            .arg(file, cadFormatName(format), occtUnavailableMessage()));
        return cli::kExitBadInput;
    }
    if (!file.isEmpty() && !import) {
        // Fail before any window (or Qt platform) appears, with the loader's one-line message.
        if (const Expected<Scene> scene = readKnotFile(file); !scene) {
            cli::printError(scene.message());
            return cli::kExitBadInput;
        }
    }
    if (parser.isSet(shot) && file.isEmpty() && !parser.isSet(demo)) {
        cli::printError(QStringLiteral("knotwork: --screenshot needs a FILE or --demo"));
        return cli::kExitUsage;
    }

    QSurfaceFormat::setDefaultFormat(requiredSurfaceFormat()); // before QApplication
    QApplication app(argc, argv);
    QCoreApplication::setOrganizationName(QStringLiteral("Knotwork"));
    QCoreApplication::setApplicationName(QStringLiteral("knotwork"));
    QCoreApplication::setApplicationVersion(kw::versionString());

    if (const QString why = probeOpenGL(); !why.isEmpty()) {
        const QString text =
            QStringLiteral("Knotwork needs OpenGL 4.5 (core profile) to draw surfaces, but %1. "
                           "Update the graphics driver or use the command-line tools "
                           "(knotwork --help).")
                .arg(why);
        cli::printError(QStringLiteral("knotwork: ") + text);
        if (!headlessPlatform())
            QMessageBox::critical(nullptr, QStringLiteral("Knotwork"), text);
        return cli::kExitBadInput;
    }

    // Lets the desktop match the window to its launcher entry (Wayland app id, icon).
    QGuiApplication::setDesktopFileName(QStringLiteral("org.knotwork.Knotwork"));
    QApplication::setWindowIcon(QIcon::fromTheme(QStringLiteral("org.knotwork.Knotwork")));

    const QString quitReport = qEnvironmentVariable("KNOTWORK_QUIT_AFTER_OPEN");
    const bool scripted = parser.isSet(shot) || !quitReport.isEmpty();
    MainWindow window;
    if (scripted) // nobody to click a message box away: messages go to stderr, errors exit 1
        window.setDialogs(scriptedDialogs());
    if (windowSize.isValid())
        window.resize(windowSize);
    if (!file.isEmpty() && !import && !window.openFile(file))
        return cli::kExitBadInput;
    if (parser.isSet(demo))
        buildDemo(window);
    if (mode) {
        // Through View › Analysis, so the menu shows the mode (its actions are named after it).
        QString camel;
        for (const QString& part : analysisModeName(*mode).split(QLatin1Char('-')))
            camel += part.left(1).toUpper() + part.mid(1);
        if (QAction* a = window.action(QStringLiteral("actionAnalysis") + camel))
            a->trigger();
    }
    if (parser.isSet(shot)) {
        if (import && !window.importFile(file))
            return cli::kExitBadInput;
        return screenshot(window, parser.value(shot), parser.isSet(demo));
    }
    if (!quitReport.isEmpty())
        quitOnceShown(window, quitReport, /*loaded=*/!import);
    window.show();
    QTimer::singleShot(0, &window, [&window, file, import, scripted] {
        if (import && !window.importFile(file) && scripted) {
            QCoreApplication::exit(cli::kExitBadInput);
            return;
        }
        if (import)
            window.setProperty(kLoadedProperty, true);
        // After a crash: offer the autosaved edits once the window is up (the question is its
        // child); not to a scripted run, which must not wait for an answer.
        if (!scripted)
            window.offerRecovery();
    });
    return QApplication::exec();
}

} // namespace kw::app
