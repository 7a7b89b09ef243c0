// The exact pass's CPU planner: from the options, the camera and the scene's records it chooses
// each surface's program variant, culls, and groups the indirect draw commands into batches,
// keeping them across frames while only a few records change. No GL here (ExactSurfacePass
// issues the draws), so the plans are testable without a display.
#pragma once

#include "render/gpu_pool.h"
#include "render/partial_cells.h"
#include "render/render_types.h"

#include <QFlags>
#include <cstdint>
#include <functional>
#include <map>
#include <set>
#include <unordered_map>
#include <vector>

namespace kw {

struct SurfaceRecord;

/// glMultiDrawElementsIndirect's command layout.
struct IndirectCommand {
    std::uint32_t count = 0, instanceCount = 0, firstIndex = 0;
    std::int32_t baseVertex = 0;
    std::uint32_t baseInstance = 0; ///< the surface's table row (SurfaceGpu::slot)
    bool operator==(const IndirectCommand&) const = default;
};
static_assert(sizeof(IndirectCommand) == 20, "must match GL's DrawElementsIndirectCommand");

/// The surfaces of one program variant: their commands, at `first` in the frame's buffer.
struct ExactBatch {
    int degreeU = 1, degreeV = 1;
    bool trimmed = false, gather = false;
    bool affine = false;   ///< the polygon is the surface: no Newton step (variant bit 12)
    bool analytic = false; ///< the point from the analytic form in closed form (bit 14)
    /// The section test (ExactFeature::Section, variant bit 15) in a frame with planes: off for
    /// the cells every plane keeps, except those of the closed solids a plane may cap.
    bool section = true;
    /// Covers of closed-form faces (SurfaceGpu::cover, in sections()): the exact pass's
    /// program with KW_COVER (the first meeting in the domain, none: discarded).
    bool cover = false;
    int route = 0; ///< pre-pass batches of the deferred pass: ExactPlace::route
    int face = 0;  ///< the triangles skipped: ExactPlace::face
    std::vector<IndirectCommand> commands;
    std::int64_t first = 0;
};

/// Where a record's commands are in the planned batches. `variant` packs what selects its
/// batch: degrees (bits 0-7, 4 each), the trim lookup (8), the gather (9), the side culled
/// (10-11), affine (12), large cells drawn the forward way (13), the analytic form (14), the
/// section test (15).
struct ExactPlace {
    bool drawn = false;  ///< has exact data and a table row
    bool culled = false; ///< left out as outside the view
    int variant = -1;    ///< key into ExactPlanner::variants()
    /// Which triangles are skipped (variant bits 10-11): 0 none, 1 the back ones (the
    /// solid's outside along S_u x S_v), 2 the front ones.
    int face = 0;
    int index = -1; ///< its command in that batch
    bool prepassTrimmed = false;
    int prepassIndex = -1; ///< its command in plain() or trimmedPrepass() (pre-pass)
    /// Trimmed: its batch in trimmedPrepass(), keyed by the variant's degree, face, affine and
    /// analytic bits.
    int prepassKey() const { return variant & (0xff | 3 << 10 | 1 << 12 | 1 << 14); }
    /// Its trimmed pre-pass batch: by prepassKey, and with the deferred pass by whether it has
    /// a route.
    int trimmedPreKey(bool deferred) const {
        return prepassKey() | (deferred && route() < 0 ? 1 << 9 : 0);
    }
    /// Its route in the deferred pass: what that pass's program depends on, the degrees,
    /// affine, analytic and section bits; -1 for the surfaces the forward pass draws (variant bit
    /// 13: cells of many pixels each, where a pixel is shaded about once anyway).
    int route() const {
        return (variant >> 13) & 1 ? -1 : variant & (0xff | 1 << 12 | 1 << 14 | 1 << 15);
    }
    /// Its untrimmed pre-pass batch in plain(): by face, and with the deferred pass by route
    /// too (each route's pre-pass writes its own stencil value).
    int plainKey(bool deferred) const { return face << 16 | (deferred ? route() & 0xffff : 0); }
    /// Split by its trims (SurfaceGpu::insideIndexCount): the cells wholly inside drawn in
    /// plain() (this command), those near a curve in trimmedPrepass() (prepassIndex).
    bool split = false;
    int insideIndex = -1;
    std::int64_t awayCells = 0; ///< split: the cells left out as trimmed away
    int edgeVariant = -1;       ///< trimmed: key into edges() (degrees and gather)
    int edgeIndex = -1;         ///< its command there
    int skirtVariant = -1;      ///< with skirts: key into skirts() (degrees and trimmed)
    int skirtIndex = -1;        ///< its command there
    /// Its triangles skipped (face != 0), in aliased frames: key into backFaces() (degrees,
    /// trimmed, face, affine), and its command there; split, that is the cells near a curve,
    /// and those inside the trims are in the untrimmed batch (backVariant less bit 8).
    int backVariant = -1;
    int backIndex = -1;
    int backInsideIndex = -1;
    /// A section plane crosses it (PlanFlag::SectionSplit): key into sections() (degrees, the
    /// trim lookup, gather, face, affine, analytic) and its command there, the cells a plane
    /// crosses (SurfaceGpu::crossedIndexCount; all of them when its cells are not split by
    /// the planes). Its other commands then hold only the cells every plane keeps.
    int sectionVariant = -1;
    int sectionIndex = -1;
    /// Drawn by its cover (SurfaceGpu::cover): its one command is in sections() (variant bit
    /// 16 there), drawn with exact depth; no pre-pass, shading, skirt or back-face command.
    bool cover = false;
    /// With a route: the normalised device rectangle (x0, y0, x1, y1, within -1..1) of its
    /// control bounds, all of the view when they reach behind the eye.
    glm::vec4 window{-1.0f, -1.0f, 1.0f, 1.0f};
    /// A partial frame sends only its cells (and skirt segments) that reach the rectangle
    /// (render/partial_cells.h): each of its commands above is then the first of its runs'
    /// commands in that batch, and the plan is built again rather than patched.
    bool pieces = false;
    std::int64_t cells = 0; ///< the cells of its polygon the frame sends (drawn and not culled)
};

/// What of a frame decides the plan besides the camera, one bit each.
enum class PlanFlag : std::uint32_t {
    Trims = 1u << 0,          ///< trims on (RenderOptions::trims and a mask or grid in use)
    Prepass = 1u << 1,        ///< the depth pre-pass (RenderOptions::Shading::DepthPrepass)
    Cull = 1u << 2,           ///< RenderOptions::cullOutsideView
    Antialiased = 1u << 3,    ///< an anti-aliased frame: no split pre-pass (whole ranges)
    Skirts = 1u << 4,         ///< edge skirts drawn (adaptive, aliased, edgeSkirts)
    SkipBackFaces = 1u << 5,  ///< RenderOptions::skipBackFaces
    Adaptive = 1u << 6,       ///< adaptive partitions: the exact shaders' Newton step
    AffineNoNewton = 1u << 7, ///< RenderOptions::affineWithoutNewton
    Deferred = 1u << 8,       ///< the deferred exact pass (pre-pass batches by route)
    Analytic = 1u << 9,       ///< RenderOptions::analyticFaces
    /// Section planes with the pre-pass, aliased: the cells a plane crosses go to sections()
    /// (RenderOptions::splitCellsBySections), the kept ones are drawn the frame's way.
    SectionSplit = 1u << 10,
};
using PlanFlags = QFlags<PlanFlag>;

/// What the planned batches were built for; any difference (or a layout stamp change) builds
/// them again, else only the touched records are looked at.
struct ExactPlanKey {
    const void* scene = nullptr;
    std::uint64_t layout = 0;
    std::uint64_t marks = 0; ///< GpuScene::marksRevision: the solids' marks
    glm::mat4 viewProjection{0.0f};
    glm::ivec2 viewport{0};
    PlanFlags flags;
    double minCellPixels = 0.0;         ///< RenderOptions::gatherMinCellPixels
    double deferMaxCellPixels = 0.0;    ///< RenderOptions::deferMaxCellPixels
    std::vector<SectionPlane> sections; ///< RenderOptions::sections
    glm::ivec2 pickPixel{-1, -1};       ///< FrameCamera::pickPixel
    glm::ivec4 reach{0, 0, 0, 0};       ///< FrameCamera::reach
    /// With a reach: how far a skirt's pushed nodes may lie from their nodes, in whole pixels
    /// (kw::skirtPushPixels for the frame's tolerance).
    int skirtPush = 0;
    bool has(PlanFlag f) const { return flags.testFlag(f); }
    bool operator==(const ExactPlanKey& o) const {
        return scene == o.scene && layout == o.layout && marks == o.marks &&
               viewProjection == o.viewProjection && viewport == o.viewport && flags == o.flags &&
               minCellPixels == o.minCellPixels && deferMaxCellPixels == o.deferMaxCellPixels &&
               sections == o.sections && pickPixel == o.pickPixel && reach == o.reach &&
               skirtPush == o.skirtPush;
    }
};

/// What the planner reads of the scene: GpuScene's records in document order, those its last
/// sync touched, and the member count of each closed solid (GpuScene::solidMembers).
struct ExactPlanScene {
    const void* identity = nullptr; ///< the scene; another one builds the plan again
    std::uint64_t layout = 0;       ///< GpuScene::layoutStamp
    std::uint64_t marks = 0;        ///< GpuScene::marksRevision
    const std::vector<SurfaceRecord*>* records = nullptr;
    const std::vector<SurfaceRecord*>* touched = nullptr;
    std::function<int(int)> solidMembers;
};

class ExactPlanner {
public:
    /// The plan key of a frame: `trims` whether the frame uses them, `antialiased` an
    /// anti-aliased (coverage) frame, `deferred` whether the deferred pass can draw it.
    static ExactPlanKey keyFor(const ExactPlanScene& scene, const FrameCamera& camera,
                               const RenderOptions& options, bool trims, bool antialiased,
                               bool deferred);

