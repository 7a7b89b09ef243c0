// Baseline pass, the paper's "OpenGL API" column: surfaces tessellated on the CPU with the
// kernel at their partitions, per-vertex normals and Gouraud shading.
#pragma once

#include "model/document.h"
#include "render/render_types.h"
#include "render/shader_library.h"
#include "render/trim_mask_pass.h"

#include <QOpenGLFunctions_4_5_Core>
#include <QString>
#include <map>

namespace kw {

class TessellatedPass {
public:
    void initialize(QOpenGLFunctions_4_5_Core* gl, ShaderLibrary* shaders);
    /// Re-tessellates surfaces whose points, knots or partitions changed (partitionsU/V > 0
    /// override the surfaces' own), drops removed ones, and draws all into the bound
    /// framebuffer, cutting the surfaces that have a mask in `masks` (may be null: no trims).
    /// Returns false with *error set when the shader cannot be built.
    bool draw(const Document& doc, const TrimMaskPass* masks, const FrameCamera& camera,
              const std::vector<Light>& lights, const RenderOptions& options, QString* error);
    void release();
    /// Bytes of every mesh's buffers.
    std::int64_t residentBytes() const;
    int drawCalls = 0;   ///< counted by draw; the renderer zeroes it per frame
    UploadStats uploads; ///< counted by draw; the renderer zeroes it per frame

private:
    struct Mesh {
        Revisions revisions;
        int nu = 0, nv = 0;
        GLuint vao = 0, positions = 0, normals = 0, uvs = 0, indices = 0;
        int indexCount = 0;
        std::int64_t bytes = 0;
    };
    void update(Mesh& m, const Surface& s, const Revisions& rev, int nu, int nv);
    void destroy(Mesh& m);

    QOpenGLFunctions_4_5_Core* m_gl = nullptr;
    ShaderLibrary* m_shaders = nullptr;
    std::map<SurfaceId, Mesh> m_meshes;
};

} // namespace kw
