// The main of a subcommand that draws with OpenGL (see app/gl_command.h).
#include "app/gl_command.h"

#include "app/commands.h"
#include "app/version.h"
#include "render/gl_context.h"
#include "render/offscreen_renderer.h"
#include "render/shader_library.h"

#include <QGuiApplication>
#include <QSurfaceFormat>
#include <optional>

namespace kw::cli {

void applyDevelopmentSwitches() {
    if (const QString dir = qEnvironmentVariable("KW_SHADER_DIR"); !dir.isEmpty())
        ShaderLibrary::setSourceDirectory(dir);
    setGlDebug(qEnvironmentVariableIntValue("KW_GL_DEBUG") != 0);
}

int runGlCommand(int argc, char** argv,
                 int (*run)(const QStringList& args, const GuiStarter& startGui)) {
    applyDevelopmentSwitches();
    const QString name = QString::fromLocal8Bit(argc > 1 ? argv[1] : "");
    QCoreApplication::setApplicationName(QStringLiteral("knotwork"));
    QCoreApplication::setApplicationVersion(kw::versionString());
    QStringList rest{QStringLiteral("knotwork ") + name};
    for (int i = 2; i < argc; ++i)
        rest << QString::fromLocal8Bit(argv[i]);

    std::optional<QGuiApplication> app;
    std::optional<bool> started;
    const GuiStarter startGui = [&]() -> bool {
        if (started)
            return *started;
        // Without a display Qt's xcb platform aborts the process; say what to do instead.
        const QByteArray platform = qgetenv("QT_QPA_PLATFORM");
        if ((platform.isEmpty() || platform.startsWith("xcb")) &&
            qEnvironmentVariableIsEmpty("DISPLAY")) {
            printError(QStringLiteral("knotwork %1: no OpenGL 4.5 context can be made: no X "
                                      "display (DISPLAY is not set). Run under xvfb-run -a -s "
                                      "\"-screen 0 1280x1024x24\" with QT_QPA_PLATFORM=xcb.")
                           .arg(name));
            started = false;
            return false;
        }
        // The default format must be set before the application object exists.
        QSurfaceFormat::setDefaultFormat(OffscreenRenderer::requiredFormat());
        app.emplace(argc, argv);
        started = true;
        return true;
    };
    return run(rest, startGui);
}

} // namespace kw::cli
