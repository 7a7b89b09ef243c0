// The GPU mirror of a document: one record per SurfaceId holding everything the passes draw
// from (control points, span tables, base polygon, tessellated mesh, control net, trim mask),
// each part tagged with the revisions it was built from. One sync per frame compares revisions
// once and drops removed surfaces once; the passes only draw what the records hold.
#pragma once

#include "model/document/document.h"
#include "model/error.h"
#include "render/adaptive_partitions.h"
#include "render/analytic_table.h"
#include "render/exact_contract.h"
#include "render/frame_report.h"
#include "render/gpu_pool.h"
#include "render/render_types.h"
#include "render/scene_changes.h"
#include "render/section_cells.h"
#include "render/trim_mask_pass.h"

#include <QOpenGLFunctions_4_5_Core>
#include <QPointer>
#include <QString>
#include <cstddef>
#include <map>
#include <memory>
#include <set>
#include <vector>

namespace kw {

/// Baseline mesh of one surface (tessellated mode): positions, normals and (u, v) per grid
/// vertex and triangle indices, from kw::tessellate at the partitions.
struct MeshGpu {
    Revisions revisions; ///< points and knots it was built from
    int nu = 0, nv = 0;
    GLuint vao = 0, positions = 0, normals = 0, uvs = 0, indices = 0;
    int indexCount = 0;
    std::int64_t bytes = 0;
};

/// Control-net overlay of one surface: the points and the net lines along i and j.
struct NetGpu {
    Revisions revisions; ///< points and knots (counts) it was built from
    GLuint vao = 0, points = 0, lines = 0;
    int pointCount = 0, lineIndexCount = 0;
    std::int64_t bytes = 0;
};

/// One surface's row of the scene's surface table (8 RGBA texels, shaders/surface_data.glsl): what
/// the exact pass reads per surface instead of per-draw uniforms, addressed by the draw's surface
/// index (SurfaceGpu::slot, fed through the draw's base instance).
struct SurfaceTableEntry {
    glm::vec4 domain{0.0f};   ///< u first, u last, v first, v last
    glm::vec4 origin{0.0f};   ///< xyz: the control texels' origin
    glm::vec4 colour{0.0f};   ///< rgb material colour
    glm::vec4 material{0.0f}; ///< ka, kd, ks, shininess
    glm::vec4 trimRect{0.0f}; ///< the trim mask's or grid's (u, v) rectangle (TrimMask::rect)
    glm::vec4 trimSize{0.0f}; ///< mask or grid width, height (texels), array layer, unused
    glm::ivec4 data{0};       ///< control offset, countU, u span-table offset, v's (texels)
    glm::ivec4 ids{0};        ///< surface id, trim grid's first word, solid side, unused
    bool operator==(const SurfaceTableEntry&) const = default;
};
static_assert(sizeof(SurfaceTableEntry) == kSurfaceTableTexels * sizeof(glm::vec4));
static_assert(
    offsetof(SurfaceTableEntry, domain) == kSurfaceTableDomainTexel * sizeof(glm::vec4) &&
        offsetof(SurfaceTableEntry, origin) == kSurfaceTableOriginTexel * sizeof(glm::vec4) &&
        offsetof(SurfaceTableEntry, colour) == kSurfaceTableColourTexel * sizeof(glm::vec4) &&
        offsetof(SurfaceTableEntry, material) == kSurfaceTableMaterialTexel * sizeof(glm::vec4) &&
        offsetof(SurfaceTableEntry, trimRect) == kSurfaceTableTrimRectTexel * sizeof(glm::vec4) &&
        offsetof(SurfaceTableEntry, trimSize) == kSurfaceTableTrimSizeTexel * sizeof(glm::vec4) &&
        offsetof(SurfaceTableEntry, data) == kSurfaceTableDataTexel * sizeof(glm::vec4) &&
        offsetof(SurfaceTableEntry, ids) == kSurfaceTableIdsTexel * sizeof(glm::vec4),
    "must match exact_contract.h's texels, which surface_data.glsl reads");
// The deferred pass reads the vertex pool as 32-bit words (exact_contract.h's offsets).
static_assert(sizeof(BaseVertex) == kBaseVertexWords * 4 &&
              offsetof(BaseVertex, span) == kBaseVertexSpanWord * 4 &&
              offsetof(BaseVertex, spanScale) == kBaseVertexSpanScaleWord * 4);

/// Everything on the GPU for one surface.
struct SurfaceRecord {
    SurfaceId id;
    const Surface* surface = nullptr; ///< the document's, valid from sync to the frame's end
    /// Control points, span tables, base polygon (ranges of the scene's pools); absent (not
    /// drawn) when they exceed the GPU's buffer limit.
    std::unique_ptr<SurfaceGpu> exact;
    Revisions revisions; ///< the document's, as of the last sync
    int slot = -1;       ///< row of the surface table while `exact` is present
    MeshGpu mesh;        ///< built when a frame draws tessellated
    NetGpu net;          ///< built when a frame shows the control net
    TrimMask mask;       ///< layer >= 0 while the surface is trimmed and a frame used trims
    /// World-space bounds of `exact`'s control texels (they hold the surface and its base
    /// polygon; kw::controlBounds), kept with the data for culling; valid while `bounded`.
    glm::vec3 boundsLo{0.0f}, boundsHi{0.0f};
    bool bounded = false;
    Revisions boundsOf; ///< the exact data's revisions the bounds were taken from
    /// The window pixels (x0, y0, x1, y1 exclusive, GL rows; clamped a view beyond the view)
    /// its base polygon's vertices project to under `drawnView` at `drawnViewport`: they hold
    /// every pixel the exact passes draw of it but the skirts' and fins' few past its edge,
    /// for a partial frame's rectangle and culling (render/partial_frame.h). Taken by the
    /// renderer at the polygon serial and points revision `drawnOf`; valid while `drawnBounded`
    /// (the polygon's vertices are kept on the CPU and all lie before the eye).
    glm::ivec4 drawnRect{0};
    glm::mat4 drawnView{0.0f};
    glm::ivec2 drawnViewport{0};
    bool drawnBounded = false;
    std::pair<std::uint64_t, std::uint64_t> drawnOf{0, 0};
    /// The damage tiles its cells touch at drawnRect's view, grown by `drawnTilesPad` pixels
    /// (render/damage_tiles.h cellTiles); taken when a partial frame redraws it, dropped with
    /// drawnRect.
    std::shared_ptr<const std::vector<std::int32_t>> drawnTiles;
    int drawnTilesPad = -1, drawnTilesSide = 0; ///< the pad and tile side they were taken at
    /// The last partial frame that redrew pixels redrew it (it is being edited): its tiles are
    /// taken again in every frame that can be kept, whole ones too, for the partial frame
    /// after it. Each partial frame that redraws pixels clears it and sets it again for the
    /// surfaces it redraws.
    bool tilesWanted = false;
    /// What this record adds to the frame's partition figures (FrameReport::Partitions).
    std::int64_t cells = 0;
    double boundPixels = 0.0;
    bool inOrder = false; ///< in records() (visible) as of the last sync
};

/// Whether frames drawn with `options` may draw closed-form faces by their covers
/// (RenderOptions::coverMinCells, SurfaceGpu::cover).
bool coversAllowed(const RenderOptions& options);
/// Whether `s` can be drawn by a cover: an unedited cylinder, cone or sphere (its analytic
/// form usable) with positive weights.
bool coverable(const Surface& s);

class GpuScene {
public:
    GpuScene() = default;
    GpuScene(const GpuScene&) = delete;
    GpuScene& operator=(const GpuScene&) = delete;

