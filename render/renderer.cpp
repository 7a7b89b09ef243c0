// Renderer facade: state setup, cache sync, passes in order, overlays.
#include "render/renderer.h"

#include <QOpenGLContext>
#include <QOpenGLVersionFunctionsFactory>
#include <algorithm>
#include <tuple>

namespace kw {

Renderer::Renderer() = default;
Renderer::~Renderer() = default;

bool Renderer::initialize() {
    QOpenGLContext* ctx = QOpenGLContext::currentContext();
    if (!ctx) {
        m_error = QStringLiteral("no current OpenGL context");
        return false;
    }
    const QSurfaceFormat fmt = ctx->format();
    if (fmt.version() < qMakePair(4, 5) || ctx->isOpenGLES()) {
        m_error = QStringLiteral("OpenGL 4.5 core is required, the context is %1.%2%3")
                      .arg(fmt.majorVersion())
                      .arg(fmt.minorVersion())
                      .arg(ctx->isOpenGLES() ? QStringLiteral(" ES") : QString());
        return false;
    }
    auto* gl = QOpenGLVersionFunctionsFactory::get<QOpenGLFunctions_4_5_Core>(ctx);
    if (!gl || !gl->initializeOpenGLFunctions()) {
        m_error = QStringLiteral("OpenGL 4.5 core functions are not available");
        return false;
    }
    m_gl = gl;
    m_glDescription =
        QStringLiteral("%1, OpenGL %2")
            .arg(QString::fromLatin1(reinterpret_cast<const char*>(gl->glGetString(GL_RENDERER))),
                 QString::fromLatin1(reinterpret_cast<const char*>(gl->glGetString(GL_VERSION))));
    m_cache.initialize(gl);
    m_exact.initialize(gl, &m_shaders);
    m_tessellated.initialize(gl, &m_shaders);
    m_trimMasks.initialize(gl, &m_shaders);
    m_wireframe.initialize(gl, &m_shaders);
    m_controlNet.initialize(gl, &m_shaders);
    // Build the common programs now so a broken shader is reported at start-up.
    const RenderOptions defaults;
    const std::tuple<const char*, const char*, QStringList> common[] = {
        {"surface.vert", "depth_only.frag", {}},
        {"surface.vert", "depth_only.frag", {QStringLiteral("KW_TRIM")}},
        {"trim_mask.vert", "trim_mask.frag", {}},
        {"lines.vert", "lines.frag", {}},
        {"tessellated.vert", "tessellated.frag", {QStringLiteral("LIGHT_COUNT 2")}},
        {"surface.vert", "exact_surface.frag",
         ExactSurfacePass::variantDefines(3, 3, defaults.lightCount, defaults)}};
    for (const auto& [vs, fs, defines] : common)
        if (!m_shaders.program(QString::fromLatin1(vs), QString::fromLatin1(fs), defines)) {
            m_error = m_shaders.lastError();
            release();
            return false;
        }
    return true;
}

bool Renderer::render(const Document& doc, const Camera& camera, QSize size,
                      const RenderOptions& options, GLuint targetFbo) {
    if (!m_gl) {
        m_error = QStringLiteral("Renderer::render called before initialize()");
        return false;
    }
    if (size.width() <= 0 || size.height() <= 0) {
        m_error = QStringLiteral("render size %1x%2 is empty").arg(size.width()).arg(size.height());
        return false;
    }
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    const Scene& scene = doc.scene();
    FrameCamera fc = frameCamera(camera, scene, double(size.width()) / size.height());
    fc.viewport = glm::ivec2(size.width(), size.height());
    const std::vector<Light> lights = lightsFor(scene, camera, options.lightCount);

    if (m_document != &doc) {
        dropSurfaceCaches();
        m_document = &doc;
    }
    // Trim masks first: they draw into their own framebuffer.
    QString maskError;
    const bool masked = !options.trims || m_trimMasks.sync(doc, fc, options, &maskError);
    const TrimMaskPass* masks = options.trims ? &m_trimMasks : nullptr;

    gl->glBindFramebuffer(GL_FRAMEBUFFER, targetFbo);
    gl->glViewport(0, 0, size.width(), size.height());
    gl->glDisable(GL_BLEND);
    gl->glDisable(GL_CULL_FACE);
    gl->glEnable(GL_DEPTH_TEST);
    gl->glDepthMask(GL_TRUE);
    gl->glClearBufferfv(GL_COLOR, 0, &options.background.x);
    if (options.writeAov) {
        const GLfloat background[4] = {-1.0f, 0.0f, 0.0f, 0.0f}; // surface id -1
        const GLfloat zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        gl->glClearBufferfv(GL_COLOR, 1, background);
        gl->glClearBufferfv(GL_COLOR, 2, zero);
        gl->glClearBufferfv(GL_COLOR, 3, zero);
    }
    const GLfloat farDepth = 1.0f;
    gl->glClearBufferfv(GL_DEPTH, 0, &farDepth);

    if (options.writeCurvatureAov) {
        const GLfloat zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        gl->glClearBufferfv(GL_COLOR, 4, zero);
    }
    resolveAnalysisRange(doc, options.analysis);

    // A surface too large for a texture is left out of the frame and reported.
    QString cacheError;
    const bool cached = m_cache.sync(doc, options.partitionsU, options.partitionsV, &cacheError);
    bool ok =
        options.mode == RenderMode::Exact
            ? m_exact.draw(scene, m_cache, masks, fc, lights, options, m_analysisRange, &m_error)
            : m_tessellated.draw(doc, masks, fc, lights, options, &m_error);
    if (ok && (options.wireframe || options.controlNet)) {
        // Overlays write colour only; the AOV targets keep the surfaces' values.
        if (options.writeAov) {
            const GLenum only0 = GL_COLOR_ATTACHMENT0;
            gl->glNamedFramebufferDrawBuffers(targetFbo, 1, &only0);
        }
        if (options.wireframe)
            ok = m_wireframe.draw(scene, m_cache, fc, &m_error);
        if (ok && options.controlNet)
            ok = m_controlNet.draw(doc, fc, &m_error);
        if (options.writeAov) {
            const GLenum all[5] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2,
                                   GL_COLOR_ATTACHMENT3, GL_COLOR_ATTACHMENT4};
            gl->glNamedFramebufferDrawBuffers(targetFbo, options.writeCurvatureAov ? 5 : 4, all);
        }
    }
    gl->glBindVertexArray(0);
    gl->glUseProgram(0);
    if (ok && !cached) {
        m_error = cacheError;
        return false;
    }
    if (ok && !masked) {
        m_error = maskError;
        return false;
    }
    return ok;
}

