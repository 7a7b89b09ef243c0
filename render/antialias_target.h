// The anti-aliased frame: a private multisampled framebuffer the renderer
// draws into when RenderOptions::samples > 1, resolved into the host's framebuffer at the end.
// Silhouettes and the edges of base polygons are anti-aliased by MSAA (shading stays once per
// pixel); trim edges by coverage from the exact distance to the curve (shaders/trim_sample.glsl),
// which the edge pass sums into a second attachment. Summing instead of blending each partly
// covered fragment over the last is what keeps the shared edge of two faces free of a seam:
// faces covering 0.6 and 0.4 of a pixel give exactly their mix, with nothing of what lies behind.
#pragma once

#include "render/shader_library.h"

#include <QOpenGLFunctions_4_5_Core>
#include <QSize>
#include <QString>
#include <cstdint>

namespace kw {

/// Binds `framebuffer` with its viewport over `size` for a full-screen resolve of an
/// anti-aliased frame (AntialiasTarget::composite, AccumulateTarget::resolve) that writes colour
/// and depth: no blending, the depth test on and always passing, depth writes on.
void beginResolve(QOpenGLFunctions_4_5_Core* gl, std::uint32_t framebuffer, QSize size);

class AntialiasTarget {
public:
    /// Attachment 0: colour RGBA8 (the opaque passes); 1: RGBA16F, the edge pass's sum of
    /// coverage-weighted colour and coverage; depth 32F. All with `samples` samples.
    static constexpr GLenum kColour = GL_COLOR_ATTACHMENT0;
    static constexpr GLenum kAccumulation = GL_COLOR_ATTACHMENT1;

    void initialize(QOpenGLFunctions_4_5_Core* gl, ShaderLibrary* shaders) {
        m_gl = gl;
        m_shaders = shaders;
    }
    /// (Re)allocates for `size` and `samples` (2..the GPU's limit) when either changed. False
    /// with the error when the framebuffer cannot be made.
    Status ensure(QSize size, int samples);
    /// Binds the framebuffer, viewport over it, and clears colour to `background`, the sum to 0
    /// and depth to 1. Draw buffers: the colour only.
    void begin(const float background[4]);
    /// Draw buffers for the edge pass (the sum only) and back (the colour only).
    void drawToAccumulation(bool on);
    /// Resolves into `framebuffer` (colour and depth over `size`, its whole viewport) and leaves
    /// it bound; depth test on, writes on.
    Status composite(std::uint32_t framebuffer);
    void release();

    GLuint framebuffer() const { return m_fbo; }
    int samples() const { return m_samples; }
    /// Bytes of the attachments (samples x (4 + 8 + 4) per pixel).
    std::int64_t residentBytes() const;

private:
    QOpenGLFunctions_4_5_Core* m_gl = nullptr;
    ShaderLibrary* m_shaders = nullptr;
    GLuint m_fbo = 0, m_colour = 0, m_accumulation = 0, m_depth = 0, m_vao = 0;
    QSize m_size;
    int m_samples = 0;
};

} // namespace kw
