// Exact pass (paper 3.4.1): each surface's base polygon drawn with the degree-specialised
// per-fragment NURBS shader; a depth pre-pass (default) makes each pixel evaluated once.
// Surfaces are grouped by shader variant and each group is one glMultiDrawElementsIndirect
// (issue 15 item 3), so draw calls grow with the variants in view, not with the surfaces.
#pragma once

#include "render/analysis_gl.h"
#include "render/antialias_target.h"
#include "render/exact_contract.h"
#include "render/gpu_scene.h"
#include "render/render_types.h"
#include "render/shader_library.h"

#include <QString>
#include <map>
#include <set>
#include <tuple>
#include <unordered_map>
#include <vector>

namespace kw {

class ExactSurfacePass {
public:
    /// Needs the context current while drawing; `shaders` outlives the pass.
    void initialize(QOpenGLFunctions_4_5_Core* gl, ShaderLibrary* shaders);

    /// Draws every record of `scene` that has exact data into the bound framebuffer (depth
    /// test on), as options.shading says. With `trims`, surfaces with an active mask lose their
    /// trimmed fragments: with the depth pre-pass, its KW_TRIM variant discards
    /// them and GL_EQUAL keeps the exact shader off them; with ExactDepth the exact shader's
    /// KW_TRIM variant discards. Untrimmed surfaces use variants without the lookup. Returns false
    /// with *error set when a shader variant cannot be built.
    /// `range` is the resolved colour range of a colour-map analysis mode (else unused).
    /// With `aa` (the renderer's anti-aliased frame, bound), the trimmed surfaces' opaque
    /// passes keep only fragments their trims cover wholly, and an edge pass after every
    /// surface sums the partly covered ones into aa's accumulation (coverage from the exact
    /// distance to the trim curve, shaders/trim_sample.glsl).
    bool draw(const GpuScene& scene, bool trims, const FrameCamera& camera,
              const std::vector<Light>& lights, const RenderOptions& options,
              const ValueRange& range, AntialiasTarget* aa, QString* error);
    /// Frees the environment map texture and the command buffer; the context must be current.
    void release() {
        m_environment.release();
        releaseDeferred();
        releaseCommands();
        releaseFins();
        m_haveBatches = false;
        m_places.clear();
    }
    /// Bytes of the indirect command buffer, of the silhouette fins and of the deferred
    /// pass's input texture (FrameReport::gpuBytes.perSurface).
    std::int64_t residentBytes() const {
        return m_commandBytes + m_finBytes +
               std::int64_t(m_prepassSize.x) * m_prepassSize.y * 16; // the deferred pass's input
    }
    const EnvironmentMap& environment() const { return m_environment; }

    /// The exact shader variant for degrees (p, q) and these options. The per-cell gather
    /// (ExactFeature::CellGather) is chosen when the cell's data fits the varyings and
    /// `gatherAllowed` is true. A trimmed variant of an anti-aliased frame: `trimAa`
    /// Opaque keeps wholly covered fragments only, Edge is the edge pass's. `skirt`: the
    /// skirt pass's variant (ExactFeature::Skirt: its own Newton solve and trim test, the
    /// strip's depth; no gather, no RayNewton, no ExactDepth). `affine`: the surface is its own
    /// polygon (SurfaceGpu::affine), whose (u, v) is already the point under the pixel: no
    /// Newton step (no RayNewton) in adaptive mode.
    enum class TrimAa { Off, Opaque, Edge };
    static ExactVariant variant(int p, int q, int lightCount, const RenderOptions& options,
                                bool trimmed = false, bool gatherAllowed = true,
                                TrimAa trimAa = TrimAa::Off, bool skirt = false,
                                bool affine = false);
    /// The deferred pass's program of `route` (Place::route: degrees and the affine bit).
    static ExactVariant deferredVariant(int route, int lightCount, const RenderOptions& options);

