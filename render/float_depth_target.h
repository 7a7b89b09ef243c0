// The aliased frame's own framebuffer when the host's depth is not float: RGBA8 colour and 32-bit
// float depth with an 8-bit stencil (the deferred exact pass routes pixels by it), one sample,
// copied into the host's colour at the end of the frame (and each sample's frame of
// kw::AccumulateTarget). The editor's
// frames on a software rasteriser while the view moves (Viewport::aliasedWhileMoving) go to
// QOpenGLWidget's default framebuffer, whose depth is 24-bit integer; with the near plane at
// 1e-5 of the far one in close-ups, 24 bits do not separate faces 1e-4 of the view apart and the
// wrong one of two touching faces showed (tst_render_motion). Reversed depth in 32-bit float
// resolves about 1e-7 of the distance at any distance (render/depth_convention.h).
#pragma once

#include "model/error.h"

#include <QOpenGLFunctions_4_5_Core>
#include <QSize>
#include <QString>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace kw {

class FloatDepthTarget {
public:
    void initialize(QOpenGLFunctions_4_5_Core* gl) { m_gl = gl; }
    /// True when `framebuffer` is single-sampled and its depth buffer is not floating point
    /// (24-bit integer, as Qt's widget framebuffers) or missing: a frame into it is better drawn
    /// here and copied. State queries only.
    bool hostNeedsIt(std::uint32_t framebuffer) const;
    /// (Re)allocates for `size` when it changed. An error when the framebuffer
    /// cannot be made.
    Status ensure(QSize size);
    GLuint framebuffer() const { return m_fbo; }
    /// Changes whenever the framebuffer is made or freed: a frame kept in it is gone then.
    std::uint64_t serial() const { return m_serial; }
    GLuint colourTexture() const { return m_colour; }
    GLuint depthTexture() const { return m_depth; }
    /// Copies the colour into `framebuffer`'s draw buffers over the whole size (the host's depth
    /// is left as it was: nothing is drawn into the host after the frame's overlays); to a
    /// larger `to` (a preview, RenderOptions::previewScale) magnified, bilinear.
    void copyColourTo(std::uint32_t framebuffer, QSize to = QSize());
    /// Copies the colour of `rects` (x0, y0, x1, y1; GL pixels, clipped to the size) into the
    /// same pixels of `framebuffer`, of this size. Returns the pixels copied.
    std::int64_t copyColourRects(std::uint32_t framebuffer, const std::vector<glm::ivec4>& rects);
    void release();
    /// Bytes of the attachments (4 + 8 per pixel: colour, depth and stencil).
    std::int64_t residentBytes() const;

private:
    QOpenGLFunctions_4_5_Core* m_gl = nullptr;
    GLuint m_fbo = 0, m_colour = 0, m_depth = 0;
    QSize m_size;
    std::uint64_t m_serial = 0;
};

} // namespace kw
