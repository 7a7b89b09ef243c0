// The main of a subcommand that draws with OpenGL (render in knotwork-gl, bench in
// knotwork-bench): display check, default surface format, QGuiApplication.
#pragma once

#include <QString>
#include <QStringList>

namespace kw::cli {

/// Runs `run` as the process's command: refuses with exit code 1 and a message saying to use
/// xvfb-run when no X display can be reached (Qt's xcb plugin would abort), sets
/// OffscreenRenderer::requiredFormat() as the default surface format, creates the
/// QGuiApplication and calls `run` with the arguments after argv[1], led by "knotwork NAME"
/// where NAME is argv[1]. Returns run's exit code. Call before any Q*Application exists.
int runGlCommand(int argc, char** argv, int (*run)(const QStringList& args));

} // namespace kw::cli
