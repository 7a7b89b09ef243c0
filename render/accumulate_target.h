// The accumulated anti-aliased frame (RenderOptions::Antialiasing::Accumulate): the renderer
// draws the whole aliased frame once per sample into this target's single-sampled framebuffer,
// each time with the image shifted by that sample's sub-pixel offset (FrameCamera::jitter), adds
// its colour into a float sum, and resolves the mean into the host's framebuffer at the end.
// Every sample is then a pixel of the exact aliased frame, with the skirts and fins that close
// the seams between faces (docs/RENDERING.md, "Skirts"), which the MSAA frame
// (kw::AntialiasTarget) cannot draw.
#pragma once

#include "render/antialias_target.h"
#include "render/float_depth_target.h"
#include "render/shader_library.h"

#include <QOpenGLFunctions_4_5_Core>
#include <QSize>
#include <QString>
#include <cstdint>
#include <glm/vec2.hpp>
#include <vector>

namespace kw {

/// The sub-pixel offsets (pixels, each coordinate in [-0.5, 0.5]) of `samples` accumulated
/// samples: the rotated grids of Direct3D's standard 2, 4, 8 and 16-sample patterns, whose
/// samples fall on distinct rows and columns (an edge near horizontal or vertical still gets
/// `samples` levels), and for other counts the first points of the (2, 3) Halton sequence,
/// centred. Their mean is within 1/16 px of the pixel centre.
std::vector<glm::vec2> accumulationOffsets(int samples);

class AccumulateTarget {
public:
    void initialize(QOpenGLFunctions_4_5_Core* gl, ShaderLibrary* shaders) {
        m_gl = gl;
        m_shaders = shaders;
        m_sample.initialize(gl);
    }
    /// (Re)allocates for `size` when it changed. An error when the framebuffers
    /// cannot be made.
    Status ensure(QSize size);
    /// The framebuffer one sample is drawn into (RGBA8 colour, 32-bit float depth).
    GLuint sampleFramebuffer() const { return m_sample.framebuffer(); }
    /// Adds the sample just drawn into the sum (the first sample of a frame replaces it).
    Status add(bool first);
    /// Writes the mean of the samples added since the first into `framebuffer` (colour, and the
    /// depth of the last sample for the overlays drawn afterwards) and leaves it bound; depth
    /// test on, writes on.
    Status resolve(std::uint32_t framebuffer);
    /// The first sample of a progressive image, just drawn, resolved straight from its own
    /// framebuffer (one full-screen pass where add() and resolve() take two, so a moving
    /// view's frames cost the aliased frame and one pass). It counts as added; the sum takes it
    /// in keepFirst(), which must come before the next sample is drawn over it.
    Status resolveFirst(std::uint32_t framebuffer);
    /// Adds the sample resolveFirst() showed into the sum (nothing when there is none).
    Status keepFirst();
    void release();
    /// Samples in the sum (0 before the first add and after release or a resize).
    int added() const { return m_added; }
    /// Bytes of the attachments (4 + 4 per pixel for the sample, 16 for the sum).
    std::int64_t residentBytes() const;

private:
    Expected<QOpenGLShaderProgram*> program(const QString& fragment);

    QOpenGLFunctions_4_5_Core* m_gl = nullptr;
    ShaderLibrary* m_shaders = nullptr;
    FloatDepthTarget m_sample; ///< one sample's frame
    GLuint m_sumFbo = 0, m_sum = 0, m_vao = 0;
    QSize m_size;
    int m_added = 0; ///< samples in the sum (the first may still be in m_sample: m_firstOnly)
    bool m_firstOnly = false; ///< resolveFirst's sample is not in the sum yet
};

} // namespace kw
