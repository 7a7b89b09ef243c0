// Render options, upload statistics and per-frame camera matrices shared by the render passes.
#pragma once

#include "model/document/scene.h"
#include "render/analysis.h"

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <vector>

namespace kw {

struct EdgeBands; // render/edge_bands.h

enum class RenderMode {
    Exact,       ///< per-fragment exact NURBS evaluation on the base polygon (paper 3.4)
    Tessellated, ///< CPU tessellation at the partitions, per-vertex normals, Gouraud shading
};

/// Trim mask side limits in texels (RenderOptions::trimMaskCap).
constexpr int kMinTrimMaskSize = 32;
constexpr int kDefaultTrimMaskCap = 1024;
/// Largest exact trim grid side in texels (render/trim_grid.h's trimGridResolution cap).
constexpr int kMaxTrimGridSide = 1024;
/// Default GPU memory budget of the exact trim grids (RenderOptions::trimBudgetBytes), and the
/// range a user may set. 512 MiB: at most what one R32UI texture buffer holds on llvmpipe, and
/// room for about 1,800 trimmed faces of hammer.iges at full grids (docs/PERFORMANCE.md ##
/// Trims); larger models get coarser grids, still exact.
/// Samples per pixel of RenderOptions::samples: 1 (no anti-aliasing) to kMaxSamples (and the
/// GPU's GL_MAX_SAMPLES).
constexpr int kMaxSamples = 16;
constexpr std::int64_t kDefaultTrimBudgetBytes = std::int64_t(512) << 20;
constexpr std::int64_t kMinTrimBudgetBytes = std::int64_t(4) << 10;
constexpr std::int64_t kMaxTrimBudgetBytes = std::int64_t(4) << 30;

/// What a frame draws. Defaults are the editor's: exact surfaces, two lights, no overlays.
struct RenderOptions {
    RenderMode mode = RenderMode::Exact;
    /// Lights used for shading, 1..kMaxLights. The document's lights come first; when more are
    /// asked for than it has, further lights are derived from them (see Renderer::lightsFor).
    int lightCount = 2;
    /// Partition override for every surface; 0 keeps each surface's own setting. In adaptive
    /// mode these (or the surface's own) are the minimum.
    int partitionsU = 0;
    int partitionsV = 0;
    /// How each surface's base polygon is partitioned.
    enum class Partitioning {
        /// The paper's: nu x nv from the surface's sliders (or the override above).
        Uniform,
        /// Per surface and view, the fewest uniform partitions at or above the sliders' for
        /// which the base polygon provably lies within `pixelTolerance` pixels of the exact
        /// surface on screen (render/surface_bound.h: Filip-Magedson-Markot bounds on the
        /// homogeneous Bezier nets, projected with the nearest depth). Recomputed only when
        /// the view or the surface changes; the polygon is rebuilt only when the choice does.
        Adaptive,
    };
    Partitioning partitioning = Partitioning::Uniform;
    double pixelTolerance = 0.5; ///< adaptive mode's screen bound, kMin..kMaxPixelTolerance
    bool wireframe = false;      ///< outline of the base polygon cells
    bool controlNet = false;     ///< control points and net lines
    /// View > Analysis > Edge Continuity: bands along the edges coloured by class
    /// (render/edge_bands.h); null draws none. Shared so that a frame copies no vertices.
    std::shared_ptr<const EdgeBands> edgeBands;
    /// How exact mode shades each pixel once (docs/PERFORMANCE.md measures both, and a
    /// deferred variant that was slower on llvmpipe and removed).
    enum class Shading {
        /// Default. Depth pre-pass of the base polygons with a trivial shader, then the exact
        /// shader with GL_EQUAL and depth writes off: early-z rejects every hidden fragment,
        /// so each pixel is evaluated once. Depth is the base polygon's (a chord of the
        /// surface), so silhouettes and surface intersections follow the polygon.
        DepthPrepass,
        /// One pass writing the exact surface depth through gl_FragDepth: exact intersections
        /// between surfaces, but no early-z, so hidden fragments are evaluated too.
        ExactDepth,
    };
    Shading shading = Shading::DepthPrepass;
    /// Write the AOV attachments 1..3 (see OffscreenRenderer). Renderer::render sets it from
    /// RenderTarget::aov; the passes read it.
    bool writeAov = false;
    /// Also write K, H, k1, k2 to attachment 4 (exact mode; the target FBO must have it).
    bool writeCurvatureAov = false;
    /// Analysis colouring of exact mode (curvature maps, zebra, ...); Phong by default. The
    /// tessellated baseline ignores it.
    AnalysisOptions analysis;
    /// Cut trimmed surfaces with their trim masks (paper 3.4.2). False draws them uncut (for
    /// checks against the CPU classification, and to see what a trim removes).
    bool trims = true;
    /// The base polygon of a trimmed surface spans its trims' (u, v) box (trimParameterBox,
    /// model/nurbs/visible_bounds.h), still split at knots, so a small face on a large domain gets
    /// its partitions where it is. False spans the whole domain, as the
    /// paper does: `knotwork render --no-trims` clears both this and `trims` to show whole
    /// surfaces; with only `trims` false the same fragments as the cut frame are drawn, less
    /// the mask's discards (what the trim tests compare).
    bool polygonOverTrims = true;
    /// Exact trims with the depth pre-pass, no anti-aliasing: each trimmed surface's cells are
    /// ordered by how its trim grid cuts them (kw::splitByTrims) and the pre-pass tests the
    /// trims only on the cells near a curve; cells the trims remove are not drawn. The same
    /// pixels either way (tst_render_trims); off only to measure the difference.
    bool splitCellsByTrims = true;
    /// Adaptive partitions, aliased frames: after the exact pass each base polygon's outline gets
    /// a skirt, a strip pushed a little past its edge on screen whose fragments are kept
    /// only where Newton's method puts the pixel's ray on the exact surface inside its domain
    /// and trims (docs/RENDERING.md, "Skirts"). It fills the pixels between a polygon's edge
    /// chord and the surface's true edge, which no face covered (cracks).
    /// Off only to measure the difference.
    bool edgeSkirts = true;
    /// Adaptive partitions: a base polygon keeps only the cells that may reach the view
    /// (kw::cutInView), so a close-up holds and builds what is on screen, not every cell of
    /// each surface in view. The same pixels; off only to measure the difference.
    bool polygonsInView = true;
    /// Adaptive exact frames with the depth pre-pass, aliased (each sample of accumulated
    /// anti-aliasing is one): the pre-pass also writes each pixel's (u, v), surface and cell,
    /// and a deferred pass shades each pixel once from them, however small the adaptive
    /// polygon's cells (docs/RENDERING.md, "The deferred exact pass"). The same image as the
    /// forward pass; off only to compare the two.
    bool deferredPass = true;
    /// With the deferred pass: surfaces with at least this many estimated pixels per cell are
    /// drawn the forward way, where a pixel is shaded about once anyway (docs/PERFORMANCE.md,
    /// "The deferred exact pass"). Changed only for measuring (1e30: every surface deferred).
    double deferMaxCellPixels = 1024.0;
    /// Surfaces with fewer estimated pixels per cell use the per-fragment-fetch variant, the
    /// others the per-cell gather (docs/PERFORMANCE.md). Changed only for measuring and tests
    /// (0: always gather, 1e30: never).
    double gatherMinCellPixels = 64.0;
    /// Adaptive partitions: a surface that is its own polygon (SurfaceGpu::affine) is shaded at
    /// its polygon's (u, v) without the Newton step. The same pixels; off only to measure
    /// what it saves.
    bool affineWithoutNewton = true;
    /// Adaptive partitions: a face that kept the analytic form of its source (Surface::analytic:
    /// a plane, cylinder, cone, sphere or torus, unedited) is shaded at the point where the
    /// pixel's ray meets that form, found in closed form (a quadratic, a quartic for the
    /// torus), instead of by the Newton step onto the NURBS (docs/RENDERING.md, "Analytic
    /// faces in closed form"). The same surface to float precision; off only to compare.
    bool analyticFaces = true;
    /// Adaptive frames: an unedited cylinder, cone or sphere (Surface::analytic) whose
    /// polygon in view would take more than this many cells is drawn by a *cover* instead: one
    /// box around the Bezier control bounds of its sub-rectangles (convex hull property),
    /// shaded with the closed form's exact depth, a fragment whose ray misses the face
    /// discarded (docs/RENDERING.md, "Covers of closed-form faces"). A close-up beside such a
    /// face needs thousands of cells for the pixel tolerance, and the cover 12 triangles. The
    /// same surface to float precision; 0 covers every such face, 1e30 none (for comparing).
    double coverMinCells = 4096.0;
    /// Silhouette fins (kw::buildFins) with the edge skirts; off only to measure what they
    /// cover and cost.
    bool silhouetteFins = true;
    /// One multi-draw per shader variant; off: the same commands issued one draw per
    /// surface, for comparing images and costs.
    bool multiDraw = true;
    /// Exact mode: the base polygon triangles of a closed solid's faces (Surface::solid) that
    /// turn their inside to the eye are skipped while the solid lies wholly beyond the near
    /// plane (the eye outside it): its faces in front cover them (docs/RENDERING.md, "Back
    /// faces of closed solids"). The same pixels either way; off only to measure the
    /// difference.
    bool skipBackFaces = true;
    /// Largest trim mask side in texels (kMinTrimMaskSize..16384, also limited by the GPU).
    /// Each surface's mask follows its size on screen (four texels per pixel of its control-net
    /// length along u and v), rounded up to a power of two, within [kMinTrimMaskSize,
    /// trimMaskCap]. The array holding all masks has layers of the largest side in use, so the
    /// cap also bounds memory: cap^2 bytes per trimmed surface (1 MiB at the default 1024).
    int trimMaskCap = kDefaultTrimMaskCap;
    /// How trims cut. Exact (default): by the hybrid trim grid of render/trim_grid.h,
    /// trim edges exact at any zoom. Mask: by the paper's FBO mask alone, accurate to its texels
    /// (kept for comparison, docs/PERFORMANCE.md ## Trims).
    enum class TrimMode { Exact, Mask };
    TrimMode trimMode = TrimMode::Exact;
    /// Bytes the exact trim grids may take on the GPU (kMinTrimBudgetBytes..kMaxTrimBudgetBytes,
    /// also limited by the GPU); past it they get coarser (still exact, slower), with a warning.
    std::int64_t trimBudgetBytes = kDefaultTrimBudgetBytes;
    /// Largest exact trim grid side in texels, 1..kMaxTrimGridSide (the budget may lower it
    /// further, with its warning; this cap gives none). A grid indexes the trim curves, it does
    /// not approximate them: a coarser one classifies every pixel the same way, with more curve
    /// pieces to test in each texel, and costs less to build, send and keep. Anti-aliased trim
    /// edges (samples > 1) read the texels about a pixel, so they can differ. `knotwork render`
    /// sets it from the image size with --samples 1 (docs/PERFORMANCE.md ## Start-up); the
    /// editor keeps this.
    int trimGridCap = kMaxTrimGridSide;
    /// Anti-aliasing: 1 draws aliased, as the paper does; N > 1 draws into a
    /// private framebuffer with N MSAA samples (silhouettes and base-polygon edges; shading
    /// stays once per pixel) and covers trim-edge pixels by the exact distance to the curve
    /// (kw::AntialiasTarget). Clamped to the GPU's limit with a warning. Frames with AOVs and
    /// picks are never anti-aliased (their pixels are exact samples).
    int samples = 1;
    /// How a frame with samples > 1 is anti-aliased.
    enum class Antialiasing {
        /// `samples` whole aliased frames, each with the pixel grid shifted by its own sub-pixel
        /// offset (a rotated grid: FrameCamera::jitter), averaged (kw::AccumulateTarget). Every
        /// sample is an exact aliased frame's pixel, skirts and fins included, so seams stay
        /// closed and highlights and analysis stripes are filtered too; trim edges get
        /// `samples` levels. The default (docs/RENDERING.md, "Anti-aliasing").
        Accumulate,
        /// One frame into `samples` MSAA samples, trim edges covered by the exact distance to
        /// the curve (kw::AntialiasTarget): smooth trim edges at any sample count,
        /// but no skirts or fins, so seams of B-reps can show the far side.
        Coverage,
    };
    Antialiasing antialiasing = Antialiasing::Accumulate;
    /// Accumulated anti-aliasing a sample at a time (the editor on software OpenGL): each
    /// Renderer::render draws one more sample into the sum kept from the previous call and
    /// shows the mean so far, for as long as nothing drawn changes (the document's revision,
    /// the camera, the target and its size, these options); any change starts again at the
    /// first sample. Once all `samples` are in, a call draws no surface and resolves the sum
    /// again. FrameReport::refining asks the host for the next call. A frame costs one aliased
    /// frame and a full-screen pass or two (1.1-1.3x the aliased frame on llvmpipe at 1024 x
    /// 1024), so a view that moves stays near aliased speed and a still one converges to the
    /// image of all samples drawn at once (the same pixels: tst_render_trims_aa).
    bool progressive = false;
    /// Below 1, a preview of a view in motion (the editor on software OpenGL while it orbits
    /// or drags): the frame is drawn aliased at this fraction of the target's width and height
    /// (at least a pixel), overlays included, into the renderer's own float-depth framebuffer
    /// and magnified into the target (bilinear). Every pixel drawn is still exact; the
    /// anti-aliasing targets are kept for the full frame that follows. 1: the full frame.
    /// Ignored by AOV frames and picks. Values are clamped to [1/8, 1].
    double previewScale = 1.0;
    /// Exact mode sends no triangle of a surface whose control points lie wholly outside the
    /// view (FrameReport::culled). Off only to check that culling changes no pixel.
    bool cullOutsideView = true;
    /// What the renderer keeps of a frame for the next one (docs/RENDERING.md, "The partial
    /// frame"). Aliased exact frames only (previews included); anti-aliased, AOV and pick frames
    /// are always whole and drawn as with None.
    enum class FrameReuse {
        /// Straight into the target (`knotwork render`, the bench's tables).
        None,
        /// Into the renderer's own framebuffer (render/float_depth_target.h), copied into the
        /// target; every frame whole. What Partial is measured against (bench --full-frames).
        Full,
        /// As Full, and a frame with the last one's view, size and options that only some
        /// surfaces' data changed since redraws only the rectangle those surfaces covered then
        /// or cover now (FrameReport::partial); anything it cannot bound draws the frame whole.
        /// The editor's frames: a drag step costs the dragged face's pixels, not the view's.
        Partial,
    };
    FrameReuse frameReuse = FrameReuse::None;
    /// How a partial frame narrows its rectangle to the changed surfaces' damage tiles
    /// (render/damage_tiles.h): tiles of `tilePixels`, covered by at most `maxRects`
    /// rectangles, two merged when their union adds at most `mergePixels` pixels. Each
    /// rectangle draws every pass again (its plan, the fins, the deferred pass's set-up), which
    /// on llvmpipe measured about what several thousand of hammer's pixels cost (docs/
    /// PERFORMANCE.md ## Editing). maxRects 1: the one rectangle.
    struct DamageTiles {
        int tilePixels = 16;
        int maxRects = 4;
        std::int64_t mergePixels = 8192;
        bool operator==(const DamageTiles&) const = default;
    };
    DamageTiles damageTiles;
    glm::vec4 background{0.18f, 0.19f, 0.21f, 1.0f};
    /// With a value, the background is a vertical gradient from `background` at the view's
    /// bottom to this at its top (kw::backgroundNamed's "light", as CAD viewers offer);
    /// AOVs and picks still see no surface there.
    std::optional<glm::vec4> backgroundTop;
    /// Lights follow the camera (see lightsFor), so orbiting never leaves a part unlit.
    bool headlight = false;
    /// Section planes (kw::SectionPlane, at most kMaxSectionPlanes, each valid by
    /// checkSectionPlane; Renderer::render refuses others): every pixel whose exact point lies
    /// on a plane's removed side is discarded, in both modes and every shading, and the
    /// section curve is drawn as a line. The pre-pass's depth is the base polygon's, which
    /// cannot tell the exact point's side, so only the cells no plane crosses are drawn the
    /// frame's way (splitCellsBySections); the back faces of the closed solids a plane crosses
    /// are drawn, they are where the caps go (docs/RENDERING.md, "Section planes").
    std::vector<SectionPlane> sections;
    /// With sections and the depth pre-pass, aliased frames (each accumulated sample is
    /// one): each cut surface's cells are ordered by the planes (kw::splitCells); those wholly
    /// kept are drawn as an uncut frame's (pre-pass, deferred pass), only those a plane
    /// crosses with Shading::ExactDepth and the section test, and those removed not at all.
    /// Off (and in MSAA frames): the whole exact pass is drawn with Shading::ExactDepth. The
    /// same cut either way (tst_render_sections); off only to measure the difference.
    bool splitCellsBySections = true;
    /// With sections: where the first kept surface under a pixel is the inside of a closed
    /// solid (Surface::solid), a hatched cap at the plane, AOV id kSectionCapId.
    bool sectionCaps = true;

