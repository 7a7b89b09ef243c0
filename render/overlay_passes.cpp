// Wireframe of the base polygon and the control net.
#include "render/overlay_passes.h"

#include "render/depth_convention.h"
#include "render/shading_uniforms.h"

#include <QOpenGLShaderProgram>
#include <glm/gtc/type_ptr.hpp>

namespace kw {

namespace {

Expected<QOpenGLShaderProgram*> lineProgram(QOpenGLFunctions_4_5_Core* gl, ShaderLibrary* shaders,
                                            const FrameCamera& camera,
                                            const RenderOptions& options) {
    // Section planes cut the lines too: a cut view shows no wire of what it removed.
    const bool cut = !options.sections.empty();
    const Expected<QOpenGLShaderProgram*> built =
        shaders->program(QStringLiteral("lines.vert"), QStringLiteral("lines.frag"),
                         cut ? QStringList{QStringLiteral("KW_SECTION")} : QStringList{});
    if (!built)
        return built;
    QOpenGLShaderProgram* prog = *built;
    prog->bind();
    if (cut)
        setSectionUniforms(gl, prog, options);
    gl->glUniformMatrix4fv(ShaderLibrary::uniforms(prog).viewProjection, 1, GL_FALSE,
                           glm::value_ptr(drawnViewProjection(camera)));
    gl->glDepthFunc(kDepthNearerOrEqual);
    gl->glDepthMask(GL_FALSE);
    return prog;
}

} // namespace

void WireframePass::initialize(QOpenGLFunctions_4_5_Core* gl, ShaderLibrary* shaders) {
    m_gl = gl;
    m_shaders = shaders;
}

Status WireframePass::draw(const GpuScene& scene, const FrameCamera& camera,
                           const RenderOptions& options) {
    const Expected<QOpenGLShaderProgram*> built = lineProgram(m_gl, m_shaders, camera, options);
    if (!built)
        return built.error();
    QOpenGLShaderProgram* prog = *built;
    m_gl->glUniform1f(ShaderLibrary::uniforms(prog).depthBias, 2e-4f);
    m_gl->glUniform1f(ShaderLibrary::uniforms(prog).pointSize, 1.0f);
    m_gl->glUniform4fv(ShaderLibrary::uniforms(prog).lineColor, 1, glm::value_ptr(color));
    m_gl->glBindVertexArray(scene.outlineVao());
    for (const SurfaceRecord* r : scene.records())
        if (const SurfaceGpu* g = r->exact.get()) {
            m_gl->glDrawElementsBaseVertex(
                GL_LINES, g->outlineIndexCount, GL_UNSIGNED_INT,
                reinterpret_cast<const void*>(g->outlineOffset * std::int64_t(sizeof(unsigned))),
                GLint(g->vertexOffset));
            ++drawCalls;
        }
    m_gl->glDepthFunc(kDepthNearer);
    m_gl->glDepthMask(GL_TRUE);
    return ok();
}

void ControlNetPass::initialize(QOpenGLFunctions_4_5_Core* gl, ShaderLibrary* shaders) {
    m_gl = gl;
    m_shaders = shaders;
}

Status ControlNetPass::draw(const GpuScene& scene, const FrameCamera& camera,
                            const RenderOptions& options) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    const Expected<QOpenGLShaderProgram*> built = lineProgram(gl, m_shaders, camera, options);
    if (!built)
        return built.error();
    QOpenGLShaderProgram* prog = *built;
    gl->glEnable(GL_PROGRAM_POINT_SIZE);
    gl->glUniform1f(ShaderLibrary::uniforms(prog).depthBias, 1e-3f);
    gl->glUniform1f(ShaderLibrary::uniforms(prog).pointSize, pointSize);
    for (const SurfaceRecord* r : scene.records()) {
        const NetGpu& n = r->net;
        if (!n.vao)
            continue;
        gl->glBindVertexArray(n.vao);
        gl->glUniform4fv(ShaderLibrary::uniforms(prog).lineColor, 1, glm::value_ptr(lineColor));
        gl->glDrawElements(GL_LINES, n.lineIndexCount, GL_UNSIGNED_INT, nullptr);
        gl->glUniform4fv(ShaderLibrary::uniforms(prog).lineColor, 1, glm::value_ptr(pointColor));
        gl->glDrawArrays(GL_POINTS, 0, n.pointCount);
        drawCalls += 2;
    }
    gl->glDisable(GL_PROGRAM_POINT_SIZE);
    gl->glDepthFunc(kDepthNearer);
    gl->glDepthMask(GL_TRUE);
    return ok();
}

} // namespace kw