    /// Estimated screen pixels per base-polygon cell of `g` under `camera`: the area of the
    /// projected bounding box of its control points (clamped to the viewport) over its cell
    /// count; infinity when the box reaches behind the eye, 0 for an empty surface.
    static double projectedPixelsPerCell(const SurfaceGpu& g, const FrameCamera& camera);
    /// The same from the bounds controlBounds gave.
    static double projectedPixelsPerCell(const SurfaceGpu& g, const glm::vec3& lo,
                                         const glm::vec3& hi, const FrameCamera& camera);
    /// A box's corners projected: their normalised device bounds, or `behind` when a corner
    /// lies behind the eye (lo and hi then undefined).
    struct ScreenBox {
        glm::vec2 lo{0.0f}, hi{0.0f};
        bool behind = false;
    };
    static ScreenBox screenBox(const glm::vec3& lo, const glm::vec3& hi,
                               const glm::mat4& viewProjection);
    /// Pixels per cell of `cells` cells over the box (clamped to the view with `clampToView`;
    /// without, the cells' own size however many lie outside it); infinity when `behind`.
    static double pixelsPerCell(const ScreenBox& box, int cells, glm::ivec2 viewport,
                                bool clampToView);
    /// World-space bounds of the control points of `g` (they hold the surface and its base
    /// polygon); false without a point of positive weight.
    static bool controlBounds(const SurfaceGpu& g, glm::vec3& lo, glm::vec3& hi);
    /// True when the box lies wholly outside one plane of the clip volume (slightly grown).
    static bool outsideView(const glm::vec3& lo, const glm::vec3& hi,
                            const glm::mat4& viewProjection);

