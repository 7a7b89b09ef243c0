// Renderer's private implementation: the GPU scene and the stateless passes. Internal to render/
// (render's tests inspect uploads and masks through RendererTestHook).
#pragma once

#include "render/accumulate_target.h"
#include "render/antialias_target.h"
#include "render/damage_tiles.h"
#include "render/edge_bands_pass.h"
#include "render/exact_contract.h"
#include "render/exact_surface_pass.h"
#include "render/float_depth_target.h"
#include "render/gpu_scene.h"
#include "render/overlay_passes.h"
#include "render/partial_frame.h"
#include "render/pass_clock.h"
#include "render/renderer.h"
#include "render/shader_library.h"
#include "render/tessellated_pass.h"
#include "render/triangle_mesh_pass.h"

#include <QOpenGLFunctions_4_5_Core>
#include <QRect>
#include <optional>

namespace kw {

struct Renderer::Impl {
    /// One frame into `target`; with `scissor` only that rectangle (GL window coordinates) is
    /// cleared and drawn.
    FrameReport renderFrame(const Document& doc, const Camera& camera, const RenderTarget& target,
                            RenderOptions options, const QRect* scissor);
    /// The colour range of a colour-map analysis mode for this frame (see FrameReport).
    ValueRange resolveAnalysisRange(const Document& doc, const AnalysisOptions& analysis);
    /// Binds `target`, sets the frame's fixed state and clears colour, AOVs and depth (only
    /// the pick pixel's when `pickPixel`).
    void beginTarget(const RenderTarget& target, const RenderOptions& options,
                     const QRect* pickPixel);
    /// The samples a frame is drawn with: options.samples within the GPU's GL_MAX_SAMPLES
    /// (a warning in `report` when it is cut), 1 for AOV frames and picks.
    int frameSamples(const RenderOptions& options, bool aov, bool pick, FrameReport& report);
    /// The gradient of options.backgroundTop over the cleared colour target (not the AOVs).
    void drawBackground(const RenderOptions& options);
    Status ensurePickTarget(QSize size);
    void releasePickTarget();
    /// Draws `framebuffer`'s first `count` fragment outputs, each to its own attachment
    /// (render/exact_contract.h).
    void setDrawBuffers(GLuint framebuffer, int count);

    QOpenGLFunctions_4_5_Core* gl = nullptr;
    ShaderLibrary shaders;
    GpuScene scene; ///< every per-surface GPU object
    ExactSurfacePass exact;
    AntialiasTarget antialias;   ///< the multisampled frame of RenderOptions::samples > 1
    AccumulateTarget accumulate; ///< the accumulated frame (Antialiasing::Accumulate)
    int maxSamples = 1;          ///< GL_MAX_SAMPLES within 1..kMaxSamples, read at initialize
    FloatDepthTarget floatDepth; ///< aliased frames into hosts without float depth
    TessellatedPass tessellated;
    WireframePass wireframe;
    ControlNetPass controlNet;
    EdgeBandsPass edgeBands;
    PassClock clock; ///< Renderer::setPassProfiling
    /// Renderer::setMesh's meshes, created on first use.
    std::unique_ptr<TriangleMeshPass> meshes[Renderer::kMeshSlots];
    QString glDescription;

    /// What the automatic analysis range was computed from (revisions come from one
    /// document-wide counter and never repeat, so the newest geometry revision and the surface
    /// count identify the geometry).
    struct RangeKey {
        const Document* document = nullptr;
        AnalysisMode mode = AnalysisMode::Phong;
        size_t surfaces = 0;
        std::uint64_t newestRevision = 0;
        bool operator==(const RangeKey&) const = default;
    };
    RangeKey rangeKey;
    ValueRange autoAnalysisRange;

    /// What the progressive sum in `accumulate` was drawn from (RenderOptions::progressive);
    /// empty when the sum is not one of a progressive image.
    struct ProgressKey {
        const Document* document = nullptr;
        std::uint64_t revision = 0; ///< Document::revision: never repeats, in any document
        Camera camera;
        std::uint32_t framebuffer = 0;
        QSize size;
        RenderOptions options;
        bool operator==(const ProgressKey&) const = default;
    };
    std::optional<ProgressKey> progressKey;

