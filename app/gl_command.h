// The main of a subcommand that draws with OpenGL (render in knotwork-gl, bench in
// knotwork-bench): arguments first, then the display check, default surface format and
// QGuiApplication, only once the command knows it will draw.
#pragma once

#include <QString>
#include <QStringList>
#include <functional>

namespace kw::cli {

/// Called by a GL command once its arguments are valid: refuses with a message saying to use
/// xvfb-run when no X display can be reached (Qt's xcb plugin would abort) and returns false;
/// otherwise sets OffscreenRenderer::requiredFormat() as the default surface format, creates
/// the QGuiApplication (kept until the command returns) and returns true. Later calls return
/// the first call's answer.
using GuiStarter = std::function<bool()>;

/// Runs `run` as the process's command with the arguments after argv[1], led by
/// "knotwork NAME" where NAME is argv[1]. Usage errors and --help are answered before any
/// connection to the display exists, so they never depend on it. Returns run's exit code.
/// Call before any Q*Application exists.
int runGlCommand(int argc, char** argv,
                 int (*run)(const QStringList& args, const GuiStarter& startGui));

/// The process-wide development switches of the GL executables, applied before any context
/// or shader exists: KW_SHADER_DIR=DIR reads the shaders from DIR instead of the bundled ones
/// (ShaderLibrary::setSourceDirectory; tools/speed_floor.py measures with it), KW_GL_DEBUG=1
/// asks for debug contexts that print the driver's messages (kw::setGlDebug).
void applyDevelopmentSwitches();

} // namespace kw::cli
