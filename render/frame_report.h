// What one frame did and what the renderer holds: the result of Renderer::render, plus the
// render target and the pick query's answer. Plain data, no GL.
#pragma once

#include "model/document/scene.h"
#include "render/render_types.h"

#include <QRect>
#include <QSize>
#include <QString>
#include <QStringList>
#include <cstdint>
#include <glm/glm.hpp>
#include <optional>

namespace kw {

/// Where a frame goes: a framebuffer object of the renderer's context (0, or a
/// QOpenGLWidget's defaultFramebufferObject()) of `size` pixels. With `aov` the framebuffer has
/// the AOV colour attachments 1..3 of OffscreenRenderer, and the frame writes them; with
/// `curvatureAov` as well, attachment 4 gets K, H, k1, k2 (exact mode).
struct RenderTarget {
    std::uint32_t framebuffer = 0;
    QSize size;
    bool aov = false;
    bool curvatureAov = false;
    /// What the host drew over in this framebuffer since the renderer's last frame into it
    /// (its overlays; GL pixels, origin bottom left): an empty rectangle when nothing. Unset
    /// when not known (a new framebuffer, one the platform may discard or others draw on).
    /// Known, a kept frame (RenderOptions::FrameReuse) copied into a framebuffer that holds
    /// the last one copies only the rectangles it redrew and this one.
    std::optional<QRect> drawnOver;
};

/// Bytes of GPU memory held by the renderer, by kind (buffer and texture storage as requested
/// from the driver; the driver's own padding is not known).
struct GpuBytes {
    std::int64_t controlPoints = 0;     ///< homogeneous control points
    std::int64_t spanTables = 0;        ///< knot span tables
    std::int64_t basePolygons = 0;      ///< base polygon vertices and indices (exact mode)
    std::int64_t tessellatedMeshes = 0; ///< baseline meshes (tessellated mode)
    std::int64_t controlNets = 0;       ///< control-net overlay points and lines
    std::int64_t trimMasks = 0;         ///< the trim mask array
    std::int64_t perSurface = 0;        ///< per-surface tables (draw parameters and commands)
    std::int64_t frameTargets = 0;      ///< the anti-aliased frame's attachments (samples > 1)
    /// The aliased frame's own colour and float depth when the host's depth is not float
    /// (render/float_depth_target.h: the editor's widget framebuffer).
    std::int64_t floatDepthTarget = 0;

