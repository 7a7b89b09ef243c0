// The editor entry point: display and OpenGL checks, the main window, and --screenshot.
#include "app/editor.h"

#include "app/commands.h"
#include "model/knotfile.h"
#include "render/gl_context.h"
#include "ui/mainwindow.h"
#include "ui/viewport.h"

#include <QApplication>
#include <QCommandLineParser>
#include <QElapsedTimer>
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

/// Shows the window, waits until the viewport has drawn a few frames, saves a grab.
int screenshot(MainWindow& window, const QString& out) {
    // Show a picked control point too, so the property panel's point box is filled.
    if (const SurfaceId id = window.selection()->currentSurface(); id.isValid())
        window.selection()->setControlPoints({ControlPointRef{id, 1, 2}});
    window.show();
    QElapsedTimer clock;
    clock.start();
    // Let the window be exposed and the viewport draw (llvmpipe: allow a few seconds).
    while (clock.elapsed() < 1500)
        QCoreApplication::processEvents(QEventLoop::AllEvents, 50);
    // QWidget::grab() may show the viewport's previous composition; paint its current frame
    // (which includes the picked-point marks drawn with QPainter) over it.
    QImage image = window.grab().toImage();
    {
        QPainter p(&image);
        const QPoint at = window.viewport()->mapTo(&window, QPoint(0, 0));
        p.drawImage(QRect(at, window.viewport()->size()), window.viewport()->grabFramebuffer());
    }
    if (image.isNull() || !image.save(out)) {
        cli::printError(QStringLiteral("%1: cannot write the screenshot").arg(out));
        return 1;
    }
    return 0;
}

} // namespace

int runEditor(int argc, char** argv) {
    // Without a display Qt's xcb plugin aborts; say so plainly instead.
    if (qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM") && qEnvironmentVariableIsEmpty("DISPLAY") &&
        qEnvironmentVariableIsEmpty("WAYLAND_DISPLAY")) {
        cli::printError(QStringLiteral(
            "knotwork: cannot start the editor: no display (DISPLAY and WAYLAND_DISPLAY are "
            "unset). The command-line tools work without one: see knotwork --help."));
        return cli::kExitBadInput;
    }
    QStringList arguments;
    for (int k = 0; k < argc; ++k)
        arguments << QString::fromLocal8Bit(argv[k]);
    QCommandLineParser parser;
    const QCommandLineOption shot(QStringLiteral("screenshot"),
                                  QStringLiteral("Open FILE, select its first surface, save a "
                                                 "picture of the window to OUT and exit."),
                                  QStringLiteral("OUT"));
    const QCommandLineOption size(QStringLiteral("size"),
                                  QStringLiteral("Window size, e.g. 1280x800."),
                                  QStringLiteral("WxH"));
    parser.addOptions({shot, size});
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
    const QString file = parser.positionalArguments().value(0);
    if (!file.isEmpty()) {
        // Fail before any window (or Qt platform) appears, with the loader's one-line message.
        QString error;
        if (!readKnotFile(file, &error)) {
            cli::printError(error);
            return cli::kExitBadInput;
        }
    }
    if (parser.isSet(shot) && file.isEmpty()) {
        cli::printError(QStringLiteral("knotwork: --screenshot needs a FILE"));
        return cli::kExitUsage;
    }

    QSurfaceFormat::setDefaultFormat(requiredSurfaceFormat()); // before QApplication
    QApplication app(argc, argv);
    QCoreApplication::setOrganizationName(QStringLiteral("Knotwork"));
    QCoreApplication::setApplicationName(QStringLiteral("knotwork"));
    QCoreApplication::setApplicationVersion(QStringLiteral(KW_VERSION));

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

    MainWindow window;
    if (windowSize.isValid())
        window.resize(windowSize);
    if (!file.isEmpty() && !window.openFile(file))
        return cli::kExitBadInput;
    if (parser.isSet(shot))
        return screenshot(window, parser.value(shot));
    window.show();
    // After a crash: offer the autosaved edits once the window is up (the question is its child).
    QTimer::singleShot(0, &window, [&window] { window.offerRecovery(); });
    return QApplication::exec();
}

} // namespace kw::app