    bool operator==(const RenderOptions&) const = default;
};

/// The backgrounds by name, the command line's and the project's spelling: "dark" (the
/// default, a flat dark grey) and "light" (a light grey-blue gradient, brighter at the top).
/// Sets options.background and options.backgroundTop; false for any other name.
inline bool backgroundNamed(const QString& name, RenderOptions& options) {
    if (name == QLatin1String("dark")) {
        options.background = RenderOptions{}.background;
        options.backgroundTop.reset();
        return true;
    }
    if (name == QLatin1String("light")) {
        options.background = glm::vec4(0.62f, 0.66f, 0.72f, 1.0f);
        options.backgroundTop = glm::vec4(0.93f, 0.94f, 0.96f, 1.0f);
        return true;
    }
    return false;
}

/// The trim mode named "exact" or "mask" (the command line's and the settings' spelling), or
/// nothing for any other name.
inline std::optional<RenderOptions::TrimMode> trimModeNamed(const QString& name) {
    if (name == QLatin1String("exact"))
        return RenderOptions::TrimMode::Exact;
    if (name == QLatin1String("mask"))
        return RenderOptions::TrimMode::Mask;
    return std::nullopt;
}

/// The anti-aliasing method named "accumulate" or "coverage" (the command line's and the
/// settings' spelling), or nothing for any other name.
inline std::optional<RenderOptions::Antialiasing> antialiasingNamed(const QString& name) {
    if (name == QLatin1String("accumulate"))
        return RenderOptions::Antialiasing::Accumulate;
    if (name == QLatin1String("coverage"))
        return RenderOptions::Antialiasing::Coverage;
    return std::nullopt;
}

/// The partitioning a saved or preferred mode name asks for: "uniform" is the paper's, any
/// other (validation allows only "adaptive" and "") the adaptive default.
inline RenderOptions::Partitioning partitioningNamed(const QString& name) {
    return name == QLatin1String("uniform") ? RenderOptions::Partitioning::Uniform
                                            : RenderOptions::Partitioning::Adaptive;
}

/// Counts of data sent to the GPU, kept per surface and in total, and per frame in FrameReport.
struct UploadStats {
    std::int64_t fullUploads = 0;       ///< control-point textures (re)created and filled
    std::int64_t subImageUploads = 0;   ///< glTexSubImage2D calls on control-point textures
    std::int64_t texels = 0;            ///< control-point texels sent (full and sub-image)
    std::int64_t bytes = 0;             ///< all bytes sent: texels, span tables, vertices
    std::int64_t spanTableUploads = 0;  ///< knot span tables (u and v count one each)
    std::int64_t basePolygonBuilds = 0; ///< base polygon rebuilt (cells, vertices, indices)
    std::int64_t vertexUpdates = 0;     ///< partial base polygon vertex updates after a move
    std::int64_t vertexBytes = 0;       ///< bytes of those partial updates
    std::int64_t meshBuilds = 0;        ///< tessellated meshes (re)built (tessellated mode)
    std::int64_t netBuilds = 0;         ///< control-net overlays (re)built