    /// `gl` must stay valid and its context current for every call below.
    void initialize(QOpenGLFunctions_4_5_Core* gl, ShaderLibrary* shaders);

    /// Brings the records up to date for one frame of `doc` with `options` seen by `camera`:
    /// drops the records of removed surfaces (and everything when `doc` is not the document
    /// of the last sync), skips hidden surfaces (their records are kept as they are), then per
    /// visible surface compares its revisions once (and in adaptive partitioning, chooses its
    /// partitions for the view when the view or the surface changed) and rebuilds the
    /// stale parts the frame needs: the exact data always (SurfaceGpu rules: a moved point is
    /// a sub-image upload), the tessellated mesh in tessellated mode, the control net when
    /// shown, the trim mask when trims are on. Adds to `report` its uploads, mask work and
    /// warnings. Returns the error when a surface is too large for a texture or
    /// the masks exceed the GPU's limits (the rest is synced regardless).
    ///
    /// Which surfaces it compares: every visible one after a structural change (insert,
    /// removal, reset, another document), a hidden surface shown or a shown one hidden, or a
    /// change of view or of the options the records depend on; otherwise only those the
    /// document reported changed since the last sync (SceneChanges), plus those
    /// that did not fit and are retried. FrameReport::recordsSynced counts them. Call
    /// prepare() first in the frame.
    Status sync(const Document& doc, const FrameCamera& camera, const RenderOptions& options,
                FrameReport& report);
    /// Starts a frame of `doc`: pulls what changed since the last frame (dropping everything
    /// when it is not the document of the last frame) and brings the scene's control bounds up to
    /// date from the surfaces that changed. The frame's camera planes come from bounds().
    void prepare(const Document& doc);
    /// The scene's control bounds as of prepare() (kw::sceneBounds); false without points.
    bool bounds(glm::dvec3& lo, glm::dvec3& hi) const { return m_changes.bounds(lo, hi); }
    /// Records whose exact data, table row or partitions the last sync may have changed, when
    /// it was incremental (layoutStamp() unchanged); when layoutStamp() moved, any record may
    /// have changed. For the exact pass's cached draw commands.
    const std::vector<SurfaceRecord*>& touched() const { return m_touched; }
    /// Bumped by every sync that walked every record or redrew trim masks.
    std::uint64_t layoutStamp() const { return m_layoutStamp; }
    /// How many of the document's surfaces, hidden ones included, carry the mark of `solid`
    /// (Surface::solid) as of the last sync: counted again by every full walk and every sync
    /// after Document::marksRevision() moved (an edit opened a solid, an undo closed one), so
    /// a solid whose members are all among records() has them all drawn.
    int solidMembers(int solid) const {
        const auto it = m_solidMembers.find(solid);
        return it == m_solidMembers.end() ? 0 : it->second;
    }
    /// Document::marksRevision() as of the last sync: the passes' batches depend on the marks
    /// (which solids skip their back faces), so it is part of their cache key.
    std::uint64_t marksRevision() const { return m_marksRevision; }
    /// Records of the last sync that have exact data (FrameReport::surfaces).
    int drawnCount() const { return m_drawn; }

