// Exact pass (paper 3.4.1), the GL side: each surface's base polygon drawn with the
// degree-specialised per-fragment NURBS shader; a depth pre-pass (default) makes each pixel
// evaluated once. ExactPlanner groups the surfaces by shader variant and each group is one
// glMultiDrawElementsIndirect, so draw calls grow with the variants in view, not the surfaces.
#pragma once

#include "render/analysis_gl.h"
#include "render/antialias_target.h"
#include "render/exact_contract.h"
#include "render/exact_planner.h"
#include "render/gpu_scene.h"
#include "render/pass_clock.h"
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
    /// KW_TRIM variant discards. Untrimmed surfaces use variants without the lookup. Returns the
    /// error when a shader variant cannot be built. `range` is the resolved colour range of a
    /// colour-map analysis mode (else unused). With `aa` (the renderer's anti-aliased frame,
    /// bound), the trimmed surfaces' opaque passes keep only fragments their trims cover wholly,
    /// and an edge pass after every surface sums the partly covered ones into aa's accumulation
    /// (coverage from the exact distance to the trim curve, shaders/trim_sample.glsl).
    Status draw(const GpuScene& scene, bool trims, const FrameCamera& camera,
                const std::vector<Light>& lights, const RenderOptions& options,
                const ValueRange& range, AntialiasTarget* aa);
    /// Frees the environment map texture and the command buffer; the context must be current.
    void release() {
        m_environment.release();
        releaseDeferred();
        releaseCommands();
        releaseFins();
        m_plan.clear();
    }
    /// Bytes of the indirect command buffer, of the silhouette fins and of the deferred
    /// pass's input texture (FrameReport::gpuBytes.perSurface).
    std::int64_t residentBytes() const {
        return m_commandBytes + m_finBytes +
               std::int64_t(m_prepassSize.x) * m_prepassSize.y * 16; // the deferred pass's input
    }
    /// Host bytes of the silhouette fins' vertices and indices (FrameReport::hostCopyBytes).
    std::int64_t hostCopyBytes() const {
        std::int64_t bytes = 0;
        for (const auto& [record, f] : m_fins)
            bytes += std::int64_t(f.vertices.size() * sizeof(SkirtVertex) +
                                  f.indices.size() * sizeof(unsigned));
        return bytes;
    }
    const EnvironmentMap& environment() const { return m_environment; }
    /// The deferred pass's input as the last deferred frame left it (0 before one): per pixel
    /// the polygon's (u, v), the surface's table row and the cell's vertex
    /// (shaders/surface_data.glsl, kwPrepassWords), valid where that frame's stencil is not 0.
    GLuint prepassTexture() const { return m_prepassTexture; }
    glm::ivec2 prepassSize() const { return m_prepassSize; }
    /// Counts the frames whose pre-pass wrote prepassTexture() (or made it anew): a partial
    /// frame keeps the last frame's data outside its rectangle only while no other frame
    /// wrote it since.
    std::uint64_t prepassWrites() const { return m_prepassWrites; }
    /// The closed solids whose back faces the last draw skipped (ExactPlanner::backCulled).
    const std::set<int>& backCulledSolids() const { return m_plan.backCulled(); }
    /// The cells the last draw sent (ExactPlanner::cellsSent).
    std::int64_t cellsSent() const { return m_plan.cellsSent(); }

    /// The exact shader variant for degrees (p, q) and these options. The per-cell gather
    /// (ExactFeature::CellGather) is chosen when the cell's data fits the varyings and
    /// `gatherAllowed` is true. A trimmed variant of an anti-aliased frame: `trimAa`
    /// Opaque keeps wholly covered fragments only, Edge is the edge pass's. `skirt`: the
    /// skirt pass's variant (ExactFeature::Skirt: its own Newton solve and trim test, the
    /// strip's depth; no gather, no RayNewton, no ExactDepth). `affine`: the surface is its own
    /// polygon (SurfaceGpu::affine), whose (u, v) is already the point under the pixel: no
    /// Newton step (no RayNewton) in adaptive mode. `analytic`: the surface's analytic form
    /// gives the point under the pixel in closed form (ExactFeature::Analytic, with RayNewton
    /// in adaptive mode; never with the gather, which only serves the NURBS evaluation).
    enum class TrimAa { Off, Opaque, Edge };
    static ExactVariant variant(int p, int q, int lightCount, const RenderOptions& options,
                                bool trimmed = false, bool gatherAllowed = true,
                                TrimAa trimAa = TrimAa::Off, bool skirt = false,
                                bool affine = false, bool analytic = false);
    /// The deferred pass's program of `route` (ExactPlace::route: degrees, the affine and the
    /// analytic bits).
    static ExactVariant deferredVariant(int route, int lightCount, const RenderOptions& options);

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
    /// FrameReport::Partitions::analyticSurfaces of the last draw.
    int analyticSurfaces = 0;
    /// FrameReport::Partitions::coverSurfaces of the last draw.
    int coverSurfaces = 0;
    /// Surfaces the deferred pass shaded in the last draw (FrameReport::partitions).
    int deferredSurfaces = 0;
    /// FrameReport::Partitions::sectionCrossedCells of the last draw.
    std::int64_t sectionCrossedCells = 0;
    /// How far past its exact edge a face's skirt may show it, in pixels on screen: the small
    /// conservative overlap where faces meet. B-rep faces meet within the
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
    /// The renderer's pass clock (null: none): draw marks each of its passes on it.
    PassClock* clock = nullptr;