    /// The last frame whose deferred pre-pass left (u, v) and the surface's row per pixel
    /// (Renderer::pickInLastFrame): what it showed, and the framebuffer whose stencil says
    /// which pixels that is (non-zero: a deferred surface).
    struct LastFrame {
        const Document* document = nullptr;
        std::uint64_t revision = 0;
        Camera camera;
        QSize size;
        std::uint32_t framebuffer = 0;
        bool operator==(const LastFrame&) const = default;
    };
    std::optional<LastFrame> lastFrame;

    /// The last frame kept in the own framebuffer for a partial frame after it
    /// (RenderOptions::FrameReuse; render/partial_frame.h).
    PartialFrames partial;
    /// The partial frame being drawn: its rectangle (GL window pixels), which beginTarget
    /// scissors every clear and draw to; null otherwise.
    QRect partialScissor;
    /// Set while a partial frame is drawn again whole (its plan skipped other solids' back
    /// faces than the kept frame's).
    bool wholeFrameAgain = false;
    /// The host framebuffer the last frame's kept colour was copied into (it holds that frame
    /// but for what its host drew over since, RenderTarget::drawnOver); unset after any other
    /// frame the renderer draws.
    struct Presented {
        std::uint32_t framebuffer = 0;
        QSize size;
        std::uint64_t serial = 0; ///< floatDepth's
        bool operator==(const Presented&) const = default;
    };
    std::optional<Presented> presented;
    /// The frame's view as partial frames compare it, and its surfaces' footprints.
    PartialFrameView partialView(const Document& doc, const RenderTarget& target, QSize drawnSize,
                                 const FrameCamera& fc, const std::vector<Light>& lights,
                                 const RenderOptions& options, const ValueRange& range) const;
    /// Brings each record's polygon rectangle (SurfaceRecord::drawnRect) up to date first; with
    /// options.controlNet a footprint holds the control points too (the net is drawn); a
    /// surface being edited (SurfaceRecord::tilesWanted) carries its damage tiles.
    std::vector<SurfaceFootprint> surfaceFootprints(const FrameCamera& fc,
                                                    const RenderOptions& options);
    /// r's damage tiles at fc's view (kw::cellTiles, grown by `pad`), taken when missing and
    /// kept in the record (SurfaceRecord::drawnTiles); null when its polygon cannot tell them.
    /// Marks it SurfaceRecord::tilesWanted.
    std::shared_ptr<const std::vector<std::int32_t>>
    recordTiles(SurfaceRecord& r, const FrameCamera& fc, const TileGrid& grid, int pad);

