#include "render/accumulate_target.h"

#include "render/depth_convention.h"
#include "render/exact_contract.h"

#include <QOpenGLShaderProgram>
#include <algorithm>
#include <glm/common.hpp>

namespace kw {

std::vector<glm::vec2> accumulationOffsets(int samples) {
    // Direct3D's standard sample positions, in sixteenths of a pixel from its centre.
    static const int two[2][2] = {{4, 4}, {-4, -4}};
    static const int four[4][2] = {{-2, -6}, {6, -2}, {-6, 2}, {2, 6}};
    static const int eight[8][2] = {{1, -3}, {-1, 3},  {5, 1}, {-3, -5},
                                    {-5, 5}, {-7, -1}, {3, 7}, {7, -7}};
    static const int sixteen[16][2] = {{1, 1},  {-1, -3}, {-3, 2}, {4, -1}, {-5, -2}, {2, 5},
                                       {5, 3},  {3, -5},  {-2, 6}, {0, -7}, {-4, -6}, {-6, 4},
                                       {-8, 0}, {7, -4},  {6, 7},  {-7, -8}};
    std::vector<glm::vec2> offsets;
    const auto fromTable = [&](const int(*table)[2], int n) {
        for (int i = 0; i < n; ++i)
            offsets.emplace_back(float(table[i][0]) / 16.0f, float(table[i][1]) / 16.0f);
    };
    if (samples <= 1)
        offsets.emplace_back(0.0f, 0.0f);
    else if (samples == 2)
        fromTable(two, 2);
    else if (samples == 4)
        fromTable(four, 4);
    else if (samples == 8)
        fromTable(eight, 8);
    else if (samples == 16)
        fromTable(sixteen, 16);
    else {
        const auto halton = [](int i, int base) {
            float f = 1.0f, r = 0.0f;
            for (; i > 0; i /= base) {
                f /= float(base);
                r += f * float(i % base);
            }
            return r;
        };
        glm::vec2 mean(0.0f);
        for (int i = 1; i <= samples; ++i) {
            offsets.emplace_back(halton(i, 2) - 0.5f, halton(i, 3) - 0.5f);
            mean += offsets.back() / float(samples);
        }
        // Centred, so that the image does not drift by the points' mean (up to 0.13 px).
        for (glm::vec2& o : offsets)
            o = glm::clamp(o - mean, glm::vec2(-0.5f), glm::vec2(0.5f));
    }
    return offsets;
}

Status AccumulateTarget::ensure(QSize size) {
    if (m_sumFbo && size == m_size)
        return ok();
    release();
    // One sample's frame is the aliased frame's own float-depth framebuffer.
    if (Status sample = m_sample.ensure(size); !sample)
        return sample;
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    gl->glCreateTextures(GL_TEXTURE_2D, 1, &m_sum);
    gl->glTextureStorage2D(m_sum, 1, GL_RGBA32F, size.width(), size.height());
    gl->glCreateFramebuffers(1, &m_sumFbo);
    gl->glNamedFramebufferTexture(m_sumFbo, GL_COLOR_ATTACHMENT0, m_sum, 0);
    if (gl->glCheckNamedFramebufferStatus(m_sumFbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        release();
        return Error(QStringLiteral("the accumulated anti-aliasing sum (%1x%2) is incomplete")
                         .arg(size.width())
                         .arg(size.height()));
    }
    gl->glCreateVertexArrays(1, &m_vao);
    m_size = size;
    return ok();
}

Expected<QOpenGLShaderProgram*> AccumulateTarget::program(const QString& fragment) {
    return m_shaders->program(QStringLiteral("aa_composite.vert"), fragment);
}

Status AccumulateTarget::add(bool first) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    const Expected<QOpenGLShaderProgram*> built = program(QStringLiteral("accumulate_add.frag"));
    if (!built)
        return built.error();
    QOpenGLShaderProgram* prog = *built;
    gl->glBindFramebuffer(GL_FRAMEBUFFER, m_sumFbo);
    gl->glViewport(0, 0, m_size.width(), m_size.height());
    gl->glDisable(GL_DEPTH_TEST);
    if (first) {
        gl->glDisable(GL_BLEND);
    } else {
        gl->glEnable(GL_BLEND);
        gl->glBlendEquation(GL_FUNC_ADD);
        gl->glBlendFunc(GL_ONE, GL_ONE);
    }
    prog->bind();
    gl->glBindTextureUnit(kAccumulateSampleUnit, m_sample.colourTexture());
    gl->glBindVertexArray(m_vao);
    gl->glDrawArrays(GL_TRIANGLES, 0, 3);
    gl->glBindVertexArray(0);
    gl->glBindTextureUnit(kAccumulateSampleUnit, 0);
    gl->glDisable(GL_BLEND);
    gl->glEnable(GL_DEPTH_TEST);
    m_added = first ? 1 : m_added + 1;
    m_firstOnly = false;
    return ok();
}

Status AccumulateTarget::resolveFirst(std::uint32_t framebuffer) {
    m_added = 1;
    m_firstOnly = true;
    return resolve(framebuffer);
}

Status AccumulateTarget::keepFirst() {
    if (!m_firstOnly)
        return ok();
    m_firstOnly = false;
    return add(true);
}

Status AccumulateTarget::resolve(std::uint32_t framebuffer) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    const Expected<QOpenGLShaderProgram*> built =
        program(QStringLiteral("accumulate_resolve.frag"));
    if (!built)
        return built.error();
    QOpenGLShaderProgram* prog = *built;
    beginResolve(gl, framebuffer, m_size);
    prog->bind();
    gl->glUniform1f(prog->uniformLocation("uScale"), 1.0f / float(std::max(m_added, 1)));
    // The colour of one sample not yet in the sum is the sample's own.
    gl->glBindTextureUnit(kAccumulateSampleUnit, m_firstOnly ? m_sample.colourTexture() : m_sum);
    gl->glBindTextureUnit(kAccumulateDepthUnit, m_sample.depthTexture());
    gl->glBindVertexArray(m_vao);
    gl->glDrawArrays(GL_TRIANGLES, 0, 3);
    gl->glBindVertexArray(0);
    gl->glBindTextureUnit(kAccumulateSampleUnit, 0);
    gl->glBindTextureUnit(kAccumulateDepthUnit, 0);
    gl->glDepthFunc(kDepthNearer);
    return ok();
}

std::int64_t AccumulateTarget::residentBytes() const {
    if (!m_sumFbo)
        return 0;
    return m_sample.residentBytes() + std::int64_t(m_size.width()) * m_size.height() * 16;
}

void AccumulateTarget::release() {
    if (!m_gl)
        return;
    m_sample.release();
    if (m_sumFbo)
        m_gl->glDeleteFramebuffers(1, &m_sumFbo);
    if (m_sum)
        m_gl->glDeleteTextures(1, &m_sum);
    m_sumFbo = m_sum = 0;
    if (m_vao)
        m_gl->glDeleteVertexArrays(1, &m_vao);
    m_vao = 0;
    m_size = QSize();
    m_added = 0;
    m_firstOnly = false;
}

} // namespace kw
