// Off-screen context and framebuffer with colour and AOV targets; read-back of both.
#include "render/offscreen_renderer.h"

namespace kw {

const char* const AovBuffer::kChannelNames[AovBuffer::kChannels] = {
    "id", "u", "v", "P.x", "P.y", "P.z", "N.x", "N.y", "N.z", "Z"};
const char* const AovBuffer::kCurvatureNames[AovBuffer::kCurvatureChannels] = {"K", "H", "k1",
                                                                               "k2"};

OffscreenRenderer::OffscreenRenderer() = default;

OffscreenRenderer::~OffscreenRenderer() {
    if (m_context && makeCurrent()) {
        destroyFramebuffer();
        m_renderer.release();
        m_context->doneCurrent();
    }
}

QSurfaceFormat OffscreenRenderer::requiredFormat() {
    QSurfaceFormat f;
    f.setRenderableType(QSurfaceFormat::OpenGL);
    f.setVersion(4, 5);
    f.setProfile(QSurfaceFormat::CoreProfile);
    f.setDepthBufferSize(24);
    return f;
}

bool OffscreenRenderer::makeCurrent() {
    return m_context && m_surface && m_context->makeCurrent(m_surface.get());
}

bool OffscreenRenderer::create(QString* error) {
    m_context = std::make_unique<QOpenGLContext>();
    m_context->setFormat(requiredFormat());
    if (!m_context->create()) {
        *error = QStringLiteral("could not create an OpenGL context (an OpenGL 4.5 core context "
                                "needs an X server: run under xvfb-run with QT_QPA_PLATFORM=xcb)");
        m_context.reset();
        return false;
    }
    m_surface = std::make_unique<QOffscreenSurface>();
    m_surface->setFormat(m_context->format());
    m_surface->create();
    if (!makeCurrent()) {
        *error = QStringLiteral("could not make the OpenGL context current");
        return false;
    }
    const QSurfaceFormat got = m_context->format();
    if (got.version() < qMakePair(4, 5) || got.profile() != QSurfaceFormat::CoreProfile) {
        *error = QStringLiteral("OpenGL 4.5 core is required, got %1.%2 (run under xvfb-run with "
                                "QT_QPA_PLATFORM=xcb on Mesa)")
                     .arg(got.majorVersion())
                     .arg(got.minorVersion());
        return false;
    }
    if (!m_renderer.initialize()) {
        *error = m_renderer.lastError();
        return false;
    }
    return true;
}

void OffscreenRenderer::destroyFramebuffer() {
    QOpenGLFunctions_4_5_Core* gl = m_renderer.gl();
    if (!gl)
        return;
    if (m_fbo)
        gl->glDeleteFramebuffers(1, &m_fbo);
    GLuint tex[6] = {m_color, m_depth, m_aov[0], m_aov[1], m_aov[2], m_aov[3]};
    for (GLuint t : tex)
        if (t)
            gl->glDeleteTextures(1, &t);
    m_fbo = m_color = m_depth = 0;
    m_aov[0] = m_aov[1] = m_aov[2] = m_aov[3] = 0;
}

bool OffscreenRenderer::setSize(QSize size, bool withAov, QString* error, bool withCurvature) {
    withCurvature = withCurvature && withAov;
    if (size.width() < 1 || size.height() < 1 || size.width() > 16384 || size.height() > 16384) {
        *error = QStringLiteral("image size %1x%2 is outside 1..16384")
                     .arg(size.width())
                     .arg(size.height());
        return false;
    }
    if (!makeCurrent() || !m_renderer.gl()) {
        *error = QStringLiteral("the off-screen renderer has no OpenGL context");
        return false;
    }
    if (size == m_size && withAov == m_withAov && withCurvature == m_withCurvature && m_fbo)
        return true;
    destroyFramebuffer();
    QOpenGLFunctions_4_5_Core* gl = m_renderer.gl();
    auto texture = [&](GLenum format) {
        GLuint t = 0;
        gl->glCreateTextures(GL_TEXTURE_2D, 1, &t);
        gl->glTextureStorage2D(t, 1, format, size.width(), size.height());
        return t;
    };
    gl->glCreateFramebuffers(1, &m_fbo);
    m_color = texture(GL_RGBA8);
    m_depth = texture(GL_DEPTH_COMPONENT24);
    gl->glNamedFramebufferTexture(m_fbo, GL_COLOR_ATTACHMENT0, m_color, 0);
    gl->glNamedFramebufferTexture(m_fbo, GL_DEPTH_ATTACHMENT, m_depth, 0);
    GLenum buffers[5] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2,
                         GL_COLOR_ATTACHMENT3, GL_COLOR_ATTACHMENT4};
    const int aovTargets = withAov ? (withCurvature ? 4 : 3) : 0;
    for (int k = 0; k < aovTargets; ++k) {
        m_aov[k] = texture(GL_RGBA32F);
        gl->glNamedFramebufferTexture(m_fbo, GL_COLOR_ATTACHMENT1 + GLenum(k), m_aov[k], 0);
    }
    gl->glNamedFramebufferDrawBuffers(m_fbo, 1 + aovTargets, buffers);
    const GLenum status = gl->glCheckNamedFramebufferStatus(m_fbo, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        *error = QStringLiteral("framebuffer incomplete (status 0x%1)").arg(status, 0, 16);
        destroyFramebuffer();
        return false;
    }
    m_size = size;
    m_withAov = withAov;
    m_withCurvature = withCurvature;
    return true;
}

