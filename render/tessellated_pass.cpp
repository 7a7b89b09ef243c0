// Baseline pass: meshes from kw::tessellate (built by GpuScene), Gouraud shading on the GPU.
#include "render/tessellated_pass.h"

#include "render/depth_convention.h"
#include "render/exact_contract.h"
#include "render/shader_library.h"
#include "render/shading_uniforms.h"
#include "render/thread_clock.h"

#include <QOpenGLShaderProgram>

namespace kw {

void setMeshAttributes(QOpenGLFunctions_4_5_Core* gl, GLuint vao, const GLuint (&buffers)[3]) {
    const int locations[3] = {kAttrPosition, kAttrMeshNormal, kAttrMeshUv};
    const int sizes[3] = {3, 3, 2};
    for (int k = 0; k < 3; ++k) {
        const GLuint a = GLuint(locations[k]);
        gl->glVertexArrayVertexBuffer(vao, a, buffers[k], 0, GLsizei(sizes[k] * sizeof(float)));
        gl->glEnableVertexArrayAttrib(vao, a);
        gl->glVertexArrayAttribFormat(vao, a, sizes[k], GL_FLOAT, GL_FALSE, 0);
        gl->glVertexArrayAttribBinding(vao, a, a);
    }
}

void TessellatedPass::initialize(QOpenGLFunctions_4_5_Core* gl, ShaderLibrary* shaders) {
    m_gl = gl;
    m_shaders = shaders;
}

Status TessellatedPass::draw(const GpuScene& scene, bool trims, const FrameCamera& camera,
                             const std::vector<Light>& lights, const RenderOptions& options) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    QStringList defines{QStringLiteral("LIGHT_COUNT %1").arg(lights.size())};
    if (options.writeAov)
        defines << QStringLiteral("KW_AOV");
    if (!options.sections.empty())
        defines << featureDefines(ExactFeature::Section); // section.glsl's, as the exact pass's
    const Expected<QOpenGLShaderProgram*> plainBuilt = m_shaders->program(
        QStringLiteral("tessellated.vert"), QStringLiteral("tessellated.frag"), defines);
    if (!plainBuilt)
        return plainBuilt.error();
    const Expected<QOpenGLShaderProgram*> trimmedBuilt =
        m_shaders->program(QStringLiteral("tessellated.vert"), QStringLiteral("tessellated.frag"),
                           defines + scene.trimMasks().trimDefines());
    if (!trimmedBuilt)
        return trimmedBuilt.error();
    QOpenGLShaderProgram* plain = *plainBuilt;
    QOpenGLShaderProgram* trimmed = *trimmedBuilt;
    gl->glDepthFunc(kDepthNearer);
    gl->glDepthMask(GL_TRUE);
    QOpenGLShaderProgram* bound = nullptr;
    const TrimMaskPass& masks = scene.trimMasks();
    for (const SurfaceRecord* r : scene.records()) {
        const MeshGpu& m = r->mesh;
        if (!m.vao)
            continue;
        const TrimMask* mask = trims && r->mask.usable() ? &r->mask : nullptr;
        QOpenGLShaderProgram* prog = mask ? trimmed : plain;
        if (prog != bound) {
            prog->bind();
            bound = prog;
            setFrameUniforms(gl, prog, camera, lights);
            setSectionUniforms(gl, prog, options);
        }
        setSurfaceUniforms(gl, prog, *r->surface);
        if (const int side = ShaderLibrary::uniforms(prog).solidSide; side >= 0)
            gl->glUniform1i(side, r->surface->solid < 0            ? 0
                                  : r->surface->outsideAlongNormal ? 1
                                                                   : -1);
        if (mask)
            masks.setUniforms(prog, *mask, 0);
        gl->glBindVertexArray(m.vao);
        if (firstDrawCpuMs < 0.0)
            firstDrawCpuMs = threadCpuMs();
        gl->glDrawElements(GL_TRIANGLES, m.indexCount, GL_UNSIGNED_INT, nullptr);
        ++drawCalls;
    }
    return ok();
}

} // namespace kw