    /// One command that changed in place, at `at` commands into the frame's buffer.
    struct CommandWrite {
        std::int64_t at = 0;
        IndirectCommand command;
    };
    /// Brings the plan up to date for a frame with `key`: when only the touched records may
    /// have changed and none changed variant, culling or presence, their commands are patched
    /// in place and listed in `writes` (returns false); otherwise every batch is built again
    /// (returns true: commands() must be uploaded whole).
    bool update(const ExactPlanScene& scene, const ExactPlanKey& key, const FrameCamera& camera,
                std::vector<CommandWrite>& writes);
    /// The key of the plan last updated.
    const ExactPlanKey& key() const { return m_key; }
    /// Forgets the plan (the next update builds it).
    void clear();

    /// Every batch's commands in upload order (plain, trimmed pre-pass, variants, edges,
    /// skirts, back faces, sections), each batch's `first` pointing into it.
    const std::vector<IndirectCommand>& commands() const { return m_commands; }
    /// The pre-pass's untrimmed ranges, by ExactPlace::plainKey.
    const std::map<int, ExactBatch>& plain() const { return m_plain; }
    /// The pre-pass's trimmed cells near a curve, by ExactPlace::trimmedPreKey.
    const std::map<int, ExactBatch>& trimmedPrepass() const { return m_trimmedPre; }
    /// The shading pass's batches, by ExactPlace::variant.
    const std::map<int, ExactBatch>& variants() const { return m_variants; }
    /// The trimmed surfaces again for the anti-aliased edge pass, by ExactPlace::edgeVariant.
    const std::map<int, ExactBatch>& edges() const { return m_edges; }
    /// The skirts, by degrees and trimmed (they test the trims themselves: no pre-pass).
    const std::map<int, ExactBatch>& skirts() const { return m_skirts; }
    /// The back-culled solids' faces again, by ExactPlace::backVariant, for the pass that
    /// draws their skipped side where nothing nearer covered a pixel (ExactBatch::face says
    /// which side the other passes skip; this pass skips the other one). Trimmed ones test
    /// their trims in the shader. Empty in anti-aliased (coverage) frames.
    const std::map<int, ExactBatch>& backFaces() const { return m_backFaces; }
    /// The cells section planes cross, by ExactPlace::sectionVariant: drawn after the kept
    /// cells' shading with exact depth and the section test (trimmed ones look their trims
    /// up: no pre-pass covers them). Empty without PlanFlag::SectionSplit.
    const std::map<int, ExactBatch>& sections() const { return m_sections; }
    /// The cells in sections().
    std::int64_t sectionCells() const;
    /// The deferred pass's routes (ExactPlace::route): their stencil values, 1, 2, ..., and
    /// the union of their surfaces' ExactPlace::window.
    struct Route {
        int stencil = 0;
        glm::vec4 window{0.0f};
    };
    const std::map<int, Route>& routes() const { return m_routes; }
    /// The stencil value the forward pass's cells write in a deferred frame's pre-pass (with
    /// their pre-pass data, for Renderer::pickInLastFrame): no route has it, so the deferred
    /// pass leaves those pixels alone. Routes take 1 .. kForwardStencil - 1.
    static constexpr int kForwardStencil = 255;
    /// The stencil value of a pre-pass batch's route (kForwardStencil: none, the forward pass
    /// draws it).
    int stencilOf(const ExactBatch& b) const;
    /// A record's place, or null when the last plan did not see it.
    const ExactPlace* place(const SurfaceRecord* r) const;
    /// The closed solids (Surface::solid) whose back faces the plan skips.
    const std::set<int>& backCulled() const { return m_backCulled; }
    /// Surfaces left out as outside the view, or as wholly on a section plane's removed side
    /// (their control bounds hold them: the exact shader would discard every fragment).
    int culled() const { return m_culled; }
    /// The cells the split pre-pass tests the trims on, and those it leaves out.
    std::int64_t trimTestedCells() const;
    std::int64_t trimmedAwayCells() const { return m_trimmedAway; }
    /// Surfaces drawn without the Newton step (affine), and those the deferred pass shades.
    int affineSurfaces() const;
    /// Surfaces shaded from their analytic form (ExactBatch::analytic), covers included.
    int analyticSurfaces() const;
    /// Surfaces drawn by their covers (ExactPlace::cover).
    int coverSurfaces() const { return m_cover; }
    int deferredSurfaces() const;
    /// The cells of the drawn surfaces' polygons the plan sends: in a partial frame those
    /// reaching its rectangle (FrameReport::partialCells), else every drawn surface's.
    std::int64_t cellsSent() const { return m_cellsSent; }

