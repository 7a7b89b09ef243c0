// Exact pass: deferred (default), depth pre-pass + GL_EQUAL, or exact depth in one pass.
#include "render/exact_surface_pass.h"

#include "render/shading_uniforms.h"

#include <QOpenGLShaderProgram>
#include <algorithm>
#include <cmath>
#include <glm/gtc/type_ptr.hpp>

namespace kw {

namespace {

// Pixel rectangle (x0, y0, x1, y1) that contains the surface's projection: its control points'
// bounding box projected (the surface lies in the convex hull). The whole viewport when a
// corner is behind the eye.
glm::ivec4 projectedBounds(const Surface& s, const FrameCamera& camera) {
    const glm::ivec4 all(0, 0, camera.viewport.x, camera.viewport.y);
    glm::dvec3 lo, hi;
    surfaceControlBounds(s.geometry, lo, hi);
    glm::vec2 mn(1e30f), mx(-1e30f);
    for (int c = 0; c < 8; ++c) {
        const glm::vec4 p(float(c & 1 ? hi.x : lo.x), float(c & 2 ? hi.y : lo.y),
                          float(c & 4 ? hi.z : lo.z), 1.0f);
        const glm::vec4 clip = camera.viewProjection * p;
        if (!(clip.w > 1e-6f * std::abs(clip.z)) || clip.w <= 0.0f)
            return all;
        const glm::vec2 ndc = glm::vec2(clip) / clip.w;
        mn = glm::min(mn, ndc);
        mx = glm::max(mx, ndc);
    }
    const glm::vec2 vp(camera.viewport);
    const glm::ivec2 a = glm::clamp(glm::ivec2(glm::floor((mn * 0.5f + 0.5f) * vp)) - 1,
                                    glm::ivec2(0), camera.viewport);
    const glm::ivec2 b = glm::clamp(glm::ivec2(glm::ceil((mx * 0.5f + 0.5f) * vp)) + 1,
                                    glm::ivec2(0), camera.viewport);
    return glm::ivec4(a, b);
}

} // namespace

void ExactSurfacePass::initialize(QOpenGLFunctions_4_5_Core* gl, ShaderLibrary* shaders) {
    m_gl = gl;
    m_shaders = shaders;
}

QStringList ExactSurfacePass::variantDefines(int p, int q, int lightCount,
                                             const RenderOptions& options) {
    QStringList d{QStringLiteral("DEGREE_U %1").arg(p), QStringLiteral("DEGREE_V %1").arg(q),
                  QStringLiteral("LIGHT_COUNT %1").arg(lightCount)};
    if (options.writeAov)
        d << QStringLiteral("KW_AOV");
    if (options.shading == RenderOptions::Shading::ExactDepth)
        d << QStringLiteral("KW_EXACT_DEPTH");
    return d;
}

QOpenGLShaderProgram* ExactSurfacePass::exactProgram(const QString& vertex, const QString& fragment,
                                                     const SurfaceGpu& g, const FrameCamera& camera,
                                                     const std::vector<Light>& lights,
                                                     const RenderOptions& options, QString* error) {
    QOpenGLShaderProgram* prog = m_shaders->program(
        vertex, fragment, variantDefines(g.degreeU, g.degreeV, int(lights.size()), options));
    if (!prog) {
        *error = m_shaders->lastError();
        return nullptr;
    }
    if (prog != m_bound) {
        prog->bind();
        m_bound = prog;
        setFrameUniforms(m_gl, prog, camera, lights);
        m_gl->glUniform1i(prog->uniformLocation("uControl"), 0);
        m_gl->glUniform1i(prog->uniformLocation("uSpansU"), 1);
        m_gl->glUniform1i(prog->uniformLocation("uSpansV"), 2);
        m_gl->glUniform1i(prog->uniformLocation("uUvSpan"), 3);
        m_gl->glUniform1i(prog->uniformLocation("uSurface"), 4);
    }
    m_gl->glUniform4fv(prog->uniformLocation("uDomain"), 1, glm::value_ptr(g.domain));
    m_gl->glUniform3fv(prog->uniformLocation("uOrigin"), 1, glm::value_ptr(glm::vec3(g.origin)));
    m_gl->glBindTextureUnit(0, g.controlTexture);
    m_gl->glBindTextureUnit(1, g.spanTextureU);
    m_gl->glBindTextureUnit(2, g.spanTextureV);
    return prog;
}

bool ExactSurfacePass::drawBasePolygons(const Scene& scene, const SurfaceGpuCache& cache,
                                        const FrameCamera& camera, const QString& fragment,
                                        QString* error) {
    QOpenGLShaderProgram* prog = m_shaders->program(QStringLiteral("surface.vert"), fragment);
    if (!prog) {
        *error = m_shaders->lastError();
        return false;
    }
    prog->bind();
    m_bound = prog;
    m_gl->glUniformMatrix4fv(prog->uniformLocation("uViewProjection"), 1, GL_FALSE,
                             glm::value_ptr(camera.viewProjection));
    const int slotLocation = prog->uniformLocation("uSlot");
    for (size_t k = 0; k < scene.surfaces.size(); ++k)
        if (const SurfaceGpu* g = cache.find(scene.surfaces[k].id)) {
            m_gl->glUniform1f(slotLocation, float(k + 1));
            m_gl->glBindVertexArray(g->triangleVao);
            m_gl->glDrawElements(GL_TRIANGLES, g->triangleIndexCount, GL_UNSIGNED_INT, nullptr);
        }
    return true;
}

bool ExactSurfacePass::drawForward(const Scene& scene, const SurfaceGpuCache& cache,
                                   const FrameCamera& camera, const std::vector<Light>& lights,
                                   const RenderOptions& options, QString* error) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    if (options.shading == RenderOptions::Shading::DepthPrepass) {
        gl->glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        gl->glDepthFunc(GL_LESS);
        const bool ok =
            drawBasePolygons(scene, cache, camera, QStringLiteral("depth_only.frag"), error);
        gl->glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        if (!ok)
            return false;
        gl->glDepthFunc(GL_EQUAL);
        gl->glDepthMask(GL_FALSE);
    } else {
        gl->glDepthFunc(GL_LESS);
    }
    for (const Surface& s : scene.surfaces) {
        const SurfaceGpu* g = cache.find(s.id);
        if (!g)
            continue;
        QOpenGLShaderProgram* prog =
            exactProgram(QStringLiteral("surface.vert"), QStringLiteral("exact_surface.frag"), *g,
                         camera, lights, options, error);
        if (!prog)
            return false;
        setSurfaceUniforms(gl, prog, s);
        gl->glBindVertexArray(g->triangleVao);
        gl->glDrawElements(GL_TRIANGLES, g->triangleIndexCount, GL_UNSIGNED_INT, nullptr);
    }
    return true;
}

