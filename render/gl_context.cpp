// OpenGL requirement check and context description.
#include "render/gl_context.h"

#include <QDebug>
#include <QOpenGLContext>
#include <QOpenGLDebugLogger>
#include <QOpenGLFunctions>
#include <atomic>

namespace kw {

QSurfaceFormat requiredSurfaceFormat() {
    QSurfaceFormat f;
    f.setRenderableType(QSurfaceFormat::OpenGL);
    f.setVersion(4, 5);
    f.setProfile(QSurfaceFormat::CoreProfile);
    f.setDepthBufferSize(24);
    if (glDebugRequested())
        f.setOption(QSurfaceFormat::DebugContext);
    return f;
}

namespace {
std::atomic<bool> g_glDebug{false};
} // namespace

void setGlDebug(bool on) {
    g_glDebug = on;
}

bool glDebugRequested() {
    return g_glDebug;
}

std::unique_ptr<QOpenGLDebugLogger> startDebugLog() {
    const QOpenGLContext* ctx = QOpenGLContext::currentContext();
    if (!ctx || !ctx->format().testOption(QSurfaceFormat::DebugContext))
        return nullptr;
    auto log = std::make_unique<QOpenGLDebugLogger>();
    if (!log->initialize())
        return nullptr;
    QObject::connect(
        log.get(), &QOpenGLDebugLogger::messageLogged,
        [](const QOpenGLDebugMessage& m) { qWarning().noquote() << "GL debug:" << m.message(); });
    log->startLogging(QOpenGLDebugLogger::SynchronousLogging);
    return log;
}

QString openGlShortfall(const QSurfaceFormat& format, bool isOpenGLES) {
    const bool core = format.profile() == QSurfaceFormat::CoreProfile;
    if (!isOpenGLES && format.version() >= qMakePair(4, 5) && core)
        return {};
    return QStringLiteral("OpenGL %1%2.%3%4")
        .arg(isOpenGLES ? QStringLiteral("ES ") : QString())
        .arg(format.majorVersion())
        .arg(format.minorVersion())
        .arg(isOpenGLES || core ? QString() : QStringLiteral(" compatibility profile"));
}

QString currentContextReport() {
    QOpenGLContext* ctx = QOpenGLContext::currentContext();
    if (!ctx)
        return {};
    QOpenGLFunctions* f = ctx->functions();
    const auto text = [f](GLenum name) {
        return QString::fromLatin1(reinterpret_cast<const char*>(f->glGetString(name)));
    };
    return QStringLiteral("%1, OpenGL %2").arg(text(GL_RENDERER), text(GL_VERSION));
}

} // namespace kw
