// Off-screen context and framebuffer with colour and AOV targets; read-back of both.
#include "render/offscreen_renderer.h"

#include "render/depth_convention.h"
#include "render/exact_contract.h"
#include "render/gl_context.h"

#include <QOffscreenSurface>
#include <QOpenGLContext>
#include <QOpenGLDebugLogger>
#include <QOpenGLFunctions_4_5_Core>
#include <QOpenGLVersionFunctionsFactory>
#include <algorithm>
#include <vector>

namespace kw {

struct OffscreenRenderer::Impl {
    void destroyFramebuffer();

    std::unique_ptr<QOpenGLContext> context;
    std::unique_ptr<QOffscreenSurface> surface;
    std::unique_ptr<QOpenGLDebugLogger> debugLogger; ///< glDebugRequested() only
    QOpenGLFunctions_4_5_Core* gl = nullptr;         ///< set once the renderer is initialised
    Renderer renderer;
    FrameReport report;
    QSize size;
    bool withAov = false;
    bool withCurvature = false;
    GLuint fbo = 0;
    /// Only the renderer draws into `fbo`: once it has drawn a frame there, the framebuffer
    /// holds its last frame (RenderTarget::drawnOver); a new one holds nothing known.
    bool framed = false;
    GLuint color = 0, depth = 0;
    /// The AOV targets from kAovIdUvDepthOutput on, each at its output's attachment.
    GLuint aov[kCurvatureAovDrawBuffers - kAovIdUvDepthOutput] = {};
    GLuint aovTarget(int output) const { return aov[output - kAovIdUvDepthOutput]; }
};

OffscreenRenderer::OffscreenRenderer() : d(std::make_unique<Impl>()) {}

OffscreenRenderer::~OffscreenRenderer() {
    if (d->context && makeCurrent()) {
        d->destroyFramebuffer();
        d->renderer.release();
        d->debugLogger.reset(); // stops logging while its context is current
        d->context->doneCurrent();
    }
}

QSurfaceFormat OffscreenRenderer::requiredFormat() {
    return requiredSurfaceFormat();
}

Renderer& OffscreenRenderer::renderer() {
    return d->renderer;
}

const FrameReport& OffscreenRenderer::lastReport() const {
    return d->report;
}

bool OffscreenRenderer::makeCurrent() {
    return d->context && d->surface && d->context->makeCurrent(d->surface.get());
}

Status OffscreenRenderer::create() {
    d->context = std::make_unique<QOpenGLContext>();
    d->context->setFormat(requiredFormat());
    if (!d->context->create()) {
        d->context.reset();
        return Error(QStringLiteral("could not create an OpenGL context (an OpenGL 4.5 core "
                                    "context needs an X server: run under xvfb-run with "
                                    "QT_QPA_PLATFORM=xcb)"));
    }
    d->surface = std::make_unique<QOffscreenSurface>();
    d->surface->setFormat(d->context->format());
    d->surface->create();
    if (!makeCurrent())
        return Error(QStringLiteral("could not make the OpenGL context current"));
    d->debugLogger = startDebugLog(); // glDebugRequested() only
    // Renderer::initialize checks the version (render/gl_context.h).
    if (const Status initialized = d->renderer.initialize(); !initialized)
        return Error(initialized.message() +
                     QStringLiteral(" (run under xvfb-run with QT_QPA_PLATFORM=xcb on Mesa)"));
    d->gl = QOpenGLVersionFunctionsFactory::get<QOpenGLFunctions_4_5_Core>(d->context.get());
    return ok();
}

void OffscreenRenderer::Impl::destroyFramebuffer() {
    if (!gl)
        return;
    if (fbo)
        gl->glDeleteFramebuffers(1, &fbo);
    for (GLuint* t : {&color, &depth})
        if (*t)
            gl->glDeleteTextures(1, t), *t = 0;
    for (GLuint& t : aov)
        if (t)
            gl->glDeleteTextures(1, &t), t = 0;
    fbo = 0;
    framed = false;
}

Status OffscreenRenderer::setSize(QSize size, bool withAov, bool withCurvature) {
    withCurvature = withCurvature && withAov;
    if (size.width() < 1 || size.height() < 1 || size.width() > 16384 || size.height() > 16384)
        return Error(QStringLiteral("image size %1x%2 is outside 1..16384")
                         .arg(size.width())
                         .arg(size.height()));
    if (!makeCurrent() || !d->gl)
        return Error(QStringLiteral("the off-screen renderer has no OpenGL context"));
    if (size == d->size && withAov == d->withAov && withCurvature == d->withCurvature && d->fbo)
        return ok();
    d->destroyFramebuffer();
    QOpenGLFunctions_4_5_Core* gl = d->gl;
    auto texture = [&](GLenum format) {
        GLuint t = 0;
        gl->glCreateTextures(GL_TEXTURE_2D, 1, &t);
        gl->glTextureStorage2D(t, 1, format, size.width(), size.height());
        return t;
    };
    gl->glCreateFramebuffers(1, &d->fbo);
    d->color = texture(GL_RGBA8);
    d->depth = texture(kDepthStencilFormat);
    // Each output at its own attachment (render/exact_contract.h).
    const auto attachment = [](int output) {
        return GL_COLOR_ATTACHMENT0 + GLenum(output);
    };
    gl->glNamedFramebufferTexture(d->fbo, attachment(kColourOutput), d->color, 0);
    gl->glNamedFramebufferTexture(d->fbo, GL_DEPTH_STENCIL_ATTACHMENT, d->depth, 0);
    const int drawBuffers =
        withAov ? (withCurvature ? kCurvatureAovDrawBuffers : kAovDrawBuffers) : kColourOutput + 1;
    GLenum buffers[kCurvatureAovDrawBuffers];
    for (int k = 0; k < drawBuffers; ++k)
        buffers[k] = attachment(k);
    for (int k = kAovIdUvDepthOutput; k < drawBuffers; ++k) {
        GLuint& aov = d->aov[k - kAovIdUvDepthOutput];
        aov = texture(GL_RGBA32F);
        gl->glNamedFramebufferTexture(d->fbo, attachment(k), aov, 0);
    }
    gl->glNamedFramebufferDrawBuffers(d->fbo, drawBuffers, buffers);
    const GLenum status = gl->glCheckNamedFramebufferStatus(d->fbo, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        d->destroyFramebuffer();
        return Error(QStringLiteral("framebuffer incomplete (status 0x%1)").arg(status, 0, 16));
    }
    d->size = size;
    d->withAov = withAov;
    d->withCurvature = withCurvature;
    return ok();
}

QSize OffscreenRenderer::size() const {
    return d->size;
}

Status OffscreenRenderer::render(const Document& doc, const Camera& camera,
                                 const RenderOptions& options) {
    if (!d->fbo || !makeCurrent())
        return Error(
            QStringLiteral("OffscreenRenderer::render needs create() and setSize() first"));
    const std::optional<QRect> drawnOver = d->framed ? std::optional<QRect>(QRect()) : std::nullopt;
    d->report = d->renderer.render(
        doc, camera, {d->fbo, d->size, d->withAov, d->withCurvature, drawnOver}, options);
    d->framed = true;
    if (!d->report.ok)
        return Error(d->report.error);
    return ok();
}

std::int64_t OffscreenRenderer::setMesh(int slot, const TriangleMesh& mesh) {
    return makeCurrent() ? d->renderer.setMesh(slot, mesh) : -1;
}

Status OffscreenRenderer::renderMesh(const Document& doc, int slot, const Camera& camera,
                                     const RenderOptions& options) {
    return renderMeshes(doc, {slot}, camera, options);
}

Status OffscreenRenderer::renderMeshes(const Document& doc, const std::vector<int>& slots,
                                       const Camera& camera, const RenderOptions& options) {
    if (!d->fbo || !makeCurrent())
        return Error(
            QStringLiteral("OffscreenRenderer::renderMesh needs create() and setSize() first"));
    d->report = d->renderer.renderMeshes(
        doc, slots, camera, {d->fbo, d->size, d->withAov, d->withCurvature, std::nullopt}, options);
    if (!d->report.ok)
        return Error(d->report.error);
    return ok();
}

std::optional<PickHit> OffscreenRenderer::pick(const Document& doc, const Camera& camera,
                                               QPointF pixel, const RenderOptions& options) {
    if (!d->fbo || !makeCurrent())
        return std::nullopt;
    return d->renderer.pick(doc, camera, d->size, pixel, options);
}

void OffscreenRenderer::finish() {
    if (makeCurrent() && d->gl)
        d->gl->glFinish();
}

QImage OffscreenRenderer::colorImage() {
    if (!d->fbo || !makeCurrent())
        return {};
    QImage img(d->size, QImage::Format_RGBA8888);
    QOpenGLFunctions_4_5_Core* gl = d->gl;
    gl->glPixelStorei(GL_PACK_ALIGNMENT, 4);
    gl->glGetTextureImage(d->color, 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(img.sizeInBytes()),
                          img.bits());
    return img.mirrored(false, true); // GL rows run bottom-up
}

AovBuffer OffscreenRenderer::aov() {
    AovBuffer out;
    if (!d->fbo || !d->withAov || !makeCurrent())
        return out;
    const int w = d->size.width(), h = d->size.height();
    out.width = w;
    out.height = h;
    out.data.resize(size_t(w) * size_t(h) * AovBuffer::kChannels);
    std::vector<float> planes[3];
    QOpenGLFunctions_4_5_Core* gl = d->gl;
    const int outputs[3] = {kAovIdUvDepthOutput, kAovPositionOutput, kAovNormalOutput};
    for (int k = 0; k < 3; ++k) {
        planes[k].resize(size_t(w) * size_t(h) * 4);
        gl->glGetTextureImage(d->aovTarget(outputs[k]), 0, GL_RGBA, GL_FLOAT,
                              GLsizei(planes[k].size() * sizeof(float)), planes[k].data());
    }
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t src = (size_t(h - 1 - y) * size_t(w) + size_t(x)) * 4;
            float* dst =
                out.data.data() + (size_t(y) * size_t(w) + size_t(x)) * AovBuffer::kChannels;
            const float* a = &planes[0][src];
            const float* p = &planes[1][src];
            const float* n = &planes[2][src];
            const float values[AovBuffer::kChannels] = {a[0], a[1], a[2], p[0], p[1],
                                                        p[2], n[0], n[1], n[2], a[3]};
            std::copy(values, values + AovBuffer::kChannels, dst);
        }
    if (d->withCurvature) {
        // K, H, k1, k2 then d1.x, d1.y, d1.z, per pixel.
        constexpr int n = AovBuffer::kCurvatureChannels;
        std::vector<float> curv(size_t(w) * size_t(h) * 4), dir(curv.size());
        gl->glGetTextureImage(d->aovTarget(kAovCurvatureOutput), 0, GL_RGBA, GL_FLOAT,
                              GLsizei(curv.size() * sizeof(float)), curv.data());
        gl->glGetTextureImage(d->aovTarget(kAovDirectionOutput), 0, GL_RGBA, GL_FLOAT,
                              GLsizei(dir.size() * sizeof(float)), dir.data());
        out.curvature.resize(size_t(w) * size_t(h) * n);
        for (int y = 0; y < h; ++y) // GL rows run bottom-up
            for (int x = 0; x < w; ++x) {
                const size_t src = (size_t(h - 1 - y) * size_t(w) + size_t(x)) * 4;
                float* dst = out.curvature.data() + (size_t(y) * size_t(w) + size_t(x)) * n;
                std::copy_n(&curv[src], 4, dst);
                std::copy_n(&dir[src], 3, dst + 4);
            }
    }
    return out;
}

} // namespace kw