void Renderer::resolveAnalysisRange(const Document& doc, const AnalysisOptions& analysis) {
    if (!isColourMap(analysis.mode))
        return;
    if (analysis.range) {
        m_analysisRange = *analysis.range;
        return;
    }
    // Revisions come from one document-wide counter and never repeat, so the largest geometry
    // revision and the surface count identify the geometry the range was computed from.
    std::uint64_t newest = 0;
    for (const Surface& s : doc.scene().surfaces) {
        const Revisions r = doc.revisions(s.id);
        newest = std::max({newest, r.points, r.knots});
    }
    const RangeKey key{&doc, analysis.mode, doc.scene().surfaces.size(), newest};
    if (analysis.holdRange && m_rangeKey.document == &doc && m_rangeKey.mode == analysis.mode)
        return;
    if (key == m_rangeKey)
        return;
    m_analysisRange = autoRange(doc.scene(), analysis.mode);
    m_rangeKey = key;
}

void Renderer::dropSurfaceCaches() {
    m_cache.release();
    m_trimMasks.release();
    m_tessellated.release();
    m_controlNet.release();
}

void Renderer::release() {
    if (!m_gl)
        return;
    dropSurfaceCaches();
    m_exact.release();
    m_document = nullptr;
    m_rangeKey = {};
    m_shaders.clear();
    m_gl = nullptr;
}

} // namespace kw