    std::int64_t total() const {
        return controlPoints + spanTables + basePolygons + tessellatedMeshes + controlNets +
               trimMasks + perSurface + frameTargets + floatDepthTarget;
    }
    bool operator==(const GpuBytes&) const = default;
};

/// CPU time of one render call by phase, in milliseconds (wall clock on the calling thread;
/// GPU work runs asynchronously and is not included).
struct FrameTimes {
    double sync = 0.0;     ///< bringing the GPU scene up to date (uploads, meshes)
    double masks = 0.0;    ///< trim masks: flattening loops and issuing their draws
    double surfaces = 0.0; ///< issuing the surface passes
    double overlays = 0.0; ///< wireframe and control net
    double total = 0.0;    ///< the whole call
    /// Thread CPU (CLOCK_THREAD_CPUTIME_ID, not wall) from the call's start to the first draw
    /// call of the surface pass: sync, uploads, partition choices, masks, culling and batching,
    /// everything the frame does before it draws (the whole call when it draws no surface).
    /// The "mouse-move to draw call" is the edit's own time plus this.
    double beforeDraws = 0.0;
};

/// A frame's passes one by one (Renderer::setPassProfiling): each ended by glFinish, so its
/// GPU work counts to it, in wall ms and process CPU ms (every thread: llvmpipe's rasteriser
/// threads too). The glFinish after each pass removes the overlap of CPU and GPU work, so the
/// sum is a little above the unprofiled frame.
struct PassTimes {
    enum Pass {
        Sync,         ///< the GPU scene brought up to date: uploads, partitions, trim masks
        Prepass,      ///< the depth pre-pass (exact trims tested there near trim curves)
        Exact,        ///< the exact pass: deferred shading and the forward batches
        Sections,     ///< the cells a section plane crosses (exact depth, the section test)
        Skirts,       ///< edge skirts
        Fins,         ///< silhouette fins
        BackFaces,    ///< back faces of closed solids seen from inside or cut
        TrimEdges,    ///< MSAA's trim coverage pass
        Antialiasing, ///< adding samples into the sum and resolving it, or the MSAA composite
        Overlays,     ///< wireframe, control net, edge bands
        Present,      ///< the frame copied (or magnified) into the host's framebuffer
        kCount
    };
    double wallMs[kCount] = {};
    double cpuMs[kCount] = {};
    bool measured = false; ///< profiling was on for this frame
    static const char* name(int pass) {
        static const char* const names[kCount] = {
            "sync",       "prepass",    "exact",         "sections", "skirts", "fins",
            "back faces", "trim edges", "anti-aliasing", "overlays", "present"};
        return pass >= 0 && pass < kCount ? names[pass] : "";
    }
};

/// The result of Renderer::render.
struct FrameReport {
    /// False when the frame could not be drawn as asked; `error` says why. A surface left out
    /// (control net too large for the GPU) or drawn untrimmed (mask limits) sets ok to false
    /// after the rest of the frame was drawn.
    bool ok = true;
    QString error;
    UploadStats uploads; ///< data sent to the GPU by this frame
    TrimMaskStats masks; ///< trim mask work of this frame (masks.redraws: mask rebuilds)
    int drawCalls = 0;   ///< glDraw* calls issued by this frame
    int surfaces = 0;    ///< surfaces drawn (hidden ones are not)
    /// Of those, left out of the exact passes as wholly outside the view (their control
    /// bounds are; RenderOptions::cullOutsideView).
    int culled = 0;
    /// Closed solids (Surface::solid) whose polygons' back faces the exact passes skipped
    /// (RenderOptions::skipBackFaces): every face drawn, the eye outside.
    int solidsBackCulled = 0;
    /// Surface records whose revisions the sync compared: every visible one after a
    /// structural change or a new view, else only those the document reported changed.
    int recordsSynced = 0;
    GpuBytes gpuBytes; ///< resident after this frame
    /// Host memory the renderer keeps beside gpuBytes, after this frame: the CPU copies that
    /// partial updates and the silhouette fins read (control texels, base polygon vertices,
    /// cell breaks and spans, the span bounds of the adaptive choice, the fins' vertices).
    std::int64_t hostCopyBytes = 0;
    /// What the frame drew differently from the document: trim loops repaired or ignored
    /// (each prefixed with its surface id) and surfaces left out. The current state, not only
    /// what changed in this frame.
    QStringList warnings;
    FrameTimes cpuMs;
    /// Adaptive partitions (RenderOptions::Partitioning::Adaptive): the surfaces whose choice
    /// was evaluated again this frame (view or surface changed), the largest guaranteed screen
    /// bound in pixels over the drawn surfaces, the cells of their base polygons, and the
    /// surfaces that could not reach the tolerance within kMaxPartitions (also a warning).
    struct Partitions {
        int choicesEvaluated = 0;
        double worstBoundPixels = 0.0;
        std::int64_t cells = 0; ///< base polygon cells drawn, in either mode
        int unmet = 0;
        /// Exact mode with the depth pre-pass: the cells whose pre-pass fragments test the
        /// trims (every cell of a trimmed surface, or with RenderOptions::splitCellsByTrims
        /// only those near a curve), and the cells the split left out as trimmed away.
        std::int64_t trimTestedCells = 0, trimmedAwayCells = 0;
        /// Triangles of the edge skirts drawn (RenderOptions::edgeSkirts); 0 without.
        std::int64_t skirtTriangles = 0;
        /// Adaptive exact frames: the surfaces drawn without the Newton step onto the pixel's
        /// ray, because they are affine in (u, v) (planes: kw::surfaceIsAffine) and their
        /// polygon's (u, v) is already the point under the pixel.
        int affineSurfaces = 0;
        /// Adaptive exact frames: the surfaces shaded from their analytic form in closed form
        /// (RenderOptions::analyticFaces), not by the Newton step onto their NURBS.
        int analyticSurfaces = 0;
        /// Adaptive exact frames: of those, the faces drawn by their covers (RenderOptions::
        /// coverMinCells): a box bounding the face, shaded with the closed form's exact depth.
        int coverSurfaces = 0;
        /// Surfaces shaded by the deferred exact pass (RenderOptions::deferredPass) in the
        /// last aliased frame; 0 when every surface was drawn the forward way.
        int deferredSurfaces = 0;
        /// Frames with section planes and the pre-pass: the cells a plane crosses, drawn with
        /// exact depth and the section test (RenderOptions::splitCellsBySections); the cells
        /// of the surfaces a plane crosses that every plane keeps are drawn the frame's way.
        std::int64_t sectionCrossedCells = 0;
    } partitions;
    /// The colour range a colour-map analysis mode used (the user's, or the automatic one of
    /// kw::autoRange, recomputed only when the geometry or mode changed and held while
    /// AnalysisOptions::holdRange is set); {0, 1} for other modes. For the legend.
    ValueRange analysisRange;
    /// Samples per pixel in the image: 1 aliased, RenderOptions::samples when anti-aliased, and
    /// with RenderOptions::progressive those accumulated so far.
    int samplesInImage = 1;
    /// Progressive accumulation has samples left to add: render again, unchanged, to add the
    /// next one.
    bool refining = false;
    /// The pixels drawn (RenderOptions::previewScale below 1: fewer than the target's).
    QSize drawnSize;
    /// RenderOptions::FrameReuse::Partial: the frame redrew only `partialRect` (pixels of the
    /// drawn frame, x right, y down; empty: nothing changed, the kept frame was copied again)
    /// and kept the rest of the last frame; `partialSurfaces` surfaces reached it, with
    /// `partialSurfaceCells` base polygon cells, of which it drew the `partialCells` that reach
    /// it (partitions.cells counts every surface's). False: the whole frame was drawn.
    /// Within partialRect it redrew `partialRegions` rectangles of `partialPixels` pixels in
    /// all (the damage tiles of the changed surfaces, render/damage_tiles.h; one rectangle,
    /// partialRect, with overlays).
    bool partial = false;
    QRect partialRect;
    int partialRegions = 0;
    std::int64_t partialPixels = 0;
    int partialSurfaces = 0;
    std::int64_t partialSurfaceCells = 0;
    std::int64_t partialCells = 0;
    /// Pixels of the kept frame copied into the host (RenderOptions::FrameReuse): the whole
    /// frame, or a partial frame's rectangles and what the host drew over
    /// (RenderTarget::drawnOver); 0 when the frame went straight to the host.
    std::int64_t presentedPixels = 0;
    /// The host's framebuffer now holds the kept frame (not a magnified preview, not a frame
    /// drawn straight into it): the next partial frame into it may copy only what changed, so
    /// a host that draws over it should say where (RenderTarget::drawnOver).
    bool keptInHost = false;
    /// Per pass, when Renderer::setPassProfiling is on (else measured is false).
    PassTimes passes;
};

/// The answer of Renderer::pick: the surface visible at a pixel, its parameters there and the
/// kernel's point at them.
struct PickHit {
    SurfaceId surface;
    glm::dvec2 uv{0.0};    ///< (u, v) of the fragment, as the exact pass evaluated it
    glm::dvec3 point{0.0}; ///< surfacePoint(surface, u, v) in double precision
    double depth = 0.0;    ///< eye-space depth of the fragment along the view direction
};

} // namespace kw