bool ExactSurfacePass::ensureGBuffer(QSize size, QString* error) {
    if (m_gFbo && size == m_gSize)
        return true;
    destroyGBuffer();
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    auto texture = [&](GLenum format) {
        GLuint t = 0;
        gl->glCreateTextures(GL_TEXTURE_2D, 1, &t);
        gl->glTextureStorage2D(t, 1, format, size.width(), size.height());
        gl->glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl->glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        return t;
    };
    m_gUvSpan = texture(GL_RGBA32F);
    m_gSurface = texture(GL_RGBA32F);
    m_gDepth = texture(GL_DEPTH_COMPONENT24);
    gl->glCreateFramebuffers(1, &m_gFbo);
    gl->glNamedFramebufferTexture(m_gFbo, GL_COLOR_ATTACHMENT0, m_gUvSpan, 0);
    gl->glNamedFramebufferTexture(m_gFbo, GL_COLOR_ATTACHMENT1, m_gSurface, 0);
    gl->glNamedFramebufferTexture(m_gFbo, GL_DEPTH_ATTACHMENT, m_gDepth, 0);
    const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    gl->glNamedFramebufferDrawBuffers(m_gFbo, 2, buffers);
    if (gl->glCheckNamedFramebufferStatus(m_gFbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        *error = QStringLiteral("the G-buffer framebuffer is incomplete");
        destroyGBuffer();
        return false;
    }
    if (!m_emptyVao)
        gl->glCreateVertexArrays(1, &m_emptyVao);
    m_gSize = size;
    return true;
}

bool ExactSurfacePass::drawDeferred(const Scene& scene, const SurfaceGpuCache& cache,
                                    const FrameCamera& camera, const std::vector<Light>& lights,
                                    const RenderOptions& options, GLuint targetFbo,
                                    QString* error) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    if (!ensureGBuffer(QSize(camera.viewport.x, camera.viewport.y), error))
        return false;
    // Pass 1: (u, v, span, slot, span scale, depth) of the nearest base polygon per pixel.
    gl->glBindFramebuffer(GL_FRAMEBUFFER, m_gFbo);
    const GLfloat zero[4] = {0.0f, 0.0f, 0.0f, 0.0f}, farDepth = 1.0f;
    gl->glClearBufferfv(GL_COLOR, 0, zero);
    gl->glClearBufferfv(GL_COLOR, 1, zero);
    gl->glClearBufferfv(GL_DEPTH, 0, &farDepth);
    gl->glDepthFunc(GL_LESS);
    gl->glDepthMask(GL_TRUE);
    if (!drawBasePolygons(scene, cache, camera, QStringLiteral("gbuffer.frag"), error))
        return false;

    // Pass 2: one screen-space triangle per surface, scissored to its projected bounds.
    gl->glBindFramebuffer(GL_FRAMEBUFFER, targetFbo);
    gl->glDepthFunc(GL_ALWAYS);
    gl->glEnable(GL_SCISSOR_TEST);
    gl->glBindTextureUnit(3, m_gUvSpan);
    gl->glBindTextureUnit(4, m_gSurface);
    gl->glBindVertexArray(m_emptyVao);
    bool ok = true;
    for (size_t k = 0; k < scene.surfaces.size() && ok; ++k) {
        const Surface& s = scene.surfaces[k];
        const SurfaceGpu* g = cache.find(s.id);
        if (!g)
            continue;
        const glm::ivec4 r = projectedBounds(s, camera);
        if (r.z <= r.x || r.w <= r.y)
            continue;
        QOpenGLShaderProgram* prog =
            exactProgram(QStringLiteral("fullscreen.vert"), QStringLiteral("exact_resolve.frag"),
                         *g, camera, lights, options, error);
        if (!prog) {
            ok = false;
            break;
        }
        setSurfaceUniforms(gl, prog, s);
        gl->glUniform1f(prog->uniformLocation("uSlot"), float(k + 1));
        gl->glScissor(r.x, r.y, r.z - r.x, r.w - r.y);
        gl->glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    gl->glDisable(GL_SCISSOR_TEST);
    return ok;
}

bool ExactSurfacePass::draw(const Scene& scene, const SurfaceGpuCache& cache,
                            const FrameCamera& camera, const std::vector<Light>& lights,
                            const RenderOptions& options, GLuint targetFbo, QString* error) {
    m_bound = nullptr;
    const bool ok = options.shading == RenderOptions::Shading::Deferred
                        ? drawDeferred(scene, cache, camera, lights, options, targetFbo, error)
                        : drawForward(scene, cache, camera, lights, options, error);
    m_gl->glDepthFunc(GL_LESS);
    m_gl->glDepthMask(GL_TRUE);
    m_bound = nullptr;
    return ok;
}

void ExactSurfacePass::release() {
    if (!m_gl)
        return;
    destroyGBuffer();
    if (m_emptyVao)
        m_gl->glDeleteVertexArrays(1, &m_emptyVao), m_emptyVao = 0;
}

void ExactSurfacePass::destroyGBuffer() {
    if (m_gFbo)
        m_gl->glDeleteFramebuffers(1, &m_gFbo);
    for (GLuint* t : {&m_gUvSpan, &m_gSurface, &m_gDepth})
        if (*t)
            m_gl->glDeleteTextures(1, t), *t = 0;
    m_gFbo = 0;
    m_gSize = QSize();
}

} // namespace kw