private:
    /// GL_BACK, GL_FRONT or 0 for ExactPlace::face 1, 2, 0.
    static GLenum cullFaceOf(int face) { return face == 1 ? GL_BACK : face == 2 ? GL_FRONT : 0; }
    /// Writes the plan's commands into the command buffer (whole after a rebuild, else the
    /// patched ones) and binds it.
    void uploadCommands(bool rebuilt, const std::vector<ExactPlanner::CommandWrite>& writes);
    /// Draws `batch`'s commands, culling its ExactBatch::face, or with `otherSide` the
    /// opposite side (the back-face pass).
    void drawBatch(const ExactBatch& batch, bool otherSide = false);
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
    Status depthPrepass(const std::map<int, ExactBatch>& plain,
                        const std::map<int, ExactBatch>& trimmed, const GpuScene& scene,
                        const FrameCamera& camera, const std::vector<Light>& lights,
                        bool antialiased, bool atRay, bool deferred);
    /// The draw framebuffer's size when the deferred pass can draw into it (a framebuffer
    /// object with a stencil attachment and a texture depth attachment; a colour attachment
    /// point free for the pre-pass's buffer), else (0, 0).
    glm::ivec2 deferredTargetSize() const;
    /// The deferred exact pass (after depthPrepass with `deferred`): per route, one triangle
    /// over the view whose stencil test keeps the pixels that route's pre-pass drew.
    Status deferredPass(const GpuScene& scene, const FrameCamera& camera,
                        const std::vector<Light>& lights, const RenderOptions& options,
                        const ValueRange& range);
    /// Before the deferred frame's pre-pass: the texture (re)made for `size`, attached at
    /// kPrepassAttachment of the draw framebuffer as its only draw buffer, the stencil cleared
    /// and its test on. Returns the framebuffer's draw buffers, for detachPrepassTexture.
    std::vector<GLenum> attachPrepassTexture(glm::ivec2 size);
    /// After the pre-pass: the texture detached and the draw buffers put back.
    void detachPrepassTexture(const std::vector<GLenum>& drawBuffers);
    void releaseDeferred();
    /// Builds the exact program of `v` (exact_surface.frag after `vertexShader`) and binds it
    /// with the frame's, the analysis' and the section planes' uniforms set and, when
    /// `trimmed`, the trim masks bound; the build's error when it fails.
    Expected<QOpenGLShaderProgram*>
    bindExactProgram(const ExactVariant& v, bool trimmed, const GpuScene& scene,
                     const FrameCamera& camera, const std::vector<Light>& lights,
                     const RenderOptions& options, const ValueRange& range,
                     const QString& vertexShader = QStringLiteral("surface.vert"));
    /// Draws each batch with its variant's program (trimAa for the trimmed ones); with
    /// `largeCellsOnly`, only those the deferred pass leaves to it (variant bit 13).
    Status drawBatches(const std::map<int, ExactBatch>& batches, TrimAa trimAa,
                       const GpuScene& scene, const FrameCamera& camera,
                       const std::vector<Light>& lights, const RenderOptions& options,
                       const ValueRange& range, bool largeCellsOnly = false);
    /// The skirts of every drawn polygon (the plan's skirts(); RenderOptions::edgeSkirts), then
    /// their silhouette fins (finPass), after the opaque passes: they fill only pixels no surface
    /// covered nearer.
    Status skirtPass(const GpuScene& scene, const FrameCamera& camera,
                     const std::vector<Light>& lights, const RenderOptions& options,
                     const ValueRange& range);
    /// The silhouette fins of the skirted records, rebuilt for those whose view or polygon
    /// changed, drawn with the skirt programs (skirtPass calls it after the skirts).
    Status finPass(const GpuScene& scene, const FrameCamera& camera,
                   const std::vector<Light>& lights, const RenderOptions& options,
                   const ValueRange& range);
    void releaseFins();
    /// Draws batch `b` (skirts or fins) with the skirt pass's program for its degrees and
    /// trims, adding its triangles to `triangles`; the error when the program
    /// cannot be built.
    Status drawSkirtBatch(const ExactBatch& b, const GpuScene& scene, const FrameCamera& camera,
                          const std::vector<Light>& lights, const RenderOptions& options,
                          const ValueRange& range, std::int64_t& triangles);
    /// After the skirts, in aliased frames: the back faces of the closed solids whose back
    /// faces the opaque passes skipped (ExactPlanner::backCulled), drawn with the forward
    /// programs on the pixels that nothing nearer covered: the seams' sub-pixel gaps between
    /// two faces' exact trims, where the solid's inside shows, as it does to a ray, instead of
    /// the background (docs/RENDERING.md, "Back faces of closed solids").
    Status backFacePass(const GpuScene& scene, const FrameCamera& camera,
                        const std::vector<Light>& lights, const RenderOptions& options,
                        const ValueRange& range);
    /// After the kept cells' shading: the cells section planes cross (the plan's sections()),
    /// with exact depth, nearer than what the kept cells' pre-pass left, and the section test.
    Status sectionPass(const GpuScene& scene, const FrameCamera& camera,
                       const std::vector<Light>& lights, const RenderOptions& options,
                       const ValueRange& range);
    /// The anti-aliased frame's edge pass over the plan's edges() (see draw).
    Status edgePass(const GpuScene& scene, const FrameCamera& camera,
                    const std::vector<Light>& lights, const RenderOptions& options,
                    const ValueRange& range, AntialiasTarget& aa);

    /// RenderOptions::multiDraw of the frame being drawn (drawBatch).
    bool m_multiDraw = true;
    QOpenGLFunctions_4_5_Core* m_gl = nullptr;
    ShaderLibrary* m_shaders = nullptr;
    EnvironmentMap m_environment;
    GLuint m_commands = 0;
    std::int64_t m_commandBytes = 0;

    /// The draw lists, kept while nothing but a few records changed, so a drag step does not
    /// sort every surface into its variant again.
    ExactPlanner m_plan;
    /// The pre-pass's output for the deferred pass (RGBA32UI: the polygon's (u, v), the
    /// surface row and facing, the provoking vertex), its size, and an empty vertex array.
    GLuint m_prepassTexture = 0, m_emptyVao = 0;
    GLuint m_vertexPoolView = 0; ///< the vertex pool as RGBA32UI texels (kVertexPoolUnit)
    glm::ivec2 m_prepassSize{0};
    std::uint64_t m_prepassWrites = 0;
    /// One record's fins and what they were built for.
    struct Fins {
        glm::mat4 viewProjection{0.0f};
        glm::ivec2 viewport{0};
        float pixels = 0.0f;
        std::uint64_t polygonSerial = 0;
        std::uint64_t points = 0; ///< SurfaceGpu::revisions.points
        std::vector<SkirtVertex> vertices;
        std::vector<unsigned> indices;
        /// Each fin's window rectangle and their union (partial_cells.h finRects), taken at
        /// the first partial frame after a rebuild: a moving rectangle then costs a comparison
        /// per fin, and one per record whose fins it misses or holds whole.
        std::vector<glm::ivec4> rects;
        glm::ivec4 bounds{0};
        std::uint64_t frame = 0; ///< the last finPass that drew its record
    };
    std::unordered_map<const SurfaceRecord*, Fins> m_fins;
    std::uint64_t m_finFrame = 0;
    /// The fins on the GPU: every record's, one after another, and one command per record
    /// grouped by skirt variant (the same programs as the plan's skirts()).
    GLuint m_finVertexBuffer = 0, m_finIndexBuffer = 0, m_finCommandBuffer = 0;
    std::int64_t m_finBytes = 0;
    std::vector<ExactBatch> m_finBatches; ///< `first` counts in m_finCommandBuffer
    /// The records, slots and variants the uploaded fins were laid out for, and the partial
    /// frame's reach they were chosen for (empty: all of them).
    std::vector<std::tuple<const SurfaceRecord*, int, int>> m_finLayout;
    glm::ivec4 m_finReach{0};
};

} // namespace kw