    int drawCalls = 0;        ///< counted by draw; the renderer zeroes it per frame
    int culled = 0;           ///< surfaces left out as wholly outside the view; zeroed likewise
    int solidsBackCulled = 0; ///< FrameReport::solidsBackCulled, added likewise
    /// FrameReport::Partitions' trimTestedCells and trimmedAwayCells of the last draw.
    std::int64_t trimTestedCells = 0, trimmedAwayCells = 0;
    /// Triangles of the edge skirts the last draw sent (FrameReport::Partitions), silhouette
    /// fins included; the fins alone in finTriangles.
    std::int64_t skirtTriangles = 0;
    std::int64_t finTriangles = 0;
    /// FrameReport::Partitions::affineSurfaces of the last draw: in adaptive mode, the surfaces
    /// drawn without the Newton step because their polygon is the surface.
    int affineSurfaces = 0;
    /// Surfaces the deferred pass shaded in the last draw (FrameReport::partitions).
    int deferredSurfaces = 0;
    /// How far past its exact edge a face's skirt may show it, in pixels on screen: the small
    /// conservative overlap where faces meet (issue 10 item 4). B-rep faces meet within the
    /// model's tolerance, not exactly; Axis_of_bearing's faces miss each other by 0.1-0.15 px
    /// at 256^2, which showed as a pinhole with 0.05 px here (tst_render_motion).
    static constexpr float kSkirtReachPixels = 0.25f;
    /// The strip's width past the adaptive tolerance, square to the polygon's edge on screen:
    /// the true edge lies within the tolerance of the edge's chord, the reach beyond it, and
    /// the margin covers rounding.
    static constexpr float kSkirtMarginPixels = kSkirtReachPixels + 0.1f;
    /// How far behind its polygon a skirt lies, in pixels' worth of distance along the ray at
    /// its depth. The adaptive bound is isotropic in 3D, so a neighbour's polygon lies within
    /// the tolerance of the surface along the ray too, and near a shared edge both approximate
    /// the same depth: a skirt pushed back this far fills gaps but never covers a face's
    /// polygon next to its edge (it did at 1e-3 of the distance: 16 depth disagreements on
    /// the sphere's seam at 256 x 192, tst_render_edges).
    static constexpr float kSkirtDepthPixels = 4.0f;
    /// The clip z factor that moves a point kSkirtDepthPixels pixels' worth further along its
    /// ray under `camera`'s perspective with reversed depth (z_clip is constant, w the distance:
    /// z / w = near / distance), the same at every distance.
    static float skirtDepthScale(const FrameCamera& camera);
    /// Thread CPU ms (kw::threadCpuMs) when draw issued its first draw call, or < 0 before
    /// (FrameTimes::beforeDraws); the renderer sets it to -1 per frame.
    double firstDrawCpuMs = -1.0;

private:
    /// glMultiDrawElementsIndirect's command layout.
    struct DrawCommand {
        GLuint count, instanceCount, firstIndex;
        GLint baseVertex;
        GLuint baseInstance; ///< the surface's table row (SurfaceGpu::slot)
    };
    /// The surfaces of one shader variant: their commands, at `first` in the frame's buffer.
    struct Batch {
        int degreeU = 1, degreeV = 1;
        bool trimmed = false, gather = false;
        bool affine = false; ///< the polygon is the surface: no Newton step (variant bit 12)
        int route = 0;       ///< pre-pass batches of the deferred pass: Place::route
        GLenum cullFace = 0; ///< GL_BACK or GL_FRONT: a closed solid's back faces skipped
        std::vector<DrawCommand> commands;
        std::int64_t first = 0;
    };
    /// Where a record's commands are in the cached batches.
    struct Place {
        bool drawn = false;  ///< has exact data and a table row
        bool culled = false; ///< left out as outside the view
        int variant = -1;    ///< key into m_variants
        /// Which triangles are skipped (variant bits 10-11): 0 none, 1 the back ones (the
        /// solid's outside along S_u x S_v), 2 the front ones (cullFaceOf).
        int face = 0;
        int index = -1; ///< its command in that batch
        bool prepassTrimmed = false;
        int prepassIndex = -1; ///< its command in m_plain or m_trimmedPre (pre-pass)
        /// Trimmed: its batch in m_trimmedPre, keyed by the variant's degree, face and affine
        /// bits.
        int prepassKey() const { return variant & (0xff | 3 << 10 | 1 << 12); }
        /// Its trimmed pre-pass batch: by prepassKey, and with the deferred pass by whether
        /// it has a route.
        int trimmedPreKey(bool deferred) const {
            return prepassKey() | (deferred && route() < 0 ? 1 << 9 : 0);
        }
        /// Its route in the deferred pass: what that pass's program depends on, the degrees
        /// and affine bits; -1 for the surfaces the forward pass draws (variant bit 13: cells
        /// of many pixels each, where a pixel is shaded about once anyway).
        int route() const { return (variant >> 13) & 1 ? -1 : variant & (0xff | 1 << 12); }
        /// Its untrimmed pre-pass batch in m_plain: by face, and with the deferred pass by
        /// route too (each route's pre-pass writes its own stencil value).
        int plainKey(bool deferred) const { return face << 14 | (deferred ? route() & 0x1fff : 0); }
        /// Split by its trims (SurfaceGpu::insideIndexCount): the cells wholly inside drawn in
        /// m_plain (this command), those near a curve in m_trimmedPre (prepassIndex).
        bool split = false;
        int insideIndex = -1;
        std::int64_t awayCells = 0; ///< split: the cells left out as trimmed away
        int edgeVariant = -1;       ///< trimmed: key into m_edges (degrees and gather)
        int edgeIndex = -1;         ///< its command there
        int skirtVariant = -1;      ///< with skirts: key into m_skirts (degrees and trimmed)
        int skirtIndex = -1;        ///< its command there
        /// With a route: the normalised device rectangle (x0, y0, x1, y1, within -1..1) of its
        /// control bounds, all of the view when they reach behind the eye.
        glm::vec4 window{-1.0f, -1.0f, 1.0f, 1.0f};
    };
    /// What the cached batches were built for; any difference (or a GpuScene layout stamp
    /// change) builds them again, else only the records GpuScene::touched() are looked at.
    struct CacheKey {
        const GpuScene* scene = nullptr;
        std::uint64_t layout = 0;
        std::uint64_t marks = 0; ///< GpuScene::marksRevision: the solids' marks
        glm::mat4 viewProjection{0.0f};
        glm::ivec2 viewport{0};
        bool trims = false, prepass = false, cull = false;
        bool antialiased = false;   ///< no split pre-pass (the edge pass wants whole ranges)
        bool skirts = false;        ///< edge skirts drawn (adaptive, aliased, edgeSkirts)
        bool skipBackFaces = false; ///< RenderOptions::skipBackFaces
        bool adaptive = false;      ///< adaptive partitions: the exact shaders' Newton step
        bool affineWithoutNewton = false; ///< RenderOptions::affineWithoutNewton
        double minCellPixels = 0.0;
        double deferMaxCellPixels = 0.0;
        bool deferred = false; ///< the deferred exact pass (pre-pass batches by route)
        bool operator==(const CacheKey&) const = default;
    };
    /// A record's commands: its whole triangle range (the shading pass, and the pre-pass when
    /// not split); split: the cells inside the trims and those near a curve, and the shading
    /// pass's range covering both (not the trimmed-away cells).
    struct Commands {
        DrawCommand all{}, inside{}, edge{}, skirt{};
    };
    /// A record's variant and commands as this frame would draw it.
    Place classify(const SurfaceRecord& r, const CacheKey& key, const FrameCamera& camera,
                   Commands& commands) const;
    /// m_backCulled for this frame: the closed solids (Surface::solid) all of whose members are
    /// records with exact data (none hidden, none too large: GpuScene::solidMembers) and whose
    /// members' control bounds lie wholly beyond the near plane, so the eye sees them from
    /// outside and nothing of them is clipped. Empty unless key.skipBackFaces.
    void chooseBackCulled(const GpuScene& scene, const CacheKey& key, const FrameCamera& camera);
    /// GL_BACK, GL_FRONT or 0 for Place::face 1, 2, 0.
    static GLenum cullFaceOf(int face) { return face == 1 ? GL_BACK : face == 2 ? GL_FRONT : 0; }
    /// Builds the batches from every record (and uploads them all).
    void buildBatches(const GpuScene& scene, const CacheKey& key, const FrameCamera& camera);
    /// Updates the commands of the touched records in place; false when one changed variant,
    /// culling or presence (then the batches are built again).
    bool patchBatches(const GpuScene& scene, const CacheKey& key, const FrameCamera& camera);
    /// Writes every batch's commands into the command buffer (one upload per frame) and binds it.
    void uploadCommands(const std::vector<Batch*>& batches);
    void drawBatch(const Batch& batch);
    void releaseCommands();
    /// The depth pre-pass: `plain` with the empty fragment shader, the trimmed surfaces' cells
    /// near a curve by degrees, tested on the trims. `atRay` (adaptive, aliased frames) tests
    /// them at the point under the pixel (the colour pass's Newton step; exact_surface.frag
    /// KW_DEPTH_ONLY), not at the polygon's (u, v), which lies up to the tolerance away: a
    /// pixel centre just inside a trimmed edge was dropped there and the face behind showed
    /// through (docs/RENDERING.md, "Adaptive partitions: the point under the pixel");
    /// otherwise, and for affine surfaces (whose polygon's (u, v) is that point),
    /// depth_only.frag.
    /// With `deferred`, each batch also writes its route's stencil value and the deferred
    /// pass's input (KW_GBUFFER) into the bound draw buffer 0.
    bool depthPrepass(std::map<int, Batch>& plain, std::map<int, Batch>& trimmed,
                      const GpuScene& scene, const FrameCamera& camera,
                      const std::vector<Light>& lights, bool antialiased, bool atRay, bool deferred,
                      QString* error);
    /// The draw framebuffer's size when the deferred pass can draw into it (a framebuffer
    /// object with a stencil attachment and a texture depth attachment; a colour attachment
    /// point free for the pre-pass's buffer), else (0, 0).
    glm::ivec2 deferredTargetSize() const;
    /// The deferred exact pass (after depthPrepass with `deferred`): per route, one triangle
    /// over the view whose stencil test keeps the pixels that route's pre-pass drew.
    bool deferredPass(const GpuScene& scene, const FrameCamera& camera,
                      const std::vector<Light>& lights, const RenderOptions& options,
                      const ValueRange& range, QString* error);
    /// Before the deferred frame's pre-pass: the texture (re)made for `size`, attached at
    /// kPrepassAttachment of the draw framebuffer as its only draw buffer, the stencil cleared
    /// and its test on. Returns the framebuffer's draw buffers, for detachPrepassTexture.
    std::vector<GLenum> attachPrepassTexture(glm::ivec2 size);
    /// After the pre-pass: the texture detached and the draw buffers put back.
    void detachPrepassTexture(const std::vector<GLenum>& drawBuffers);
    void releaseDeferred();
    /// Draws each batch with its variant's program (trimAa for the trimmed ones); with
    /// `largeCellsOnly`, only those the deferred pass leaves to it (variant bit 13).
    bool drawBatches(const std::map<int, Batch>& batches, TrimAa trimAa, const GpuScene& scene,
                     const FrameCamera& camera, const std::vector<Light>& lights,
                     const RenderOptions& options, const ValueRange& range, QString* error,
                     bool largeCellsOnly = false);
    /// The skirts of every drawn polygon (m_skirts; RenderOptions::edgeSkirts), then their
    /// silhouette fins (finPass), after the opaque passes: they fill only pixels no surface
    /// covered nearer.
    bool skirtPass(const GpuScene& scene, const FrameCamera& camera,
                   const std::vector<Light>& lights, const RenderOptions& options,
                   const ValueRange& range, QString* error);
    /// The silhouette fins of the skirted records, rebuilt for those whose view or polygon
    /// changed, drawn with the skirt programs (skirtPass calls it after the skirts).
    bool finPass(const GpuScene& scene, const FrameCamera& camera, const std::vector<Light>& lights,
                 const RenderOptions& options, const ValueRange& range, QString* error);
    void releaseFins();
    /// Draws batch `b` (skirts or fins) with the skirt pass's program for its degrees and
    /// trims, adding its triangles to `triangles`; false (and *error set) when the program
    /// cannot be built.
    bool drawSkirtBatch(const Batch& b, const GpuScene& scene, const FrameCamera& camera,
                        const std::vector<Light>& lights, const RenderOptions& options,
                        const ValueRange& range, std::int64_t& triangles, QString* error);
    /// The anti-aliased frame's edge pass over m_edges (see draw).
    bool edgePass(const GpuScene& scene, const FrameCamera& camera,
                  const std::vector<Light>& lights, const RenderOptions& options,
                  const ValueRange& range, AntialiasTarget& aa, QString* error);

