// Camera, light and material uniforms of phong.glsl.
#include "render/shading_uniforms.h"

#include "render/shader_library.h"

#include <QOpenGLShaderProgram>
#include <algorithm>
#include <glm/gtc/type_ptr.hpp>

namespace kw {

void setFrameUniforms(QOpenGLFunctions_4_5_Core* gl, QOpenGLShaderProgram* program,
                      const FrameCamera& camera, const std::vector<Light>& lights) {
    gl->glUniformMatrix4fv(ShaderLibrary::uniforms(program).viewProjection, 1, GL_FALSE,
                           glm::value_ptr(drawnViewProjection(camera)));
    gl->glUniform3fv(ShaderLibrary::uniforms(program).eye, 1, glm::value_ptr(camera.eye));
    gl->glUniform3fv(ShaderLibrary::uniforms(program).forward, 1, glm::value_ptr(camera.forward));
    if (ShaderLibrary::uniforms(program).viewport >= 0)
        gl->glUniform4f(ShaderLibrary::uniforms(program).viewport, float(camera.viewportOrigin.x),
                        float(camera.viewportOrigin.y), float(camera.viewport.x),
                        float(camera.viewport.y));
    const int n = std::min<int>(int(lights.size()), kMaxLights);
    glm::vec4 vec[kMaxLights];
    glm::vec3 amb[kMaxLights], dif[kMaxLights], spe[kMaxLights];
    for (int k = 0; k < n; ++k) {
        const Light& l = lights[size_t(k)];
        if (l.kind == Light::Kind::Directional) {
            const glm::dvec3 d =
                glm::length(l.vector) > 0.0 ? glm::normalize(l.vector) : glm::dvec3(0.0, 0.0, 1.0);
            vec[k] = glm::vec4(glm::vec3(d), 0.0f);
        } else {
            vec[k] = glm::vec4(glm::vec3(l.vector), 1.0f);
        }
        amb[k] = glm::vec3(l.ambient);
        dif[k] = glm::vec3(l.diffuse);
        spe[k] = glm::vec3(l.specular);
    }
    glm::vec3 ambient(0.0f);
    for (int k = 0; k < n; ++k)
        ambient += amb[k];
    gl->glUniform3fv(ShaderLibrary::uniforms(program).ambient, 1, glm::value_ptr(ambient));
    gl->glUniform2f(ShaderLibrary::uniforms(program).fill, float(kViewerFill.base),
                    float(kViewerFill.facing));
    if (n > 0) {
        gl->glUniform4fv(ShaderLibrary::uniforms(program).lightVector, n, glm::value_ptr(vec[0]));
        gl->glUniform3fv(ShaderLibrary::uniforms(program).lightDiffuse, n, glm::value_ptr(dif[0]));
        gl->glUniform3fv(ShaderLibrary::uniforms(program).lightSpecular, n, glm::value_ptr(spe[0]));
    }
}

void setSectionUniforms(QOpenGLFunctions_4_5_Core* gl, QOpenGLShaderProgram* program,
                        const RenderOptions& options) {
    const UniformLocations& u = ShaderLibrary::uniforms(program);
    if (u.sectionCount < 0)
        return;
    glm::vec4 planes[kMaxSectionPlanes];
    int n = 0;
    for (const SectionPlane& p : options.sections) {
        const glm::dvec3 normal = p.removedSide();
        if (n == kMaxSectionPlanes || normal == glm::dvec3(0.0))
            continue; // the renderer refuses such frames; never cut by a plane without normal
        // The offset in double: a plane far from the origin keeps its place in float.
        planes[n++] = glm::vec4(glm::vec3(normal), float(-glm::dot(normal, p.position)));
    }
    if (n > 0)
        gl->glUniform4fv(u.sectionPlanes, n, glm::value_ptr(planes[0]));
    gl->glUniform1i(u.sectionCount, n);
    gl->glUniform1i(u.sectionCaps, options.sectionCaps ? 1 : 0);
}

void setSurfaceUniforms(QOpenGLFunctions_4_5_Core* gl, QOpenGLShaderProgram* program,
                        const Surface& surface) {
    const Material& m = surface.material;
    gl->glUniform3fv(ShaderLibrary::uniforms(program).color, 1, glm::value_ptr(glm::vec3(m.color)));
    gl->glUniform4f(ShaderLibrary::uniforms(program).material, float(m.ka), float(m.kd),
                    float(m.ks), float(std::max(m.shininess, 1e-3)));
    gl->glUniform1f(ShaderLibrary::uniforms(program).surfaceId, float(surface.id.value));
}

} // namespace kw
