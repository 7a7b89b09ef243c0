// Draws the Edge Continuity overlay (render/edge_bands.h) over the surfaces.
#pragma once

#include "render/edge_bands.h"
#include "render/render_types.h"
#include "render/shader_library.h"

#include <QOpenGLFunctions_4_5_Core>
#include <QString>

namespace kw {

/// Owns the bands' VBO, uploaded only when EdgeBands::revision changes, and then only the ranges
/// re-made since when the layout is the one it holds; draws the segments
/// in a square of pixel offsets so that each is a band about widthPixels wide.
class EdgeBandsPass {
public:
    void initialize(QOpenGLFunctions_4_5_Core* gl, ShaderLibrary* shaders);
    Status draw(const EdgeBands& bands, const FrameCamera& camera);
    void release();
    int drawCalls = 0; ///< counted by draw; the renderer zeroes it per frame
    /// Vertices the last upload sent (all of them, or a drag step's re-made ranges).
    size_t uploadedVertices = 0;

private:
    QOpenGLFunctions_4_5_Core* m_gl = nullptr;
    ShaderLibrary* m_shaders = nullptr;
    GLuint m_vao = 0, m_vbo = 0;
    std::uint64_t m_revision = 0, m_layoutRevision = 0;
    bool m_uploaded = false;
    GLsizei m_count = 0;
};

} // namespace kw
