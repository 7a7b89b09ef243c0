// Off-screen rendering for the CLI, the tests and the benchmark: its own OpenGL 4.5 core context
// on a QOffscreenSurface and an FBO with a colour target and float AOV targets.
#pragma once

#include "render/renderer.h"

#include <QImage>
#include <QOffscreenSurface>
#include <QOpenGLContext>
#include <memory>
#include <vector>

namespace kw {

/// Per-pixel arbitrary output variables, row 0 at the top. Channels per pixel (kAovChannels):
/// surface id (-1 background; the SurfaceId value otherwise), u, v, P.x, P.y, P.z, N.x, N.y,
/// N.z (unit, Su x Sv side), Z (eye-space depth along the view direction, model units).
struct AovBuffer {
    static constexpr int kChannels = 10;
    static const char* const kChannelNames[kChannels]; ///< id,u,v,P.x,P.y,P.z,N.x,N.y,N.z,Z
    int width = 0;
    int height = 0;
    std::vector<float> data;
    /// With the curvature AOV (RenderOptions::writeCurvatureAov): kCurvatureChannels floats
    /// per pixel K, H, k1, k2 (kw::surfaceCurvature's signs; 0 on background); else empty.
    static constexpr int kCurvatureChannels = 4;
    static const char* const kCurvatureNames[kCurvatureChannels]; ///< K,H,k1,k2
    std::vector<float> curvature;

    const float* pixel(int x, int y) const {
        return data.data() + (size_t(y) * size_t(width) + size_t(x)) * kChannels;
    }
    /// Nullptr without the curvature AOV.
    const float* curvaturePixel(int x, int y) const {
        return curvature.empty() ? nullptr
                                 : curvature.data() +
                                       (size_t(y) * size_t(width) + size_t(x)) * kCurvatureChannels;
    }
};

/// FBO attachments: 0 colour RGBA8; 1 RGBA32F (id, u, v, Z); 2 RGBA32F (P, 1); 3 RGBA32F
/// (N, 0); 4 RGBA32F (K, H, k1, k2); depth 24-bit. The AOV attachments exist only when
/// requested in setSize (4 only with the curvature AOV).
class OffscreenRenderer {
public:
    OffscreenRenderer();
    ~OffscreenRenderer();
    OffscreenRenderer(const OffscreenRenderer&) = delete;
    OffscreenRenderer& operator=(const OffscreenRenderer&) = delete;

    /// The surface format every Knotwork GL context asks for: OpenGL 4.5 core, depth 24.
    /// Set it as the default (QSurfaceFormat::setDefaultFormat) before creating the app.
    static QSurfaceFormat requiredFormat();

    /// Creates the context and initialises the Renderer. Needs a QGuiApplication. Returns
    /// false with *error set when no OpenGL 4.5 core context can be made (e.g. no X server
    /// for the xcb platform, or the offscreen platform, which offers no desktop GL).
    bool create(QString* error);
    /// (Re)allocates the framebuffer; width and height in 1..16384. False with *error on failure.
    /// withCurvature adds the curvature target (only with withAov).
    bool setSize(QSize size, bool withAov, QString* error, bool withCurvature = false);
    QSize size() const { return m_size; }

    /// Renders one frame into the FBO (options.writeAov and writeCurvatureAov are forced to the
    /// FBO's AOV state).
    bool render(const Document& doc, const Camera& camera, RenderOptions options, QString* error);
    /// glFinish on the context: the frame is complete when this returns (for timing).
    void finish();
    /// The colour target as RGBA8888, top row first.
    QImage colorImage();
    /// The AOV targets (empty buffer when the FBO has none).
    AovBuffer aov();

    Renderer& renderer() { return m_renderer; }
    bool makeCurrent();

private:
    void destroyFramebuffer();

    std::unique_ptr<QOpenGLContext> m_context;
    std::unique_ptr<QOffscreenSurface> m_surface;
    Renderer m_renderer;
    QSize m_size;
    bool m_withAov = false;
    bool m_withCurvature = false;
    GLuint m_fbo = 0;
    GLuint m_color = 0, m_depth = 0;
    GLuint m_aov[4] = {0, 0, 0, 0};
};

} // namespace kw