    /// RenderOptions::multiDraw of the frame being drawn (drawBatch).
    bool m_multiDraw = true;
    QOpenGLFunctions_4_5_Core* m_gl = nullptr;
    ShaderLibrary* m_shaders = nullptr;
    EnvironmentMap m_environment;
    GLuint m_commands = 0;
    std::int64_t m_commandBytes = 0;

    /// The draw lists of the last frame, kept while nothing but a few records changed, so a
    /// drag step does not sort every surface into its variant again (issue 15).
    bool m_haveBatches = false;
    CacheKey m_key;
    /// The pre-pass's untrimmed ranges, by Place::plainKey.
    std::map<int, Batch> m_plain;
    /// The deferred pass's routes (Place::route): their stencil values, 1, 2, ..., and the
    /// union of their surfaces' Place::window.
    struct Route {
        int stencil = 0;
        glm::vec4 window{0.0f};
    };
    std::map<int, Route> m_routes;
    /// The stencil value of a pre-pass batch's route (0: none, the forward pass draws it).
    int stencilOf(const Batch& b) const;
    /// Adds a record's place to its route (m_routes), growing the route's window by its own.
    void addToRoute(const Place& p);
    /// The pre-pass's output for the deferred pass (RGBA32UI: the polygon's (u, v), the
    /// surface row and facing, the provoking vertex), its size, and an empty vertex array.
    GLuint m_prepassTexture = 0, m_emptyVao = 0;
    glm::ivec2 m_prepassSize{0};
    /// The closed solids (Surface::solid) whose back faces this frame skips.
    std::set<int> m_backCulled;
    /// The pre-pass's trimmed cells near a curve, by degrees (DEGREE_U | DEGREE_V << 4), face
    /// and affine (Place::prepassKey).
    std::map<int, Batch> m_trimmedPre;
    std::map<int, Batch> m_variants;
    /// The trimmed surfaces again, by degrees, gather, face and affine, for the anti-aliased
    /// edge pass.
    std::map<int, Batch> m_edges;
    /// The skirts, by degrees and trimmed (they test the trims themselves: no pre-pass).
    std::map<int, Batch> m_skirts;
    std::unordered_map<const SurfaceRecord*, Place> m_places;
    std::int64_t m_trimmedAway = 0; ///< the batches' Place::awayCells, summed
    int m_culled = 0;

    /// One record's fins and what they were built for.
    struct Fins {
        glm::mat4 viewProjection{0.0f};
        glm::ivec2 viewport{0};
        float pixels = 0.0f;
        std::uint64_t polygonSerial = 0;
        std::uint64_t points = 0; ///< SurfaceGpu::revisions.points
        std::vector<SkirtVertex> vertices;
        std::vector<unsigned> indices;
        std::uint64_t frame = 0; ///< the last finPass that drew its record
    };
    std::unordered_map<const SurfaceRecord*, Fins> m_fins;
    std::uint64_t m_finFrame = 0;
    /// The fins on the GPU: every record's, one after another, and one command per record
    /// grouped by skirt variant (the same programs as m_skirts).
    GLuint m_finVertexBuffer = 0, m_finIndexBuffer = 0, m_finCommandBuffer = 0;
    std::int64_t m_finBytes = 0;
    std::vector<Batch> m_finBatches; ///< `first` counts in m_finCommandBuffer
    /// The records, slots and variants the uploaded fins were laid out for.
    std::vector<std::tuple<const SurfaceRecord*, int, int>> m_finLayout;
};

} // namespace kw
