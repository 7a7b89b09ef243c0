// TriangleMeshPass: the benchmark's comparison meshes drawn through the renderer.
#include "render/triangle_mesh_pass.h"

#include "render/depth_convention.h"
#include "render/shading_uniforms.h"
#include "render/tessellated_pass.h"

#include <QOpenGLShaderProgram>
#include <unordered_map>

namespace kw {

void TriangleMeshPass::initialize(QOpenGLFunctions_4_5_Core* gl, ShaderLibrary* shaders) {
    m_gl = gl;
    m_shaders = shaders;
    gl->glCreateVertexArrays(1, &m_vao);
    gl->glCreateBuffers(4, m_buffers);
    setMeshAttributes(gl, m_vao, {m_buffers[0], m_buffers[1], m_buffers[2]});
    gl->glVertexArrayElementBuffer(m_vao, m_buffers[3]);
}

std::int64_t TriangleMeshPass::upload(const TriangleMesh& mesh) {
    m_positions.clear();
    m_normals.clear();
    m_uvs.clear();
    m_indices.clear();
    m_ranges.clear();
    for (const SurfaceMesh& s : mesh.surfaces) {
        m_ranges.push_back(Range{s.id, GLsizei(s.indices.size()),
                                 m_indices.size() * sizeof(unsigned), GLint(m_positions.size())});
        m_positions.insert(m_positions.end(), s.positions.begin(), s.positions.end());
        m_normals.insert(m_normals.end(), s.normals.begin(), s.normals.end());
        m_uvs.insert(m_uvs.end(), s.uvs.begin(), s.uvs.end());
        m_indices.insert(m_indices.end(), s.indices.begin(), s.indices.end());
    }
    m_bytes = 0;
    auto send = [&](GLuint buffer, const auto& v) {
        const auto bytes = GLsizeiptr(v.size() * sizeof(v[0]));
        m_gl->glNamedBufferData(buffer, bytes, v.empty() ? nullptr : v.data(), GL_STREAM_DRAW);
        m_bytes += bytes;
    };
    send(m_buffers[0], m_positions);
    send(m_buffers[1], m_normals);
    send(m_buffers[2], m_uvs);
    send(m_buffers[3], m_indices);
    return m_bytes;
}

Status TriangleMeshPass::draw(const Scene& scene, const FrameCamera& camera,
                              const std::vector<Light>& lights, const RenderOptions& options) {
    drawCalls = surfaces = 0;
    QStringList defines{QStringLiteral("LIGHT_COUNT %1").arg(lights.size())};
    if (options.writeAov)
        defines << QStringLiteral("KW_AOV");
    const Expected<QOpenGLShaderProgram*> built = m_shaders->program(
        QStringLiteral("tessellated.vert"), QStringLiteral("tessellated.frag"), defines);
    if (!built)
        return built.error();
    QOpenGLShaderProgram* prog = *built;
    std::unordered_map<std::uint32_t, const Surface*> byId;
    for (const Surface& s : scene.surfaces)
        byId.emplace(s.id.value, &s);
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    prog->bind();
    setFrameUniforms(gl, prog, camera, lights);
    gl->glEnable(GL_DEPTH_TEST);
    gl->glDepthFunc(kDepthNearer);
    gl->glDepthMask(GL_TRUE);
    gl->glBindVertexArray(m_vao);
    for (const Range& r : m_ranges) {
        const auto it = byId.find(r.id.value);
        if (it == byId.end() || r.count == 0)
            continue;
        setSurfaceUniforms(gl, prog, *it->second);
        gl->glDrawElementsBaseVertex(GL_TRIANGLES, r.count, GL_UNSIGNED_INT,
                                     reinterpret_cast<const void*>(r.firstIndexByte), r.baseVertex);
        ++drawCalls;
        ++surfaces;
    }
    gl->glBindVertexArray(0);
    gl->glUseProgram(0);
    return ok();
}

void TriangleMeshPass::release() {
    if (!m_gl)
        return;
    m_gl->glDeleteBuffers(4, m_buffers);
    m_gl->glDeleteVertexArrays(1, &m_vao);
    m_vao = 0;
    m_buffers[0] = m_buffers[1] = m_buffers[2] = m_buffers[3] = 0;
    m_bytes = 0;
    m_gl = nullptr;
}

} // namespace kw