    /// The records of the last sync in the document's surface order: the frame's draw list.
    /// Hidden surfaces (Surface::hidden) are not in it, so no pass draws or picks them.
    const std::vector<SurfaceRecord*>& records() const { return m_order; }
    const SurfaceRecord* find(SurfaceId id) const;
    /// The exact-mode data of a surface, or nullptr (unknown, or too large to draw).
    const SurfaceGpu* surfaceGpu(SurfaceId id) const;
    /// The active trim mask of a surface, or nullptr.
    const TrimMask* mask(SurfaceId id) const;
    const TrimMaskPass& trimMasks() const { return m_masks; }
    TrimMaskPass& trimMasks() { return m_masks; }

    /// Upload statistics of one surface (zero for an unknown id) or of all, since the last
    /// reset; trim mask statistics likewise.
    UploadStats stats(SurfaceId id) const;
    UploadStats totalStats() const;
    TrimMaskStats maskStats(SurfaceId id) const;
    TrimMaskStats totalMaskStats() const;
    void resetStats();
    /// Warnings of every current trim mask, each prefixed with its surface id.
    QStringList maskWarnings() const;
    /// Mask texels of a surface (see TrimMaskPass::readMask); empty without an active mask.
    std::vector<unsigned char> readMask(SurfaceId id) const;

    /// The shared buffers the exact pass draws from (valid after sync; renamed when they grow).
    const ScenePools& pools() const { return m_pools; }
    /// Binds the surface table and the control and span pools as texture buffers to the units
    /// of shaders/surface_data.glsl (kSurfaceTableUnit..kSpanUnit) and the triangle VAO.
    void bindSurfaceData() const;
    /// The vertex array of the cell outlines over the pools (the triangles' is bound by
    /// bindSurfaceData: attributes 0-3 of BaseVertex, the surface index at 4 per instance).
    GLuint outlineVao() const { return m_outlineVao; }
    /// The vertex array of the skirts (kw::SkirtVertex: attributes 0-3 as the triangles', the
    /// outward direction at 5, the surface index at 4 per instance) over the skirt pools.
    GLuint skirtVao() const { return m_skirtVao; }
    /// A vertex array with the skirts' layout and surface index binding, and no vertex or
    /// element buffer: the exact pass points binding 0 and the elements at its silhouette
    /// fins (kw::buildFins), which change with the view.
    GLuint finVao() const { return m_finVao; }
    /// The most bytes one pool may hold: GL_MAX_TEXTURE_BUFFER_SIZE RGBA32F texels, or less
    /// after setBufferLimitForTests.
    std::int64_t bufferLimit() const;
    /// Test hook, process-wide: lowers every scene's bufferLimit to `bytes` (0: the GPU's own),
    /// so tests reach the too-large path with small data. Read at each sync.
    static void setBufferLimitForTests(std::int64_t bytes);