    UploadStats& operator+=(const UploadStats& o);
    bool operator==(const UploadStats&) const = default;
};

/// Counts of trim mask work, kept by TrimMaskPass per surface and in total.
struct TrimMaskStats {
    std::int64_t redraws = 0;          ///< masks (re)drawn: trims or mask resolution changed
    std::int64_t loops = 0;            ///< loop fans drawn in those redraws
    std::int64_t triangles = 0;        ///< fan triangles drawn
    std::int64_t texels = 0;           ///< mask texels cleared and covered (width x height)
    std::int64_t arrayAllocations = 0; ///< mask array (re)allocated (total only)
    std::int64_t cpuNanoseconds = 0;   ///< flattening and issuing the draws (not GPU time)
    int largestSide = 0;               ///< largest mask side (texels) redrawn; max under +=

    TrimMaskStats& operator+=(const TrimMaskStats& o);
    bool operator==(const TrimMaskStats&) const = default;
};

/// Camera matrices for one frame, for the GPU: x, y and w as OpenGL's, depth reversed for the
/// zero-to-one clip range (render/depth_convention.h): 1 at the near plane, towards 0 far away.
struct FrameCamera {
    glm::mat4 view{1.0f};
    glm::mat4 projection{1.0f};
    glm::mat4 viewProjection{1.0f};
    glm::vec3 eye{0.0f};
    glm::vec3 forward{0.0f, 0.0f, -1.0f}; ///< unit view direction
    float nearPlane = 0.1f;
    float farPlane = 100.0f;
    glm::ivec2 viewport{1, 1}; ///< pixels
    /// Window position of the viewport's lower left corner (glViewport's x, y): non-zero when
    /// a pick draws one pixel of the frame into a 1 x 1 target.
    glm::ivec2 viewportOrigin{0, 0};
    /// A pick's one pixel (GL rows, bottom-up), or (-1, -1): the whole view is drawn. The exact
    /// pass then leaves out the surfaces whose bounds do not reach that pixel.
    glm::ivec2 pickPixel{-1, -1};
    /// A partial frame's reach (window pixels x0, y0, x1, y1 exclusive, GL rows bottom-up):
    /// the rectangle it redraws, which the scissor keeps. The exact pass leaves out the
    /// surfaces whose bounds, grown by how far their skirts and fins may draw past them, miss
    /// it, and of the others the cells whose triangles and skirts miss it. Empty (x1 <= x0):
    /// the whole view.
    glm::ivec4 reach{0, 0, 0, 0};
    /// Sub-pixel shift of the whole image, in pixels (RenderOptions::Antialiasing::Accumulate's
    /// samples): applied to what the shaders get (drawnViewProjection), not to viewProjection,
    /// which the passes' caches and the CPU's choices keep, so a frame's samples share them.
    glm::vec2 jitter{0.0f};
};

/// The view-projection the shaders draw with: camera.viewProjection followed by the shift of
/// camera.jitter pixels on screen (a translation in normalised device coordinates).
glm::mat4 drawnViewProjection(const FrameCamera& camera);

/// The same camera in double precision, for picking and dragging on the CPU (pixels round-trip
/// exactly); frameCamera is this, rounded to float.
struct CameraMatrices {
    glm::dmat4 view{1.0};
    glm::dmat4 projection{1.0};
    glm::dvec3 eye{0.0};
    glm::dvec3 forward{0.0, 0.0, -1.0}; ///< unit view direction
    double nearPlane = 0.1;
    double farPlane = 100.0;
};

/// Perspective matrices for `camera` at `aspect` (width / height > 0). A degenerate view
/// direction falls back to +y, an up vector parallel to it to z (or y when looking along z).
/// Near and far planes enclose the scene's control bounds (the surfaces lie inside them) with a
/// margin; near is kept >= far * 1e-5 so depth precision stays usable.
CameraMatrices cameraMatrices(const Camera& camera, const Scene& scene, double aspect);
/// cameraMatrices in float for the GPU (viewport left {1, 1}).
FrameCamera frameCamera(const Camera& camera, const Scene& scene, double aspect);
/// The same from the scene's control bounds already known (`bounds` null: no surface has
/// points), as the renderer keeps them per surface instead of walking every point per frame.
CameraMatrices cameraMatrices(const Camera& camera, const glm::dvec3 (*bounds)[2], double aspect);
FrameCamera frameCamera(const Camera& camera, const glm::dvec3 (*bounds)[2], double aspect);

/// The viewer's own fill, added to the scene's lights in every view (phong.glsl's uFill,
/// kw::shadeReference): a diffuse term kd (base + facing |N.V|) colour. Lights authored for
/// one side leave the other side of a part black (a connecting rod's lower faces, the inside
/// of a lofted cone); CAD viewers give every visible face a readable grey with a headlight and
/// ambient, and this is that: never below kd base colour, brighter as a face turns to the eye,
/// the same for either orientation of the B-rep (N is turned to the eye first). With the
/// default material and light (ka 0.15 of ambient 0.2, kd 0.75, colour luminance 0.82) the
/// darkest visible pixel is 0.20, 0.17 without the light's ambient (tst_render_lighting).
struct ViewerFill {
    double base = 0.0;
    double facing = 0.0;
};
inline constexpr ViewerFill kViewerFill{0.28, 0.12};

/// The `count` lights (clamped to 1..kMaxLights) used to shade `scene`: its own lights first,
/// then copies of them rotated about the camera's up axis, so `--lights 8` works on any file.
/// With `headlight`, every light is turned with the camera: the lights as authored light the
/// scene from the front view (looking along +y, z up), and keep that relation to the eye in
/// every other view.
std::vector<Light> lightsFor(const Scene& scene, const Camera& camera, int count,
                             bool headlight = false);

} // namespace kw
