// The one place Knotwork states its OpenGL requirement (4.5 core), checks a context against it
// and describes a context for reports. No GL headers: QSurfaceFormat is plain Qt Gui.
#pragma once

#include <QString>
#include <QSurfaceFormat>
#include <memory>

class QOpenGLDebugLogger;

namespace kw {

/// The surface format every Knotwork GL context asks for: OpenGL 4.5 core, depth 24 (and a
/// debug context after setGlDebug(true)). Set it as the default
/// (QSurfaceFormat::setDefaultFormat) before creating the application.
QSurfaceFormat requiredSurfaceFormat();

/// Debug contexts whose driver messages go to stderr (startDebugLog), for development and for
/// reports from users' GPUs; off by default. Process-wide: set it before the first context
/// (the executables do for KW_GL_DEBUG=1, kw::cli::applyDevelopmentSwitches).
void setGlDebug(bool on);
bool glDebugRequested();

/// For a current debug context: a logger printing each driver message to stderr ("GL debug:
/// ..."), synchronously, so each follows the call that raised it. Null for other contexts.
/// Destroy it while its context is current.
std::unique_ptr<QOpenGLDebugLogger> startDebugLog();

/// Empty when a created context with `format` (QOpenGLContext::format()) and `isOpenGLES`
/// meets the requirement; otherwise what it is instead, e.g. "OpenGL ES 3.2" or "OpenGL 3.1
/// compatibility profile", for messages of the form "OpenGL 4.5 core is required, got ...".
QString openGlShortfall(const QSurfaceFormat& format, bool isOpenGLES);

/// GL_RENDERER and GL_VERSION of the current context ("llvmpipe (LLVM 15.0.6, 256 bits),
/// OpenGL 4.5 (Core Profile) Mesa 22.3.6"); empty when no context is current.
QString currentContextReport();

} // namespace kw
