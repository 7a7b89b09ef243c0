// Baseline pass: CPU tessellation with kw::surfaceFrame, Gouraud shading on the GPU.
#include "render/tessellated_pass.h"

#include "render/gpu_layout.h"
#include "render/shading_uniforms.h"

#include <QOpenGLShaderProgram>

namespace kw {

void TessellatedPass::initialize(QOpenGLFunctions_4_5_Core* gl, ShaderLibrary* shaders) {
    m_gl = gl;
    m_shaders = shaders;
}

void TessellatedPass::update(Mesh& m, const Surface& s, const Revisions& rev, int nu, int nv) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    const TessellatedMesh t = tessellate(s.geometry, nu, nv);
    if (!m.vao) {
        gl->glCreateVertexArrays(1, &m.vao);
        GLuint* bufs[] = {&m.positions, &m.normals, &m.uvs, &m.indices};
        for (GLuint* b : bufs)
            gl->glCreateBuffers(1, b);
        const GLuint attrBuf[] = {m.positions, m.normals, m.uvs};
        const int sizes[] = {3, 3, 2};
        for (GLuint a = 0; a < 3; ++a) {
            gl->glVertexArrayVertexBuffer(m.vao, a, attrBuf[a], 0,
                                          GLsizei(sizes[a] * sizeof(float)));
            gl->glEnableVertexArrayAttrib(m.vao, a);
            gl->glVertexArrayAttribFormat(m.vao, a, sizes[a], GL_FLOAT, GL_FALSE, 0);
            gl->glVertexArrayAttribBinding(m.vao, a, a);
        }
        gl->glVertexArrayElementBuffer(m.vao, m.indices);
    }
    gl->glNamedBufferData(m.positions, GLsizeiptr(t.positions.size() * sizeof(glm::vec3)),
                          t.positions.data(), GL_DYNAMIC_DRAW);
    gl->glNamedBufferData(m.normals, GLsizeiptr(t.normals.size() * sizeof(glm::vec3)),
                          t.normals.data(), GL_DYNAMIC_DRAW);
    gl->glNamedBufferData(m.uvs, GLsizeiptr(t.uvs.size() * sizeof(glm::vec2)), t.uvs.data(),
                          GL_DYNAMIC_DRAW);
    gl->glNamedBufferData(m.indices, GLsizeiptr(t.indices.size() * sizeof(unsigned)),
                          t.indices.data(), GL_DYNAMIC_DRAW);
    m.indexCount = int(t.indices.size());
    m.bytes =
        std::int64_t(t.positions.size() * sizeof(glm::vec3) + t.normals.size() * sizeof(glm::vec3) +
                     t.uvs.size() * sizeof(glm::vec2) + t.indices.size() * sizeof(unsigned));
    uploads.meshBuilds += 1;
    uploads.bytes += m.bytes;
    m.revisions = rev;
    m.nu = nu;
    m.nv = nv;
}

bool TessellatedPass::draw(const Document& doc, const TrimMaskPass* masks,
                           const FrameCamera& camera, const std::vector<Light>& lights,
                           const RenderOptions& options, QString* error) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    for (auto it = m_meshes.begin(); it != m_meshes.end();) {
        if (!doc.surface(it->first)) {
            destroy(it->second);
            it = m_meshes.erase(it);
        } else {
            ++it;
        }
    }
    QStringList defines{QStringLiteral("LIGHT_COUNT %1").arg(lights.size())};
    if (options.writeAov)
        defines << QStringLiteral("KW_AOV");
    QOpenGLShaderProgram* plain = m_shaders->program(QStringLiteral("tessellated.vert"),
                                                     QStringLiteral("tessellated.frag"), defines);
    QOpenGLShaderProgram* trimmed =
        m_shaders->program(QStringLiteral("tessellated.vert"), QStringLiteral("tessellated.frag"),
                           defines + QStringList{QStringLiteral("KW_TRIM")});
    if (!plain || !trimmed) {
        *error = m_shaders->lastError();
        return false;
    }
    gl->glDepthFunc(GL_LESS);
    gl->glDepthMask(GL_TRUE);
    QOpenGLShaderProgram* bound = nullptr;
    for (const Surface& s : doc.scene().surfaces) {
        const int nu = options.partitionsU > 0 ? options.partitionsU : s.partitionsU;
        const int nv = options.partitionsV > 0 ? options.partitionsV : s.partitionsV;
        const Revisions rev = doc.revisions(s.id);
        Mesh& m = m_meshes[s.id];
        if (!m.vao || m.revisions.points != rev.points || m.revisions.knots != rev.knots ||
            m.nu != nu || m.nv != nv)
            update(m, s, rev, nu, nv);
        const TrimMask* mask = masks ? masks->find(s.id) : nullptr;
        QOpenGLShaderProgram* prog = mask ? trimmed : plain;
        if (prog != bound) {
            prog->bind();
            bound = prog;
            setFrameUniforms(gl, prog, camera, lights);
        }
        setSurfaceUniforms(gl, prog, s);
        if (mask)
            masks->setUniforms(prog, *mask, 0);
        gl->glBindVertexArray(m.vao);
        gl->glDrawElements(GL_TRIANGLES, m.indexCount, GL_UNSIGNED_INT, nullptr);
        ++drawCalls;
    }
    return true;
}

void TessellatedPass::destroy(Mesh& m) {
    GLuint* bufs[] = {&m.positions, &m.normals, &m.uvs, &m.indices};
    for (GLuint* b : bufs)
        if (*b)
            m_gl->glDeleteBuffers(1, b), *b = 0;
    if (m.vao)
        m_gl->glDeleteVertexArrays(1, &m.vao), m.vao = 0;
}

std::int64_t TessellatedPass::residentBytes() const {
    std::int64_t total = 0;
    for (const auto& [id, m] : m_meshes)
        total += m.bytes;
    return total;
}

void TessellatedPass::release() {
    if (m_gl)
        for (auto& [id, m] : m_meshes)
            destroy(m);
    m_meshes.clear();
}

} // namespace kw
