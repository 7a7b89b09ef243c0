// Per-surface GPU data keyed by SurfaceId: control-point and span-table textures and the base
// polygon buffers. Remembers the Revisions it uploaded and uploads only what is stale.
#pragma once

#include "model/document.h"
#include "render/frame_report.h"
#include "render/gpu_layout.h"
#include "render/render_types.h"

#include <QOpenGLFunctions_4_5_Core>
#include <QString>
#include <map>
#include <memory>

namespace kw {

/// GPU objects of one surface. Textures: control points RGBA32F countU x countV (texel (i, j) =
/// (w P, w)), span tables RGBA32F spanTableTexels(p) x (count - p). Two VAOs share the vertex
/// buffer of BaseVertex: one with triangle indices, one with cell outlines.
struct SurfaceGpu {
    SurfaceId id;
    Revisions revisions; ///< what is on the GPU
    int partitionsU = 0, partitionsV = 0;
    int degreeU = 1, degreeV = 1, countU = 0, countV = 0;
    glm::vec4 domain{0.0f, 1.0f, 0.0f, 1.0f};
    glm::dvec3 origin{0.0}; ///< control texels are relative to it (packControlPoints)
    GLuint controlTexture = 0, spanTextureU = 0, spanTextureV = 0;
    GLuint vertexBuffer = 0, triangleBuffer = 0, outlineBuffer = 0;
    GLuint triangleVao = 0, outlineVao = 0;
    int triangleIndexCount = 0, outlineIndexCount = 0;
    std::vector<glm::vec4> control; ///< the texels now on the GPU
    BasePolygon polygon;            ///< the vertices now on the GPU
    UploadStats stats;              ///< since creation or resetStats()
};

class SurfaceGpuCache {
public:
    /// `gl` must stay valid and its context current for every call below.
    void initialize(QOpenGLFunctions_4_5_Core* gl) { m_gl = gl; }

    /// Brings the GPU data of every surface of `doc` up to date and drops entries of removed
    /// surfaces. partitionsU/V > 0 override the surfaces' own partitions. Per surface:
    /// new, or Knots revision changed -> full upload; Points changed -> the bounding rectangle
    /// of the changed texels as one sub-image and the affected base polygon vertices only;
    /// partitions changed -> base polygon rebuilt, textures untouched.
    /// A surface whose control net exceeds GL_MAX_TEXTURE_SIZE in either direction is not
    /// uploaded (nor drawn); sync then returns false with *error naming it. The others are
    /// synced regardless.
    bool sync(const Document& doc, int partitionsU = 0, int partitionsV = 0,
              QString* error = nullptr);

    const SurfaceGpu* find(SurfaceId id) const;
    /// Statistics of one surface (zero for an unknown id) or of all, since the last reset.
    UploadStats stats(SurfaceId id) const;
    UploadStats totalStats() const;
    void resetStats();
    /// What the last sync uploaded (for FrameReport).
    const UploadStats& frameStats() const { return m_frame; }
    /// Adds the bytes of every surface's textures and buffers to `out` by kind.
    void residentBytes(GpuBytes& out) const;
    /// Frees every GL object; the context must be current.
    void release();

private:
    void uploadAll(SurfaceGpu& g, const Surface& s, int nu, int nv);
    void uploadChangedPoints(SurfaceGpu& g, const Surface& s);
    void rebuildPolygon(SurfaceGpu& g, const Surface& s, int nu, int nv);
    void destroy(SurfaceGpu& g);

    QOpenGLFunctions_4_5_Core* m_gl = nullptr;
    std::map<SurfaceId, std::unique_ptr<SurfaceGpu>> m_surfaces;
    UploadStats m_delta; ///< of the surface being synced
    UploadStats m_frame; ///< of the last sync
};

} // namespace kw
