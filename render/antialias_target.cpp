#include "render/antialias_target.h"

#include "render/depth_convention.h"
#include "render/exact_contract.h"

#include <QOpenGLShaderProgram>

namespace kw {

void beginResolve(QOpenGLFunctions_4_5_Core* gl, std::uint32_t framebuffer, QSize size) {
    gl->glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    gl->glViewport(0, 0, size.width(), size.height());
    gl->glDisable(GL_BLEND);
    gl->glEnable(GL_DEPTH_TEST);
    gl->glDepthFunc(GL_ALWAYS);
    gl->glDepthMask(GL_TRUE);
}

Status AntialiasTarget::ensure(QSize size, int samples) {
    if (m_fbo && size == m_size && samples == m_samples)
        return ok();
    release();
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    auto texture = [&](GLenum format) {
        GLuint t = 0;
        gl->glCreateTextures(GL_TEXTURE_2D_MULTISAMPLE, 1, &t);
        gl->glTextureStorage2DMultisample(t, samples, format, size.width(), size.height(), GL_TRUE);
        return t;
    };
    m_colour = texture(GL_RGBA8);
    m_accumulation = texture(GL_RGBA16F);
    m_depth = texture(kDepthFormat);
    gl->glCreateFramebuffers(1, &m_fbo);
    gl->glNamedFramebufferTexture(m_fbo, kColour, m_colour, 0);
    gl->glNamedFramebufferTexture(m_fbo, kAccumulation, m_accumulation, 0);
    gl->glNamedFramebufferTexture(m_fbo, GL_DEPTH_ATTACHMENT, m_depth, 0);
    if (gl->glCheckNamedFramebufferStatus(m_fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        release();
        return Error(
            QStringLiteral("the anti-aliased framebuffer (%1x%2, %3 samples) is incomplete")
                .arg(size.width())
                .arg(size.height())
                .arg(samples));
    }
    gl->glCreateVertexArrays(1, &m_vao);
    m_size = size;
    m_samples = samples;
    return ok();
}

void AntialiasTarget::begin(const float background[4]) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    gl->glBindFramebuffer(GL_FRAMEBUFFER, m_fbo);
    gl->glViewport(0, 0, m_size.width(), m_size.height());
    const GLenum both[2] = {kColour, kAccumulation};
    gl->glNamedFramebufferDrawBuffers(m_fbo, 2, both);
    const GLfloat zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    gl->glClearBufferfv(GL_COLOR, 0, background);
    gl->glClearBufferfv(GL_COLOR, 1, zero);
    gl->glClearBufferfv(GL_DEPTH, 0, &kFarDepth);
    drawToAccumulation(false);
}

void AntialiasTarget::drawToAccumulation(bool on) {
    const GLenum buffer = on ? kAccumulation : kColour;
    m_gl->glNamedFramebufferDrawBuffers(m_fbo, 1, &buffer);
}

Status AntialiasTarget::composite(std::uint32_t framebuffer) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    const Expected<QOpenGLShaderProgram*> built = m_shaders->program(
        QStringLiteral("aa_composite.vert"), QStringLiteral("aa_composite.frag"));
    if (!built)
        return built.error();
    QOpenGLShaderProgram* prog = *built;
    beginResolve(gl, framebuffer, m_size);
    prog->bind();
    gl->glBindTextureUnit(kCompositeColourUnit, m_colour);
    gl->glBindTextureUnit(kCompositeAccumUnit, m_accumulation);
    gl->glBindTextureUnit(kCompositeDepthUnit, m_depth);
    gl->glBindVertexArray(m_vao);
    gl->glDrawArrays(GL_TRIANGLES, 0, 3);
    gl->glBindVertexArray(0);
    for (const int unit : {kCompositeColourUnit, kCompositeAccumUnit, kCompositeDepthUnit})
        gl->glBindTextureUnit(GLuint(unit), 0);
    gl->glDepthFunc(kDepthNearer);
    return ok();
}

std::int64_t AntialiasTarget::residentBytes() const {
    if (!m_fbo)
        return 0;
    return std::int64_t(m_size.width()) * m_size.height() * m_samples * (4 + 8 + 4);
}

void AntialiasTarget::release() {
    if (!m_gl)
        return;
    if (m_fbo)
        m_gl->glDeleteFramebuffers(1, &m_fbo);
    for (GLuint* t : {&m_colour, &m_accumulation, &m_depth})
        if (*t)
            m_gl->glDeleteTextures(1, t), *t = 0;
    if (m_vao)
        m_gl->glDeleteVertexArrays(1, &m_vao);
    m_fbo = m_vao = 0;
    m_size = QSize();
    m_samples = 0;
}

} // namespace kw
