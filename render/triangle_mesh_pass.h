// Draws a TriangleMesh built outside the renderer (Renderer::setMesh / renderMesh) with the
// baseline's Gouraud shader (tessellated.vert/.frag): one VAO, three attribute buffers and one
// index buffer for all surfaces, a draw per surface with its material.
#pragma once

#include "render/render_types.h"
#include "render/shader_library.h"
#include "render/triangle_mesh.h"

#include <QOpenGLFunctions_4_5_Core>
#include <QString>

namespace kw {

class TriangleMeshPass {
public:
    TriangleMeshPass() = default;
    TriangleMeshPass(const TriangleMeshPass&) = delete;
    TriangleMeshPass& operator=(const TriangleMeshPass&) = delete;

    /// Needs the context current for every call below; `shaders` outlives the pass.
    void initialize(QOpenGLFunctions_4_5_Core* gl, ShaderLibrary* shaders);
    /// Sends `mesh` to the GPU, replacing the previous one. Returns the bytes sent.
    std::int64_t upload(const TriangleMesh& mesh);
    /// Draws the uploaded mesh into the bound framebuffer with the nearer depth test
    /// (render/depth_convention.h), writing the AOV attachments when options.writeAov; each surface
    /// with the material of the surface of `scene` with its id (others are skipped). Returns the
    /// error when the shader does not build.
    Status draw(const Scene& scene, const FrameCamera& camera, const std::vector<Light>& lights,
                const RenderOptions& options);
    /// Frees the GL objects.
    void release();

    std::int64_t residentBytes() const { return m_bytes; }
    int drawCalls = 0; ///< of the last draw
    int surfaces = 0;  ///< surfaces the last draw drew

private:
    struct Range {
        SurfaceId id;
        GLsizei count = 0;
        size_t firstIndexByte = 0;
        GLint baseVertex = 0;
    };
    QOpenGLFunctions_4_5_Core* m_gl = nullptr;
    ShaderLibrary* m_shaders = nullptr;
    GLuint m_vao = 0;
    GLuint m_buffers[4] = {0, 0, 0, 0}; ///< positions, normals, uvs, indices
    std::vector<Range> m_ranges;
    std::int64_t m_bytes = 0;
    std::vector<glm::vec3> m_positions, m_normals; ///< staging, kept to avoid reallocation
    std::vector<glm::vec2> m_uvs;
    std::vector<unsigned> m_indices;
};

} // namespace kw
