// The main of a subcommand that draws with OpenGL (see app/gl_command.h).
#include "app/gl_command.h"

#include "app/commands.h"
#include "render/offscreen_renderer.h"

#include <QGuiApplication>
#include <QSurfaceFormat>

namespace kw::cli {

int runGlCommand(int argc, char** argv, int (*run)(const QStringList& args)) {
    const QString name = QString::fromLocal8Bit(argc > 1 ? argv[1] : "");
    // Without a display Qt's xcb platform aborts the process; say what to do instead.
    const QByteArray platform = qgetenv("QT_QPA_PLATFORM");
    if ((platform.isEmpty() || platform.startsWith("xcb")) &&
        qEnvironmentVariableIsEmpty("DISPLAY")) {
        printError(QStringLiteral("knotwork %1: no OpenGL 4.5 context can be made: no X display "
                                  "(DISPLAY is not set). Run under xvfb-run -a -s \"-screen 0 "
                                  "1280x1024x24\" with QT_QPA_PLATFORM=xcb.")
                       .arg(name));
        return kExitBadInput;
    }
    // The default format must be set before the application object exists.
    QSurfaceFormat::setDefaultFormat(OffscreenRenderer::requiredFormat());
    QGuiApplication app(argc, argv);
    QCoreApplication::setApplicationName(QStringLiteral("knotwork"));
    QCoreApplication::setApplicationVersion(QStringLiteral(KW_VERSION));
    QStringList rest = QCoreApplication::arguments().mid(2);
    rest.prepend(QStringLiteral("knotwork ") + name);
    return run(rest);
}

} // namespace kw::cli