    /// Adds the bytes of every record and of the mask array to `out` by kind.
    void residentBytes(GpuBytes& out) const;
    /// FrameReport::hostCopyBytes of the records: their control texels, base polygon vertices,
    /// breaks and spans kept on the CPU, and their adaptive choices' span bounds.
    std::int64_t hostCopyBytes() const;
    /// Frees every GL object; the context must be current.
    void release();

private:
    struct Entry {
        SurfaceRecord record;
        UploadStats stats;
        TrimMaskStats maskStats;
        std::uint64_t seen = 0; ///< the last sync whose document held the surface
        AdaptivePartitions adaptive;
        /// The section split's per-cell data (splitSections): the cells' bounds for the
        /// polygon and points they were taken from, and the classes last written.
        struct Sections {
            std::uint64_t polygonSerial = 0, points = 0, knots = 0;
            std::vector<CellBox> boxes;
            std::vector<std::uint8_t> classes;
            std::uint64_t serial = 0;
        } sections;
    };
    /// The cells of `records` ordered for the frame: by their trims (with `splitTrims`) and,
    /// with planes and RenderOptions::splitCellsBySections, by the planes (kw::splitCells).
    void splitRecords(const std::vector<SurfaceRecord*>& records, bool splitTrims,
                      const FrameCamera& camera, const RenderOptions& options);
    /// What one sync knows while it goes through the records.
    struct Pass;
    // sync's steps, in its order.
    /// Sizes the pools for the GPU's buffer limit and sets the pass's adaptive view.
    void beginPass(Pass& pass);
    /// Whether every record is compared this frame (the structure, the view or an option a
    /// record depends on changed); else `work` gets the indices of the surfaces to sync: those
    /// the document reported changed and those that did not fit last time.
    bool needsFullWalk(const Scene& scene, const FrameCamera& camera, const RenderOptions& options,
                       std::vector<int>& work);
    /// Every visible surface synced, the draw list rebuilt, the removed surfaces dropped and
    /// the frame's figures summed again.
    void syncAll(const Scene& scene, Pass& pass);
    /// The surfaces of `work` synced, and their shares of the frame's figures replaced.
    void syncChanged(const Scene& scene, const std::vector<int>& work, Pass& pass);
    /// Each solid's member count, again after a full walk or when the marks changed.
    void countSolidMembers(const Document& doc, bool full);
    /// The pass's figures, its CPU time `cpuMs` and its warnings into `report`; the error
    /// naming the surfaces that did not fit, if any did not.
    Status reportPass(const Scene& scene, const Pass& pass, double cpuMs,
                      FrameReport& report) const;
    /// The trim mask pass, when a touched record (any after a full walk) needs a new mask;
    /// its error replaces an ok `status`. True when it ran.
    bool syncMasks(const Document& doc, const FrameCamera& camera, const RenderOptions& options,
                   bool full, Status& status, FrameReport& report);
    /// splitRecords on the records whose cells may have moved: all of them when the masks ran
    /// or the section planes or the view changed, else the touched ones.
    void orderCells(bool masksRan, const FrameCamera& camera, const RenderOptions& options);
    void drop(Entry& e);
    void dropExact(SurfaceRecord& r);
    /// Brings one visible surface's record up to date (the per-record part of sync).
    void syncSurface(Entry& e, const Surface& s, int index, Pass& pass);
    /// Whether the trim mask pass has anything to do for record `r` (its layer, revisions or
    /// resolution are stale), so that a frame that changed no mask skips the pass.
    bool maskStale(const SurfaceRecord& r, const FrameCamera& camera,
                   const RenderOptions& options) const;
    /// Writes the rows of `records` that changed since the last frame and re-points the VAOs
    /// at the pools' current buffers.
    void syncTable(const std::vector<SurfaceRecord*>& records);
    /// Packs the polygon pools that hold more than twice what their polygons need
    /// (GpuPool::compact): a close-up's polygons are allocated while the fitted view's are
    /// still held, and a view back out leaves them at the close-up's size. When something
    /// moved, the layout stamp moves (the draw commands hold the offsets).
    void compactPools();
    void syncMesh(SurfaceRecord& r, const Revisions& rev, int nu, int nv, UploadStats& up);
    void syncNet(SurfaceRecord& r, const Revisions& rev, UploadStats& up);

