// The GPU's depth convention (internal to render/): reversed depth. frameCamera's projection
// maps the near plane to depth 1 and infinity towards 0 in glClipControl's zero-to-one clip
// range, so a 32-bit float depth buffer resolves about 1e-7 of the distance at any distance
// (exact visibility: with GL's -1..1 range and near = 1e-5 far, which close-ups with
// the eye inside the scene's bounds get, 24 bits resolve only 1e-3 and a trimmed-away
// fragment's depth can equal the face behind it). Nearer is greater; the buffers clear to 0.
#pragma once

#include <QOpenGLFunctions_4_5_Core>

namespace kw {

inline constexpr GLenum kDepthNearer = GL_GREATER;
inline constexpr GLenum kDepthNearerOrEqual = GL_GEQUAL;
inline constexpr GLfloat kFarDepth = 0.0f;
/// The depth format of Knotwork's own framebuffers (off-screen, pick, anti-aliasing).
inline constexpr GLenum kDepthFormat = GL_DEPTH_COMPONENT32F;
/// The same with an 8-bit stencil (8 bytes a pixel), for the framebuffers aliased frames are
/// drawn into (off-screen, float-depth): the deferred exact pass routes pixels by stencil.
inline constexpr GLenum kDepthStencilFormat = GL_DEPTH32F_STENCIL8;

/// Switches the clip range to zero-to-one for a frame, and back to GL's default after it (the
/// host, e.g. QPainter on the same context, expects the default).
inline void beginReversedDepth(QOpenGLFunctions_4_5_Core* gl) {
    gl->glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
}
inline void endReversedDepth(QOpenGLFunctions_4_5_Core* gl) {
    gl->glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
}

} // namespace kw
