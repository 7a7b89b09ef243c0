// Wireframe of the base polygon and the control net.
#include "render/overlay_passes.h"

#include <QOpenGLShaderProgram>
#include <glm/gtc/type_ptr.hpp>

namespace kw {

namespace {

QOpenGLShaderProgram* lineProgram(QOpenGLFunctions_4_5_Core* gl, ShaderLibrary* shaders,
                                  const FrameCamera& camera, QString* error) {
    QOpenGLShaderProgram* prog =
        shaders->program(QStringLiteral("lines.vert"), QStringLiteral("lines.frag"));
    if (!prog) {
        *error = shaders->lastError();
        return nullptr;
    }
    prog->bind();
    gl->glUniformMatrix4fv(prog->uniformLocation("uViewProjection"), 1, GL_FALSE,
                           glm::value_ptr(camera.viewProjection));
    gl->glDepthFunc(GL_LEQUAL);
    gl->glDepthMask(GL_FALSE);
    return prog;
}

} // namespace

void WireframePass::initialize(QOpenGLFunctions_4_5_Core* gl, ShaderLibrary* shaders) {
    m_gl = gl;
    m_shaders = shaders;
}

bool WireframePass::draw(const Scene& scene, const SurfaceGpuCache& cache,
                         const FrameCamera& camera, QString* error) {
    QOpenGLShaderProgram* prog = lineProgram(m_gl, m_shaders, camera, error);
    if (!prog)
        return false;
    m_gl->glUniform1f(prog->uniformLocation("uDepthBias"), 2e-4f);
    m_gl->glUniform1f(prog->uniformLocation("uPointSize"), 1.0f);
    m_gl->glUniform4fv(prog->uniformLocation("uLineColor"), 1, glm::value_ptr(color));
    for (const Surface& s : scene.surfaces)
        if (const SurfaceGpu* g = cache.find(s.id)) {
            m_gl->glBindVertexArray(g->outlineVao);
            m_gl->glDrawElements(GL_LINES, g->outlineIndexCount, GL_UNSIGNED_INT, nullptr);
            ++drawCalls;
        }
    m_gl->glDepthFunc(GL_LESS);
    m_gl->glDepthMask(GL_TRUE);
    return true;
}

void ControlNetPass::initialize(QOpenGLFunctions_4_5_Core* gl, ShaderLibrary* shaders) {
    m_gl = gl;
    m_shaders = shaders;
}

void ControlNetPass::update(Net& n, const NurbsSurface& s, const Revisions& rev) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    if (!n.vao) {
        gl->glCreateVertexArrays(1, &n.vao);
        gl->glCreateBuffers(1, &n.points);
        gl->glCreateBuffers(1, &n.lines);
        gl->glVertexArrayVertexBuffer(n.vao, 0, n.points, 0, sizeof(glm::vec3));
        gl->glEnableVertexArrayAttrib(n.vao, 0);
        gl->glVertexArrayAttribFormat(n.vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
        gl->glVertexArrayAttribBinding(n.vao, 0, 0);
        gl->glVertexArrayElementBuffer(n.vao, n.lines);
    }
    std::vector<glm::vec3> pts(s.points.begin(), s.points.end());
    std::vector<unsigned> idx;
    for (int j = 0; j < s.countV; ++j)
        for (int i = 0; i < s.countU; ++i) {
            if (i + 1 < s.countU)
                idx.insert(idx.end(), {unsigned(s.index(i, j)), unsigned(s.index(i + 1, j))});
            if (j + 1 < s.countV)
                idx.insert(idx.end(), {unsigned(s.index(i, j)), unsigned(s.index(i, j + 1))});
        }
    gl->glNamedBufferData(n.points, GLsizeiptr(pts.size() * sizeof(glm::vec3)), pts.data(),
                          GL_DYNAMIC_DRAW);
    gl->glNamedBufferData(n.lines, GLsizeiptr(idx.size() * sizeof(unsigned)), idx.data(),
                          GL_DYNAMIC_DRAW);
    n.pointCount = int(pts.size());
    n.lineIndexCount = int(idx.size());
    n.revisions = rev;
    n.bytes = std::int64_t(pts.size() * sizeof(glm::vec3) + idx.size() * sizeof(unsigned));
    uploads.netBuilds += 1;
    uploads.bytes += n.bytes;
}

bool ControlNetPass::draw(const Document& doc, const FrameCamera& camera, QString* error) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    for (auto it = m_nets.begin(); it != m_nets.end();) {
        if (!doc.surface(it->first)) {
            const GLuint bufs[] = {it->second.points, it->second.lines};
            gl->glDeleteBuffers(2, bufs);
            gl->glDeleteVertexArrays(1, &it->second.vao);
            it = m_nets.erase(it);
        } else {
            ++it;
        }
    }
    QOpenGLShaderProgram* prog = lineProgram(gl, m_shaders, camera, error);
    if (!prog)
        return false;
    gl->glEnable(GL_PROGRAM_POINT_SIZE);
    gl->glUniform1f(prog->uniformLocation("uDepthBias"), 1e-3f);
    gl->glUniform1f(prog->uniformLocation("uPointSize"), pointSize);
    for (const Surface& s : doc.scene().surfaces) {
        const Revisions rev = doc.revisions(s.id);
        Net& n = m_nets[s.id];
        if (!n.vao || n.revisions.points != rev.points || n.revisions.knots != rev.knots)
            update(n, s.geometry, rev);
        gl->glBindVertexArray(n.vao);
        gl->glUniform4fv(prog->uniformLocation("uLineColor"), 1, glm::value_ptr(lineColor));
        gl->glDrawElements(GL_LINES, n.lineIndexCount, GL_UNSIGNED_INT, nullptr);
        gl->glUniform4fv(prog->uniformLocation("uLineColor"), 1, glm::value_ptr(pointColor));
        gl->glDrawArrays(GL_POINTS, 0, n.pointCount);
        drawCalls += 2;
    }
    gl->glDisable(GL_PROGRAM_POINT_SIZE);
    gl->glDepthFunc(GL_LESS);
    gl->glDepthMask(GL_TRUE);
    return true;
}

std::int64_t ControlNetPass::residentBytes() const {
    std::int64_t total = 0;
    for (const auto& [id, n] : m_nets)
        total += n.bytes;
    return total;
}

void ControlNetPass::release() {
    if (m_gl)
        for (auto& [id, n] : m_nets) {
            const GLuint bufs[] = {n.points, n.lines};
            m_gl->glDeleteBuffers(2, bufs);
            m_gl->glDeleteVertexArrays(1, &n.vao);
        }
    m_nets.clear();
}

} // namespace kw
