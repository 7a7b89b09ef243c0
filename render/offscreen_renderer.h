// Off-screen rendering for the CLI, the tests and the benchmark: its own OpenGL 4.5 core context
// on a QOffscreenSurface and an FBO with a colour target and float AOV targets.
#pragma once

#include "render/aov_buffer.h"
#include "render/renderer.h"

#include <QImage>
#include <QSurfaceFormat>
#include <memory>

namespace kw {

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
    /// the error when no OpenGL 4.5 core context can be made (e.g. no X server for the xcb
    /// platform, or the offscreen platform, which offers no desktop GL).
    Status create();
    /// (Re)allocates the framebuffer; width and height in 1..16384. An error on failure.
    /// withCurvature adds the curvature target (attachment 4: K, H, k1, k2; only with withAov).
    Status setSize(QSize size, bool withAov, bool withCurvature = false);
    QSize size() const;

    /// Renders one frame into the FBO (with AOVs when the FBO has them). Returns the report's
    /// error when it is not ok; lastReport() holds the whole report.
    Status render(const Document& doc, const Camera& camera, const RenderOptions& options);
    const FrameReport& lastReport() const;
    /// Renderer::setMesh with this context current (-1 when it cannot be made current).
    std::int64_t setMesh(int slot, const TriangleMesh& mesh);
    /// Renderer::renderMesh into the FBO; returns and reports as render().
    Status renderMesh(const Document& doc, int slot, const Camera& camera,
                      const RenderOptions& options);
    /// Renderer::renderMeshes into the FBO; returns and reports as render().
    Status renderMeshes(const Document& doc, const std::vector<int>& slots, const Camera& camera,
                        const RenderOptions& options);
    /// Renderer::pick at `pixel` of a frame of size() with this context current.
    std::optional<PickHit> pick(const Document& doc, const Camera& camera, QPointF pixel,
                                const RenderOptions& options = {});
    /// glFinish on the context: the frame is complete when this returns (for timing).
    void finish();
    /// The colour target as RGBA8888, top row first.
    QImage colorImage();
    /// The AOV targets (empty buffer when the FBO has none).
    AovBuffer aov();

    Renderer& renderer();
    bool makeCurrent();

private:
    struct Impl;
    std::unique_ptr<Impl> d;
};

} // namespace kw