    QOpenGLFunctions_4_5_Core* m_gl = nullptr;
    ScenePools m_pools;
    std::int64_t m_glBufferLimit = 0;
    /// The surface table: rows by slot, as on the GPU; `instances` holds 0, 1, 2, ... for the
    /// per-instance surface index attribute (a draw's base instance selects its row).
    struct Table {
        std::vector<SurfaceTableEntry> rows;
        std::vector<int> freeSlots;
        int used = 0;
        GLuint buffer = 0, instances = 0;
        int capacity = 0;
    } m_table;
    /// The analytic forms' rows, by the table's slots (written with the table's rows).
    AnalyticTable m_analytic;
    GLuint m_triangleVao = 0, m_outlineVao = 0, m_skirtVao = 0, m_finVao = 0;
    /// Texture buffer views: the table as RGBA32F and as RGBA32I, the control and span pools.
    GLuint m_views[kSurfaceDataViews] = {0, 0, 0, 0};
    TrimMaskPass m_masks;
    QPointer<const Document> m_document;
    std::map<SurfaceId, Entry> m_entries;
    std::vector<SurfaceRecord*> m_order;
    std::uint64_t m_syncs = 0;
    /// Adaptive partitions: the view they were chosen for, and its stamp (bumped on change).
    struct ViewKey {
        glm::mat4 viewProjection{0.0f};
        glm::ivec2 viewport{0};
        double tolerance = 0.0;
        bool operator==(const ViewKey&) const = default;
    } m_viewKey;
    std::uint64_t m_viewStamp = 0;
    /// What the section classes were last taken for: any difference splits every record again.
    struct SectionKey {
        std::vector<SectionPlane> planes;
        glm::mat4 viewProjection{0.0f};
        glm::ivec2 viewport{0};
        bool operator==(const SectionKey&) const = default;
    } m_sectionKey;
    std::uint64_t m_sectionSerial = 0; ///< names each new set of a record's section classes
    UploadStats m_removedStats;
    TrimMaskStats m_removedMaskStats;

    SceneChanges m_changes;
    /// What the records were last synced for: any difference walks them all.
    struct FrameKey {
        glm::mat4 viewProjection{0.0f};
        glm::ivec2 viewport{0};
        RenderMode mode = RenderMode::Exact;
        RenderOptions::Partitioning partitioning = RenderOptions::Partitioning::Uniform;
        double pixelTolerance = 0.0;
        int partitionsU = 0, partitionsV = 0, trimMaskCap = 0;
        bool polygonOverTrims = false, controlNet = false, trims = false;
        RenderOptions::TrimMode trimMode = RenderOptions::TrimMode::Exact;
        std::int64_t trimBudgetBytes = 0;
        int trimGridCap = 0;
        bool splitCellsByTrims = false, edgeSkirts = false, polygonsInView = false;
        bool wireframe = false; ///< outlines are uploaded once a frame draws them
        bool cullOutsideView = false; ///< exact trim grids are held for what is in view
        bool covers = false;          ///< kw::coversAllowed: closed-form faces may have covers
        double coverMinCells = 0.0;   ///< RenderOptions::coverMinCells
        bool operator==(const FrameKey&) const = default;
    };
    FrameKey m_frameKey;
    bool m_haveFrameKey = false;
    std::vector<SurfaceRecord*> m_touched;
    std::uint64_t m_layoutStamp = 0;
    std::map<int, int> m_solidMembers; ///< solidMembers()
    std::uint64_t m_marksRevision = 0; ///< Document::marksRevision() when they were counted
    int m_drawn = 0;
    /// The partition figures over records(), kept across incremental syncs.
    std::int64_t m_cells = 0;
    double m_worstBound = 0.0;
    std::set<int> m_unmet;    ///< indices of surfaces whose tolerance was not met
    std::set<int> m_tooLarge; ///< indices of visible surfaces whose data did not fit
    /// The mask pass's last answer, repeated by frames that skip it.
    QStringList m_maskWarnings;
    QString m_maskError;
    int m_maxTextureSize = 0;
    std::int64_t m_meshBytes = 0, m_netBytes = 0; ///< over every record
};

} // namespace kw