    // renderFrame's steps.
    /// Zeroes the passes' per-frame counters.
    void resetPassCounters();
    /// Where a frame is drawn: the multisampled or the accumulation target for `samples` > 1,
    /// the float-depth target for an aliased frame into a host without float depth (`size`
    /// becomes the target's when that cannot be had), else `target`. Frees the targets a frame
    /// no longer uses; warns in `report` when anti-aliasing is off.
    struct FrameTargets {
        AntialiasTarget* aa = nullptr;
        AccumulateTarget* accumulated = nullptr;
        RenderTarget drawn;
    };
    FrameTargets frameTargets(const RenderTarget& target, int samples, const RenderOptions& options,
                              bool preview, bool pick, QSize& size, FrameReport& report);
    /// The sub-pixel offsets of the frame's samples and those this call draws, [first, end):
    /// all of them, or the next one of a progressive image (none once all are in).
    struct SampleRange {
        std::vector<glm::vec2> offsets;
        size_t first = 0, end = 0;
    };
    SampleRange sampleRange(const Document& doc, const Camera& camera, const RenderTarget& target,
                            QSize size, const RenderOptions& options, int samples, bool accumulated,
                            bool pick);
    /// Draws the samples [range.first, range.end) into `sampleTarget` (`fc` shifted by each
    /// one's offset, unshifted after), then resolves the accumulated or multisampled frame into
    /// `framebuffer`. Stops at the first failure, which it returns; the composite runs anyway.
    Status drawSamples(const SampleRange& range, const RenderTarget& sampleTarget,
                       std::uint32_t framebuffer, const FrameTargets& targets, FrameCamera& fc,
                       const std::vector<Light>& lights, const RenderOptions& options,
                       const ValueRange& analysisRange, const QRect* pickPixel);
    /// The wireframe, control net and edge bands over the frame, into its colour only.
    Status drawOverlays(const RenderTarget& target, const FrameCamera& fc,
                        const RenderOptions& options);
    /// The passes' counters and the GPU memory into `report`.
    void reportPassFigures(FrameReport& report) const;
    /// Keeps `now` for pickInLastFrame when it can be read there (`pickable`: an exact,
    /// full-size, successful frame) and a sample was drawn, or the same view was resolved.
    void rememberLastFrame(const LastFrame& now, bool drewSample, bool pickable);
    /// What the frame does as a partial frame: whether it can be kept for the next one
    /// (`keepable`), and what of the kept frame it redraws (`damage`, GL window pixels; none:
    /// the whole frame). Sets fc.reach, partialScissor and the report's partial figures.
    struct PartialPlan {
        bool keepable = false;
        PartialFrameView view;
        std::vector<SurfaceFootprint> footprints;
        std::optional<glm::ivec4> damage;
        /// What of `damage` is redrawn, one pass sequence each: its changed surfaces' tiles
        /// (render/damage_tiles.h), or `damage` itself with overlays.
        std::vector<glm::ivec4> regions;
        bool unchanged = false; ///< nothing to redraw: the kept frame is the image
    };
    /// Copies the kept frame into the host: whole, or where a partial frame redrew and the host
    /// drew over when the host still holds the last frame copied. Returns the pixels copied.
    std::int64_t present(const PartialPlan& plan, const RenderTarget& target, bool preview);
    PartialPlan planPartialFrame(const Document& doc, const RenderTarget& target, QSize size,
                                 FrameCamera& fc, const std::vector<Light>& lights,
                                 const RenderOptions& options, const FrameTargets& targets,
                                 bool pick, FrameReport& report);
    /// The rectangles covering the damage tiles (render/damage_tiles.h) of the `changed`
    /// surfaces, as they were (their footprint's tiles, else its rectangle's) and as they are
    /// drawn now (their cells' tiles, taken here, kept in the record and in `footprints`).
    std::vector<glm::ivec4> damageRegions(const std::vector<DamagedSurface>& changed,
                                          const FrameCamera& fc, int pad,
                                          const RenderOptions::DamageTiles& options,
                                          std::vector<SurfaceFootprint>& footprints);
    /// Draws the frame's samples (drawSamples): over the whole frame or `plan`'s one rectangle,
    /// or over each of plan.regions with its own reach. Adds the cells sent to `report`'s
    /// partial figures; `backCulledMoved`: a partial frame skipped other solids' back faces
    /// than the kept frame (it must be drawn again whole).
    Status drawRegions(const PartialPlan& plan, const SampleRange& range,
                       const RenderTarget& sampleTarget, std::uint32_t framebuffer,
                       const FrameTargets& targets, FrameCamera& fc,
                       const std::vector<Light>& lights, const RenderOptions& options,
                       const QRect* pickPixel, FrameReport& report, bool& backCulledMoved);
    /// After a frame that is not a pick: what pickInLastFrame and the next partial frame may
    /// read from it (`ok`: the frame succeeded).
    void rememberFrame(const LastFrame& now, const FrameCamera& fc, const RenderOptions& options,
                       const PartialPlan& plan, bool drewSample, bool pickable, bool ok);

    GLuint backgroundVao = 0; ///< attribute-less, for drawBackground's one triangle
    /// Framebuffer of the pick query: depth and the three AOVs' attachments (the colour's too,
    /// so the surface shaders' outputs keep their locations).
    GLuint pickFbo = 0;
    /// Colour and the AOVs, each at its output (kColourOutput .. kAovNormalOutput), then depth.
    GLuint pickTextures[kAovDrawBuffers + 1] = {};
    QSize pickSize;
};

} // namespace kw
