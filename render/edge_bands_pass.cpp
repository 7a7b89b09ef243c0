// The Edge Continuity overlay's GL pass.
#include "render/edge_bands_pass.h"

#include "render/depth_convention.h"
#include "render/exact_contract.h"

#include <QOpenGLShaderProgram>
#include <cmath>
#include <glm/gtc/type_ptr.hpp>

namespace kw {

void EdgeBandsPass::initialize(QOpenGLFunctions_4_5_Core* gl, ShaderLibrary* shaders) {
    m_gl = gl;
    m_shaders = shaders;
}

void EdgeBandsPass::release() {
    if (m_gl && m_vao) {
        m_gl->glDeleteVertexArrays(1, &m_vao);
        m_gl->glDeleteBuffers(1, &m_vbo);
    }
    m_vao = m_vbo = 0;
    m_uploaded = false;
    m_count = 0;
}

Status EdgeBandsPass::draw(const EdgeBands& bands, const FrameCamera& camera) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    if (!m_vao) {
        gl->glCreateVertexArrays(1, &m_vao);
        gl->glCreateBuffers(1, &m_vbo);
        gl->glVertexArrayVertexBuffer(m_vao, 0, m_vbo, 0, sizeof(EdgeBandVertex));
        gl->glEnableVertexArrayAttrib(m_vao, kAttrPosition);
        gl->glVertexArrayAttribFormat(m_vao, kAttrPosition, 3, GL_FLOAT, GL_FALSE,
                                      offsetof(EdgeBandVertex, position));
        gl->glVertexArrayAttribBinding(m_vao, kAttrPosition, 0);
        gl->glEnableVertexArrayAttrib(m_vao, kAttrBandColour);
        gl->glVertexArrayAttribFormat(m_vao, kAttrBandColour, 4, GL_FLOAT, GL_FALSE,
                                      offsetof(EdgeBandVertex, color));
        gl->glVertexArrayAttribBinding(m_vao, kAttrBandColour, 0);
    }
    if (!m_uploaded || m_revision != bands.revision) {
        // Layout revisions are process-wide and unique, so an equal one is these very bands,
        // updated in place since the upload held.
        const bool sameLayout = m_uploaded && m_layoutRevision == bands.layoutRevision &&
                                m_revision < bands.revision &&
                                m_count == GLsizei(bands.vertices.size());
        if (sameLayout) {
            // A drag step re-made a few edges' lines in place: only their ranges (adjacent ones
            // merged) go up, the rest of the buffer (millions of vertices on a large model)
            // stays.
            uploadedVertices = 0;
            size_t runFirst = 0, runCount = 0;
            const auto flush = [&] {
                if (runCount == 0)
                    return;
                gl->glNamedBufferSubData(m_vbo, GLintptr(runFirst * sizeof(EdgeBandVertex)),
                                         GLsizeiptr(runCount * sizeof(EdgeBandVertex)),
                                         bands.vertices.data() + runFirst);
                uploadedVertices += runCount;
                runCount = 0;
            };
            for (const EdgeBandRange& r : bands.ranges) {
                if (r.revision <= m_revision)
                    continue;
                if (runCount > 0 && runFirst + runCount == r.first) {
                    runCount += r.count;
                } else {
                    flush();
                    runFirst = r.first;
                    runCount = r.count;
                }
            }
            flush();
        } else {
            gl->glNamedBufferData(m_vbo, GLsizeiptr(bands.vertices.size() * sizeof(EdgeBandVertex)),
                                  bands.vertices.data(), GL_DYNAMIC_DRAW);
            m_count = GLsizei(bands.vertices.size());
            uploadedVertices = bands.vertices.size();
        }
        m_revision = bands.revision;
        m_layoutRevision = bands.layoutRevision;
        m_uploaded = true;
    }
    if (m_count == 0)
        return ok();
    // Bands wholly off screen are left out (a close-up of a large model draws a few of many
    // thousands); the margin covers the band's pixels beside its line.
    const glm::mat4 viewProjection = drawnViewProjection(camera);
    const float margin = 2.0f * (bands.widthPixels + 2.0f) /
                         float(std::max(1, std::min(camera.viewport.x, camera.viewport.y)));
    const EdgeBandRuns runs = m_count == GLsizei(bands.vertices.size())
                                  ? visibleEdgeBands(bands, viewProjection, margin)
                                  : EdgeBandRuns{{0}, {m_count}};
    if (runs.first.empty())
        return ok();
    const Expected<QOpenGLShaderProgram*> built =
        m_shaders->program(QStringLiteral("edge_bands.vert"), QStringLiteral("edge_bands.frag"));
    if (!built)
        return built.error();
    QOpenGLShaderProgram* prog = *built;
    prog->bind();
    gl->glUniformMatrix4fv(prog->uniformLocation("uViewProjection"), 1, GL_FALSE,
                           glm::value_ptr(viewProjection));
    gl->glUniform1f(prog->uniformLocation("uDepthBias"), 2e-3f);
    const GLint offset = prog->uniformLocation("uOffset");
    gl->glDepthFunc(kDepthNearerOrEqual);
    gl->glDepthMask(GL_FALSE);
    gl->glBindVertexArray(m_vao);
    // A cross of offsets one pixel apart, widthPixels across (clip units: 2 / viewport): the
    // row widens a line across x, the column across y, so every direction gets a band at least
    // widthPixels / sqrt(2) wide. A square of offsets (n² draws rather than 2n - 1) made the
    // 10,000-face model's bands cost 16 draws of 3.7 M vertices a frame.
    const int half = std::max(0, int(std::lround(bands.widthPixels * 0.5f)) - 1);
    const auto drawAt = [&](int dx, int dy) {
        gl->glUniform2f(offset, 2.0f * (float(dx) - 0.5f) / float(camera.viewport.x),
                        2.0f * (float(dy) - 0.5f) / float(camera.viewport.y));
        gl->glMultiDrawArrays(GL_LINES, runs.first.data(), runs.count.data(),
                              GLsizei(runs.first.size()));
        ++drawCalls;
    };
    for (int dx = -half; dx <= half + 1; ++dx)
        drawAt(dx, 0);
    for (int dy = -half; dy <= half + 1; ++dy)
        if (dy != 0)
            drawAt(0, dy);
    gl->glDepthFunc(kDepthNearer);
    gl->glDepthMask(GL_TRUE);
    return ok();
}

} // namespace kw
