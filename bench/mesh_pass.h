// Draws a CPU-built SceneMesh with the baseline's Gouraud shader (tessellated.vert/.frag) in the
// OpenGL 4.5 core context: the GLU tessellator's output (re-uploaded each frame) and the
// prebuilt fine mesh (uploaded once).
#pragma once

#include "bench/bench_mesh.h"
#include "render/render_types.h"
#include "render/shader_library.h"

#include <QOpenGLFunctions_4_5_Core>
#include <QString>

namespace kw::bench {

class MeshPass {
public:
    MeshPass() = default;
    MeshPass(const MeshPass&) = delete;
    MeshPass& operator=(const MeshPass&) = delete;
    ~MeshPass(); ///< GL objects must have been freed by release() (the context is not ours)

    /// Needs the off-screen renderer's context current; keeps its GL functions for later calls.
    void initialize();
    /// Sends `mesh` to the GPU (replacing the previous one): one vertex buffer per attribute and
    /// one index buffer for all surfaces.
    void upload(const SceneMesh& mesh);
    /// Draws the uploaded mesh into the bound framebuffer with depth test GL_LESS, writing the
    /// AOV attachments when `writeAov`. Surfaces are matched to `scene` by id for their material.
    /// Returns false with *error set when the shader does not build.
    bool draw(const Scene& scene, const FrameCamera& camera, const std::vector<Light>& lights,
              bool writeAov, QString* error);
    /// Frees the GL objects; the initialising context must be current.
    void release();

    long long uploadedBytes() const { return m_bytes; }

private:
    struct Range {
        SurfaceId id;
        GLsizei count = 0;
        size_t firstIndexByte = 0;
        GLint baseVertex = 0;
    };
    QOpenGLFunctions_4_5_Core* m_gl = nullptr;
    ShaderLibrary m_shaders;
    GLuint m_vao = 0;
    GLuint m_buffers[4] = {0, 0, 0, 0}; ///< positions, normals, uvs, indices
    std::vector<Range> m_ranges;
    long long m_bytes = 0;
    std::vector<glm::vec3> m_positions, m_normals; ///< staging, kept to avoid reallocation
    std::vector<glm::vec2> m_uvs;
    std::vector<unsigned> m_indices;
};

} // namespace kw::bench