bool OffscreenRenderer::render(const Document& doc, const Camera& camera, RenderOptions options,
                               QString* error) {
    if (!m_fbo || !makeCurrent()) {
        *error = QStringLiteral("OffscreenRenderer::render needs create() and setSize() first");
        return false;
    }
    options.writeAov = m_withAov;
    options.writeCurvatureAov = m_withCurvature;
    if (!m_renderer.render(doc, camera, m_size, options, m_fbo)) {
        *error = m_renderer.lastError();
        return false;
    }
    return true;
}

void OffscreenRenderer::finish() {
    if (makeCurrent())
        m_renderer.gl()->glFinish();
}

QImage OffscreenRenderer::colorImage() {
    if (!m_fbo || !makeCurrent())
        return {};
    QImage img(m_size, QImage::Format_RGBA8888);
    QOpenGLFunctions_4_5_Core* gl = m_renderer.gl();
    gl->glPixelStorei(GL_PACK_ALIGNMENT, 4);
    gl->glGetTextureImage(m_color, 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(img.sizeInBytes()),
                          img.bits());
    return img.mirrored(false, true); // GL rows run bottom-up
}

AovBuffer OffscreenRenderer::aov() {
    AovBuffer out;
    if (!m_fbo || !m_withAov || !makeCurrent())
        return out;
    const int w = m_size.width(), h = m_size.height();
    out.width = w;
    out.height = h;
    out.data.resize(size_t(w) * size_t(h) * AovBuffer::kChannels);
    std::vector<float> planes[3];
    QOpenGLFunctions_4_5_Core* gl = m_renderer.gl();
    for (int k = 0; k < 3; ++k) {
        planes[k].resize(size_t(w) * size_t(h) * 4);
        gl->glGetTextureImage(m_aov[k], 0, GL_RGBA, GL_FLOAT,
                              GLsizei(planes[k].size() * sizeof(float)), planes[k].data());
    }
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t src = (size_t(h - 1 - y) * size_t(w) + size_t(x)) * 4;
            float* d = out.data.data() + (size_t(y) * size_t(w) + size_t(x)) * AovBuffer::kChannels;
            const float* a = &planes[0][src];
            const float* p = &planes[1][src];
            const float* n = &planes[2][src];
            const float values[AovBuffer::kChannels] = {a[0], a[1], a[2], p[0], p[1],
                                                        p[2], n[0], n[1], n[2], a[3]};
            std::copy(values, values + AovBuffer::kChannels, d);
        }
    if (m_withCurvature) {
        std::vector<float> plane(size_t(w) * size_t(h) * 4);
        gl->glGetTextureImage(m_aov[3], 0, GL_RGBA, GL_FLOAT, GLsizei(plane.size() * sizeof(float)),
                              plane.data());
        out.curvature.resize(plane.size());
        for (int y = 0; y < h; ++y) // GL rows run bottom-up
            std::copy_n(plane.data() + size_t(h - 1 - y) * size_t(w) * 4, size_t(w) * 4,
                        out.curvature.data() + size_t(y) * size_t(w) * 4);
    }
    return out;
}

} // namespace kw