    /// Estimated screen pixels per base-polygon cell of `g` under `camera`: the area of the
    /// projected bounding box of its control points (clamped to the viewport) over its cell
    /// count; infinity when the box reaches behind the eye, 0 for an empty surface.
    static double projectedPixelsPerCell(const SurfaceGpu& g, const FrameCamera& camera);
    /// A box's corners projected: their normalised device bounds, or `behind` when a corner
    /// lies behind the eye (lo and hi then undefined).
    struct ScreenBox {
        glm::vec2 lo{0.0f}, hi{0.0f};
        bool behind = false;
    };
    static ScreenBox screenBox(const glm::vec3& lo, const glm::vec3& hi,
                               const glm::mat4& viewProjection);
    /// `box` in window pixels of `viewport` (x0, y0, x1, y1, GL rows), widened to whole pixels.
    static glm::ivec4 pixelRect(const ScreenBox& box, glm::ivec2 viewport);
    /// Pixels per cell of `cells` cells over the box (clamped to the view with `clampToView`;
    /// without, the cells' own size however many lie outside it); infinity when `behind`.
    static double pixelsPerCell(const ScreenBox& box, int cells, glm::ivec2 viewport,
                                bool clampToView);
    /// True when the box lies wholly outside one plane of the clip volume (slightly grown).
    static bool outsideView(const glm::vec3& lo, const glm::vec3& hi,
                            const glm::mat4& viewProjection);
    /// Where a box lies for section planes: Removed when it lies wholly on one plane's removed
    /// side (with a margin for the shader's float test: every point of it is cut), Kept when
    /// wholly on every plane's kept side, else Crossed. No planes: Kept.
    enum class SectionSide { Kept, Crossed, Removed };
    static SectionSide sectionSide(const glm::vec3& lo, const glm::vec3& hi,
                                   const std::vector<SectionPlane>& planes);

private:
    /// A record's commands: its whole triangle range (the shading pass, and the pre-pass when
    /// not split); split: the cells inside the trims and those near a curve, and the shading
    /// pass's range covering both (not the trimmed-away cells).
    struct Commands {
        IndirectCommand all{}, inside{}, edge{}, skirt{}, section{};
        /// ExactPlace::pieces: the runs of the cells to send (in cells of the triangle range
        /// at `triangles`) and of the skirt's indices (at `skirtIndices`; `skirtWhole`: all).
        std::vector<CellRun> cells, skirtRuns;
        bool skirtWhole = true;
        std::uint32_t triangles = 0, skirtIndices = 0;
    };
    /// Appends `command` to `b`, or with `p.pieces` the parts of it `cs`'s runs keep (`skirt`:
    /// the skirt's runs). Returns where its first command is in `b`.
    static int addCommand(ExactBatch& b, const IndirectCommand& command, const ExactPlace& p,
                          const Commands& cs, bool skirt = false);
    /// A record's variant and commands as this frame would draw it.
    ExactPlace classify(const SurfaceRecord& r, const ExactPlanKey& key, const FrameCamera& camera,
                        Commands& commands) const;
    /// m_backCulled for this frame: the closed solids all of whose members are records with
    /// exact data (none hidden, none too large) and whose members' control bounds lie wholly
    /// beyond the near plane, so the eye sees them from outside and nothing of them is
    /// clipped, and on the kept side of every section plane (a cut solid's back faces carry
    /// its caps). Empty without PlanFlag::SkipBackFaces.
    void chooseBackCulled(const ExactPlanScene& scene, const ExactPlanKey& key,
                          const FrameCamera& camera);
    void build(const ExactPlanScene& scene, const ExactPlanKey& key, const FrameCamera& camera);
    /// Adds `r`'s place `p` and commands to the batches.
    void addToBatches(const SurfaceRecord& r, ExactPlace& p, const Commands& cs,
                      const ExactPlanKey& key);
    bool patch(const ExactPlanScene& scene, const ExactPlanKey& key, const FrameCamera& camera,
               std::vector<CommandWrite>& writes);
    /// Adds a record's place to its route, growing the route's window by its own.
    void addToRoute(const ExactPlace& p);

    bool m_have = false;
    ExactPlanKey m_key;
    std::map<int, ExactBatch> m_plain, m_trimmedPre, m_variants, m_edges, m_skirts, m_backFaces,
        m_sections;
    std::map<int, Route> m_routes;
    std::set<int> m_backCulled;
    std::unordered_map<const SurfaceRecord*, ExactPlace> m_places;
    std::vector<IndirectCommand> m_commands;
    std::int64_t m_trimmedAway = 0; ///< the batches' ExactPlace::awayCells, summed
    std::int64_t m_cellsSent = 0;   ///< ExactPlace::cells, summed
    int m_culled = 0;
    /// The drawn surfaces that are affine, analytic, and shaded by the deferred pass.
    int m_affine = 0, m_analytic = 0, m_deferred = 0, m_cover = 0;
};

// In the namespace, so that argument-dependent lookup finds the operators.
Q_DECLARE_OPERATORS_FOR_FLAGS(PlanFlags)

} // namespace kw
