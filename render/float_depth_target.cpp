// Single-sample colour + float depth framebuffer for aliased frames into 24-bit hosts.
#include "render/float_depth_target.h"

#include "render/depth_convention.h"

namespace kw {

bool FloatDepthTarget::hostNeedsIt(std::uint32_t framebuffer) const {
    // A multisampled host cannot be blitted into from one sample (and is not what Qt's widgets
    // give); left alone.
    GLint samples = 0;
    m_gl->glGetNamedFramebufferParameteriv(framebuffer, GL_SAMPLES, &samples);
    if (samples > 0)
        return false;
    // The default framebuffer names its depth GL_DEPTH, a framebuffer object GL_DEPTH_ATTACHMENT.
    const GLenum attachment = framebuffer == 0 ? GL_DEPTH : GL_DEPTH_ATTACHMENT;
    GLint type = GL_NONE;
    m_gl->glGetNamedFramebufferAttachmentParameteriv(framebuffer, attachment,
                                                     GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
    if (type == GL_NONE)
        return true; // no depth at all: the frame needs one
    GLint component = GL_FLOAT;
    m_gl->glGetNamedFramebufferAttachmentParameteriv(
        framebuffer, attachment, GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE, &component);
    return component != GL_FLOAT;
}

Status FloatDepthTarget::ensure(QSize size) {
    if (m_fbo && size == m_size)
        return ok();
    release();
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    auto texture = [&](GLenum format) {
        GLuint t = 0;
        gl->glCreateTextures(GL_TEXTURE_2D, 1, &t);
        gl->glTextureStorage2D(t, 1, format, size.width(), size.height());
        return t;
    };
    m_colour = texture(GL_RGBA8);
    m_depth = texture(kDepthStencilFormat);
    gl->glCreateFramebuffers(1, &m_fbo);
    gl->glNamedFramebufferTexture(m_fbo, GL_COLOR_ATTACHMENT0, m_colour, 0);
    gl->glNamedFramebufferTexture(m_fbo, GL_DEPTH_STENCIL_ATTACHMENT, m_depth, 0);
    if (gl->glCheckNamedFramebufferStatus(m_fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        release();
        return Error(QStringLiteral("the float-depth framebuffer (%1x%2) is incomplete")
                         .arg(size.width())
                         .arg(size.height()));
    }
    m_size = size;
    ++m_serial;
    return ok();
}

void FloatDepthTarget::copyColourTo(std::uint32_t framebuffer, QSize to) {
    const int w = m_size.width(), h = m_size.height();
    if (!to.isValid())
        to = m_size;
    m_gl->glBlitNamedFramebuffer(m_fbo, framebuffer, 0, 0, w, h, 0, 0, to.width(), to.height(),
                                 GL_COLOR_BUFFER_BIT, to == m_size ? GL_NEAREST : GL_LINEAR);
    m_gl->glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
}

std::int64_t FloatDepthTarget::copyColourRects(std::uint32_t framebuffer,
                                               const std::vector<glm::ivec4>& rects) {
    std::int64_t pixels = 0;
    for (const glm::ivec4& r : rects) {
        const glm::ivec2 from = glm::max(glm::ivec2(r.x, r.y), glm::ivec2(0));
        const glm::ivec2 to =
            glm::min(glm::ivec2(r.z, r.w), glm::ivec2(m_size.width(), m_size.height()));
        if (to.x <= from.x || to.y <= from.y)
            continue;
        m_gl->glBlitNamedFramebuffer(m_fbo, framebuffer, from.x, from.y, to.x, to.y, from.x, from.y,
                                     to.x, to.y, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        pixels += std::int64_t(to.x - from.x) * (to.y - from.y);
    }
    m_gl->glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    return pixels;
}

void FloatDepthTarget::release() {
    if (!m_gl)
        return;
    if (m_fbo)
        m_gl->glDeleteFramebuffers(1, &m_fbo);
    const GLuint textures[2] = {m_colour, m_depth};
    for (GLuint t : textures)
        if (t)
            m_gl->glDeleteTextures(1, &t);
    m_fbo = m_colour = m_depth = 0;
    m_size = QSize();
    ++m_serial;
}

std::int64_t FloatDepthTarget::residentBytes() const {
    return m_fbo ? std::int64_t(m_size.width()) * m_size.height() * 12 : 0;
}

} // namespace kw
